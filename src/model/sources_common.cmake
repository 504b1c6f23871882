list(APPEND CUTROUTE_MODEL_SOURCES common_lines.cpp common_graph.cpp common_entries.cpp common_job.cpp)
