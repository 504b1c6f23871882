#include <cutroute/nc/rapid_detours.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <cutroute/core/tolerances.hpp>

namespace cutroute::nc {
namespace {

using geometry::Vec2;

double orient(Vec2 a, Vec2 b, Vec2 c) { return geometry::cross(b - a, c - a); }

bool inside(const std::vector<Vec2>& poly, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 u = poly[i], v = poly[j];
    if ((u.y > p.y) != (v.y > p.y) && p.x < (v.x - u.x) * (p.y - u.y) / (v.y - u.y) + u.x) in = !in;
  }
  return in;
}

// Andrew's monotone chain; counter-clockwise, no repeated first point.
std::vector<Vec2> convex_hull(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (pts.size() < 3) return pts;
  std::vector<Vec2> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && orient(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && orient(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  return h;
}

geometry::Box box_of(Vec2 a, Vec2 b) {
  geometry::Box x;
  x.add(a);
  x.add(b);
  return x;
}

}  // namespace

PartObstacles::PartObstacles(const model::Nest& nest, double margin_mm) {
  // Eight points on a circle of radius margin / cos(22.5°) around each hull corner: their hull
  // contains the margin disc around the corner, so the grown hull keeps margin from the part.
  const double r = std::max(margin_mm, 0.0) / std::cos(std::numbers::pi / 8);
  for (const auto& part : nest.parts) {
    Obstacle o;
    o.polygon = geometry::flatten(nest.contours[part.outer].source.contour, tol::kArcChordMm);
    for (const auto& p : o.polygon) o.box.add(p);
    std::vector<Vec2> grown;
    for (const auto& p : convex_hull(o.polygon))
      for (int k = 0; k < 8; ++k) {
        const double phi = std::numbers::pi / 4 * k + std::numbers::pi / 8;
        grown.push_back(p + Vec2{r * std::cos(phi), r * std::sin(phi)});
      }
    o.hull = convex_hull(std::move(grown));
    parts_.push_back(std::move(o));
  }
}

bool PartObstacles::crosses(int part, Vec2 a, Vec2 b) const {
  const Obstacle& o = parts_[static_cast<std::size_t>(part)];
  if (o.polygon.size() < 3 || !o.box.intersects(box_of(a, b))) return false;
  // Where the move meets the boundary (crossings, and touches at corners, which a crossing test
  // alone misses when the move runs corner to corner); between two such places the move is wholly
  // inside or outside, so one point between each pair decides.
  std::vector<double> ts{0.0, 1.0};
  const Vec2 d = b - a;
  for (std::size_t i = 0, j = o.polygon.size() - 1; i < o.polygon.size(); j = i++) {
    const Vec2 p = o.polygon[j], e = o.polygon[i] - p;
    const double den = geometry::cross(d, e);
    if (std::abs(den) < 1e-300) continue;  // parallel: the ends of the neighbouring edges are met instead
    const double t = geometry::cross(p - a, e) / den, u = geometry::cross(p - a, d) / den;
    if (t > 0 && t < 1 && u >= 0 && u <= 1) ts.push_back(t);
  }
  std::sort(ts.begin(), ts.end());
  for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
    if (ts[k + 1] - ts[k] < 1e-12) continue;
    if (inside(o.polygon, a + d * ((ts[k] + ts[k + 1]) / 2))) return true;
  }
  return false;
}

std::vector<int> PartObstacles::crossed(Vec2 a, Vec2 b) const {
  std::vector<int> out;
  for (int k = 0; k < part_count(); ++k)
    if (crosses(k, a, b)) out.push_back(k);
  return out;
}

std::optional<std::vector<Vec2>> PartObstacles::detour(Vec2 a, Vec2 b, const std::vector<char>& freed) const {
  auto blockers = [&](Vec2 u, Vec2 v, std::vector<int>* out) {
    bool blocked = false;
    for (int k = 0; k < part_count(); ++k) {
      if (!freed[static_cast<std::size_t>(k)] || !crosses(k, u, v)) continue;
      blocked = true;
      if (!out) return true;
      out->push_back(k);
    }
    return blocked;
  };
  std::vector<int> set;
  blockers(a, b, &set);
  if (set.empty()) return std::vector<Vec2>{};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (int round = 0; round < 8; ++round) {
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    std::vector<Vec2> nodes{a, b};
    for (int k : set)
      for (const auto& p : parts_[static_cast<std::size_t>(k)].hull) nodes.push_back(p);
    const std::size_t n = nodes.size();
    // Dijkstra on the visibility graph, legs checked lazily when a node is settled.
    std::vector<double> dist(n, kInf);
    std::vector<std::size_t> prev(n, n);
    std::vector<char> done(n, 0);
    std::vector<int> more;
    dist[0] = 0;
    for (;;) {
      std::size_t u = n;
      for (std::size_t i = 0; i < n; ++i)
        if (!done[i] && dist[i] < kInf && (u == n || dist[i] < dist[u])) u = i;
      if (u == n || u == 1) break;
      done[u] = 1;
      for (std::size_t v = 0; v < n; ++v) {
        if (done[v] || v == u) continue;
        const double d = dist[u] + geometry::distance(nodes[u], nodes[v]);
        if (d >= dist[v]) continue;
        std::vector<int> hit;
        if (blockers(nodes[u], nodes[v], &hit)) {
          more.insert(more.end(), hit.begin(), hit.end());
          continue;
        }
        dist[v] = d;
        prev[v] = u;
      }
    }
    if (dist[1] < kInf) {
      std::vector<Vec2> via;
      for (std::size_t v = prev[1]; v != 0; v = prev[v]) via.push_back(nodes[v]);
      std::reverse(via.begin(), via.end());
      return via;
    }
    const std::size_t before = set.size();
    set.insert(set.end(), more.begin(), more.end());
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    if (set.size() == before) break;  // nothing new to go around: enclosed
  }
  return std::nullopt;
}

DetourStats route_rapids_around_freed_parts(Toolpath& path, const model::Nest& nest, double margin_mm) {
  DetourStats st;
  const PartObstacles obstacles(nest, margin_mm);
  std::vector<char> freed(nest.parts.size(), 0);
  auto route = [&](Vec2 from, Vec2 to, std::vector<Vec2>& via) {
    via.clear();
    bool over = false;
    for (int k = 0; k < obstacles.part_count() && !over; ++k) over = freed[static_cast<std::size_t>(k)] && obstacles.crosses(k, from, to);
    if (!over) return;
    ++st.rapids_over_freed;
    auto d = obstacles.detour(from, to, freed);
    if (!d || d->empty()) {
      ++st.unavoidable;
      return;
    }
    via = std::move(*d);
    double len = 0;
    Vec2 at = from;
    for (const auto& p : via) {
      len += geometry::distance(at, p);
      at = p;
    }
    st.extra_mm += len + geometry::distance(at, to) - geometry::distance(from, to);
    ++st.detours;
  };
  Vec2 at = path.start;
  for (auto& seg : path.segments) {
    route(at, seg.pierce, seg.rapid_via);
    for (const auto& piece : seg.pieces) {
      if (piece.contour < 0) continue;
      const auto& c = nest.contours[model::ContourId(piece.contour)];
      if (c.role == model::ContourRole::outer && c.part.valid()) freed[c.part.index()] = 1;
    }
    at = tool_off_point(seg);
  }
  route(at, path.end, path.end_via);
  return st;
}

}  // namespace cutroute::nc
