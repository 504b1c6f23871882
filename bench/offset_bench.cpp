// Google Benchmark of the kerf offset: time per contour against its piece count, for a smooth
// outline (joins only) and a wavy one whose raw offset crosses itself (pruning at work).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>

#include <cutroute/geometry/offset.hpp>

namespace {

using cutroute::geometry::Contour;

// A circle of radius 100 mm as `n` vertices, every third segment an arc (bulge 0.1), radii
// jittered by up to `wave` mm with a fixed linear congruential sequence (deterministic).
Contour wavy_circle(int n, double wave) {
  Contour c;
  c.closed = true;
  std::uint64_t s = 1;
  for (int i = 0; i < n; ++i) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u = static_cast<double>(s >> 11) / 9007199254740992.0;
    const double ang = 2 * 3.14159265358979323846 * i / n;
    const double r = 100 + wave * u;
    c.vertices.push_back({{r * std::cos(ang), r * std::sin(ang)}, i % 3 == 0 ? 0.1 : 0.0});
  }
  return c;
}

void offset_smooth(benchmark::State& state) {
  const Contour c = wavy_circle(static_cast<int>(state.range(0)), 0.0);
  for (auto _ : state) benchmark::DoNotOptimize(cutroute::geometry::offset_contour(c, -0.1));
  state.SetComplexityN(state.range(0));
}

void offset_wavy(benchmark::State& state) {
  const Contour c = wavy_circle(static_cast<int>(state.range(0)), 0.5);
  for (auto _ : state) benchmark::DoNotOptimize(cutroute::geometry::offset_contour(c, 1.0));
  state.SetComplexityN(state.range(0));
}

}  // namespace

BENCHMARK(offset_smooth)->RangeMultiplier(4)->Range(16, 4096)->Unit(benchmark::kMicrosecond)->Complexity();
BENCHMARK(offset_wavy)->RangeMultiplier(4)->Range(16, 4096)->Unit(benchmark::kMicrosecond)->Complexity();
