// Batches of planar arc costs: one node against every node of a cluster.
//
// Cluster optimisation, its windows and insertion spend nearly all their time (90 % on 100C10k.0,
// 31C3k.0) pricing one node against a whole cluster. Through Problem::step each arc is a dispatch,
// a scalar sqrt with its errno branch and a rounding; here the points sit in cluster-blocked arrays
// and the distances are computed in one loop that GCC vectorises (this file is built with
// -fno-math-errno -fno-trapping-math, see sources.cmake), then rounded exactly as
// Problem::planar_arc does, so the costs, and therefore the routes, are the same to the last tick.
#include <algorithm>
#include <cmath>
#include <vector>

#include <cutroute/solve/heuristic.hpp>

#include "planar_rows.hpp"
#include "tour.hpp"

namespace cutroute::solve::detail {

namespace {

constexpr std::size_t kChunk = 64;

// out[j] = the planar price of the arc between (qx, qy) and (xs[j], ys[j]), rounded as
// Problem::planar_arc rounds it, plus add[j] (or nothing when add is null) plus add_all.
// Compiled into each kernel below with that kernel's instruction set. Subtraction,
// multiplication, addition, sqrt and min are correctly rounded lane by lane at any width and no
// FMA is formed (-ffp-contract=off), so every kernel gives the same bits.
[[gnu::always_inline]] inline void price_row_body(const PlanarCosts& pc, double qx, double qy, const double* xs, const double* ys,
                                                  std::size_t k, const Cost* add, Cost add_all, Cost* out) {
  const double base = pc.base, per = pc.per_unit, scale = pc.scale;
  constexpr double kCap = static_cast<double>(kMaxCost);
  double buf[kChunk];
  for (std::size_t j0 = 0; j0 < k; j0 += kChunk) {
    const std::size_t n = std::min(kChunk, k - j0);
    for (std::size_t j = 0; j < n; ++j) {
      const double dx = xs[j0 + j] - qx, dy = ys[j0 + j] - qy;
      const double t = (base + per * std::sqrt(dx * dx + dy * dy)) * scale;
      buf[j] = std::min(t, kCap) + 0.5;
    }
    for (std::size_t j = 0; j < n; ++j) out[j0 + j] = static_cast<Cost>(buf[j]) + add_all + (add ? add[j0 + j] : 0);
  }
}

// Three builds of the same loop: baseline x86-64 (SSE2, 2 lanes), x86-64-v3 (AVX2, 4 lanes) and
// x86-64-v4 (AVX-512, 8 lanes, and a vector conversion to int64 where AVX2 converts lane by lane).
// 100C10k.0 at a fixed budget: 0.90 -> 0.63 s (v3) -> 0.53 s (v4) of CPU, the same route
// (docs/solver-bench-2026-11-28-session29.md). Written out rather than as target_clones so that a
// test can run each build the processor supports, not only the one the loader picks.
void price_row_baseline(const PlanarCosts& pc, double qx, double qy, const double* xs, const double* ys, std::size_t k,
                        const Cost* add, Cost add_all, Cost* out) {
  price_row_body(pc, qx, qy, xs, ys, k, add, add_all, out);
}
[[gnu::target("arch=x86-64-v3")]] void price_row_v3(const PlanarCosts& pc, double qx, double qy, const double* xs, const double* ys,
                                                     std::size_t k, const Cost* add, Cost add_all, Cost* out) {
  price_row_body(pc, qx, qy, xs, ys, k, add, add_all, out);
}
[[gnu::target("arch=x86-64-v4")]] void price_row_v4(const PlanarCosts& pc, double qx, double qy, const double* xs, const double* ys,
                                                     std::size_t k, const Cost* add, Cost add_all, Cost* out) {
  price_row_body(pc, qx, qy, xs, ys, k, add, add_all, out);
}

using PriceRow = void (*)(const PlanarCosts&, double, double, const double*, const double*, std::size_t, const Cost*, Cost, Cost*);

PriceRow kernel(PriceLevel level) {
  switch (level) {
    case PriceLevel::x86_64_v4: return price_row_v4;
    case PriceLevel::x86_64_v3: return price_row_v3;
    case PriceLevel::baseline: break;
  }
  return price_row_baseline;
}

// The widest build this processor runs, chosen at the first call (a function-local static, so
// that no other file's static initialiser can find it unset).
PriceRow widest() {
  static const PriceRow f = [] {
    if (solve::price_level_supported(PriceLevel::x86_64_v4)) return kernel(PriceLevel::x86_64_v4);
    if (solve::price_level_supported(PriceLevel::x86_64_v3)) return kernel(PriceLevel::x86_64_v3);
    return kernel(PriceLevel::baseline);
  }();
  return f;
}

}  // namespace

void planar_row(const PlanarCosts& pc, PlanarPoint from, const double* xs, const double* ys, std::size_t k, Cost* out) {
  widest()(pc, from.x, from.y, xs, ys, k, nullptr, 0, out);
}

void Ops::planar_into(NodeId b, ClusterId a, Cost* out) const {
  const PlanarCosts& pc = *p_.planar();
  const PlanarPoint q = pc.in[b.index()];
  const std::size_t s = blk_off_[a.index()], k = blk_off_[a.index() + 1] - s;
  // planar_arc(from, to) takes in[to] - out[from]; squaring makes the operand order irrelevant,
  // and IEEE subtraction is exact under negation, so x - q here gives the same bits.
  widest()(pc, q.x, q.y, pox_.data() + s, poy_.data() + s, k, nullptr, p_.inner_cost(b), out);
}

void Ops::planar_from(NodeId u, ClusterId c, Cost* out) const {
  const PlanarCosts& pc = *p_.planar();
  const PlanarPoint q = pc.out[u.index()];
  const std::size_t s = blk_off_[c.index()], k = blk_off_[c.index() + 1] - s;
  widest()(pc, q.x, q.y, pix_.data() + s, piy_.data() + s, k, pinner_.empty() ? nullptr : pinner_.data() + s, 0, out);
}

}  // namespace cutroute::solve::detail

namespace cutroute::solve {

bool price_level_supported(PriceLevel level) {
  __builtin_cpu_init();
  switch (level) {
    case PriceLevel::x86_64_v4: return __builtin_cpu_supports("x86-64-v4") != 0;
    case PriceLevel::x86_64_v3: return __builtin_cpu_supports("x86-64-v3") != 0;
    case PriceLevel::baseline: break;
  }
  return true;
}

std::vector<Cost> planar_prices(const Problem& p, PriceLevel level, NodeId from, std::span<const NodeId> to) {
  const PlanarCosts& pc = *p.planar();
  std::vector<double> xs, ys;
  std::vector<Cost> inner, out(to.size());
  for (NodeId v : to) xs.push_back(pc.in[v.index()].x), ys.push_back(pc.in[v.index()].y), inner.push_back(p.inner_cost(v));
  const PlanarPoint q = pc.out[from.index()];
  detail::kernel(level)(pc, q.x, q.y, xs.data(), ys.data(), to.size(), inner.data(), 0, out.data());
  return out;
}

}  // namespace cutroute::solve
