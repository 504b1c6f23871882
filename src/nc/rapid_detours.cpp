#include <cutroute/nc/rapid_detours.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <cutroute/core/tolerances.hpp>

namespace cutroute::nc {
namespace {

using geometry::Vec2;

// Detour legs run along the grown hull's edges; they are tested against a hull shrunk by this
// factor (2 µm for a 2 mm margin) so that running along an edge does not count as inside.
constexpr double kGuardShrink = 1 - 1e-3;

bool inside(const std::vector<Vec2>& poly, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 u = poly[i], v = poly[j];
    if ((u.y > p.y) != (v.y > p.y) && p.x < (v.x - u.x) * (p.y - u.y) / (v.y - u.y) + u.x) in = !in;
  }
  return in;
}

geometry::Box box_of(Vec2 a, Vec2 b) {
  geometry::Box x;
  x.add(a);
  x.add(b);
  return x;
}

// Does some stretch of the move a -> b lie inside the polygon? Where the move meets the boundary
// (crossings, and touches at corners, which a crossing test alone misses when the move runs corner
// to corner), it may change sides; between two such places it is wholly inside or outside, so one
// point between each pair decides.
bool passes_inside(const std::vector<Vec2>& poly, const geometry::Box& box, Vec2 a, Vec2 b) {
  if (poly.size() < 3 || !box.intersects(box_of(a, b))) return false;
  std::vector<double> ts{0.0, 1.0};
  const Vec2 d = b - a;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 p = poly[j], e = poly[i] - p;
    const double den = geometry::cross(d, e);
    if (den == 0) continue;  // parallel: the ends of the neighbouring edges are met instead
    const double t = geometry::cross(p - a, e) / den, u = geometry::cross(p - a, d) / den;
    if (t > 0 && t < 1 && u >= 0 && u <= 1) ts.push_back(t);
  }
  std::sort(ts.begin(), ts.end());
  for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
    if (ts[k + 1] - ts[k] <= 0) continue;  // the same place met twice (a corner)
    if (inside(poly, a + d * ((ts[k] + ts[k + 1]) / 2))) return true;
  }
  return false;
}

}  // namespace

PartObstacles::PartObstacles(const model::Nest& nest, double margin_mm) {
  // The grown hull is the 16-gon of the part's extents in 16 directions pushed out by the margin:
  // every edge keeps at least the margin from the part, and 16 corners per part keep the
  // visibility graph of a detour small (curved parts would otherwise bring hundreds).
  constexpr int kSides = 16;
  const double margin = std::max(margin_mm, 0.0);
  for (const auto& part : nest.parts) {
    Obstacle o;
    o.polygon = geometry::flatten(nest.contours[part.outer].source.contour, tol::kArcChordMm);
    for (const auto& p : o.polygon) o.box.add(p);
    auto sixteen_gon = [&](double grow) {
      std::array<Vec2, kSides> normal{};
      std::array<double, kSides> reach{};
      for (int k = 0; k < kSides; ++k) {
        const double phi = 2 * std::numbers::pi * k / kSides;
        normal[static_cast<std::size_t>(k)] = {std::cos(phi), std::sin(phi)};
        double h = -std::numeric_limits<double>::infinity();
        for (const auto& p : o.polygon) h = std::max(h, geometry::dot(p, normal[static_cast<std::size_t>(k)]));
        reach[static_cast<std::size_t>(k)] = h + grow;
      }
      // Corner between the supporting lines k and k+1: n_k . x = h_k, n_k+1 . x = h_k+1.
      std::vector<Vec2> out;
      for (int k = 0; k < kSides && !o.polygon.empty(); ++k) {
        const auto i = static_cast<std::size_t>(k), j = static_cast<std::size_t>((k + 1) % kSides);
        const Vec2 a = normal[i], b = normal[j];
        const double det = geometry::cross(a, b);
        out.push_back({(reach[i] * b.y - reach[j] * a.y) / det, (a.x * reach[j] - b.x * reach[i]) / det});
      }
      return out;
    };
    o.hull = sixteen_gon(margin);
    if (margin > 0) {
      o.guard = sixteen_gon(margin * kGuardShrink);
      for (const auto& p : o.guard) o.guard_box.add(p);
    }
    parts_.push_back(std::move(o));
  }
  std::vector<geometry::Box> boxes;
  for (const auto& o : parts_) boxes.push_back(o.guard.empty() ? o.box : o.guard_box);
  index_ = geometry::StaticSpatialIndex(boxes);
}

bool PartObstacles::crosses(int part, Vec2 a, Vec2 b) const {
  const Obstacle& o = parts_[static_cast<std::size_t>(part)];
  return passes_inside(o.polygon, o.box, a, b);
}

