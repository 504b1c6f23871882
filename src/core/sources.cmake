set(CUTROUTE_CORE_SOURCES diagnostic.cpp random.cpp stop.cpp version.cpp)
