list(APPEND CUTROUTE_SOLVE_SOURCES history_search.cpp)  # shop rules: history-dependent costs
