set(CUTROUTE_SOLVE_SOURCES problem.cpp solution.cpp params.cpp exact_dp.cpp exact_ideals.cpp exact_common.cpp lower_bound.cpp assignment.cpp node_sets.cpp tour.cpp or_opt.cpp swap.cpp cluster_optimise.cpp construction.cpp planar_rows.cpp planar_neighbours.cpp segment_exchange.cpp elite_destroy.cpp population.cpp neighbour_opt.cpp asym_two_opt.cpp reversing_exchange.cpp lin_kernighan.cpp heuristic.cpp solve.cpp)
# The batched planar arcs vectorise only when sqrt need not set errno and the clamp's comparison may
# be made branch-free (nothing here reads errno or traps on floating-point exceptions); neither flag
# changes a computed value. -ffp-contract=off: the AVX2/AVX-512 builds of price_row (planar_rows.cpp)
# must not fuse a multiply and an add into one FMA, which rounds once instead of twice and would
# price an arc one tick off Problem::planar_arc.
set_source_files_properties(${CMAKE_CURRENT_SOURCE_DIR}/solve/planar_rows.cpp PROPERTIES COMPILE_OPTIONS "-fno-math-errno;-fno-trapping-math;-ffp-contract=off")
