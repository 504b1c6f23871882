set(CUTROUTE_IO_SOURCES output_file.cpp)
