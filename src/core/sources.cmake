set(CUTROUTE_CORE_SOURCES diagnostic.cpp number_format.cpp random.cpp stop.cpp version.cpp)
