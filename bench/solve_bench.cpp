// Solver benchmarks: the exact DP on the issue's 16-cluster x 8-node instance with 10 precedence
// pairs, and the heuristic on GTSPLIB files (the accuracy tables come from bench/gtsp_bench.py).
#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <cutroute/io/instance.hpp>
#include <cutroute/solve/exact_dp.hpp>
#include <cutroute/solve/lower_bound.hpp>
#include <cutroute/solve/solve.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include <cutroute/core/random.hpp>

namespace {

using namespace cutroute;

solve::Problem issue_instance(std::uint64_t seed, bool symmetric) {
  // Exactly 16 clusters x 8 nodes (test::random_problem draws cluster sizes at random), random
  // points (symmetric) or a random matrix (asymmetric), 10 precedence pairs from a hidden order.
  Rng rng(seed);
  const int m = 16, k = 8, n = m * k, pairs = 10;
  std::vector<solve::Cost> cost(static_cast<std::size_t>(n * n));
  std::vector<double> x(static_cast<std::size_t>(n)), y(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) x[static_cast<std::size_t>(i)] = static_cast<double>(rng.below(1000)), y[static_cast<std::size_t>(i)] = static_cast<double>(rng.below(1000));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      cost[static_cast<std::size_t>(i * n + j)] =
          symmetric ? static_cast<solve::Cost>(std::hypot(x[static_cast<std::size_t>(i)] - x[static_cast<std::size_t>(j)], y[static_cast<std::size_t>(i)] - y[static_cast<std::size_t>(j)]) + 0.5)
                    : static_cast<solve::Cost>(rng.below(1000));
  solve::ProblemBuilder b(n);
  b.set_cost_matrix(std::move(cost));
  for (int c = 0; c < m; ++c) {
    std::vector<solve::NodeId> nodes;
    for (int j = 0; j < k; ++j) nodes.push_back(solve::NodeId(c * k + j));
    b.add_cluster(nodes);
  }
  std::vector<int> order;
  for (int c = 1; c < m; ++c) order.push_back(c);
  rng.shuffle(order.begin(), order.end());
  for (int p = 0; p < pairs; ++p) {
    const auto i = rng.below(order.size() - 1);
    const auto j = i + 1 + rng.below(order.size() - 1 - i);
    b.add_precedence(solve::ClusterId(order[i]), solve::ClusterId(order[j]));
  }
  return std::move(b.build()).value();
}

void BM_ExactDp_16x8_10Precedence(benchmark::State& state) {
  const auto p = issue_instance(static_cast<std::uint64_t>(state.range(0)), state.range(1) != 0);
  solve::SolveParams params;
  params.solver = solve::SolverKind::exact;
  params.threads = 1;
  params.time_limit_s = 0;
  solve::Solution s;
  for (auto _ : state) {
    s = solve::solve(p, params);
    benchmark::DoNotOptimize(s.cost);
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  state.counters["optimal"] = s.status == solve::SolveStatus::optimal ? 1 : 0;
  state.counters["cost"] = static_cast<double>(s.cost);
  state.counters["table_MB"] = static_cast<double>(solve::estimate_exact_memory(p)) / 1048576.0;
  state.counters["max_rss_MB"] = static_cast<double>(ru.ru_maxrss) / 1024.0;
}
BENCHMARK(BM_ExactDp_16x8_10Precedence)->Args({1, 1})->Args({2, 1})->Args({3, 0})->Unit(benchmark::kSecond)->Iterations(1);

// The DP over precedence ideals (solve_exact_ideals) on TSPLIB SOP instances beyond the dense table,
// through the exact solver (its short heuristic run included): time, peak memory, proven or not.
void BM_ExactIdeals_Sop(benchmark::State& state, const char* name) {
  auto inst = io::read_instance(std::string(CUTROUTE_SHARED_DIR) + "/data/sop/" + name + ".sop");
  if (!inst) {
    state.SkipWithError(inst.error().message.c_str());
    return;
  }
  solve::SolveParams params;
  params.solver = solve::SolverKind::exact;
  params.threads = 1;
  params.time_limit_s = 60;
  solve::Solution s;
  for (auto _ : state) s = solve::solve(inst->problem, params);
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  state.counters["optimal"] = s.status == solve::SolveStatus::optimal ? 1 : 0;
  state.counters["cost"] = static_cast<double>(s.cost);
  state.counters["lower_bound"] = s.lower_bound ? static_cast<double>(*s.lower_bound) : 0.0;
  state.counters["max_rss_MB"] = static_cast<double>(ru.ru_maxrss) / 1024.0;
}
BENCHMARK_CAPTURE(BM_ExactIdeals_Sop, p43_4, "p43.4")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ExactIdeals_Sop, ry48p_4, "ry48p.4")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ExactIdeals_Sop, ft53_4, "ft53.4")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ExactIdeals_Sop, rbg109a, "rbg109a")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ExactIdeals_Sop, ft70_4, "ft70.4")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_ExactIdeals_Sop, esc25, "esc25")->Unit(benchmark::kSecond)->Iterations(1);

