list(APPEND CUTROUTE_MODEL_SOURCES kerf_offset.cpp)
list(APPEND CUTROUTE_MODEL_SOURCES kerf_neighbours.cpp)
