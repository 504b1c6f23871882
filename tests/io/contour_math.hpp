// Independent arc math for the io tests (lengths, areas, points on bulge segments): written here
// on purpose, so the reader is checked against code it does not share.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::test {

using geometry::Contour;
using geometry::Vec2;

struct Arc {
  Vec2 c;
  double r = 0;
  double a0 = 0;     // start angle [rad]
  double sweep = 0;  // signed [rad]
};

inline Arc arc_of(Vec2 a, Vec2 b, double bulge) {
  const double sweep = 4 * std::atan(bulge);
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double chord = std::sqrt(dx * dx + dy * dy);
  const double r = chord / (2 * std::sin(std::abs(sweep) / 2));
  // Centre: rotate the half chord by (pi/2 - sweep/2) towards the arc's inside.
  const double h = r * std::cos(sweep / 2);  // signed distance from the chord midpoint
  const Vec2 m{(a.x + b.x) / 2, (a.y + b.y) / 2};
  const Vec2 n{-dy / chord, dx / chord};  // left normal
  const double s = sweep > 0 ? 1.0 : -1.0;
  const Vec2 c{m.x + n.x * h * s, m.y + n.y * h * s};
  return {c, r, std::atan2(a.y - c.y, a.x - c.x), sweep};
}

inline std::size_t nseg(const Contour& c) {
  const std::size_t n = c.vertices.size();
  return c.closed ? n : (n == 0 ? 0 : n - 1);
}

inline double seg_length(Vec2 a, Vec2 b, double bulge) {
  const double chord = std::hypot(b.x - a.x, b.y - a.y);
  if (bulge == 0) return chord;
  const Arc arc = arc_of(a, b, bulge);
  return arc.r * std::abs(arc.sweep);
}

inline double path_length(const Contour& c) {
  double l = 0;
  const std::size_t n = c.vertices.size();
  for (std::size_t i = 0; i < nseg(c); ++i) l += seg_length(c.vertices[i].p, c.vertices[(i + 1) % n].p, c.vertices[i].bulge);
  return l;
}

// Shoelace plus circular segments; > 0 counter-clockwise.
inline double path_area(const Contour& c) {
  double s = 0;
  const std::size_t n = c.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = c.vertices[i].p, b = c.vertices[(i + 1) % n].p;
    s += (a.x * b.y - b.x * a.y) / 2;
    const double bu = c.vertices[i].bulge;
    if (bu != 0) {
      const Arc arc = arc_of(a, b, bu);
      const double t = std::abs(arc.sweep);
      s += (bu > 0 ? 1 : -1) * arc.r * arc.r * (t - std::sin(t)) / 2;
    }
  }
  return s;
}

// Points along every segment: `per` per segment, segment starts included, final end included
// (the start again for a closed contour).
inline std::vector<Vec2> sample(const Contour& c, int per) {
  std::vector<Vec2> out;
  const std::size_t n = c.vertices.size();
  for (std::size_t i = 0; i < nseg(c); ++i) {
    const Vec2 a = c.vertices[i].p, b = c.vertices[(i + 1) % n].p;
    const double bu = c.vertices[i].bulge;
    for (int k = 0; k < per; ++k) {
      const double t = double(k) / per;
      if (bu == 0) {
        out.push_back({a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t});
      } else {
        const Arc arc = arc_of(a, b, bu);
        const double ang = arc.a0 + arc.sweep * t;
        out.push_back({arc.c.x + arc.r * std::cos(ang), arc.c.y + arc.r * std::sin(ang)});
      }
    }
  }
  if (n > 0) out.push_back(c.closed ? c.vertices.front().p : c.vertices.back().p);
  return out;
}

inline double dist(Vec2 a, Vec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

// Two-sided deviation between a contour and a parametric curve f on [t0, t1], both densely
// sampled (the sampling error is far below the tolerances tested).
inline double deviation(const Contour& c, const std::function<Vec2(double)>& f, double t0, double t1, int n = 2000) {
  std::vector<Vec2> curve;
  for (int i = 0; i <= n; ++i) curve.push_back(f(t0 + (t1 - t0) * i / n));
  const std::vector<Vec2> pts = sample(c, 32);
  auto to_poly = [](const std::vector<Vec2>& poly, Vec2 p) {
    double best = 1e300;
    for (std::size_t i = 0; i + 1 < poly.size(); ++i) {
      const Vec2 a = poly[i], b = poly[i + 1];
      const double dx = b.x - a.x, dy = b.y - a.y;
      const double l2 = dx * dx + dy * dy;
      double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
      t = std::clamp(t, 0.0, 1.0);
      best = std::min(best, std::hypot(a.x + dx * t - p.x, a.y + dy * t - p.y));
    }
    return best;
  };
  double d = 0;
  for (const Vec2& p : pts) d = std::max(d, to_poly(curve, p));
  for (const Vec2& p : curve) d = std::max(d, to_poly(pts, p));
  return d;
}

}  // namespace cutroute::test
