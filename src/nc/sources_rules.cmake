list(APPEND CUTROUTE_NC_SOURCES rapid_detours.cpp micro_joints.cpp)  # shop rules
