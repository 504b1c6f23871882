list(APPEND CUTROUTE_NC_SOURCES build_toolpath.cpp compensation_check.cpp gcode_writer.cpp post_dialect.cpp)
