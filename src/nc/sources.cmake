set(CUTROUTE_NC_SOURCES dialect.cpp frames.cpp gcode_reader.cpp)
