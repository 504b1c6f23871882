set(CUTROUTE_NC_SOURCES gcode_writer.cpp post_dialect.cpp build_toolpath.cpp)
