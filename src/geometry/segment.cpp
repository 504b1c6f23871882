// Segment: line or bulge arc as a value — length, centre, points, tangents, exact box.
#include <cutroute/geometry/arc.hpp>
#include <cutroute/geometry/contour.hpp>
#include <cutroute/core/tolerances.hpp>

#include "geometry/arc_detail.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace cutroute::geometry {

bool Segment::is_arc() const {
  const double beta = sanitize_bulge(bulge);
  return std::abs(beta) > tol::kStraightBulge && a != b;
}

double Segment::sweep() const { return is_arc() ? 4.0 * std::atan(sanitize_bulge(bulge)) : 0.0; }

double Segment::length() const {
  const double d = norm(b - a);
  if (!is_arc()) return d;
  const double beta = sanitize_bulge(bulge);
  // d (1+β²) atan(β)/β: well conditioned for small β, and for huge β about d·β·π/4.
  return d * (1.0 + beta * beta) * (std::atan(beta) / beta);
}

Vec2 Segment::center() const {
  const Vec2 m = (a + b) * 0.5;
  if (!is_arc()) return m;
  const double beta = sanitize_bulge(bulge);
  return m + perp(b - a) * ((1.0 - beta * beta) / (4.0 * beta));
}

double Segment::radius() const {
  if (!is_arc()) return a == b ? 0.0 : std::numeric_limits<double>::infinity();
  const double beta = sanitize_bulge(bulge);
  return norm(b - a) * (1.0 + beta * beta) / (4.0 * std::abs(beta));
}

Vec2 Segment::point_at(double t) const {
  if (!(t > 0.0)) return a;  // also NaN
  if (t >= 1.0) return b;
  if (!is_arc()) return a + (b - a) * t;
  const double beta = sanitize_bulge(bulge);
  return arc_point_at_sweep(a, b, beta, 4.0 * std::atan(beta) * t);
}

Vec2 Segment::tangent_at(double t) const {
  const Vec2 u = normalized(b - a);
  if (!is_arc()) return u;
  const double tt = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
  const double theta = sweep();
  return rotated(u, theta * tt - theta / 2.0);
}

namespace detail {

double arc_start_radial_angle(const Segment& s) {
  const Vec2 c = s.b - s.a;
  const double theta = s.sweep();
  const double half_pi = std::numbers::pi / 2.0;
  return std::atan2(c.y, c.x) - theta / 2.0 - (theta > 0 ? half_pi : -half_pi);
}

double sweep_to_angle(const Segment& s, double angle) {
  const double two_pi = 2.0 * std::numbers::pi;
  const double theta = s.sweep();
  const double start = arc_start_radial_angle(s);
  double phi = theta > 0 ? angle - start : start - angle;
  phi = std::fmod(phi, two_pi);
  if (phi < 0) phi += two_pi;
  if (!(phi < two_pi)) phi = 0.0;  // rounding or NaN
  return theta > 0 ? phi : -phi;
}

bool nearly_straight(const Segment& s) {
  return !s.is_arc() || norm(s.b - s.a) * std::abs(sanitize_bulge(s.bulge)) / 2.0 <= tol::kCollinearMm;
}

Box coarse_box(const Segment& s) {
  Box box;
  box.add(s.a);
  box.add(s.b);
  if (!s.is_arc()) return box;
  const double beta = std::abs(sanitize_bulge(s.bulge));
  if (beta <= 1.0) return box.inflated(norm(s.b - s.a) * beta / 2.0);
  const Vec2 c = s.center();
  const double r = s.radius();
  box.add(Box{c.x - r, c.y - r, c.x + r, c.y + r});
  return box;
}

}  // namespace detail

Box Segment::bounding_box() const {
  Box box;
  box.add(a);
  box.add(b);
  if (!is_arc()) return box;
  // Without trigonometry (the angle form took 13 atan calls per arc, 10-15 % of building the cut
  // job of a plate of holes): the chord splits the circle in two, and a quadrant extreme c ± r e
  // lies on the arc iff it is on the chord's side of the arc's midpoint, m - perp(b - a) β/2
  // (the sagitta |b - a| |β| / 2 from the chord's middle). Extremes on the chord line are the end
  // points, already in the box.
  const double beta = sanitize_bulge(bulge);
  const Vec2 c = center(), chord = b - a;
  const double r = radius();
  const Vec2 mid = (a + b) * 0.5 - perp(chord) * (beta / 2.0);
  const double side = cross(chord, mid - a);
  for (const Vec2 e : {Vec2{r, 0}, Vec2{0, r}, Vec2{-r, 0}, Vec2{0, -r}}) {
    const Vec2 p = c + e;
    const double s = cross(chord, p - a);
    if ((s > 0 && side > 0) || (s < 0 && side < 0)) box.add(p);
  }
  return box;
}

}  // namespace cutroute::geometry
