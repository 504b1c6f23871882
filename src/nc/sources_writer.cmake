list(APPEND CUTROUTE_NC_SOURCES build_toolpath.cpp gcode_writer.cpp post_dialect.cpp)
