set(CUTROUTE_MODEL_SOURCES demo_nest.cpp cut_job.cpp path_ops.cpp)
