set(CUTROUTE_SOLVE_SOURCES problem.cpp solution.cpp params.cpp exact_dp.cpp tour.cpp heuristic.cpp solve.cpp)
