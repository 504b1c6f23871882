list(APPEND CUTROUTE_MODEL_SOURCES cut_job.cpp demo_nest.cpp path_ops.cpp)
