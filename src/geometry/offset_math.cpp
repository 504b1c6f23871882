// Line/arc primitives of the kerf offset (see offset_math.hpp).
#include "geometry/offset_math.hpp"

#include <algorithm>
#include <cmath>

#include <cutroute/core/tolerances.hpp>

namespace cutroute::geometry::offset_detail {

namespace {

double sign_of(double v) { return v < 0 ? -1.0 : 1.0; }

// Is q (on p's line or circle) within tol_mm of the piece, measured along it?
bool on_piece(const Piece& p, Vec2 q, double tol_mm) {
  const double len = length(p);
  if (!(len > 0)) return distance(p.a, q) <= tol_mm;
  const double t = param_of(p, q);
  return t * len >= -tol_mm && (t - 1.0) * len <= tol_mm;
}

// Pieces on the same line or circle: their common parts end at end points of one of them.
void add_overlap_ends(const Piece& p, const Piece& q, double tol_mm, Hits& hits) {
  for (Vec2 e : {p.a, p.b})
    if (on_piece(q, e, tol_mm)) hits.add(e, tol_mm);
  for (Vec2 e : {q.a, q.b})
    if (on_piece(p, e, tol_mm)) hits.add(e, tol_mm);
}

void keep_if_on_both(const Piece& p, const Piece& q, Vec2 x, double tol_mm, Hits& hits) {
  if (is_finite(x) && on_piece(p, x, tol_mm) && on_piece(q, x, tol_mm)) hits.add(x, tol_mm);
}

Hits intersect_lines(const Piece& p, const Piece& q, double tol_mm) {
  Hits hits;
  const Vec2 d1 = p.b - p.a;
  const Vec2 d2 = q.b - q.a;
  const double den = cross(d1, d2);
  const double n1 = norm(d1);
  const double n2 = norm(d2);
  if (!(n1 > 0) || !(n2 > 0)) return hits;
  // Parallel within 1e-12 rad: either on the same line (overlap) or disjoint.
  if (std::abs(den) <= 1e-12 * n1 * n2) {
    const double off_a = std::abs(cross(d1, q.a - p.a)) / n1;
    const double off_b = std::abs(cross(d1, q.b - p.a)) / n1;
    if (off_a <= tol_mm && off_b <= tol_mm) add_overlap_ends(p, q, tol_mm, hits);
    return hits;
  }
  const double t = cross(q.a - p.a, d2) / den;
  keep_if_on_both(p, q, p.a + d1 * t, tol_mm, hits);
  return hits;
}

Hits intersect_line_arc(const Piece& line, const Piece& arc, double tol_mm) {
  Hits hits;
  const Vec2 d = line.b - line.a;
  const double n = norm(d);
  if (!(n > 0)) return hits;
  const Vec2 u = d / n;
  const Vec2 foot = line.a + u * dot(arc.c - line.a, u);
  const double h = distance(foot, arc.c);
  if (h > arc.r + tol_mm) return hits;
  const double half2 = (arc.r - h) * (arc.r + h);
  if (half2 <= tol_mm * tol_mm) {
    // Tangent (within tol): one point, moved onto the circle.
    const Vec2 x = h > 0 ? arc.c + (foot - arc.c) * (arc.r / h) : foot;
    keep_if_on_both(line, arc, x, tol_mm, hits);
    return hits;
  }
  const double half = std::sqrt(half2);
  keep_if_on_both(line, arc, foot - u * half, tol_mm, hits);
  keep_if_on_both(line, arc, foot + u * half, tol_mm, hits);
  return hits;
}

Hits intersect_arcs(const Piece& p, const Piece& q, double tol_mm) {
  Hits hits;
  const Vec2 cc = q.c - p.c;
  const double dc = norm(cc);
  if (dc <= tol_mm) {
    if (std::abs(p.r - q.r) <= tol_mm) add_overlap_ends(p, q, tol_mm, hits);
    return hits;
  }
  if (dc > p.r + q.r + tol_mm || dc < std::abs(p.r - q.r) - tol_mm) return hits;
  const double along = (dc * dc + p.r * p.r - q.r * q.r) / (2.0 * dc);
  const double h2 = p.r * p.r - along * along;
  const Vec2 u = cc / dc;
  const Vec2 base = p.c + u * along;
  if (h2 <= tol_mm * tol_mm) {
    keep_if_on_both(p, q, p.c + u * (p.r * sign_of(along)), tol_mm, hits);
    return hits;
  }
  const double h = std::sqrt(h2);
  keep_if_on_both(p, q, base - perp(u) * h, tol_mm, hits);
  keep_if_on_both(p, q, base + perp(u) * h, tol_mm, hits);
  return hits;
}

}  // namespace

double Piece::bulge() const { return std::tan(sweep / 4.0); }

Piece make_line(Vec2 a, Vec2 b) { return Piece{a, b, 0.0, {}, 0.0}; }

Piece make_arc(Vec2 c, double r, Vec2 a, Vec2 b, double sweep) { return Piece{a, b, sweep, c, r}; }

Piece make_piece(Vec2 a, Vec2 b, double bulge) {
  bulge = std::clamp(bulge, -kMaxBulge, kMaxBulge);
  const Vec2 chord = b - a;
  const double len = norm(chord);
  if (std::abs(bulge) < tol::kStraightBulge || !(len > 0)) return make_line(a, b);
  // The centre lies on the chord's bisector, at chord/2 * cot(sweep/2) = chord (1 - k²) / (4k)
  // to the left of the chord for k = bulge; the radius is chord (1 + k²) / (4|k|).
  const Vec2 c = (a + b) / 2.0 + perp(chord) * ((1.0 - bulge * bulge) / (4.0 * bulge));
  const double r = len * (1.0 + bulge * bulge) / (4.0 * std::abs(bulge));
  return make_arc(c, r, a, b, 4.0 * std::atan(bulge));
}

double length(const Piece& p) { return p.is_arc() ? p.r * std::abs(p.sweep) : distance(p.a, p.b); }

Vec2 point_at(const Piece& p, double t) {
  if (t == 0.0) return p.a;
  if (t == 1.0) return p.b;
  if (!p.is_arc()) return p.a + (p.b - p.a) * t;
  const double start = std::atan2(p.a.y - p.c.y, p.a.x - p.c.x);
  const double ang = start + p.sweep * t;
  return p.c + Vec2{std::cos(ang), std::sin(ang)} * p.r;
}

Vec2 start_tangent(const Piece& p) {
  if (!p.is_arc()) return normalized(p.b - p.a);
  return perp(normalized(p.a - p.c)) * sign_of(p.sweep);
}

Vec2 end_tangent(const Piece& p) {
  if (!p.is_arc()) return normalized(p.b - p.a);
  return perp(normalized(p.b - p.c)) * sign_of(p.sweep);
}

double param_of(const Piece& p, Vec2 q) {
  if (!p.is_arc()) {
    const Vec2 d = p.b - p.a;
    const double n2 = norm2(d);
    return n2 > 0 ? dot(q - p.a, d) / n2 : 0.0;
  }
  const Vec2 u = p.a - p.c;
  const Vec2 v = q - p.c;
  double ang = std::atan2(cross(u, v), dot(u, v));  // (-π, π], counter-clockwise from a
  if (p.sweep < 0) ang = -ang;
  if (ang < 0) ang += kTwoPi;  // [0, 2π) in the direction of travel
  const double s = std::abs(p.sweep);
  // Beyond the end: attribute the point to the nearer end, in angle.
  if (ang > s + (kTwoPi - s) / 2.0) ang -= kTwoPi;
  return ang / s;
}

Piece sub_piece(const Piece& p, double t0, double t1, Vec2 q0, Vec2 q1) {
  if (!p.is_arc()) return make_line(q0, q1);
  return make_arc(p.c, p.r, q0, q1, p.sweep * (t1 - t0));
}

double distance_to(const Piece& p, Vec2 q) {
  if (!p.is_arc()) {
    const double t = std::clamp(param_of(p, q), 0.0, 1.0);
    return distance(q, p.a + (p.b - p.a) * t);
  }
  const double dc = distance(q, p.c);
  if (!(dc > 0)) return p.r;
  const double t = param_of(p, q);
  if (t >= 0.0 && t <= 1.0) return std::abs(dc - p.r);
  return std::min(distance(q, p.a), distance(q, p.b));
}

Box box_of(const Piece& p) {
  Box box;
  box.add(p.a);
  box.add(p.b);
  if (p.is_arc()) {
    for (Vec2 e : {Vec2{1, 0}, Vec2{0, 1}, Vec2{-1, 0}, Vec2{0, -1}}) {
      const Vec2 x = p.c + e * p.r;
      const double t = param_of(p, x);
      if (t >= 0.0 && t <= 1.0) box.add(x);
    }
  }
  return box;
}

double area_term(const Piece& p) {
  double a = 0.5 * cross(p.a, p.b);
  if (p.is_arc()) {
    const double s = std::abs(p.sweep);
    a += sign_of(p.sweep) * 0.5 * p.r * p.r * (s - std::sin(s));
  }
  return a;
}

void Hits::add(Vec2 p, double tol_mm) {
  for (std::size_t i = 0; i < count; ++i)
    if (distance(points[i], p) <= tol_mm) return;
  if (count < points.size()) points[count++] = p;
}

Hits intersect(const Piece& p, const Piece& q, double tol_mm) {
  if (!p.is_arc() && !q.is_arc()) return intersect_lines(p, q, tol_mm);
  if (!p.is_arc()) return intersect_line_arc(p, q, tol_mm);
  if (!q.is_arc()) return intersect_line_arc(q, p, tol_mm);
  return intersect_arcs(p, q, tol_mm);
}

}  // namespace cutroute::geometry::offset_detail
