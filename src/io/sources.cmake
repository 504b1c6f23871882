set(CUTROUTE_IO_SOURCES output_file.cpp instance.cpp instance_distance.cpp)
