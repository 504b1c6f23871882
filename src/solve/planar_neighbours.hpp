// Private: the candidate neighbour lists of a problem with planar costs, from k-d trees over its points.
#pragma once

#include <cstddef>
#include <vector>

#include <cutroute/solve/problem.hpp>

namespace cutroute::solve::detail {

// For every cluster a, the kn clusters b != a with the cheapest arc b -> a (pred) and a -> b (succ),
// exact over all nodes: a planar arc's cost grows with its length, so the nearest points are the
// cheapest arcs (forbidden arcs are not looked at). Rows of kn ids, row a at [a * kn, a * kn + kn);
// ties within a row go to the lower cluster id, a tie for its last place to the cluster the tree
// search met first. Needs p.planar() and kn < cluster_count(). With `two_threads` the
// two lists are built at once (the same lists).
void planar_neighbours(const Problem& p, std::size_t kn, std::vector<ClusterId>& pred, std::vector<ClusterId>& succ,
                       bool two_threads = false);

// For every node v, a lower bound on every planar arc u -> v from a node u of another cluster: the
// price of the nearest such arc, computed from a distance shrunk by 1e-12 so that the k-d tree's
// arithmetic (not Problem::planar_arc's) cannot make it one tick too high. Forbidden arcs are
// priced like the rest. O(n log n). Needs p.planar() and at least 2 clusters.
std::vector<Cost> planar_cheapest_arcs_in(const Problem& p);

}  // namespace cutroute::solve::detail
