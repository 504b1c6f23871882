// The heuristic solver: precedence-respecting construction, local-search operators, and the
// multi-start adaptive large neighbourhood search (ALNS) built from them. docs/SOLVER.md explains
// every operator by example (STYLE.md #9); the comments here give the contract and the cost.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/core/stop.hpp>
#include <cutroute/solve/params.hpp>
#include <cutroute/solve/problem.hpp>
#include <cutroute/solve/solution.hpp>

namespace cutroute::solve {

// Random precedence-respecting cheapest insertion: clusters are taken in a random topological order
// (a cluster becomes available once all its predecessors are placed) and each is inserted with its
// best node at the cheapest position after its predecessors. O(m * n) for m clusters, n nodes.
// The result visits every cluster once and keeps precedence; it may use a forbidden arc when the
// construction is forced to (the local search then tries to remove it).
std::vector<NodeId> construct_route(const Problem& p, Rng& rng);

// Local-search operators on a complete route (route[0] in the start cluster, precedence kept).
// Each returns true when it made the route strictly cheaper; none ever makes it more expensive,
// moves route[0] out of position 0, or breaks a precedence.
//   reinsertion: remove one cluster, put it back at its best position with its best node. O(m * n) a pass.
//   two_opt: reverse a segment (no precedence pair inside it). O(m^2) a pass; with candidate lists
//     on symmetric matrices without inner costs or precedence also the neighbour-optimised move
//     below when the plain one does not pay.
//   or_opt: move a segment of 2 or 3 clusters elsewhere, same direction. O(m^2) a pass.
//   swap: exchange two clusters (used on problems with precedence). O(m^2) a pass.
//   segment_exchange: swap two adjacent segments, both kept in direction (SOP-3-exchange, the
//     orientation-preserving 3-opt move), feasibility checked lexicographically. O(m^2) per examined
//     position with precedence (routes <= 160 clusters), O(k^2) with candidate lists without.
//   reversing_exchange: swap two adjacent segments and reverse one of them (asymmetric matrices
//     within 10 % of symmetric only, routes <= 160 clusters; no precedence pair inside the reversed
//     one). O(L^2) per examined position.
//   two_opt on such matrices prices every arc of the reversed segment (prefix sums, O(1) a move).
//   lk: Lin-Kernighan chains of up to 10 2-opt moves from every examined cluster (the same matrices,
//     and symmetric ones of >= 96 clusters without precedence; without inner costs; no-op
//     elsewhere); intermediate routes may break precedence, the kept one does not. The first step
//     tries 5 alternatives, on matrices symmetric but for forbidden arcs the first four steps 5, 5,
//     3 and 2 (backtracking when a chain finds nothing). O(L) per chain step. `tracked_cost`, when
//     given, receives the cost the pass tracked (priced incrementally on symmetric closed tours).
//   cluster_optimise: for the fixed cluster order, the best node of every cluster (shortest path
//     through the layered graph, all nodes of the smallest cluster tried as the cyclic start when
//     the work fits `max_work`, else only its current node). O(k_min * sum |C_i||C_i+1|).
bool reinsertion_pass(const Problem& p, std::vector<NodeId>& route);
bool two_opt_pass(const Problem& p, std::vector<NodeId>& route);
bool or_opt_pass(const Problem& p, std::vector<NodeId>& route);
bool swap_pass(const Problem& p, std::vector<NodeId>& route);
bool segment_exchange_pass(const Problem& p, std::vector<NodeId>& route);
bool reversing_exchange_pass(const Problem& p, std::vector<NodeId>& route);
// `breadth`: alternatives tried at each step of a chain (empty: the solver's own, which depend on
// the matrix; see lin_kernighan.cpp).
bool lk_pass(const Problem& p, std::vector<NodeId>& route, Cost* tracked_cost = nullptr, std::span<const int> breadth = {});
bool cluster_optimise(const Problem& p, std::vector<NodeId>& route, double max_work = 2.0e6);
// All of the above until none improves.
void local_search(const Problem& p, std::vector<NodeId>& route);

// One move of 2-opt with neighbour optimisation, which two_opt runs next to candidate neighbours on
// symmetric matrices without inner costs or precedence: reverses route[i..j] and gives the four
// clusters at its ends (route[i-1], route[i], route[j], route[j+1]) their best nodes for the new
// order, when that is cheaper. Needs 2 <= i, i + 2 <= j, j + 1 < route.size(); returns false
// (route untouched) when the move does not pay or the problem is not of that kind. `tracked_cost`
// receives the route's cost as the move kept it up to date (for tests against a recomputation).
// O(|A||C| + |B||D|) for the four end clusters, most candidates refused in O(1) by bounds.
bool two_opt_neighbour_move(const Problem& p, std::vector<NodeId>& route, int i, int j, Cost& tracked_cost);

// The metaheuristic's elite-difference destroy on its own: removes from `route` every cluster
// (except route[0]) at an end of an arc, at cluster level and in either direction on symmetric
// problems, that `elite` does not have. Returns the removed clusters; `tracked_cost` receives the
// shortened route's cost as the operator kept it up to date (for tests against a recomputation).
std::vector<ClusterId> remove_differences(const Problem& p, std::vector<NodeId>& route,
                                          const std::vector<NodeId>& elite, Cost& tracked_cost);

// The population mode's ordered crossover on its own: a[i..j] in place (1 <= i <= j < size), the
// other clusters in b's order from after a[j]'s cluster in b, with b's nodes; a and b complete routes.
std::vector<NodeId> order_crossover(const Problem& p, const std::vector<NodeId>& a, const std::vector<NodeId>& b, int i,
                                    int j);
// The population's survivor selection on its own: adds the complete `routes` in order to a
// population of `mu` survivors and generations of `lambda`; returns the routes it holds at the end.
std::vector<std::vector<NodeId>> population_survivors(const Problem& p, const std::vector<std::vector<NodeId>>& routes,
                                                      int mu, int lambda);

// The batched planar prices that cluster optimisation and insertion use on plain planar problems
// (one node against many), built for several instruction sets: the solver runs the widest this
// processor supports, and every build gives the same bits. planar_prices(p, level, from, to)[j] =
// p.step(from, to[j]) computed by the `level` build, which must be supported; for tests, which
// compare the builds the processor runs.
enum class PriceLevel { baseline, x86_64_v3, x86_64_v4 };
bool price_level_supported(PriceLevel level);
std::vector<Cost> planar_prices(const Problem& p, PriceLevel level, NodeId from, std::span<const NodeId> to);

// The candidate lists of a problem with planar costs (k-d trees over its points), for tests: row a
// of `succ` holds the kn clusters b != a nearest to a through an arc a -> b, of `pred` through
// b -> a, each measured from up to 8 of a's nodes (its nodes 0, s, 2s, ... with s = ceil(size / 8))
// and to every node of b, nearest first (ties by cluster id; a tie for the last place goes to the
// cluster the tree search met first). Needs p.planar() and kn < cluster_count(). O(n log n).
struct CandidateLists {
  std::vector<ClusterId> pred, succ;  // row a at [a * kn, a * kn + kn)
};
CandidateLists planar_candidate_lists(const Problem& p, std::size_t kn);

// The node-set search on its own (docs/SOLVER.md "Node sets"), for closed tours on asymmetric
// matrices without precedence or inner costs: from `route`'s nodes, an iterated descent over the
// choice of one node per cluster that lowers the assignment bound of the chosen nodes, until
// `patience` kicks in a row bring no lower bound. Returns the nodes (by cluster) and their bound.
// O(m^2) per node change solved (most are refused by an O(m) bound first).
struct NodeSetResult {
  std::vector<NodeId> nodes;
  Cost bound = 0;
};
NodeSetResult node_set_search(const Problem& p, const std::vector<NodeId>& route, std::uint64_t seed, int patience);
// The assignment bound of one node per cluster (`nodes` by cluster): the cheapest way to give every
// chosen node a successor among the others, each used once (a cover by cycles of two or more
// clusters), so no tour through these nodes is cheaper. Solved from scratch, O(m^3).
Cost assignment_bound(const Problem& p, const std::vector<NodeId>& nodes);
// The same bound re-solved after each (cluster, node) change in turn, in O(m^2) from the previous
// solution as the node-set search does; for each change also the O(m) lower bound the search uses
// to skip it. Returns {skip bound, new bound} per change.
std::vector<std::pair<Cost, Cost>> assignment_bounds_after(const Problem& p, std::vector<NodeId> nodes,
                                                           const std::vector<std::pair<ClusterId, NodeId>>& changes);

// The metaheuristic (docs/SOLVER.md): per thread, construction + local search, then rounds of
// destroy (random / segment / worst / related removal of 1..30 % of the clusters, double bridge, and
// on wide problems the elite-difference removal above), repair (cheapest
// unified insertion, optionally noisy), local search and threshold acceptance; after every round
// all threads continue from the best route so far (on asymmetric matrices, see node_set_search, they
// start from the best route through the node set the search found). On large problems without
// precedence the threads breed children from a population instead (SolveParams::population_size).
// Stops on time limit, target, stagnation, work budget, cancel.
// Deterministic for a fixed seed and thread count when no time limit or cancel cuts it.
Solution solve_heuristic(const Problem& p, const SolveParams& params, const StopToken& stop,
                         const ProgressFn& progress = {});

}  // namespace cutroute::solve
