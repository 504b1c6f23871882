set(CUTROUTE_MODEL_SOURCES demo_nest.cpp)
