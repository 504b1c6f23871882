// Private: the optional NLopt COBYLA refinement (MACHINING.md 5.3), a stub returning the start point
// when the library is built without CUTROUTE_WITH_NLOPT.
#pragma once

#include <cutroute/machining/optimize.hpp>

namespace cutroute::machining::detail {

// LN_COBYLA on (ln vc, ln f) inside the set's box, every enabled g_k as an inequality, xtol_rel 1e-12,
// started from the grid optimum. Returns the better of the start and the COBYLA point.
PointEval cobyla_refine(const Problem& p, int set, const SearchBox& box, const PointEval& start, long& evals);

}  // namespace cutroute::machining::detail
