// Private building blocks of the optimizer: golden section, boundary bisection and the 1-D line search in log space.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <cutroute/core/tolerances.hpp>

namespace cutroute::machining::detail {

// Minimises fn over u in [a, b] by golden section until b − a <= width; returns the best u seen.
// With u = ln x the width is a relative width in x.
template <class Fn>
double golden_min(Fn&& fn, double a, double b, double width = tol::kGoldenSectionRel) {
  constexpr double kInvPhi = 0.6180339887498949;
  double c = b - kInvPhi * (b - a);
  double d = a + kInvPhi * (b - a);
  double fc = fn(c), fd = fn(d);
  double best_u = fc <= fd ? c : d;
  double best_f = std::min(fc, fd);
  while (b - a > width) {
    if (fc <= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - kInvPhi * (b - a);
      fc = fn(c);
      if (fc < best_f) best_f = fc, best_u = c;
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + kInvPhi * (b - a);
      fd = fn(d);
      if (fd < best_f) best_f = fd, best_u = d;
    }
  }
  return best_u;
}

// Boundary between u_bad (predicate false) and u_good (true), to |u_good − u_bad| <= width; returns a
// point where the predicate holds.
template <class Pred>
double bisect_boundary(Pred&& ok, double u_bad, double u_good, double width = tol::kBoundaryBisectRel) {
  for (int it = 0; it < 200 && std::abs(u_good - u_bad) > width; ++it) {
    const double mid = 0.5 * (u_bad + u_good);
    if (ok(mid))
      u_good = mid;
    else
      u_bad = mid;
  }
  return u_good;
}

// The cheapest point that meets every limit along one line of the search: `at(x)` evaluates the
// point at x of the free variable (vc at a fixed feed, or f at a fixed speed), `grid` samples x
// (log-spaced, ascending). Feasible runs of samples are bisected onto g <= 0 (not the slack, so
// the answer is strictly feasible) and searched by golden section in u = ln x, the ends kept when
// cheaper; near a corner of two active constraints the feasible stretch can be narrower than a
// grid cell, so without a feasible sample the largest violation (quasi-convex) is minimised around
// the least-violated one and the sliver kept when it reaches g <= 0. Returns u, or nullopt.
template <class At>
std::optional<double> cheapest_on_line(At&& at, const std::vector<double>& grid) {
  const auto ok_at = [&](double u) { return at(std::exp(u)).max_violation() <= 0.0; };
  const auto ct_at = [&](double u) { return at(std::exp(u)).cost.total; };
  const std::size_t n = grid.size();
  std::vector<char> ok(n);
  std::vector<double> viol(n);
  for (std::size_t i = 0; i < n; ++i) {
    viol[i] = at(grid[i]).max_violation();
    ok[i] = viol[i] <= tol::kConstraintSlackRel ? 1 : 0;
  }
  std::vector<std::array<double, 2>> intervals;
  for (std::size_t a = 0; a < n;) {
    if (!ok[a]) {
      ++a;
      continue;
    }
    std::size_t b = a;
    while (b + 1 < n && ok[b + 1]) ++b;
    double lo = std::log(grid[a]);
    double hi = std::log(grid[b]);
    if (a > 0) lo = bisect_boundary(ok_at, std::log(grid[a - 1]), lo);
    if (b + 1 < n) hi = bisect_boundary(ok_at, std::log(grid[b + 1]), hi);
    intervals.push_back({lo, hi});
    a = b + 1;
  }
  if (intervals.empty() && n >= 2) {
    const std::size_t k = static_cast<std::size_t>(std::min_element(viol.begin(), viol.end()) - viol.begin());
    const double ua = std::log(grid[k == 0 ? 0 : k - 1]);
    const double ub = std::log(grid[std::min(n - 1, k + 1)]);
    const auto worst = [&](double u) { return at(std::exp(u)).max_violation(); };
    const double u0 = golden_min(worst, ua, ub, tol::kBoundaryBisectRel);
    if (worst(u0) <= 0.0) {
      const double lo = u0 > ua && !ok_at(ua) ? bisect_boundary(ok_at, ua, u0) : ua;
      const double hi = u0 < ub && !ok_at(ub) ? bisect_boundary(ok_at, ub, u0) : ub;
      intervals.push_back({lo, hi});
    }
  }
  double best_ct = std::numeric_limits<double>::infinity(), best_u = 0.0;
  for (const auto& [lo, hi] : intervals) {
    double u = hi > lo ? golden_min(ct_at, lo, hi) : lo;
    double ct = ct_at(u);
    for (double e : {lo, hi}) {
      const double c = ct_at(e);
      if (c < ct) ct = c, u = e;
    }
    if (!at(std::exp(u)).feasible()) {  // keep the promise of feasibility
      u = ct_at(lo) <= ct_at(hi) ? lo : hi;
      ct = ct_at(u);
    }
    if (ct < best_ct) best_ct = ct, best_u = u;
  }
  if (best_ct == std::numeric_limits<double>::infinity()) return std::nullopt;
  return best_u;
}

}  // namespace cutroute::machining::detail
