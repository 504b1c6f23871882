list(APPEND CUTROUTE_COST_SOURCES route_problem.cpp)
