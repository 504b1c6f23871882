// solve::Solution (route, cost, status, bound, statistics), route cost from scratch, and validate().
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <cutroute/solve/problem.hpp>

namespace cutroute::solve {

// optimal: proven optimal (exact solver, or a heuristic route equal to a proven lower bound);
// feasible: a valid route without proof; infeasible: proven that no route exists;
// no_solution: stopped (time, memory, cancel) before any valid route was found.
enum class SolveStatus { optimal, feasible, infeasible, no_solution };
const char* to_string(SolveStatus s);

struct SolveStats {
  double seconds = 0.0;          // wall time of solve()
  std::string solver;            // "exact", "heuristic", "exact+heuristic"
  long long iterations = 0;      // heuristic: destroy/repair iterations over all threads; exact: states expanded
  double work = 0.0;             // heuristic: work done, in the units of SolveParams::work_budget
  int threads = 1;
  bool stopped_by_limit = false; // time limit, memory limit or cancel cut the run
};

struct Solution {
  std::vector<NodeId> route;            // one node per cluster, route[0] in the start cluster
  Cost cost = 0;                        // as the solver computed it
  SolveStatus status = SolveStatus::no_solution;
  std::optional<Cost> lower_bound;      // proven lower bound on the optimum, when known
  SolveStats stats;
};

// The cost of `route` recomputed from the problem: arcs (and the closing arc of a tour) plus
// inner costs. kForbiddenCost-sized terms appear when a forbidden arc is used.
Cost route_cost(const Problem& p, std::span<const NodeId> route);

// True when `route` takes a forbidden arc (its closing arc included on a closed tour). A route's
// cost cannot tell: arcs may cost up to 2^40, so a long route of dear arcs costs more than
// kForbiddenCost without taking one.
bool uses_forbidden_arc(const Problem& p, std::span<const NodeId> route);

// Every reason `s` is not a valid route of `p` (empty when valid): node ids in range, exactly one
// node of every cluster, route[0] in the start cluster, every precedence (transitively) kept,
// no forbidden arc, and s.cost equal to the cost recomputed from scratch.
std::vector<std::string> validate(const Problem& p, const Solution& s);

}  // namespace cutroute::solve
