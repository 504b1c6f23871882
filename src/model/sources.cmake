set(CUTROUTE_MODEL_SOURCES
  cut_job.cpp
  demo_nest.cpp
  nest.cpp
  path_ops.cpp
)
