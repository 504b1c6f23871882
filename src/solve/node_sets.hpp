// Private: the node-set search of asymmetric matrix problems, which picks one node per cluster by
// the assignment bound of the nodes picked, and the problem restricted to such a set.
#pragma once

#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/core/stop.hpp>
#include <cutroute/solve/problem.hpp>

namespace cutroute::solve::detail {

// The search applies to closed tours on an asymmetric cost matrix without precedence whose clusters
// are not all single nodes (GTSPLIB's AGTSP instances; not cutting nests, whose costs are planar).
bool node_sets_apply(const Problem& p);

struct NodeSet {
  std::vector<NodeId> nodes;  // by cluster
  Cost bound = 0;             // assignment-problem optimum on these nodes: no tour through them is cheaper
};

// Iterated local search over node sets, starting from the nodes of `route`: a descent that changes
// one cluster's node while the assignment bound drops, then random changes of 2-4 clusters, until
// `patience` rounds in a row found no lower bound.
NodeSet search_node_sets(const Problem& p, const std::vector<NodeId>& route, Rng& rng, int patience,
                         const StopToken& stop);

// p with cluster c reduced to nodes[c] (node c of the result), same start cluster, kind and costs.
Problem restrict_to_nodes(const Problem& p, const std::vector<NodeId>& nodes);

// The start route of solve_heuristic on problems where node_sets_apply(): one node-set search per
// thread (each from the nodes of a random construction, with its own stream from `rng`), then the
// best route through the set of least bound (ties: first thread), searched on the restricted problem
// with `threads` threads until it reaches that bound or stagnates. Empty when stopped.
std::vector<NodeId> node_set_start(const Problem& p, int threads, Rng& rng, const StopToken& stop);

}  // namespace cutroute::solve::detail
