// plan_common_lines(): the cut graph of a nest with common stretches merged, and its basic segments.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>

#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>
#include <cutroute/model/common_lines.hpp>

#include "common_detail.hpp"
#include "path_ops.hpp"

namespace cutroute::model {

using geometry::Contour;
using geometry::Vec2;

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
};

// An edge of the cut graph: a common stretch, or a piece of one contour's boundary between
// stretches ("own": material on one side only), oriented with the material on its left.
struct Edge {
  Contour path;       // open, from node `from` to node `to` (up to a connector at each end)
  int from = -1, to = -1;
  int stretch = -1;   // common edge: the stretch; own edge: -1
  ContourId contour;  // own edge: the contour it bounds
};

struct Graph {
  std::vector<Vec2> nodes;
  std::vector<Edge> edges;
  std::vector<std::vector<int>> out_own;   // per node: own edges leaving it
  std::vector<std::vector<int>> common;    // per node: common edges touching it
};

// Tangent of an open path at its start (at_end: at its end), in its direction of travel.
Vec2 end_tangent(const Contour& p, bool at_end) {
  const std::size_t n = geometry::segment_count(p);
  return at_end ? geometry::segment(p, n - 1).tangent_at(1) : geometry::segment(p, 0).tangent_at(0);
}

// Counter-clockwise angle from a to b in [0, 2π).
double ccw_angle(Vec2 a, Vec2 b) {
  double t = std::atan2(geometry::cross(a, b), geometry::dot(a, b));
  return t < 0 ? t + kTwoPi : t;
}

// The node of merged stretch ends (end, tangent there): the point nearest to the lines carrying
// them (least squares), so that the connectors continue each centre line straight to the junction.
// At a T of parts drawn kerf apart the centroid of the three ends lies off the through line: the
// connectors dipped toward the corners of the parts beside the stem (0.04 mm into them at kerf
// 1.5), and the through line's kerf no longer reached the through part's edge across the stem's
// mouth, which was left to a "loop" narrower than the kerf. The centroid when the lines are
// parallel or meet farther than `merge` from an end (nearly parallel).
Vec2 junction_point(const std::vector<std::pair<Vec2, Vec2>>& ends, double merge) {
  Vec2 centroid{};
  for (const auto& [p, t] : ends) centroid += p;
  centroid = centroid / static_cast<double>(ends.size());
  double a = 0, b = 0, c = 0, rx = 0, ry = 0;  // normal equations [a b; b c] x = r
  for (const auto& [p, t] : ends) {
    const Vec2 n = geometry::perp(t);
    const double d = geometry::dot(n, p);
    a += n.x * n.x;
    b += n.x * n.y;
    c += n.y * n.y;
    rx += n.x * d;
    ry += n.y * d;
  }
  const double det = a * c - b * b;
  if (!(det > 1e-6 * (a + c) * (a + c))) return centroid;
  const Vec2 x{(c * rx - b * ry) / det, (a * ry - b * rx) / det};
  for (const auto& [p, t] : ends)
    if (geometry::distance(x, p) > merge) return centroid;
  return x;
}

