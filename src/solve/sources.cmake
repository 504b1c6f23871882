set(CUTROUTE_SOLVE_SOURCES problem.cpp solution.cpp params.cpp exact_dp.cpp tour.cpp planar_neighbours.cpp segment_exchange.cpp elite_destroy.cpp asym_two_opt.cpp heuristic.cpp solve.cpp)
