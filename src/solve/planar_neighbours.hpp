// Private: the candidate neighbour lists of a problem with planar costs, from k-d trees over its points.
#pragma once

#include <cstddef>
#include <vector>

#include <cutroute/solve/problem.hpp>

namespace cutroute::solve::detail {

// For every cluster a, the kn clusters b != a with the cheapest arc b -> a (pred) and a -> b (succ),
// exact over all nodes: a planar arc's cost grows with its length, so the nearest points are the
// cheapest arcs (forbidden arcs are not looked at). Rows of kn ids, row a at [a * kn, a * kn + kn);
// ties go to the lower cluster id. Needs p.planar() and kn < cluster_count().
void planar_neighbours(const Problem& p, std::size_t kn, std::vector<ClusterId>& pred, std::vector<ClusterId>& succ);

}  // namespace cutroute::solve::detail
