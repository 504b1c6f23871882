// History-dependent route costs (SequenceCost) and a deterministic precedence-keeping local search under them.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <cutroute/core/stop.hpp>
#include <cutroute/solve/problem.hpp>

namespace cutroute::solve {

// Prices a whole route (or a prefix of one: route[0] in the start cluster, each cluster at most
// once) when the price of a step depends on what was visited before it: shop rules such as "do
// not cut next to the contour cut a moment ago" or "do not move the head over a part already cut
// free". The cost must include everything the search should minimise (usually route_cost() of the
// problem plus the rules' penalties) and must be pure and deterministic. The search calls it from
// one thread only.
using SequenceCost = std::function<Cost(std::span<const NodeId> route)>;

struct HistorySearchParams {
  // Longest block of consecutive clusters moved by one Or-opt move.
  int max_block = 3;
  // Budget of SequenceCost evaluations (each prices a whole route: O(route) for the rules of the
  // pipeline). The search stops earlier at a local optimum or when `stop` fires.
  long long max_evaluations = 400000;
};

struct HistorySearchResult {
  std::vector<NodeId> route;
  Cost cost = 0;                 // SequenceCost of `route`
  Cost initial_cost = 0;         // SequenceCost of the best start route
  long long evaluations = 0;
  int improvements = 0;          // moves applied
  bool local_optimum = false;    // false: stopped by the budget or the stop token
};

// The route with the clusters of `route` (a valid route of p) put in the order of increasing
// `priority[cluster]`, ties kept in their order in `route`, as far as precedence allows: Kahn's
// topological order that always takes the available cluster of lowest (priority, position). The
// start cluster stays first. Nodes are kept (only the order changes). O(m log m + precedence).
std::vector<NodeId> order_by_priority(const Problem& p, std::span<const NodeId> route, std::span<const double> priority);

// Improves the best of `starts` (each a valid route of p, same node per cluster or not) under
// `cost`. Moves, tried in a fixed order, first improvement taken, until none improves:
//  - Or-opt: a block of 1..max_block consecutive clusters moved elsewhere, e.g. with block (c d)
//    0 a b [c d] e f -> 0 a e [c d] b f  or  0 [c d] a b e f;
//  - swap: two clusters exchange places, 0 a b c d -> 0 d b c a;
//  - 2-opt: a stretch is reversed, 0 a [b c d] e -> 0 a [d c b] e.
// The start cluster never moves; a move that would break a precedence pair (checked on the
// closure of the problem) is not evaluated. Every candidate is priced by a full SequenceCost
// evaluation, so rules whose cost depends on the whole history stay exact; one pass over all moves
// is O(m² (max_block + 2)) evaluations of O(m) each, bounded by params.max_evaluations.
// Deterministic: no randomness, no threads.
HistorySearchResult history_search(const Problem& p, const SequenceCost& cost,
                                   const std::vector<std::vector<NodeId>>& starts, const HistorySearchParams& params,
                                   const StopToken& stop = {});

// A route built step by step: from route[0] of `nodes` (the start), always append the node, among
// those of `nodes` whose clusters' predecessors are all placed, that makes cost(prefix) smallest
// (ties: earliest in `nodes`). `nodes` holds one node per cluster (e.g. a solver route: the node
// choice is kept, only the order is rebuilt). O(m²) evaluations of cost on prefixes.
std::vector<NodeId> greedy_route(const Problem& p, const SequenceCost& cost, std::span<const NodeId> nodes);

// Whether route keeps every precedence pair of p (transitive closure included). O(m + pairs).
bool keeps_precedence(const Problem& p, std::span<const NodeId> route);

}  // namespace cutroute::solve
