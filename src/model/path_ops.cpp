#include "path_ops.hpp"

#include <algorithm>
#include <cmath>

namespace cutroute::model::detail {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

PathPoint at_length(const Contour& c, double s) {
  const std::size_t n = geometry::segment_count(c);
  PathPoint out;
  if (n == 0) {
    if (!c.vertices.empty()) out.point = c.vertices.front().p;
    out.tangent = {1, 0};
    return out;
  }
  const double total = geometry::length(c);
  if (c.closed && total > 0) {
    s = std::fmod(s, total);
    if (s < 0) s += total;
  } else {
    s = std::clamp(s, 0.0, total);
  }
  double acc = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto seg = geometry::segment(c, i);
    const double len = seg.length();
    if (s <= acc + len || i + 1 == n) {
      const double t = len > 0 ? std::clamp((s - acc) / len, 0.0, 1.0) : 0.0;
      out.point = seg.point_at(t);
      out.tangent = seg.tangent_at(t);
      out.segment = i;
      out.t = t;
      return out;
    }
    acc += len;
  }
  return out;
}

void split_bulge(double bulge, double u, double& first, double& second) {
  const double sweep = 4 * std::atan(bulge);
  first = std::tan(sweep * u / 4);
  second = std::tan(sweep * (1 - u) / 4);
}

Contour sub_path(const Contour& c, double s0, double length) {
  Contour out;
  out.closed = false;
  const std::size_t n = geometry::segment_count(c);
  if (n == 0 || length <= 0) return out;
  const PathPoint start = at_length(c, s0);
  double remaining = length;
  std::size_t i = start.segment;
  double t0 = start.t;
  out.vertices.push_back({start.point, 0});
  // Walk segments from (i, t0), cutting the last one at the remaining length.
  for (std::size_t guard = 0; remaining > 0 && guard < 4 * n + 4; ++guard) {
    const auto seg = geometry::segment(c, i);
    const double len = seg.length();
    const double avail = len * (1 - t0);
    const double take = std::min(avail, remaining);
    if (len > 0 && take > 0) {
      const double t1 = t0 + take / len;
      double b = 0;
      if (seg.is_arc()) {
        // bulge of the portion [t0, t1] of the arc: a quarter of its sweep's tangent.
        b = std::tan(seg.sweep() * (t1 - t0) / 4);
      }
      out.vertices.back().bulge = b;
      out.vertices.push_back({seg.point_at(t1), 0});
      remaining -= take;
    }
    i = (i + 1) % n;
    t0 = 0;
    if (!c.closed && i == 0) break;
  }
  return out;
}

}  // namespace cutroute::model::detail
