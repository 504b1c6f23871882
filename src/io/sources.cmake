set(CUTROUTE_IO_SOURCES output_file.cpp curve_fit.cpp dxf_scan.cpp dxf_reader.cpp dxf_writer.cpp instance.cpp instance_distance.cpp)
