#include "path_ops.hpp"

#include <algorithm>
#include <cmath>

namespace cutroute::model::detail {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

Measured measure(const Contour& c) {
  Measured m;
  const std::size_t n = geometry::segment_count(c);
  m.seg_len.reserve(n);
  m.cum.reserve(n + 1);
  m.cum.push_back(0.0);
  double acc = 0.0;  // summed in the order geometry::length sums: cum[n] equals it exactly
  for (std::size_t i = 0; i < n; ++i) {
    m.seg_len.push_back(geometry::segment(c, i).length());
    acc += m.seg_len.back();
    m.cum.push_back(acc);
  }
  return m;
}

PathPoint at_length(const Contour& c, double s) { return at_length(c, measure(c), s); }

PathPoint at_length(const Contour& c, const Measured& m, double s) {
  const std::size_t n = m.seg_len.size();
  PathPoint out;
  if (n == 0) {
    if (!c.vertices.empty()) out.point = c.vertices.front().p;
    out.tangent = {1, 0};
    return out;
  }
  const double total = m.cum[n];
  if (c.closed && total > 0) {
    s = std::fmod(s, total);
    if (s < 0) s += total;
  } else {
    s = std::clamp(s, 0.0, total);
  }
  // The first segment whose end lies at or beyond s (the last one when none does).
  const auto it = std::lower_bound(m.cum.begin() + 1, m.cum.end(), s);
  const std::size_t i = it == m.cum.end() ? n - 1 : static_cast<std::size_t>(it - m.cum.begin()) - 1;
  const auto seg = geometry::segment(c, i);
  const double len = m.seg_len[i];
  const double t = len > 0 ? std::clamp((s - m.cum[i]) / len, 0.0, 1.0) : 0.0;
  out.point = seg.point_at(t);
  out.tangent = seg.tangent_at(t);
  out.segment = i;
  out.t = t;
  return out;
}

void split_bulge(double bulge, double u, double& first, double& second) {
  const double sweep = 4 * std::atan(bulge);
  first = std::tan(sweep * u / 4);
  second = std::tan(sweep * (1 - u) / 4);
}

Contour sub_path(const Contour& c, double s0, double length) { return sub_path(c, measure(c), s0, length); }

Contour sub_path(const Contour& c, const Measured& m, double s0, double length) {
  Contour out;
  out.closed = false;
  const std::size_t n = m.seg_len.size();
  if (n == 0 || length <= 0) return out;
  const PathPoint start = at_length(c, m, s0);
  double remaining = length;
  std::size_t i = start.segment;
  double t0 = start.t;
  out.vertices.push_back({start.point, 0});
  // Walk segments from (i, t0), cutting the last one at the remaining length.
  for (std::size_t guard = 0; remaining > 0 && guard < 4 * n + 4; ++guard) {
    const auto seg = geometry::segment(c, i);
    const double len = m.seg_len[i];
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
