// Arc math on the bulge representation: centre, radius, sweep, points by sweep, and arc construction.
#pragma once

#include <cmath>

#include <cutroute/geometry/vec2.hpp>

namespace cutroute::geometry {

// Bulge convention (DXF): an arc from a to b with signed sweep θ (> 0 counter-clockwise) has
// bulge β = tan(θ/4), so |β| < 1 is a minor arc, |β| = 1 a half circle, |β| > 1 a major arc.
// With chord c = b - a and d = |c|:
//   sin(θ/2) = 2β/(1+β²), cos(θ/2) = (1-β²)/(1+β²)         (exact, no trigonometry)
//   radius    r = d (1+β²) / (4|β|)
//   centre    m + perp(c) (1-β²)/(4β),  m = (a+b)/2
//   length    d (1+β²) atan(β)/β                           (→ d as β → 0)
// A counter-clockwise arc (β > 0) bulges to the RIGHT of its chord a→b.
// Everything below is written in terms of the chord so that near-straight arcs (tiny β, huge
// radius) keep full precision; formulas through the centre lose ~r·1e-16 mm.

// Largest bulge magnitude honoured (Vertex comment); larger values and ±inf are clamped to it,
// NaN is read as 0, so that no NaN or inf ever leaves the arc math.
inline constexpr double kMaxBulge = 1e9;

inline double sanitize_bulge(double bulge) {
  if (std::isnan(bulge)) return 0.0;
  return bulge > kMaxBulge ? kMaxBulge : (bulge < -kMaxBulge ? -kMaxBulge : bulge);
}

// Unit vector u rotated by angle phi [rad].
inline Vec2 rotated(Vec2 u, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  return {u.x * c - u.y * s, u.x * s + u.y * c};
}

// Bulge of an arc with signed sweep [rad], |sweep| < 2π.
inline double bulge_from_sweep(double sweep) { return std::tan(sweep / 4.0); }

// Point of the arc a→b (bulge β, sweep θ = 4 atan β) reached after sweeping phi (same sign as θ,
// |phi| ≤ |θ|): a + rot(u, (φ-θ)/2) · d · sin(φ/2)/sin(θ/2). Exact at both ends up to rounding.
inline Vec2 arc_point_at_sweep(Vec2 a, Vec2 b, double bulge, double phi) {
  const Vec2 c = b - a;
  const double d = norm(c);
  if (!(d > 0.0)) return a;
  const double beta = sanitize_bulge(bulge);
  const double theta = 4.0 * std::atan(beta);
  const double sin_half_theta = 2.0 * beta / (1.0 + beta * beta);
  if (sin_half_theta == 0.0) return a + c * (theta == 0.0 ? 0.0 : phi / theta);
  const double len = d * std::sin(phi / 2.0) / sin_half_theta;
  return a + rotated(c / d, (phi - theta) / 2.0) * len;
}

// Power of p with respect to the circle through a and b with bulge β, multiplied by β so that
// it stays well conditioned as β → 0: < 0 inside the disk, 0 on the circle, > 0 outside
// (for β > 0; the sign flips with β, see arc_disk_side()).
//   power = (p-a)·(p-b) - 2k·cross(c, p-m),  k = (1-β²)/(4β)
inline double arc_scaled_power(Vec2 a, Vec2 b, double bulge, Vec2 p) {
  const Vec2 c = b - a;
  const Vec2 m = (a + b) * 0.5;
  return bulge * dot(p - a, p - b) - 0.5 * (1.0 - bulge * bulge) * cross(c, p - m);
}

// -1 inside the arc's full circle, 0 on it, +1 outside.
inline int arc_disk_side(Vec2 a, Vec2 b, double bulge, Vec2 p) {
  const double s = arc_scaled_power(a, b, bulge, p) * (bulge > 0 ? 1.0 : -1.0);
  return s < 0 ? -1 : (s > 0 ? 1 : 0);
}

// Is p on the arc's side of the chord line (where the arc bulges)? For a point on the arc's
// circle this is exactly "p lies on the arc" (minor and major arcs alike).
inline bool on_arc_side_of_chord(Vec2 a, Vec2 b, double bulge, Vec2 p) {
  const double s = cross(b - a, p - a);
  return bulge > 0 ? s <= 0 : s >= 0;
}

}  // namespace cutroute::geometry
