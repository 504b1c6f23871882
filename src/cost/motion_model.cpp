#include <cutroute/cost/motion_model.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cutroute::cost {

namespace {

// Time to cover `len` starting at v0 and ending at v1 with peak speed at most vmax and
// acceleration a, where v0, v1 are reachable from each other (|v1^2 - v0^2| <= 2 a len).
double trapezoid_time(double len, double v0, double v1, double vmax, double a) {
  if (len <= 0.0) return 0.0;
  // Peak speed of the triangle profile; when it exceeds vmax there is a cruise phase.
  const double vp2 = a * len + 0.5 * (v0 * v0 + v1 * v1);
  const double vp = std::min(std::sqrt(vp2), vmax);
  const double d_acc = (vp * vp - v0 * v0) / (2.0 * a);
  const double d_dec = (vp * vp - v1 * v1) / (2.0 * a);
  const double cruise = std::max(0.0, len - d_acc - d_dec);
  return (vp - v0) / a + (vp - v1) / a + cruise / vp;
}

}  // namespace

Result<MotionTime> time_moves(const std::vector<MotionMove>& moves, const MotionParams& p) {
  if (!(p.accel_mm_s2 > 0.0) || !std::isfinite(p.accel_mm_s2))
    return make_error("motion: acceleration must be > 0");
  if (!(p.junction_deviation_mm >= 0.0)) return make_error("motion: junction deviation must be >= 0");
  if (!(p.block_time_s >= 0.0)) return make_error("motion: block time must be >= 0");
  const double a = p.accel_mm_s2;
  const std::size_t n = moves.size();
  std::vector<double> vmax(n);
  std::vector<double> entry(n + 1, 0.0);  // entry[i]: speed at the start of move i; entry[n] = 0 (stop)
  for (std::size_t i = 0; i < n; ++i) {
    const auto& m = moves[i];
    if (!(m.length_mm >= 0.0) || !(m.feed_mm_s > 0.0))
      return make_error("motion: move lengths must be >= 0 and feeds > 0");
    vmax[i] = m.feed_mm_s;
    if (m.radius_mm > 0.0) vmax[i] = std::min(vmax[i], std::sqrt(a * m.radius_mm));
  }
  // Junction limits.
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 || moves[i].from_rest) {
      entry[i] = 0.0;
      continue;
    }
    const double s = std::sin(std::clamp(moves[i].turn_rad, 0.0, std::numbers::pi) / 2.0);
    double vj = std::min(vmax[i - 1], vmax[i]);
    if (s > 1e-12) {
      vj = s >= 1.0 - 1e-12 ? 0.0 : std::min(vj, std::sqrt(a * p.junction_deviation_mm * s / (1.0 - s)));
    }
    entry[i] = vj;
  }
  // Backward pass: every move must be able to brake to the next entry speed.
  for (std::size_t i = n; i-- > 0;) {
    entry[i] = std::min(entry[i], std::sqrt(entry[i + 1] * entry[i + 1] + 2.0 * a * moves[i].length_mm));
  }
  // Forward pass: every move must be able to accelerate to its exit speed.
  for (std::size_t i = 0; i < n; ++i) {
    entry[i + 1] = std::min(entry[i + 1], std::sqrt(entry[i] * entry[i] + 2.0 * a * moves[i].length_mm));
  }
  MotionTime t;
  for (std::size_t i = 0; i < n; ++i) {
    double dt = trapezoid_time(moves[i].length_mm, entry[i], entry[i + 1], vmax[i], a);
    if (dt < p.block_time_s) {
      dt = p.block_time_s;
      ++t.block_limited;
    }
    t.time_s += dt;
    t.length_mm += moves[i].length_mm;
  }
  t.mean_speed_mm_s = t.time_s > 0.0 ? t.length_mm / t.time_s : 0.0;
  return t;
}

}  // namespace cutroute::cost