// Step 2: nodes from the stretch ends (merged within kerf + tol, and across own pieces shorter
// than tol), edges from the stretches and the own pieces between them.
Graph build_graph(const Nest& nest, const std::vector<CommonStretch>& stretches, const CommonLineOptions& o) {
  const std::size_t m = stretches.size();
  UnionFind uf(2 * m);
  std::vector<Vec2> ends(2 * m);
  for (std::size_t k = 0; k < m; ++k) {
    ends[2 * k] = stretches[k].centre.a;
    ends[2 * k + 1] = stretches[k].centre.b;
  }
  // Sweep in x: pairs of ends closer than the merge distance.
  const double merge = o.kerf_mm + o.tol_mm;
  std::vector<int> by_x(2 * m);
  std::iota(by_x.begin(), by_x.end(), 0);
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) {
    return std::tie(ends[static_cast<std::size_t>(a)].x, a) < std::tie(ends[static_cast<std::size_t>(b)].x, b);
  });
  for (std::size_t a = 0; a < by_x.size(); ++a) {
    const Vec2 pa = ends[static_cast<std::size_t>(by_x[a])];
    for (std::size_t b = a + 1; b < by_x.size() && ends[static_cast<std::size_t>(by_x[b])].x - pa.x <= merge; ++b)
      if (geometry::distance(pa, ends[static_cast<std::size_t>(by_x[b])]) <= merge) uf.unite(by_x[a], by_x[b]);
  }
  // Per contour: its stretch intervals in arc-length order with the end node beside each bound.
  struct Interval {
    double lo, hi;
    int node_lo, node_hi;
  };
  std::map<std::int32_t, std::vector<Interval>> per_contour;
  for (std::size_t k = 0; k < m; ++k) {
    const auto& s = stretches[k];
    const int a = static_cast<int>(2 * k), b = a + 1;
    per_contour[s.first.value()].push_back({s.first_s0, s.first_s1, a, b});
    if (s.second_s0 <= s.second_s1)
      per_contour[s.second.value()].push_back({s.second_s0, s.second_s1, a, b});
    else
      per_contour[s.second.value()].push_back({s.second_s1, s.second_s0, b, a});
  }
  struct Piece {
    ContourId contour;
    double s0, len;
    int from, to;
  };
  std::vector<Piece> pieces;
  for (auto& [id, ivs] : per_contour) {
    std::sort(ivs.begin(), ivs.end(), [](const Interval& x, const Interval& y) { return x.lo < y.lo; });
    const ContourId cid(id);
    const double total = geometry::length(nest.contours[cid].source.contour);
    for (std::size_t k = 0; k < ivs.size(); ++k) {
      const Interval& cur = ivs[k];
      const Interval& next = ivs[(k + 1) % ivs.size()];
      const double len = k + 1 < ivs.size() ? next.lo - cur.hi : next.lo + total - cur.hi;
      if (len < o.tol_mm)
        uf.unite(cur.node_hi, next.node_lo);
      else
        pieces.push_back({cid, cur.hi, len, cur.node_hi, next.node_lo});
    }
  }
  // Node ids in order of their smallest end; position: where the centre lines of the merged
  // stretches meet (see junction_point()).
  Graph g;
  std::vector<int> node_of(2 * m, -1);
  std::vector<std::vector<std::pair<Vec2, Vec2>>> lines;  // per node: (end, tangent) of its stretch ends
  for (std::size_t e = 0; e < 2 * m; ++e) {
    const auto root = static_cast<std::size_t>(uf.find(static_cast<int>(e)));
    if (node_of[root] < 0) {
      node_of[root] = static_cast<int>(g.nodes.size());
      g.nodes.push_back({});
      lines.emplace_back();
    }
    node_of[e] = node_of[root];
    lines[static_cast<std::size_t>(node_of[root])].emplace_back(ends[e], stretches[e / 2].centre.tangent_at(e % 2 == 0 ? 0 : 1));
  }
  for (std::size_t v = 0; v < g.nodes.size(); ++v) g.nodes[v] = junction_point(lines[v], merge);
  g.out_own.resize(g.nodes.size());
  g.common.resize(g.nodes.size());
  for (std::size_t k = 0; k < m; ++k) {
    Edge e;
    e.path.vertices = {{stretches[k].centre.a, stretches[k].centre.bulge}, {stretches[k].centre.b, 0}};
    e.from = node_of[2 * k];
    e.to = node_of[2 * k + 1];
    e.stretch = static_cast<int>(k);
    g.common[static_cast<std::size_t>(e.from)].push_back(static_cast<int>(g.edges.size()));
    if (e.to != e.from) g.common[static_cast<std::size_t>(e.to)].push_back(static_cast<int>(g.edges.size()));
    g.edges.push_back(std::move(e));
  }
  for (const auto& p : pieces) {
    const auto& c = nest.contours[p.contour];
    Edge e;
    e.path = detail::sub_path(c.source.contour, p.s0, p.len);
    e.from = node_of[static_cast<std::size_t>(p.from)];
    e.to = node_of[static_cast<std::size_t>(p.to)];
    e.contour = p.contour;
    if (!detail::material_left(c)) {
      e.path = geometry::reversed(e.path);
      std::swap(e.from, e.to);
    }
    g.out_own[static_cast<std::size_t>(e.from)].push_back(static_cast<int>(g.edges.size()));
    g.edges.push_back(std::move(e));
  }
  return g;
}

// A walk through the graph: edges with their direction, from node `first` to node `last`.
struct Walk {
  std::vector<std::pair<int, bool>> steps;  // (edge, forward)
  int first = -1, last = -1;
};

