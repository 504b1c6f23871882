// Route-independent lower bounds on a problem's optimum, from the cheapest steps between clusters.
//
// Cluster graph. D(A, B) = min over u in A, v in B of step(u, v): every route is a cycle over the
// clusters (an open path closed by a free arc back to the start) that costs at least the sum of D
// over its arcs. The arc into the start cluster is the closing arc plus the start node's inner cost
// (closed tours) or that inner cost alone (open paths). Precedence forbids cluster arcs no route can
// use: A -> B when B must precede A, or when some C must lie between them (A before C before B);
// the start cluster -> B when B has another predecessor; A -> the start cluster (the last step)
// when something must follow A.
//
// Bounds on that graph, the larger one counts:
// - assignment (every cluster entered and left once; Jonker & Volgenant's shortest augmenting
//   paths, O(m^3)): strong on asymmetric matrices (stacker-crane GTSPLIB, SOP);
// - Held–Karp 1-tree with subgradient ascent (Held & Karp 1971, Polyak steps towards the incumbent;
//   O(m^2) per step, at most a few hundred steps) on the symmetric relaxation (each edge at the
//   cheaper of its usable directions), where the assignment is weak: symmetric closed tours without
//   precedence, and any problem whose assignment puts at least a fifth of the clusters in 2-cycles.
//   Arcs are the cheapest between the clusters' nodes, plus every cluster's cheapest inner cost.
// The optimum of the original problem is an integer no smaller than either.
#pragma once

#include <optional>
#include <vector>

#include <cutroute/core/stop.hpp>
#include <cutroute/solve/problem.hpp>

namespace cutroute::solve {

// A lower bound on every route's cost, or nothing when the problem is beyond the size limits
// (more than 1 500 clusters or 12 000 nodes: the O(n^2) cluster graph, O(m^2) memory, about 70 MB
// at the limit) or `stop` fires first. `upper`: the cost of a known route (or kMaxCost when none),
// the target of the ascent's steps; a bound that reaches it proves that route optimal.
// `one_tree = false` keeps to the assignment bound (the 1-tree ascent costs most of the time on
// problems of a few hundred clusters and adds little on cutting nests; see estimate_bound_seconds).
std::optional<Cost> route_lower_bound(const Problem& p, const StopToken& stop, Cost upper = kMaxCost,
                                      bool one_tree = true);

// The cheapest entries: every cluster but an open path's start is entered once, by an arc from
// another cluster, so the sum over clusters of the cheapest (arc into a node + its inner cost) bounds
// every route (the start cluster of an open path counts its cheapest inner cost). Precedence and
// forbidden arcs are left out, which only lowers it. Planar costs only (nothing otherwise), any size:
// a k-d tree finds each node's nearest point of another cluster, O(n log n) time and O(n) memory,
// where the cluster graph needs O(n^2) and O(m^2). On cutting nests it is the column minima of
// that graph, 0.1-0.3 % below its assignment bound (d2g_DRAAK, vrs_Lv10_SHEET_001 and _004).
std::optional<Cost> entry_lower_bound(const Problem& p);

// What route_lower_bound() is expected to take on this problem, in seconds, from its size alone:
// the cluster graph and its assignment, and the 1-tree ascent when it runs. About 1.5 times what
// an AVX-512 machine measured (docs/SOLVER.md, "In `auto` mode the bound"), for slower ones.
struct BoundSeconds {
  double graph = 0.0;     // n^2 priced arcs, and the assignment from its column reduction
  double one_tree = 0.0;  // at least 50 steps of O(m^2)
};
BoundSeconds estimate_bound_seconds(const Problem& p);

// Potentials of the assignment bound, by cluster: every arc (a, b) of the cluster graph that a route
// can use costs at least row[a] + col[b], and sum(row) + sum(col) is the assignment bound. A route's
// arcs after any prefix ending in cluster c, through the set R of clusters not yet visited and back to
// the start cluster s, thus cost at least row[c] + sum over R of (row + col) + col[s], less the start
// node's inner cost (closed tours) or the start cluster's cheapest inner cost (open paths), which the
// arc into s carries. The exact DPs prune their states with it. Nothing beyond the size limits above,
// when stopped, or when no cycle cover of usable arcs exists.
struct ClusterPotentials {
  std::vector<Cost> row, col;
};
std::optional<ClusterPotentials> assignment_potentials(const Problem& p, const StopToken& stop);

}  // namespace cutroute::solve
