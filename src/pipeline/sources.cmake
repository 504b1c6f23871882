set(CUTROUTE_PIPELINE_SOURCES optimize.cpp refine.cpp)
