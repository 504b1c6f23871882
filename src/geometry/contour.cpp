// Contour measures: segments, length, exact signed area with arcs, box, reversal, arc-length walk, flattening.
#include <cutroute/geometry/contour.hpp>

#include <algorithm>
#include <limits>
#include <cmath>
#include <numbers>

#include <cutroute/core/tolerances.hpp>
#include <cutroute/geometry/arc.hpp>
#include <cutroute/geometry/intersect.hpp>

namespace cutroute::geometry {

std::size_t segment_count(const Contour& c) {
  const std::size_t n = c.vertices.size();
  if (n == 0) return 0;
  return c.closed ? n : n - 1;
}

Segment segment(const Contour& c, std::size_t i) {
  const std::size_t n = c.vertices.size();
  const Vertex& v = c.vertices[i];
  return Segment{v.p, c.vertices[(i + 1) % n].p, v.bulge};
}

double length(const Contour& c) {
  double sum = 0.0;
  const std::size_t n = segment_count(c);
  for (std::size_t i = 0; i < n; ++i) sum += segment(c, i).length();
  return sum;
}

namespace {

// Signed area [mm²] between an arc and its chord, > 0 for counter-clockwise arcs:
// r²/2 (θ - sin θ) with r = d/(2 sin(θ/2)); the series keeps precision for tiny sweeps,
// where θ - sin θ cancels.
double arc_segment_area(const Segment& s) {
  if (!s.is_arc()) return 0.0;
  const double beta = sanitize_bulge(s.bulge);
  const double theta = 4.0 * std::atan(beta);
  const double d2 = norm2(s.b - s.a);
  const double sin_half = 2.0 * beta / (1.0 + beta * beta);
  const double r2 = d2 / (4.0 * sin_half * sin_half);
  double t_minus_sin = 0.0;
  if (std::abs(theta) < 1e-2) {
    const double t2 = theta * theta;
    t_minus_sin = theta * t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0 * (1.0 - t2 / 72.0)));
  } else {
    t_minus_sin = theta - std::sin(theta);
  }
  return 0.5 * r2 * t_minus_sin;
}

}  // namespace

double signed_area(const Contour& c) {
  if (!c.closed || c.vertices.empty()) return 0.0;
  // Shoelace relative to the first vertex: drawings far from the origin keep their precision.
  const Vec2 o = c.vertices.front().p;
  double twice = 0.0;
  double arcs = 0.0;
  const std::size_t n = c.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Segment s = segment(c, i);
    twice += cross(s.a - o, s.b - o);
    arcs += arc_segment_area(s);
  }
  return 0.5 * twice + arcs;
}

Orientation orientation(const Contour& c) {
  const double a = signed_area(c);
  // A contour thinner than the same-point tolerance everywhere has no direction.
  const double tiny = tol::kSamePointMm * std::max(length(c), tol::kSamePointMm);
  if (!(std::abs(a) > tiny)) return Orientation::degenerate;
  return a > 0 ? Orientation::ccw : Orientation::cw;
}

Box bounding_box(const Contour& c) {
  Box box;
  const std::size_t n = segment_count(c);
  if (n == 0) {
    for (const Vertex& v : c.vertices) box.add(v.p);
    return box;
  }
  for (std::size_t i = 0; i < n; ++i) box.add(segment(c, i).bounding_box());
  return box;
}

Contour reversed(const Contour& c) {
  Contour r;
  r.closed = c.closed;
  const std::size_t n = c.vertices.size();
  r.vertices.reserve(n);
  if (n == 0) return r;
  if (c.closed) {
    // Keep vertices[0] as the start: w_0 = v_0, w_j = v_{n-j}; segment j of the result is
    // segment n-1-j of the input, travelled backwards.
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t src = j == 0 ? 0 : n - j;
      r.vertices.push_back({c.vertices[src].p, -c.vertices[n - 1 - j].bulge});
    }
  } else {
    for (std::size_t j = 0; j < n; ++j) {
      const double bulge = j + 1 < n ? -c.vertices[n - 2 - j].bulge : 0.0;
      r.vertices.push_back({c.vertices[n - 1 - j].p, bulge});
    }
  }
  return r;
}