// Step 3: pair the common edges at each node by straightness and follow the pairs.
std::vector<Walk> trace_trails(const Graph& g) {
  // partner[(edge, end)] = (edge, end) continuing it through the node; end 0 = from, 1 = to.
  std::map<std::pair<int, int>, std::pair<int, int>> partner;
  for (std::size_t v = 0; v < g.nodes.size(); ++v) {
    struct End {
      int edge, end;
      Vec2 dir;  // leaving the node
    };
    std::vector<End> ends;
    for (const int e : g.common[v]) {
      const Edge& ed = g.edges[static_cast<std::size_t>(e)];
      if (ed.from == static_cast<int>(v)) ends.push_back({e, 0, end_tangent(ed.path, false)});
      if (ed.to == static_cast<int>(v)) ends.push_back({e, 1, -end_tangent(ed.path, true)});
    }
    std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
    for (std::size_t a = 0; a < ends.size(); ++a)
      for (std::size_t b = a + 1; b < ends.size(); ++b)
        if (ends[a].edge != ends[b].edge) pairs.emplace_back(geometry::dot(ends[a].dir, ends[b].dir), a, b);
    std::sort(pairs.begin(), pairs.end());
    std::vector<char> used(ends.size(), 0);
    for (const auto& [d, a, b] : pairs) {
      if (used[a] || used[b]) continue;
      used[a] = used[b] = 1;
      partner[{ends[a].edge, ends[a].end}] = {ends[b].edge, ends[b].end};
      partner[{ends[b].edge, ends[b].end}] = {ends[a].edge, ends[a].end};
    }
  }
  std::vector<char> done(g.edges.size(), 0);
  std::vector<Walk> out;
  // From (edge, entering end): walk until an end without partner, or back to the first edge.
  const auto follow = [&](int edge, int enter_end) {
    Walk w;
    const Edge& e0 = g.edges[static_cast<std::size_t>(edge)];
    w.first = enter_end == 0 ? e0.from : e0.to;
    int e = edge, end = enter_end;
    while (true) {
      done[static_cast<std::size_t>(e)] = 1;
      w.steps.emplace_back(e, end == 0);
      const Edge& ed = g.edges[static_cast<std::size_t>(e)];
      const int exit_end = 1 - end;
      w.last = exit_end == 0 ? ed.from : ed.to;
      const auto it = partner.find({e, exit_end});
      if (it == partner.end() || done[static_cast<std::size_t>(it->second.first)]) break;
      e = it->second.first;
      end = it->second.second;
    }
    out.push_back(std::move(w));
  };
  for (std::size_t v = 0; v < g.nodes.size(); ++v)
    for (const int e : g.common[v]) {
      const Edge& ed = g.edges[static_cast<std::size_t>(e)];
      for (int end : {0, 1}) {
        if ((end == 0 ? ed.from : ed.to) != static_cast<int>(v)) continue;
        if (!done[static_cast<std::size_t>(e)] && !partner.count({e, end})) follow(e, end);
      }
    }
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    if (g.edges[e].stretch >= 0 && !done[e]) follow(static_cast<int>(e), 0);  // closed runs
  return out;
}

// Step 4: the own edges traced face by face, taking the tightest left turn at each node.
std::vector<Walk> trace_loops(const Graph& g) {
  std::vector<char> used(g.edges.size(), 0);
  std::vector<Walk> out;
  for (std::size_t start = 0; start < g.edges.size(); ++start) {
    if (g.edges[start].stretch >= 0 || used[start]) continue;
    Walk w;
    w.first = g.edges[start].from;
    int e = static_cast<int>(start);
    while (true) {
      used[static_cast<std::size_t>(e)] = 1;
      w.steps.emplace_back(e, true);
      const Edge& ed = g.edges[static_cast<std::size_t>(e)];
      w.last = ed.to;
      const Vec2 back = -end_tangent(ed.path, true);
      int best = -1;
      double best_cw = 0;
      for (const int o : g.out_own[static_cast<std::size_t>(ed.to)]) {
        if (used[static_cast<std::size_t>(o)] && o != static_cast<int>(start)) continue;
        double cw = kTwoPi - ccw_angle(back, end_tangent(g.edges[static_cast<std::size_t>(o)].path, false));
        if (cw <= 0) cw = kTwoPi;
        if (best < 0 || cw < best_cw) {
          best = o;
          best_cw = cw;
        }
      }
      if (best < 0 || best == static_cast<int>(start)) break;
      e = best;
    }
    out.push_back(std::move(w));
  }
  return out;
}

