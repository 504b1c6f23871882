set(CUTROUTE_MODEL_SOURCES
  nest.cpp
)
