set(CUTROUTE_PIPELINE_SOURCES compensation_fallback.cpp optimize.cpp refine.cpp)