Vec2 point_at_length(const Contour& c, double s) {
  const std::size_t n = segment_count(c);
  if (n == 0) return c.vertices.empty() ? Vec2{} : c.vertices.front().p;
  const double total = length(c);
  if (!(total > 0.0) || std::isnan(s)) return c.vertices.front().p;
  if (c.closed) {
    s = std::fmod(s, total);
    if (s < 0) s += total;
  } else {
    s = std::clamp(s, 0.0, total);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Segment seg = segment(c, i);
    const double l = seg.length();
    if (s <= l || i + 1 == n) return l > 0 ? seg.point_at(s / l) : seg.a;
    s -= l;
  }
  return c.vertices.front().p;
}

ClosestPoint closest_point(const Contour& c, Vec2 p) {
  ClosestPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  const std::size_t n = segment_count(c);
  if (n == 0) {
    if (!c.vertices.empty()) {
      best.point = c.vertices.front().p;
      best.distance = geometry::distance(best.point, p);
    }
    return best;
  }
  double along = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Segment seg = segment(c, i);
    const SegmentClosest sc = closest_point(seg, p);
    if (sc.distance < best.distance) {
      best.point = sc.point;
      best.distance = sc.distance;
      best.segment = i;
      best.length_along = along + sc.length_along;
    }
    along += seg.length();
  }
  if (std::isinf(best.distance)) {  // only non-finite input gets here
    best.point = c.vertices.front().p;
    best.distance = geometry::distance(best.point, p);
  }
  return best;
}

bool intersects(const Contour& a, const Contour& b, double tol_mm) {
  return count_close_segment_pairs(a, b, tol_mm, 1) > 0;
}

std::vector<Vec2> flatten(const Contour& c, double chord_tol_mm) {
  if (!(chord_tol_mm > 0.0) || !std::isfinite(chord_tol_mm)) chord_tol_mm = tol::kArcChordMm;
  // A cap per arc so that an absurd tolerance cannot exhaust memory; 2^16 chords keep a 1 m
  // radius half circle within 1.2e-6 mm.
  constexpr double kMaxChordsPerArc = 65536.0;
  std::vector<Vec2> out;
  const std::size_t n = segment_count(c);
  out.reserve(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    const Segment s = segment(c, i);
    out.push_back(s.a);
    if (!s.is_arc()) continue;
    const double r = s.radius();
    const double theta = s.sweep();
    if (r <= chord_tol_mm) {
      // A chord of any sweep stays within r of the arc; one midpoint keeps the shape.
      out.push_back(s.point_at(0.5));
      continue;
    }
    // Sagitta of a chord spanning sweep α is r (1 - cos(α/2)) <= tol  ⇔  α <= 2 acos(1 - tol/r).
    const double max_step = 2.0 * std::acos(1.0 - chord_tol_mm / r);
    double pieces = std::ceil(std::abs(theta) / max_step);
    if (!(pieces >= 1.0)) pieces = 1.0;
    pieces = std::min(pieces, kMaxChordsPerArc);
    const int k = static_cast<int>(pieces);
    const double beta = sanitize_bulge(s.bulge);
    for (int j = 1; j < k; ++j) out.push_back(arc_point_at_sweep(s.a, s.b, beta, theta * j / k));
  }
  if (!c.closed && !c.vertices.empty()) out.push_back(c.vertices.back().p);
  return out;
}

double narrowest_width(const Contour& c, double chord_tol_mm) {
  const std::vector<Vec2> pts = flatten(c, chord_tol_mm);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec2 e = pts[(i + 1) % pts.size()] - pts[i];
    const double len = norm(e);
    if (len <= 0.0) continue;
    const Vec2 n = perp(e) / len;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec2 p : pts) lo = std::min(lo, dot(p, n)), hi = std::max(hi, dot(p, n));
    best = std::min(best, hi - lo);
  }
  // The chords lie inside their arcs, by up to the tolerance on either side: the arcs' width is
  // that much more at most, and the result must not be less than the contour's least width.
  const bool arcs = std::any_of(c.vertices.begin(), c.vertices.end(), [](const Vertex& v) { return v.bulge != 0.0; });
  return arcs ? best + 2 * chord_tol_mm : best;
}

}  // namespace cutroute::geometry
