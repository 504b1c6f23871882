// Private: what the dense DP (exact_dp.cpp) and the DP over ideals (exact_ideals.cpp) share: the
// numbering of the non-start clusters and their nodes, the local step matrix, the cheapest-entry
// bound terms and the incumbent.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include <cutroute/core/stop.hpp>
#include <cutroute/solve/problem.hpp>
#include <cutroute/solve/solution.hpp>

namespace cutroute::solve::detail {

inline constexpr Cost kDpInf = std::numeric_limits<Cost>::max() / 4;

// Non-start clusters as bits 0..mp-1 (in cluster order), their nodes as contiguous local ids.
struct DpLayout {
  ClusterId start;
  int mp = 0;                      // non-start clusters
  int np = 0;                      // non-start nodes
  std::vector<ClusterId> cluster;  // bit -> cluster
  std::vector<int> first, size;    // bit -> local node range
  std::vector<NodeId> node;        // local -> node
  std::vector<int> bit_of_local;   // local -> bit
  std::vector<int> bit_of;         // cluster -> bit (-1: the start cluster)
};
DpLayout dp_layout(const Problem& p, ClusterId start);

// np x np steps between local nodes; kDpInf for forbidden arcs and within a cluster.
std::vector<Cost> dp_local_steps(const Problem& p, const DpLayout& L);
// By bit: the cheapest step into the cluster from any node outside it (the terms of LB(S)).
std::vector<Cost> dp_min_in(const Problem& p, const DpLayout& L);
// Their sum, kDpInf when a cluster cannot be entered.
Cost dp_sum(const std::vector<Cost>& min_in);
// The cheapest arc from a non-start node back to s on a closed tour (0 on a path), kDpInf if none.
Cost dp_closing_lb(const Problem& p, const DpLayout& L, NodeId s);
// Starts `out` (solver "exact") from a valid incumbent; returns its cost, or kDpInf without one.
Cost dp_take_incumbent(const Problem& p, const Solution* incumbent, Solution& out);
// The assignment potentials (lower_bound.hpp) by bit: a second bound on what remains after a state
// (S, v in cluster b): row[b] + apr(S), apr(S) = sum over the bits b' outside S of row + col, plus
// col[start], less the inner cost the arc into the start carries (inner(s) on a closed tour, the
// start cluster's cheapest on a path). On SOP instances with zero-cost arcs the cheapest entries
// bound nothing (esc25, esc47, rbg048a: 0) while this one is within 4-10 % of the optimum.
struct DpPotentials {
  bool ok = false;
  std::vector<Cost> row, rc;  // by bit: row, row + col
  Cost all = 0;               // sum of rc + col[start]
  Cost min_inner_start = 0;
  Cost apr0(const Problem& p, NodeId s) const { return all - (p.closed() ? p.inner_cost(s) : min_inner_start); }
  Cost remaining(Cost rest, int b, Cost apr) const {
    return ok && rest < kDpInf ? std::max(rest, row[static_cast<std::size_t>(b)] + apr) : rest;
  }
};
DpPotentials dp_potentials(const Problem& p, const DpLayout& L, const StopToken& stop);
// Reports a finished layer: stage "exact", fraction `done` (start nodes finished plus the share of
// layers of the current one) over the start nodes; the incumbent's cost when below kDpInf.
void dp_progress(const ProgressFn& progress, double done, std::size_t start_nodes, Cost ub);
// One cluster only: its node of least inner cost (the first of equals) is the optimal route.
Solution dp_single_cluster(const Problem& p, ClusterId start, Solution& out);
// A better route found by a walk back from the last node: `rev` holds its nodes from the last back to
// the one after the start s. Sets `out` to the route (status feasible) and returns its cost, the new
// upper bound.
Cost dp_keep_route(Solution& out, std::vector<NodeId>& rev, NodeId s, Cost cost);
// A DP that ran to the end: its best route (or the incumbent) is optimal, or no route exists.
Solution dp_proven(Solution& out);

}  // namespace cutroute::solve::detail
