set(CUTROUTE_CORE_SOURCES diagnostic.cpp number_format.cpp random.cpp stop.cpp text.cpp version.cpp)
