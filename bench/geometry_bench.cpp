// Chaining 100 000 shuffled, randomly reversed LINE segments, and a grid of parts drawn edge to edge; build_nest on ~2000 contours.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/geometry/chain.hpp>
#include <cutroute/geometry/shapes.hpp>
#include <cutroute/geometry/spatial_index.hpp>
#include <cutroute/model/nest.hpp>

namespace {

using namespace cutroute;
using geometry::Vec2;

// `polygons` star polygons of `edges` edges on a grid, as single LINE pieces, shuffled and
// half of them reversed (fixed seed).
std::vector<geometry::ChainPiece> shuffled_lines(int polygons, int edges) {
  Rng rng(12345);
  std::vector<geometry::ChainPiece> pieces;
  pieces.reserve(static_cast<std::size_t>(polygons) * static_cast<std::size_t>(edges));
  const int side = static_cast<int>(std::ceil(std::sqrt(polygons)));
  for (int p = 0; p < polygons; ++p) {
    const Vec2 c{20.0 * (p % side), 20.0 * (p / side)};
    std::vector<Vec2> pts;
    for (int i = 0; i < edges; ++i) {
      const double a = 2 * std::numbers::pi * i / edges, r = 6 + 3 * rng.uniform01();
      pts.push_back(c + Vec2{std::cos(a), std::sin(a)} * r);
    }
    for (int i = 0; i < edges; ++i) {
      geometry::ChainPiece piece{geometry::polygon({pts[i], pts[(i + 1) % edges]}, false), p * edges + i, 0};
      if (rng.chance(0.5)) piece.path = geometry::reversed(piece.path);
      pieces.push_back(std::move(piece));
    }
  }
  rng.shuffle(pieces.begin(), pieces.end());
  return pieces;
}

// Chains `pieces` in every iteration; an error unless `want` closed contours come out.
void chain_each_iteration(benchmark::State& state, const std::vector<geometry::ChainPiece>& pieces, std::size_t want) {
  std::size_t closed = 0;
  for (auto _ : state) {
    const auto r = geometry::chain_contours(pieces, 0.01);
    closed = r.closed.size();
    benchmark::DoNotOptimize(closed);
  }
  if (closed != want) state.SkipWithError("not every polygon closed");
  state.counters["pieces"] = static_cast<double>(pieces.size());
}

void BM_Chain100kShuffledLines(benchmark::State& state) { chain_each_iteration(state, shuffled_lines(1000, 100), 1000); }
BENCHMARK(BM_Chain100kShuffledLines)->Unit(benchmark::kMillisecond);

// 100 x 100 rectangles drawn edge to edge, each as its own four LINEs (every shared edge drawn
// twice: 40 000 pieces, 19 800 of them copies), shuffled and half reversed: all 10 000 close as
// faces (chain_faces.hpp).
void BM_ChainGridEdgeToEdge(benchmark::State& state) {
  Rng rng(777);
  std::vector<geometry::ChainPiece> pieces;
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) {
      const Vec2 c[4] = {{20.0 * i, 15.0 * j}, {20.0 * (i + 1), 15.0 * j}, {20.0 * (i + 1), 15.0 * (j + 1)}, {20.0 * i, 15.0 * (j + 1)}};
      for (int k = 0; k < 4; ++k) {
        geometry::ChainPiece piece{geometry::polygon({c[k], c[(k + 1) % 4]}, false), 4 * (100 * i + j) + k, 0};
        if (rng.chance(0.5)) piece.path = geometry::reversed(piece.path);
        pieces.push_back(std::move(piece));
      }
    }
  }
  rng.shuffle(pieces.begin(), pieces.end());
  chain_each_iteration(state, pieces, 10000);
}
BENCHMARK(BM_ChainGridEdgeToEdge)->Unit(benchmark::kMillisecond);

// ~2000 contours: 400 cells, each a part (circle or square) with a hole holding a part with a
// hole plus one more hole, on a sheet border on layer "Sheet".
std::vector<model::SourceContour> synthetic_nest() {
  Rng rng(7);
  std::vector<model::SourceContour> in;
  auto add = [&](geometry::Contour c, const char* layer) {
    model::SourceContour s;
    s.contour = std::move(c);
    s.layer = layer;
    in.push_back(std::move(s));
  };
  add(geometry::rectangle({-50, -50, 20 * 100.0, 20 * 100.0}), "Sheet");
  for (int cell = 0; cell < 400; ++cell) {
    const Vec2 c{100.0 * (cell % 20), 100.0 * (cell / 20)};
    const bool round = rng.chance(0.5);
    add(round ? geometry::circle(c, 45) : geometry::rectangle({c.x - 40, c.y - 40, c.x + 40, c.y + 40}), "0");
    add(geometry::circle(c, 30), "0");
    add(geometry::rectangle({c.x - 18, c.y - 18, c.x + 18, c.y + 18}), "0");
    add(geometry::circle(c, 10), "0");
    add(geometry::circle(c + Vec2{0, 36}, 3), "0");
  }
  return in;
}

void BM_BuildNest2000(benchmark::State& state) {
  const auto in = synthetic_nest();
  for (auto _ : state) {
    model::Nest nest = model::build_nest(in, model::NestOptions{});
    benchmark::DoNotOptimize(nest.max_depth);
    if (!nest.sheet || nest.parts.size() != 800) state.SkipWithError("unexpected nest");
  }
  state.counters["contours"] = static_cast<double>(in.size());
}
BENCHMARK(BM_BuildNest2000)->Unit(benchmark::kMillisecond);

// DRAAK-like: one outline of 6000 arc segments holding 1200 small contours (holes).
void BM_BuildNestBigOutline(benchmark::State& state) {
  std::vector<model::SourceContour> in;
  geometry::Contour outline;
  outline.closed = true;
  const int n = 6000;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n, r = 1000 + 20 * std::sin(40 * a);
    outline.vertices.push_back({{r * std::cos(a), r * std::sin(a)}, 0.01});
  }
  in.push_back({outline, "0", {}, {}, {}});
  for (int i = 0; i < 1200; ++i) {
    const Vec2 c{-600.0 + 35.0 * (i % 35), -600.0 + 35.0 * (i / 35)};
    in.push_back({geometry::circle(c, 10), "0", {}, {}, {}});
  }
  for (auto _ : state) {
    model::Nest nest = model::build_nest(in, model::NestOptions{});
    if (nest.parts.size() != 1 || nest.max_depth != 1) state.SkipWithError("unexpected nest");
    benchmark::DoNotOptimize(nest.max_depth);
  }
  state.counters["contours"] = static_cast<double>(in.size());
}
BENCHMARK(BM_BuildNestBigOutline)->Unit(benchmark::kMillisecond);

void BM_SpatialIndexBuildQuery(benchmark::State& state) {
  Rng rng(3);
  std::vector<geometry::Box> boxes;
  for (int i = 0; i < 100000; ++i) {
    const double x = rng.uniform01() * 10000, y = rng.uniform01() * 10000;
    boxes.push_back({x, y, x + 20, y + 20});
  }
  std::vector<std::uint32_t> hits;
  for (auto _ : state) {
    const geometry::StaticSpatialIndex index(boxes);
    std::size_t total = 0;
    for (const auto& b : boxes) {
      index.query(b, hits);
      total += hits.size();
    }
    benchmark::DoNotOptimize(total);
  }
}
BENCHMARK(BM_SpatialIndexBuildQuery)->Unit(benchmark::kMillisecond);

}  // namespace
