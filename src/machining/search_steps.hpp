// Private building blocks of the optimizer: golden section and boundary bisection in log space.
#pragma once

#include <cmath>
#include <limits>

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

}  // namespace cutroute::machining::detail
