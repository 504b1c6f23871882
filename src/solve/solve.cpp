#include <cutroute/solve/solve.hpp>

#include <chrono>
#include <stdexcept>

#include <cutroute/solve/exact_dp.hpp>
#include <cutroute/solve/heuristic.hpp>

namespace cutroute::solve {

namespace {

constexpr std::size_t kAutoMaxIdeals = 200'000;

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

Solution run_exact(const Problem& p, const SolveParams& params, const StopToken& stop, const ProgressFn& progress) {
  // A short heuristic run first: its route is the DP's initial upper bound (most states are pruned
  // by it) and the answer if the DP hits a limit.
  SolveParams h = SolveParams::fast();
  h.seed = params.seed;
  h.threads = 1;
  h.time_limit_s = 0.0;
  Solution incumbent = solve_heuristic(p, h, stop, progress);
  Solution s = solve_exact(p, params.exact_memory_limit_bytes, stop, incumbent.route.empty() ? nullptr : &incumbent, progress);
  s.stats.solver = "exact";
  s.stats.iterations += incumbent.stats.iterations;
  return s;
}

}  // namespace

Solution solve(const Problem& problem, const SolveParams& params, const StopToken& stop_in, const ProgressFn& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const StopToken stop = params.time_limit_s > 0 ? stop_in.with_time_limit(params.time_limit_s) : stop_in;
  SolveParams inner = params;
  inner.time_limit_s = 0.0;  // already folded into `stop`
  Solution s = use_exact(problem, params) ? run_exact(problem, inner, stop, progress)
                                          : solve_heuristic(problem, inner, stop, progress);
  s.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (s.status == SolveStatus::optimal || s.status == SolveStatus::feasible) {
    const auto errors = validate(problem, s);
    if (!errors.empty()) throw std::logic_error("solver returned an invalid route: " + errors.front());
  }
  return s;
}

}  // namespace cutroute::solve
