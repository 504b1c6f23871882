list(APPEND CUTROUTE_MODEL_SOURCES multi_segment.cpp)