bool PartObstacles::blocks(int part, Vec2 a, Vec2 b) const {
  const Obstacle& o = parts_[static_cast<std::size_t>(part)];
  if (!(o.guard.empty() ? o.box : o.guard_box).intersects(box_of(a, b))) return false;
  // An end point within the margin (a tool-off point beside the part just cut) cannot keep the
  // margin: for that part only the part itself counts.
  if (o.guard.empty() || inside(o.guard, a) || inside(o.guard, b)) return crosses(part, a, b);
  return passes_inside(o.guard, o.guard_box, a, b);
}

std::vector<int> PartObstacles::crossed(Vec2 a, Vec2 b) const {
  std::vector<int> out;
  index_.visit(box_of(a, b), [&](std::uint32_t i) {
    if (crosses(static_cast<int>(i), a, b)) out.push_back(static_cast<int>(i));
    return true;
  });
  std::sort(out.begin(), out.end());
  return out;
}

bool PartObstacles::crosses_any(Vec2 a, Vec2 b, const std::function<bool(int)>& counts) const {
  bool hit = false;
  index_.visit(box_of(a, b), [&](std::uint32_t i) {
    const int k = static_cast<int>(i);
    hit = counts(k) && crosses(k, a, b);
    return !hit;
  });
  return hit;
}

std::optional<std::vector<Vec2>> PartObstacles::detour(Vec2 a, Vec2 b, const std::vector<char>& freed,
                                                       std::size_t* tests_left, const StopToken* stop) const {
  // A tip-up margin of a metre around hundreds of small parts put every part in every leg's way:
  // 400 circles took 14 s and 3 000 more than 5 minutes, past the time limit and SIGTERM.
  bool spent = false;  // out of budget, or stopped
  std::size_t tested = 0;
  auto blockers = [&](Vec2 u, Vec2 v, std::vector<int>* out) {
    bool blocked = false;
    index_.visit(box_of(u, v), [&](std::uint32_t i) {
      if (stop && tested++ % kStopPollTests == 0 && stop->stop_requested()) {
        spent = true;
        return false;
      }
      if (tests_left) {
        if (*tests_left == 0) {
          spent = true;
          return false;
        }
        --*tests_left;
      }
      const int k = static_cast<int>(i);
      if (!freed[i] || !blocks(k, u, v)) return true;
      blocked = true;
      if (out) out->push_back(k);
      return out != nullptr;
    });
    return blocked;
  };
  std::vector<int> set;
  blockers(a, b, &set);
  if (spent) return std::nullopt;
  if (set.empty()) return std::vector<Vec2>{};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (int round = 0; round < 8; ++round) {
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    if (set.size() > kMaxDetourParts) break;  // a way round that many freed parts: give up
    std::vector<Vec2> nodes{a, b};
    for (int k : set)
      for (const auto& p : parts_[static_cast<std::size_t>(k)].hull) nodes.push_back(p);
    const std::size_t n = nodes.size();
    // Dijkstra on the visibility graph, legs checked lazily when a node is settled.
    std::vector<double> dist(n, kInf);
    std::vector<std::size_t> prev(n, n);
    std::vector<char> done(n, 0);
    std::vector<int> more, hit;
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
        hit.clear();
        const bool blocked = blockers(nodes[u], nodes[v], &hit);
        if (spent) return std::nullopt;
        if (blocked) {
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

DetourStats route_rapids_around_freed_parts(Toolpath& path, const model::Nest& nest, double margin_mm,
                                            const StopToken& stop) {
  DetourStats st;
  const PartObstacles obstacles(nest, margin_mm);
  std::vector<char> freed(nest.parts.size(), 0);
  std::size_t tests_left = kDetourTestBudget;
  bool stopped = false;  // stop requests stay requested: read the clock once per rapid until then
  auto route = [&](Vec2 from, Vec2 to, std::vector<Vec2>& via) {
    via.clear();
    if (!obstacles.crosses_any(from, to, [&](int k) { return freed[static_cast<std::size_t>(k)] != 0; })) return;
    ++st.rapids_over_freed;
    stopped = stopped || stop.stop_requested();
    auto d = stopped ? std::nullopt : obstacles.detour(from, to, freed, &tests_left, &stop);
    if (!d || d->empty()) {
      ++st.unavoidable;
      // A search that gave up for the token leaves it requesting a stop (see detour()).
      stopped = stopped || (!d && stop.stop_requested());
      if (stopped) {
        ++st.left_at_time_limit;
      } else if (tests_left == 0) {
        ++st.over_budget;
      }
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
