list(APPEND CUTROUTE_GEOMETRY_SOURCES offset.cpp offset_grid.cpp offset_math.cpp offset_prune.cpp)
