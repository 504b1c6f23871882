// Private: one point priced against many planar points in a single vectorised batch.
#pragma once

#include <cstddef>

#include <cutroute/solve/problem.hpp>

namespace cutroute::solve::detail {

// out[j] = the planar price of the arc from `from` to (xs[j], ys[j]), rounded to the tick exactly
// as Problem::planar_arc rounds it, by the widest build this processor runs (planar_rows.cpp).
void planar_row(const PlanarCosts& pc, PlanarPoint from, const double* xs, const double* ys, std::size_t k, Cost* out);

}  // namespace cutroute::solve::detail
