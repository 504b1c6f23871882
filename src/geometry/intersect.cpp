// Segment intersections and distances for every pair of kinds (line/line, line/arc, arc/arc).
#include <cutroute/geometry/intersect.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include <cutroute/geometry/arc.hpp>

#include "geometry/arc_detail.hpp"

namespace cutroute::geometry {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Circle {
  Vec2 c;
  double r = 0.0;
};

Circle circle_of(const Segment& s) { return {s.center(), s.radius()}; }

// Is q (a point on s's circle, or on s's line) within s? Lines: projection inside [0,1];
// arcs: on the arc side of the chord.
bool on_segment_extent(const Segment& s, Vec2 q, bool as_line) {
  if (as_line) {
    const Vec2 d = s.b - s.a;
    const double l2 = norm2(d);
    if (!(l2 > 0.0)) return q == s.a;
    const double t = dot(q - s.a, d) / l2;
    return t >= 0.0 && t <= 1.0;
  }
  return on_arc_side_of_chord(s.a, s.b, s.bulge, q);
}

// Exact common points of two segments (no tolerance), overlaps excluded (handled separately).
struct Crossings {
  int count = 0;
  Vec2 p[2];
  void add(Vec2 q) {
    if (count < 2) p[count++] = q;
  }
};

Crossings line_line(const Segment& s, const Segment& t) {
  Crossings out;
  const Vec2 d1 = s.b - s.a, d2 = t.b - t.a;
  const double denom = cross(d1, d2);
  // Parallel (or degenerate) lines meet only in an overlap, which is handled elsewhere.
  if (!(std::abs(denom) > 1e-14 * norm(d1) * norm(d2))) return out;
  const Vec2 w = t.a - s.a;
  const double ts = cross(w, d2) / denom;
  const double tt = cross(w, d1) / denom;
  if (ts >= 0.0 && ts <= 1.0 && tt >= 0.0 && tt <= 1.0) out.add(s.a + d1 * ts);
  return out;
}

// Line s against the circle of arc t; points kept when on both.
Crossings line_arc(const Segment& s, const Segment& t) {
  Crossings out;
  const Vec2 d = s.b - s.a;
  const double l2 = norm2(d);
  if (!(l2 > 0.0)) return out;
  const Circle ci = circle_of(t);
  const double tf = dot(ci.c - s.a, d) / l2;
  const Vec2 foot = s.a + d * tf;
  const double h = distance(foot, ci.c);
  if (h > ci.r) return out;
  const double w = std::sqrt(std::max(0.0, (ci.r - h) * (ci.r + h)));
  const Vec2 u = d / std::sqrt(l2);
  const Vec2 cand[2] = {foot - u * w, foot + u * w};
  for (int i = 0; i < (w > 0 ? 2 : 1); ++i) {
    if (on_segment_extent(s, cand[i], true) && on_segment_extent(t, cand[i], false)) out.add(cand[i]);
  }
  return out;
}

Crossings arc_arc(const Segment& s, const Segment& t) {
  Crossings out;
  const Circle c1 = circle_of(s), c2 = circle_of(t);
  const Vec2 dc = c2.c - c1.c;
  const double dist = norm(dc);
  if (!(dist > 0.0)) return out;  // concentric: no crossing (same circle = overlap, elsewhere)
  if (dist > c1.r + c2.r || dist < std::abs(c1.r - c2.r)) return out;
  const double x = (dist * dist + c1.r * c1.r - c2.r * c2.r) / (2.0 * dist);
  const double h = std::sqrt(std::max(0.0, c1.r * c1.r - x * x));
  const Vec2 u = dc / dist;
  const Vec2 base = c1.c + u * x;
  const Vec2 cand[2] = {base + perp(u) * h, base - perp(u) * h};
  for (int i = 0; i < (h > 0 ? 2 : 1); ++i) {
    if (on_segment_extent(s, cand[i], false) && on_segment_extent(t, cand[i], false)) out.add(cand[i]);
  }
  return out;
}

// Closest pair of points between s and t, assuming they do not cross (see distance() below).
struct Pair {
  double dist = kInf;
  Vec2 ps, pt;
  void consider(Vec2 a, Vec2 b) {
    const double d = distance(a, b);
    if (d < dist) { dist = d; ps = a; pt = b; }
  }
};

Pair closest_pair(const Segment& s, const Segment& t, bool s_line, bool t_line) {
  Pair best;
  best.consider(s.a, closest_point(t, s.a).point);
  best.consider(s.b, closest_point(t, s.b).point);
  best.consider(closest_point(s, t.a).point, t.a);
  best.consider(closest_point(s, t.b).point, t.b);
  // Interior–interior minima lie on a common normal: for a line and an arc, through the arc
  // centre perpendicular to the line; for two arcs, on the line of centres.
  if (s_line != t_line) {
    const Segment& ln = s_line ? s : t;
    const Segment& ar = s_line ? t : s;
    const Vec2 d = ln.b - ln.a;
    const double l2 = norm2(d);
    if (l2 > 0.0) {
      const Circle ci = circle_of(ar);
      const double tf = dot(ci.c - ln.a, d) / l2;
      const Vec2 foot = ln.a + d * tf;
      const Vec2 n = foot - ci.c;
      const double nn = norm(n);
      if (tf >= 0.0 && tf <= 1.0 && nn > 0.0) {
        const Vec2 q = ci.c + n * (ci.r / nn);
        if (on_segment_extent(ar, q, false)) {
          if (s_line) best.consider(foot, q); else best.consider(q, foot);
        }
      }
    }
  } else if (!s_line && !t_line) {
    const Circle c1 = circle_of(s), c2 = circle_of(t);
    const Vec2 dc = c2.c - c1.c;
    const double dist = norm(dc);
    if (dist > 0.0) {
      const Vec2 u = dc / dist;
      for (double s1 : {1.0, -1.0}) {
        const Vec2 q1 = c1.c + u * (s1 * c1.r);
        if (!on_segment_extent(s, q1, false)) continue;
        for (double s2 : {1.0, -1.0}) {
          const Vec2 q2 = c2.c + u * (s2 * c2.r);
          if (on_segment_extent(t, q2, false)) best.consider(q1, q2);
        }
      }
    }
  }
  return best;
}

// Overlap of two segments that lie on the same line or the same circle (within tol): the
// end points of each lying on the other, reduced to the two farthest apart.
SegmentIntersection same_carrier_overlap(const Segment& s, const Segment& t, double tol_mm) {
  SegmentIntersection r;
  Vec2 pts[4];
  int n = 0;
  for (Vec2 q : {t.a, t.b}) if (closest_point(s, q).distance <= tol_mm) pts[n++] = q;
  for (Vec2 q : {s.a, s.b}) if (closest_point(t, q).distance <= tol_mm) pts[n++] = q;
  if (n == 0) return r;
  double far = -1.0;
  Vec2 e0 = pts[0], e1 = pts[0];
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double d = distance(pts[i], pts[j]);
      if (d > far) { far = d; e0 = pts[i]; e1 = pts[j]; }
    }
  if (far > tol_mm) {
    r.kind = SegmentIntersection::Kind::overlap;
    r.count = 2;
    r.points[0] = e0;
    r.points[1] = e1;
  } else {
    r.kind = SegmentIntersection::Kind::points;
    r.count = 1;
    r.points[0] = (e0 + e1) * 0.5;
  }
  return r;
}

