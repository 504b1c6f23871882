list(APPEND CUTROUTE_IO_SOURCES batch_summary.cpp estimate_json.cpp inspect_report.cpp nest_loader.cpp nest_svg.cpp route_picture.cpp svg.cpp)