// The pieces of a walk: its edges, with connectors through the node positions where they do
// not meet (parts drawn kerf apart).
std::vector<CommonPiece> walk_pieces(const Graph& g, const Walk& w, const std::vector<CommonStretch>& stretches) {
  std::vector<CommonPiece> out;
  Vec2 at = g.nodes[static_cast<std::size_t>(w.first)];
  const auto connect = [&](Vec2 to) {
    if (geometry::distance(at, to) > tol::kSamePointMm) out.push_back({ContourId(), -1, Contour{{{at, 0}, {to, 0}}, false}, {}});
    at = to;
  };
  for (const auto& [e, fwd] : w.steps) {
    const Edge& ed = g.edges[static_cast<std::size_t>(e)];
    CommonPiece p;
    p.stretch = ed.stretch;
    p.contour = ed.stretch >= 0 ? stretches[static_cast<std::size_t>(ed.stretch)].first : ed.contour;
    if (ed.stretch >= 0) p.other = stretches[static_cast<std::size_t>(ed.stretch)].second;
    p.path = fwd ? ed.path : geometry::reversed(ed.path);
    connect(p.path.vertices.front().p);
    at = p.path.vertices.back().p;
    out.push_back(std::move(p));
    connect(g.nodes[static_cast<std::size_t>(fwd ? ed.to : ed.from)]);
  }
  return out;
}

Contour join(const std::vector<CommonPiece>& pieces, bool closed) {
  detail::PathJoiner j;
  for (const auto& p : pieces) j.append(p.path);
  return closed ? j.closed() : j.open();
}

// Does the kerf of the trails already cut this loop? At a T of parts drawn kerf apart the through
// part's edge across the stem's mouth (one kerf long) is a loop of its own, but it lies half a kerf
// from the through line's connector, whose kerf removes it. Cut as a loop it was narrower than the
// kerf: pierced and cut on its kerf offset inside the through part. Only short loops are measured:
// every point of their boundary pieces (sampled every kerf / 4) within kerf / 2 + tol of a trail.
// Short: an oblique mouth is kerf / sin(angle) wide (four such edges round an oblique X: 4.0 mm at
// kerf 1.5, over twice the kerf, and the loop was entered 0.42 mm inside a part), so up to eight
// kerfs. The reach allows 1 % of the kerf besides tol: where a straight gap meets a round part's
// arc, the connector is a chord short of the arc by a few µm (0.763 against 0.760 at kerf 1.5),
// and the loop, entered instead, was pierced inside the round part (0.92 mm deep).
bool cut_by_trails(const std::vector<CommonPiece>& pieces, const std::vector<Contour>& trails,
                   const geometry::StaticSpatialIndex& index, const CommonLineOptions& o) {
  if (!(o.kerf_mm > o.tol_mm)) return false;
  double own = 0;
  for (const auto& p : pieces)
    if (!p.connector()) own += geometry::length(p.path);
  if (own > 8 * (o.kerf_mm + o.tol_mm)) return false;
  const double reach = 0.5 * o.kerf_mm + std::max(o.tol_mm, 0.01 * o.kerf_mm);
  std::vector<std::uint32_t> near;
  for (const auto& p : pieces) {
    if (p.connector()) continue;
    const double len = geometry::length(p.path);
    const int n = std::max(1, static_cast<int>(std::ceil(len / (0.25 * o.kerf_mm))));
    for (int k = 0; k <= n; ++k) {
      const Vec2 q = geometry::point_at_length(p.path, len * k / n);
      index.query(geometry::Box{q.x, q.y, q.x, q.y}.inflated(reach), near);
      if (std::none_of(near.begin(), near.end(), [&](std::uint32_t t) { return geometry::distance(trails[t], q) <= reach; }))
        return false;
    }
  }
  return true;
}

// A point inside the segment's geometry, away from its nodes: the middle of its longest piece.
Vec2 sample_point(const Contour& c) {
  std::size_t best = 0;
  double best_len = -1;
  for (std::size_t i = 0; i < geometry::segment_count(c); ++i) {
    const double l = geometry::segment(c, i).length();
    if (l > best_len) {
      best_len = l;
      best = i;
    }
  }
  return geometry::segment(c, best).point_at(0.5);
}

