set(CUTROUTE_CORE_SOURCES diagnostic.cpp drawing_unit.cpp file.cpp number_format.cpp random.cpp stop.cpp text.cpp version.cpp)
