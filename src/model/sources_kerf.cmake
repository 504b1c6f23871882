list(APPEND CUTROUTE_MODEL_SOURCES kerf_offset.cpp)