// Step 5a: precedence by containment: each segment before the smallest closed segment around its
// sample point (and larger than it).
void containment_precedence(CommonLinePlan& plan) {
  const auto& segs = plan.segments;
  std::vector<geometry::Box> boxes(segs.size());
  std::vector<double> area(segs.size(), 0);
  for (std::size_t i = 0; i < segs.size(); ++i) {
    if (segs[i].kind == CommonSegmentKind::trail) continue;  // open: encloses nothing
    boxes[i] = geometry::bounding_box(segs[i].path);
    area[i] = std::abs(geometry::signed_area(segs[i].path));
  }
  const geometry::StaticSpatialIndex index(boxes);
  std::vector<std::uint32_t> hits;
  // Indexed outlines, built only for the segments that are asked (a spline outline of thousands of
  // arcs around hundreds of sample points would otherwise be walked whole for each).
  std::vector<std::optional<geometry::SegmentSet>> sets(segs.size());
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Vec2 p = sample_point(segs[i].path);
    geometry::Box b;
    b.add(p);
    index.query(b, hits);
    std::sort(hits.begin(), hits.end());
    int parent = -1;
    for (const auto h : hits) {
      // A container is larger than what it holds: with contours that cross or overlap (allowed
      // with a warning) each may hold a sample point of the other, and the order stays acyclic.
      if (h == i || area[h] <= area[i] || (parent >= 0 && area[h] >= area[static_cast<std::size_t>(parent)])) continue;
      if (!sets[h]) sets[h] = geometry::make_segment_set(segs[h].path);
      if (geometry::locate(*sets[h], p, tol::kSamePointMm) == geometry::Location::inside) parent = static_cast<int>(h);
    }
    if (parent >= 0) plan.precedence.emplace_back(static_cast<std::int32_t>(i), parent);
  }
}

}  // namespace

