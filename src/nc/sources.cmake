set(CUTROUTE_NC_SOURCES gcode_writer.cpp post_dialect.cpp)
