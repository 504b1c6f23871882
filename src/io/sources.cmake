set(CUTROUTE_IO_SOURCES output_file.cpp svg.cpp nest_loader.cpp nest_svg.cpp inspect_report.cpp route_picture.cpp)