CommonLinePlan plan_common_lines(const Nest& nest, const CommonLineOptions& options) {
  CommonLinePlan plan;
  plan.stretches = find_common_stretches(nest, options);
  const Graph g = build_graph(nest, plan.stretches, options);

  // Step 1: groups of contours joined by stretches (numbered in order of their first contour).
  UnionFind groups(nest.contours.size());
  std::vector<char> shares(nest.contours.size(), 0);
  for (const auto& s : plan.stretches) {
    groups.unite(s.first.value(), s.second.value());
    shares[s.first.index()] = shares[s.second.index()] = 1;
    plan.shared_length_mm += s.length();
  }
  std::map<int, int> group_no;
  for (std::size_t i = 0; i < nest.contours.size(); ++i)
    if (shares[i] && !group_no.count(groups.find(static_cast<int>(i))))
      group_no.emplace(groups.find(static_cast<int>(i)), static_cast<int>(group_no.size()));
  plan.groups = static_cast<int>(group_no.size());
  const auto group_of = [&](ContourId c) { return group_no.at(groups.find(c.value())); };

  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    const ContourId id(static_cast<std::int32_t>(i));
    if (nest.contours[id].role == ContourRole::sheet || shares[i]) continue;
    CommonSegment s;
    s.path = nest.contours[id].source.contour;
    s.pieces = {CommonPiece{id, -1, detail::sub_path(s.path, 0, geometry::length(s.path)), {}}};
    s.contours = {id};
    plan.segments.push_back(std::move(s));
  }
  const auto finish = [](std::vector<ContourId>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  std::vector<Walk> trails = trace_trails(g);
  std::vector<Contour> trail_paths;
  std::vector<geometry::Box> trail_boxes;
  for (const Walk& w : trails) {
    trail_paths.push_back(join(walk_pieces(g, w, plan.stretches), false));
    trail_boxes.push_back(geometry::bounding_box(trail_paths.back()));
  }
  const geometry::StaticSpatialIndex trail_index(trail_boxes);
  std::vector<char> on_loop(g.nodes.size(), 0);  // the node lies on a loop that is cut
  for (const Walk& w : trace_loops(g)) {
    CommonSegment s;
    s.kind = CommonSegmentKind::loop;
    s.pieces = walk_pieces(g, w, plan.stretches);
    if (cut_by_trails(s.pieces, trail_paths, trail_index, options)) continue;
    for (const auto& st : w.steps) {
      const Edge& ed = g.edges[static_cast<std::size_t>(st.first)];
      on_loop[static_cast<std::size_t>(ed.from)] = on_loop[static_cast<std::size_t>(ed.to)] = 1;
    }
    s.path = join(s.pieces, true);
    if (w.last != w.first) {
      // Cannot happen when every contour is closed: each node has as many own edges in as out.
      plan.diagnostics.push_back(make_warning("common lines: a boundary near " +
                                              detail::point_text(g.nodes[static_cast<std::size_t>(w.last)], nest.unit) +
                                              " does not close; closed by a straight cut"));
      plan.diagnostics.back().code = "common.open_loop";
    }
    for (const auto& p : s.pieces)
      if (!p.connector()) s.contours.push_back(p.contour);
    finish(s.contours);
    s.group = group_of(s.contours.front());
    plan.segments.push_back(std::move(s));
  }
  const std::size_t first_trail = plan.segments.size();
  for (std::size_t t = 0; t < trails.size(); ++t) {
    const Walk& w = trails[t];
    CommonSegment s;
    s.kind = CommonSegmentKind::trail;
    s.pieces = walk_pieces(g, w, plan.stretches);
    s.path = std::move(trail_paths[t]);
    for (const auto& st : w.steps) {
      const auto& str = plan.stretches[static_cast<std::size_t>(g.edges[static_cast<std::size_t>(st.first)].stretch)];
      s.contours.push_back(str.first);
      s.contours.push_back(str.second);
      s.shared_mm += str.length();
    }
    finish(s.contours);
    s.group = group_of(s.contours.front());
    s.start_on_loop = on_loop[static_cast<std::size_t>(w.first)] != 0;
    s.end_on_loop = on_loop[static_cast<std::size_t>(w.last)] != 0;
    s.enter_at_start = s.start_on_loop;
    s.enter_at_end = s.end_on_loop;
    plan.segments.push_back(std::move(s));
  }
  containment_precedence(plan);

  // Step 5b: a trail with no end on a loop is entered at a junction with a trail that can be
  // entered (found in rounds, so that no cycle of such entries arises).
  std::vector<std::vector<std::size_t>> trails_at(g.nodes.size());
  for (std::size_t t = 0; t < trails.size(); ++t)
    for (const auto& st : trails[t].steps) {
      const Edge& ed = g.edges[static_cast<std::size_t>(st.first)];
      for (const int v : {ed.from, ed.to}) trails_at[static_cast<std::size_t>(v)].push_back(t);
    }
  const auto seg = [&](std::size_t t) -> CommonSegment& { return plan.segments[first_trail + t]; };
  const auto rooted = [&](std::size_t t) { return seg(t).enter_at_start || seg(t).enter_at_end; };
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t t = 0; t < trails.size(); ++t) {
      if (rooted(t)) continue;
      for (const int end : {0, 1}) {
        const int v = end == 0 ? trails[t].first : trails[t].last;
        const auto& at = trails_at[static_cast<std::size_t>(v)];
        const auto r = std::find_if(at.begin(), at.end(), [&](std::size_t o) { return o != t && rooted(o); });
        if (r == at.end()) continue;
        (end == 0 ? seg(t).enter_at_start : seg(t).enter_at_end) = true;
        seg(t).pierce_on_line = true;
        plan.precedence.emplace_back(static_cast<std::int32_t>(first_trail + *r), static_cast<std::int32_t>(first_trail + t));
        plan.diagnostics.push_back(make_warning("common line through " + detail::point_text(seg(t).path.vertices.front().p, nest.unit) +
                                                ": no end on the outer boundary of its group; pierced at the junction " +
                                                detail::point_text(g.nodes[static_cast<std::size_t>(v)], nest.unit) + " on a line cut before"));
        plan.diagnostics.back().code = "common.pierce_on_line";
        changed = true;
        break;
      }
    }
  }
  for (std::size_t t = 0; t < trails.size(); ++t) {
    if (rooted(t)) continue;
    seg(t).enter_at_start = true;
    seg(t).pierce_on_line = true;
    plan.diagnostics.push_back(make_warning("common line through " + detail::point_text(seg(t).path.vertices.front().p, nest.unit) +
                                            ": reaches neither the outer boundary nor another common line; pierced on the line"));
    plan.diagnostics.back().code = "common.pierce_on_line";
  }
  return plan;
}

}  // namespace cutroute::model
