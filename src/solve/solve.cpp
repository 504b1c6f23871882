#include <cutroute/solve/solve.hpp>

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>

#include <cutroute/solve/exact_dp.hpp>
#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/lower_bound.hpp>

namespace cutroute::solve {

namespace {

constexpr std::size_t kAutoMaxIdeals = 200'000;
// Sizes up to which the cluster-graph bound is computed before a heuristic run (in `auto`, and the
// exact solver's short first run): the cluster graph prices every arc once (n^2), the assignment is
// O(m^3). Cutting nests, per solve: deepnest TopsNest (216 clusters, 1 151 nodes, matrix) 6.4 ms;
// vrs_Lv10_SHEET_004 (378 clusters, 4 300 nodes, planar costs) 0.09 s, 30 % of its search at the
// 2-million work budget, so not there. A cost callback is slower per arc (0.8 s at 6 000 nodes).
constexpr int kAutoBoundMaxClusters = 1000;
constexpr int kAutoBoundMaxNodes = 3000;
constexpr int kAutoBoundMaxCallbackNodes = 1500;
// Larger problems, up to route_lower_bound()'s own limits, get the bound when the run's time limit
// is at least 1 / kBoundTimeShare times its estimated cost (estimate_bound_seconds), and the 1-tree
// ascent too when the limit also covers it. `optimize`'s default 10 s gives each of a nest's two
// solves about 5 s: vrs_Lv10_SHEET_004 (4 300-4 500 nodes) gets the whole bound, SHEET_001 (7 200-
// 8 100 nodes) and d2g_DRAAK (7 500 nodes, 1 187 clusters) the assignment (the 1-tree was 0.01 %
// higher on SHEET_001's chain problem, lower on the rest). Runs without a time limit (a work budget)
// keep the fixed limits above, so the same options give the same route as before; beyond them,
// planar costs get the cheapest entries (entry_lower_bound), which no timing decides either.
constexpr double kBoundTimeShare = 0.05;

bool use_exact(const Problem& p, const SolveParams& params) {
  switch (params.solver) {
    case SolverKind::exact: return true;
    case SolverKind::heuristic: return false;
    case SolverKind::automatic:
      if (estimate_exact_work(p) <= params.exact_auto_max_work && estimate_exact_memory(p) <= params.exact_memory_limit_bytes)
        return true;
      // Beyond the dense table, precedence problems with few ideals (TSPLIB SOP p43.4, ry48p.4, ft53.4,
      // rbg109a: 0.4-7 million relaxations) are proven optimal in under a second. The estimate costs
      // at most about 0.1 s (ft70.4, 2 million ideals, turned away at the cap), mostly nothing (the
      // poset's width rules out most problems at once).
      return p.has_precedence() && estimate_ideal_work(p, kAutoMaxIdeals) <= params.exact_auto_max_work;
  }
  return false;
}

// The cluster-graph bound when it is cheap: precedence problems and asymmetric ones within the size
// limits above. Skipped on symmetric closed tours without precedence, where the bound is the
// Held-Karp ascent (0.1 s on GTSPLIB 207si1032) and rarely reaches the optimum.
std::optional<Cost> cheap_bound(const Problem& p, const StopToken& stop, double time_limit_s) {
  if (p.cluster_count() < 2) return std::nullopt;
  if (p.symmetric() && p.closed() && !p.has_precedence()) return std::nullopt;
  const bool cheap_arcs = p.has_matrix() || p.planar() != nullptr;
  if (p.cluster_count() <= kAutoBoundMaxClusters &&
      p.node_count() <= (cheap_arcs ? kAutoBoundMaxNodes : kAutoBoundMaxCallbackNodes))
    return route_lower_bound(p, stop);
  if (!cheap_arcs) return std::nullopt;
  const BoundSeconds cost = estimate_bound_seconds(p);
  const double share = kBoundTimeShare * time_limit_s;
  if (time_limit_s > 0.0 && cost.graph <= share)
    if (auto bound = route_lower_bound(p, stop, kMaxCost, cost.graph + cost.one_tree <= share)) return bound;
  // Where the cluster graph is beyond the limits or the time, planar costs still get the cheapest
  // entries: milliseconds (solve_bench BM_Bound_Entries), 0.12 % below the assignment on
  // d2g_DRAAK; a nest of 2 000 contours and 16 000 candidates had no bound at all.
  return entry_lower_bound(p);
}

// `time_limit_s`: the caller's limit (0: none), already folded into `stop`.
Solution run_exact(const Problem& p, const SolveParams& params, const StopToken& stop, const ProgressFn& progress,
                   double time_limit_s) {
  // The cluster-graph bound first when it is cheap: the short heuristic run stops when it reaches it
  // (SOP esc63), and it stays the reported bound when that run takes the whole time limit (SOP
  // prob.100, 3 s: the DP's cheapest-entry bound 547 was reported instead of 993).
  const std::optional<Cost> bound = cheap_bound(p, stop, time_limit_s);
  // A short heuristic run first: its route is the DP's initial upper bound (most states are pruned
  // by it) and the answer if the DP hits a limit.
  SolveParams h = SolveParams::fast();
  h.seed = params.seed;
  h.threads = 1;
  h.time_limit_s = 0.0;
  if (bound) h.target_cost = *bound;
  Solution incumbent = solve_heuristic(p, h, stop, progress);
  Solution s = solve_exact(p, params.exact_memory_limit_bytes, stop, incumbent.route.empty() ? nullptr : &incumbent, progress, bound);
  s.stats.solver = "exact";
  s.stats.iterations += incumbent.stats.iterations;
  return s;
}

// The heuristic, stopped as soon as it reaches the bound when there is one: its route is then optimal
// (TSPLIB SOP esc63: the assignment bound 62 is the optimum; the run took 8.8 s to stagnate, not
// knowing it was done).
Solution run_heuristic(const Problem& p, const SolveParams& params, const StopToken& stop, const ProgressFn& progress,
                      double time_limit_s) {
  const std::optional<Cost> bound = params.solver == SolverKind::automatic ? cheap_bound(p, stop, time_limit_s) : std::nullopt;
  SolveParams h = params;
  if (bound && (!h.target_cost || *h.target_cost < *bound)) h.target_cost = *bound;
  Solution s = solve_heuristic(p, h, stop, progress);
  if (bound && s.status == SolveStatus::feasible) {
    s.lower_bound = std::min(*bound, s.cost);
    if (s.cost <= *bound) s.status = SolveStatus::optimal;
  }
  return s;
}

}  // namespace

Solution solve(const Problem& problem, const SolveParams& params, const StopToken& stop_in, const ProgressFn& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const StopToken stop = params.time_limit_s > 0 ? stop_in.with_time_limit(params.time_limit_s) : stop_in;
  SolveParams inner = params;
  inner.time_limit_s = 0.0;  // already folded into `stop`
  const double limit = std::max(0.0, params.time_limit_s);
  Solution s = use_exact(problem, params) ? run_exact(problem, inner, stop, progress, limit)
                                          : run_heuristic(problem, inner, stop, progress, limit);
  s.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (s.status == SolveStatus::optimal || s.status == SolveStatus::feasible) {
    const auto errors = validate(problem, s);
    if (!errors.empty()) throw std::logic_error("solver returned an invalid route: " + errors.front());
  }
  return s;
}

}  // namespace cutroute::solve
