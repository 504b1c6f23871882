// Machining optimizer timings: one optimize() on the default 241 × 241 grid with refinement (target
// < 0.2 s), the Fig. 5 search and the full cubature at one point.
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <benchmark/benchmark.h>

#include <cutroute/core/version.hpp>
#include <cutroute/machining/optimize.hpp>
#include <cutroute/machining/problem_json.hpp>

namespace {

using namespace cutroute::machining;

Problem load(const char* file) {
  const std::string path = std::string(cutroute::data_dir()) + "/machining/" + file;
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  auto r = read_problem_json(ss.str(), path);
  if (!r) throw std::runtime_error(cutroute::format(r.error()));
  return std::move(r).value();
}

void optimize_example(benchmark::State& state, const char* file) {
  const Problem p = load(file);
  for (auto _ : state) {
    OptimizeResult r = optimize(p);  // defaults: 241 × 241, refinement, valley, contours, cubature
    benchmark::DoNotOptimize(r);
    state.counters["evaluations"] = static_cast<double>(r.evaluations);
  }
  state.SetLabel(file);
}
BENCHMARK_CAPTURE(optimize_example, E1, "boring-E1-finish-roughness.json")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(optimize_example, E2, "boring-E2-cored-accuracy.json")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(optimize_example, E3, "boring-E3-rough-power.json")->Unit(benchmark::kMillisecond);

void BM_Fig5_241(benchmark::State& state) {
  const Problem p = load("boring-E2-cored-accuracy.json");
  for (auto _ : state) benchmark::DoNotOptimize(optimize_fig5(p, 241, 241));
}
BENCHMARK(BM_Fig5_241)->Unit(benchmark::kMillisecond);

void BM_CubatureAtOnePoint(benchmark::State& state) {
  const Problem p = load("boring-E2-cored-accuracy.json");
  for (auto _ : state) benchmark::DoNotOptimize(evaluate(p, 286.9, 0.1967, 0, AccuracyMethod::cubature));
}
BENCHMARK(BM_CubatureAtOnePoint)->Unit(benchmark::kMillisecond);

}  // namespace