bool same_line(const Segment& s, const Segment& t, double tol_mm) {
  const Vec2 d1 = s.b - s.a, d2 = t.b - t.a;
  const double l1 = norm(d1), l2 = norm(d2);
  if (!(l1 > 0.0) || !(l2 > 0.0)) return false;
  if (std::abs(cross(d1, d2)) > 1e-12 * l1 * l2) {
    // Not parallel to machine precision, but both end points of t may still lie within tol of
    // s's line (nearly collinear, overlapping stretch).
    const Vec2 u = d1 / l1;
    return std::abs(cross(u, t.a - s.a)) <= tol_mm && std::abs(cross(u, t.b - s.a)) <= tol_mm;
  }
  return std::abs(cross(d1 / l1, t.a - s.a)) <= tol_mm;
}

bool same_circle(const Segment& s, const Segment& t, double tol_mm) {
  const Circle c1 = circle_of(s), c2 = circle_of(t);
  return distance(c1.c, c2.c) <= tol_mm && std::abs(c1.r - c2.r) <= tol_mm;
}

}  // namespace

SegmentClosest closest_point(const Segment& s, Vec2 p) {
  SegmentClosest r;
  if (detail::nearly_straight(s)) {
    const Vec2 d = s.b - s.a;
    const double l2 = norm2(d);
    double t = l2 > 0.0 ? dot(p - s.a, d) / l2 : 0.0;
    if (!(t > 0.0)) t = 0.0;
    if (t > 1.0) t = 1.0;
    r.point = t >= 1.0 ? s.b : s.a + d * t;
    r.distance = distance(r.point, p);
    r.length_along = s.is_arc() ? s.length() * t : std::sqrt(l2) * t;
    return r;
  }
  const Vec2 c = s.center();
  const double rad = s.radius();
  const Vec2 v = p - c;
  const double theta = s.sweep();
  const double phi = norm(v) > 0.0 ? detail::sweep_to_angle(s, std::atan2(v.y, v.x)) : 0.0;
  if (std::abs(phi) <= std::abs(theta)) {
    r.point = arc_point_at_sweep(s.a, s.b, s.bulge, phi);
    r.length_along = rad * std::abs(phi);
  } else {
    const bool to_a = distance(s.a, p) <= distance(s.b, p);
    r.point = to_a ? s.a : s.b;
    r.length_along = to_a ? 0.0 : s.length();
  }
  r.distance = distance(r.point, p);
  return r;
}

