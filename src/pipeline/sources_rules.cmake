list(APPEND CUTROUTE_PIPELINE_SOURCES shop_rules.cpp)  # shop rules