void BM_Heuristic_Gtsplib(benchmark::State& state, const char* name) {
  auto inst = io::read_instance(std::string(CUTROUTE_SHARED_DIR) + "/data/gtsplib/" + name + ".gtsp");
  if (!inst) {
    state.SkipWithError(inst.error().message.c_str());
    return;
  }
  solve::SolveParams params;
  params.solver = solve::SolverKind::heuristic;
  params.threads = 2;
  params.time_limit_s = 0;
  solve::Solution s;
  for (auto _ : state) s = solve::solve(inst->problem, params);
  state.counters["cost"] = static_cast<double>(s.cost);
  state.counters["iterations"] = static_cast<double>(s.stats.iterations);
}
BENCHMARK_CAPTURE(BM_Heuristic_Gtsplib, 40d198, "40d198")->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Heuristic_Gtsplib, 89pcb442, "89pcb442")->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Heuristic_Gtsplib, 132d657, "132d657")->Unit(benchmark::kMillisecond)->Iterations(1);
// Planar costs (EUC_2D above 3 000 nodes) with 100-node clusters: the batched prices of
// planar_rows.cpp (session 8: 31C3k.0 about 0.5 -> 0.2 s, 100C10k.0 about 2.0 -> 1.15 s of wall).
BENCHMARK_CAPTURE(BM_Heuristic_Gtsplib, 31C3k_0, "31C3k.0")->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Heuristic_Gtsplib, 100C10k_0, "100C10k.0")->Unit(benchmark::kMillisecond)->Iterations(1);

// A nest-like planar problem: `m` contours of 8 entry candidates each on a 3000 x 1500 mm sheet
// (rapid 0.25 s + 1 s/250 mm, cutting time as inner cost), an open path.
solve::Problem planar_nest(int m) {
  Rng rng(77);
  solve::PlanarCosts pc;
  pc.base = 0.25, pc.per_unit = 1.0 / 250, pc.scale = 1e6;
  const int k = 8;
  solve::ProblemBuilder b(m * k);
  std::vector<solve::Cost> inner;
  for (int c = 0; c < m; ++c) {
    const double cx = rng.uniform01() * 3000, cy = rng.uniform01() * 1500, r = 2 + rng.uniform01() * 10;
    std::vector<solve::NodeId> nodes;
    for (int j = 0; j < k; ++j) {
      const double a = 2 * std::numbers::pi * j / k;
      pc.in.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
      pc.out.push_back(pc.in.back());
      nodes.push_back(solve::NodeId(c * k + j));
      inner.push_back(static_cast<solve::Cost>((0.4 + 2 * std::numbers::pi * r / 50) * 1e6));
    }
    b.add_cluster(nodes);
  }
  b.set_planar_costs(std::move(pc));
  for (std::size_t v = 0; v < inner.size(); ++v) b.set_inner_cost(solve::NodeId(static_cast<int>(v)), inner[v]);
  b.set_kind(solve::RouteKind::open_path);
  return std::move(b.build()).value();
}

// The cheapest-entry bound (k-d tree, any size) against the cluster graph's assignment bound
// (O(n^2) prices, up to 1 500 clusters), on nests of m contours x 8 candidates.
void BM_Bound_Entries(benchmark::State& state) {
  const solve::Problem p = planar_nest(static_cast<int>(state.range(0)));
  std::optional<solve::Cost> b;
  for (auto _ : state) b = solve::entry_lower_bound(p);
  state.counters["bound"] = static_cast<double>(b.value_or(-1));
}
BENCHMARK(BM_Bound_Entries)->Arg(1000)->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond);
void BM_Bound_Assignment(benchmark::State& state) {
  const solve::Problem p = planar_nest(static_cast<int>(state.range(0)));
  std::optional<solve::Cost> b;
  for (auto _ : state) b = solve::route_lower_bound(p, StopToken{}, solve::kMaxCost, false);
  state.counters["bound"] = static_cast<double>(b.value_or(-1));
}
BENCHMARK(BM_Bound_Assignment)->Arg(1000)->Unit(benchmark::kMillisecond)->Iterations(1);

// A perforated plate: `holes` 10-mm holes on a 15-mm grid, 8 entry candidates each, inside one
// outer contour that comes last (every hole before it: sparse precedence on a long route). Solved
// with no time limit and the smallest work budget, the run is construction plus the first local
// search: both were O(m^2) with precedence (10 000 holes: 16.9 s of `optimize --time-limit 0`
// before session 41, 2.2 s after).
solve::Problem perforated_plate(int holes) {
  solve::PlanarCosts pc;
  pc.base = 0.25, pc.per_unit = 1.0 / 250, pc.scale = 1e6;
  const int k = 8, side = static_cast<int>(std::ceil(std::sqrt(holes)));
  solve::ProblemBuilder b((holes + 1) * k);
  auto add = [&](double cx, double cy, double r) {
    std::vector<solve::NodeId> nodes;
    for (int j = 0; j < k; ++j) {
      const double a = 2 * std::numbers::pi * j / k;
      pc.in.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
      pc.out.push_back(pc.in.back());
      nodes.push_back(solve::NodeId(static_cast<int>(pc.in.size()) - 1));
    }
    b.add_cluster(nodes);
  };
  for (int h = 0; h < holes; ++h) add(15.0 * (h % side), 15.0 * (h / side), 5);
  add(7.5 * side, 7.5 * side, 7.5 * side * std::numbers::sqrt2);
  b.set_planar_costs(std::move(pc));
  for (int h = 0; h < holes; ++h) b.add_precedence(solve::ClusterId(h), solve::ClusterId(holes));
  b.set_kind(solve::RouteKind::open_path);
  return std::move(b.build()).value();
}
void BM_Heuristic_PerforatedPlate(benchmark::State& state) {
  const solve::Problem p = perforated_plate(static_cast<int>(state.range(0)));
  solve::SolveParams params;
  params.solver = solve::SolverKind::heuristic;
  params.threads = 1;
  params.time_limit_s = 0;
  params.work_budget = 1e3;
  solve::Solution s;
  for (auto _ : state) s = solve::solve(p, params);
  state.counters["cost"] = static_cast<double>(s.cost);
}
BENCHMARK(BM_Heuristic_PerforatedPlate)->Arg(2000)->Arg(10000)->Arg(40000)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