SegmentIntersection intersect(const Segment& s, const Segment& t, double tol_mm) {
  if (!(tol_mm >= 0.0)) tol_mm = 0.0;
  SegmentIntersection r;
  if (!s.bounding_box().inflated(tol_mm).intersects(t.bounding_box())) return r;
  const bool s_line = detail::nearly_straight(s), t_line = detail::nearly_straight(t);
  const bool s_point = s.a == s.b, t_point = t.a == t.b;

  if (!s_point && !t_point) {
    if (s_line && t_line && same_line(s, t, tol_mm)) {
      r = same_carrier_overlap(s, t, tol_mm);
      if (r.kind != SegmentIntersection::Kind::none) return r;
    } else if (!s_line && !t_line && same_circle(s, t, tol_mm)) {
      r = same_carrier_overlap(s, t, tol_mm);
      if (r.kind != SegmentIntersection::Kind::none) return r;
    }
    Crossings x;
    if (s_line && t_line) x = line_line(s, t);
    else if (s_line) x = line_arc(s, t);
    else if (t_line) x = line_arc(t, s);
    else x = arc_arc(s, t);
    if (x.count == 2 && distance(x.p[0], x.p[1]) <= tol_mm) {
      x.p[0] = (x.p[0] + x.p[1]) * 0.5;  // a tangency split by rounding
      x.count = 1;
    }
    if (x.count > 0) {
      r.kind = SegmentIntersection::Kind::points;
      r.count = x.count;
      r.points[0] = x.p[0];
      r.points[1] = x.p[1];
      return r;
    }
  }
  const Pair near = closest_pair(s, t, s_line, t_line);
  if (near.dist <= tol_mm) {
    r.kind = SegmentIntersection::Kind::points;
    r.count = 1;
    r.points[0] = (near.ps + near.pt) * 0.5;
  }
  return r;
}

double distance(const Segment& s, const Segment& t) {
  const SegmentIntersection x = intersect(s, t, 0.0);
  if (x.kind != SegmentIntersection::Kind::none) return 0.0;
  return closest_pair(s, t, detail::nearly_straight(s), detail::nearly_straight(t)).dist;
}

std::size_t count_close_segment_pairs(const Contour& a, const Contour& b, double tol_mm, std::size_t limit) {
  if (limit == 0) return 0;
  if (!(tol_mm >= 0.0)) tol_mm = 0.0;
  const Box box_a = bounding_box(a).inflated(tol_mm);
  const Box box_b = bounding_box(b).inflated(tol_mm);
  if (!box_a.intersects(box_b)) return 0;
  // Keep only segments near the other contour's box, then sweep along x: cheap for the usual
  // case of a small contour inside a big one, O((n + m) log(n + m) + close pairs) overall.
  struct Item {
    Box box;
    Segment seg;
    bool from_a;
  };
  std::vector<Item> items;
  const std::size_t na = segment_count(a), nb = segment_count(b);
  items.reserve(na + nb);
  for (std::size_t i = 0; i < na; ++i) {
    const Segment s = segment(a, i);
    const Box bx = s.bounding_box().inflated(tol_mm);
    if (bx.intersects(box_b)) items.push_back({bx, s, true});
  }
  for (std::size_t i = 0; i < nb; ++i) {
    const Segment s = segment(b, i);
    const Box bx = s.bounding_box();
    if (bx.intersects(box_a)) items.push_back({bx, s, false});
  }
  std::sort(items.begin(), items.end(), [](const Item& x, const Item& y) { return x.box.xmin < y.box.xmin; });
  std::size_t found = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    for (std::size_t j = i + 1; j < items.size() && items[j].box.xmin <= items[i].box.xmax; ++j) {
      if (items[i].from_a == items[j].from_a) continue;
      if (!items[i].box.intersects(items[j].box)) continue;
      const Segment& sa = items[i].from_a ? items[i].seg : items[j].seg;
      const Segment& sb = items[i].from_a ? items[j].seg : items[i].seg;
      if (intersect(sa, sb, tol_mm).kind != SegmentIntersection::Kind::none) {
        if (++found >= limit) return found;
      }
    }
  }
  return found;
}

}  // namespace cutroute::geometry
