// chain_faces(): the face tracing described in chain_faces.hpp.
#include "chain_faces.hpp"
#include "chain_face_parts.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/spatial_index.hpp>

namespace cutroute::geometry::detail {

namespace {

constexpr std::int32_t kUnset = -1;
// A half-edge leaving a point: its direction and signed curvature there (left turns positive).
struct Leaving {
  double angle;
  double curvature;
  std::uint32_t half;
};

Leaving leaving(const Contour& c, std::uint32_t half, bool forward) {
  const Segment s = forward ? segment(c, 0) : segment(c, segment_count(c) - 1);
  Vec2 t = s.tangent_at(forward ? 0.0 : 1.0);
  double k = s.is_arc() ? (s.bulge > 0 ? 1.0 : -1.0) / s.radius() : 0.0;
  if (!forward) {
    t = t * -1.0;
    k = -k;
  }
  return {std::atan2(t.y, t.x), k, half};
}

// Sorts the half-edges leaving one point counter-clockwise (cyclic order). Directions within
// kSameDirection of each other are one direction, ordered by curvature (right turns first): a line
// tangent to an arc at the point leaves at the same angle but for rounding (1e-16), which must not
// decide which comes first. False when two leave along the same curve (overlapping edges: the
// order is unknown).
bool order_around(std::vector<Leaving>& list) {
  constexpr double kSameDirection = 1e-9;  // [rad]
  constexpr double kTurn = 2 * std::numbers::pi;
  if (list.size() < 2) return true;
  std::sort(list.begin(), list.end(), [](const Leaving& a, const Leaving& b) { return std::tie(a.angle, a.half) < std::tie(b.angle, b.half); });
  // Start after a real gap, so that no bundle of one direction wraps around -pi / pi.
  const std::size_t m = list.size();
  std::size_t start = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const double prev = i == 0 ? list[m - 1].angle - kTurn : list[i - 1].angle;
    if (list[i].angle - prev > kSameDirection) {
      start = i;
      break;
    }
    if (i + 1 == m) return false;  // every direction the same: all overlap
  }
  std::rotate(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(start), list.end());
  for (std::size_t i = 0; i < m;) {
    std::size_t j = i + 1;
    auto unwrapped = [&](std::size_t k) { return list[k].angle + (k >= m - start ? kTurn : 0.0); };
    while (j < m && unwrapped(j) - unwrapped(j - 1) <= kSameDirection) ++j;
    std::sort(list.begin() + static_cast<std::ptrdiff_t>(i), list.begin() + static_cast<std::ptrdiff_t>(j),
              [](const Leaving& a, const Leaving& b) { return std::tie(a.curvature, a.half) < std::tie(b.curvature, b.half); });
    for (std::size_t k = i + 1; k < j; ++k) {
      if (std::abs(list[k].curvature - list[k - 1].curvature) < 1e-9) return false;
    }
    i = j;
  }
  return true;
}

// A piece, or the stretch of a piece between two points where other pieces end on it.
struct Sub {
  std::int32_t owned;    // its path in Tracer::owned_ (a cut piece's stretch), or -1: the piece's
  std::uint32_t parent;  // index into `open`
};

// A connected group of stretches: their indices and points.
struct Group {
  std::vector<std::uint32_t> subs;
  std::vector<Vec2> points;
  bool usable = true;
};

// A stretch of a face boundary drawn by one piece (consecutive stretches of a piece merged).
struct Run {
  Contour path;  // open, in the face's direction
  std::uint32_t piece;
  bool along;  // runs in the direction the piece was drawn
};

class Tracer {
 public:
  Tracer(const std::vector<ChainPiece>& pieces, const std::vector<std::uint32_t>& open,
         const std::vector<std::vector<std::uint32_t>>& copies, const std::vector<std::uint8_t>& meeting, double snap)
      : pieces_(pieces), open_(open), copies_(copies), snap_(snap) {
    const std::size_t n = open.size();
    // Pieces that may belong to parts drawn edge to edge: one with an exact copy, or with an end
    // where other than two ends meet (a corner of three or four parts, a T, a free end). A clean
    // drawing has none and costs nothing more here.
    suspect_.assign(n, 0);
    bool any = false;
    for (std::size_t k = 0; k < n; ++k) {
      suspect_[k] = !copies[k].empty() || meeting[2 * k] != 2 || meeting[2 * k + 1] != 2;
      any = any || suspect_[k];
    }
    if (!any) return;
    grid_ = make_grid(2 * n, snap, [&](std::size_t e) { return end_point(path(static_cast<std::uint32_t>(e / 2)), e); });
    if (split()) grid_ = make_grid(2 * subs_.size(), snap, [&](std::size_t e) { return end_pos(e); });
    point_of_.assign(2 * subs_.size(), kUnset);
    end_serial_.assign(2 * subs_.size(), 0);
    in_group_.assign(subs_.size(), 0);
  }

  void run(FaceChains& out) {
    out.taken.assign(open_.size(), 0);
    for (std::uint32_t s = 0; s < subs_.size(); ++s) {
      const std::uint32_t k = subs_[s].parent;
      if (in_group_[s] || !(suspect_[k] || subs_of_[k].size() > 1)) continue;
      Group g = collect(s);
      if (g.usable) trace(g, out);
    }
  }

 private:
  const Contour& path(std::uint32_t k) const { return pieces_[open_[k]].path; }
  const Contour& sub_path(std::uint32_t s) const {
    return subs_[s].owned >= 0 ? owned_[static_cast<std::size_t>(subs_[s].owned)] : path(subs_[s].parent);
  }
  std::int32_t layer(std::uint32_t sub) const { return pieces_[open_[subs_[sub].parent]].group; }
  Vec2 end_pos(std::size_t e) const { return end_point(sub_path(static_cast<std::uint32_t>(e / 2)), e); }
  std::size_t point(std::uint32_t sub, bool end) const { return static_cast<std::size_t>(point_of_[2 * sub + end]); }

  // Cuts each single line or arc where another piece of its layer ends on it, away from its
  // ends: there the pieces of two neighbours meet a longer edge of a third (a T), and the
  // stretches on either side can then be told apart. A cut point is the other piece's end. Only
  // pieces joined to a suspect (through points, or a T found on the way) are looked at: the
  // others are never traced. Widens the suspects to them; returns whether any piece was cut (the
  // stretch of a piece not cut is the piece itself, with the piece's index).
  bool split() {
    const std::size_t n = open_.size();
    std::vector<Box> boxes(n);
    for (std::size_t k = 0; k < n; ++k) {
      if (segment_count(path(static_cast<std::uint32_t>(k))) == 1)
        boxes[k] = segment(path(static_cast<std::uint32_t>(k)), 0).bounding_box().inflated(snap_);
    }
    const StaticSpatialIndex index(boxes);
    std::vector<std::vector<std::pair<double, Vec2>>> cuts(n);
    bool any = false;
    std::vector<std::uint32_t> queue;
    for (std::uint32_t k = 0; k < n; ++k) {
      if (suspect_[k]) queue.push_back(k);
    }
    auto reach = [&](std::uint32_t k) {
      if (!suspect_[k]) {
        suspect_[k] = 1;
        queue.push_back(k);
      }
    };
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::uint32_t own = queue[q];
      const std::int32_t group = pieces_[open_[own]].group;
      for (std::size_t e = 2 * own; e <= 2 * own + 1; ++e) {
        const Vec2 p = end_point(path(own), e);
        grid_.for_near(p, [&](std::uint32_t f) {
          if (pieces_[open_[f / 2]].group == group && norm2(end_point(path(f / 2), f) - p) <= snap_ * snap_) reach(f / 2);
        });
        index.visit(Box{p.x, p.y, p.x, p.y}, [&](std::uint32_t k) {
          if (k == own || pieces_[open_[k]].group != group) return true;
          const Segment s = segment(path(k), 0);
          const SegmentClosest c = closest_point(s, p);
          if (c.distance <= snap_ && c.length_along > snap_ && c.length_along < s.length() - snap_) {
            cuts[k].emplace_back(c.length_along, p);
            any = true;
            reach(k);
          }
          return true;
        });
      }
    }
    subs_of_.resize(n);
    subs_.reserve(n);
    for (std::uint32_t k = 0; k < n; ++k) {
      auto& at = cuts[k];
      if (!any || at.empty()) {
        subs_of_[k].push_back(static_cast<std::uint32_t>(subs_.size()));
        subs_.push_back({-1, k});
        continue;
      }
      std::sort(at.begin(), at.end(), [](const auto& a, const auto& b) {
        return std::tie(a.first, a.second.x, a.second.y) < std::tie(b.first, b.second.x, b.second.y);
      });
      const Segment s = segment(path(k), 0);
      const double length = s.length(), sweep = s.sweep();
      double from = 0;
      Vec2 start = s.a;
      auto add = [&](double to, Vec2 end) {
        const double bulge = s.is_arc() ? std::tan(sweep * (to - from) / length / 4) : 0.0;
        subs_of_[k].push_back(static_cast<std::uint32_t>(subs_.size()));
        subs_.push_back({static_cast<std::int32_t>(owned_.size()), k});
        owned_.push_back(Contour{{{start, bulge}, {end, 0.0}}, false});
        from = to;
        start = end;
      };
      for (const auto& [along, p] : at) {
        if (along - from > snap_) add(along, p);
      }
      add(length, s.b);
    }
    return any;
  }

  // Breadth-first over stretches joined at points (ends within snap of each other, same layer).
  Group collect(std::uint32_t start) {
    Group g;
    ++serial_;
    std::vector<std::uint32_t> queue{start};
    in_group_[start] = 1;
    std::vector<std::uint32_t> cluster;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::uint32_t s = queue[q];
      g.subs.push_back(s);
      for (std::uint32_t e = 2 * s; e <= 2 * s + 1; ++e) {
        if (point_of_[e] != kUnset) continue;
        const auto id = static_cast<std::int32_t>(g.points.size());
        cluster.assign(1, e);
        point_of_[e] = id;
        end_serial_[e] = serial_;
        for (std::size_t c = 0; c < cluster.size(); ++c) {
          const Vec2 p = end_pos(cluster[c]);
          const bool calm = grid_.for_near(p, [&](std::uint32_t f) {
            if (layer(f / 2) != layer(s) || !(norm2(end_pos(f) - p) <= snap_ * snap_)) return;
            if (point_of_[f] != kUnset) {
              // Met through an end that a crowded cell hid from an earlier group, or joined to
              // another point of this one: the points are not what they seem.
              if (point_of_[f] != id || end_serial_[f] != serial_) g.usable = false;
              return;
            }
            point_of_[f] = id;
            end_serial_[f] = serial_;
            cluster.push_back(f);
          });
          if (!calm) g.usable = false;
        }
        // Offsets from the first end, so that coincident ends keep their exact position.
        const Vec2 origin = end_pos(cluster.front());
        Vec2 offset{0, 0};
        for (std::uint32_t f : cluster) offset = offset + (end_pos(f) - origin);
        const Vec2 mean = origin + offset * (1.0 / static_cast<double>(cluster.size()));
        for (std::uint32_t f : cluster) {
          if (!(norm2(end_pos(f) - mean) <= snap_ * snap_)) g.usable = false;
          if (!in_group_[f / 2]) {
            in_group_[f / 2] = 1;
            queue.push_back(f / 2);
          }
        }
        g.points.push_back(mean);
      }
    }
    return g;
  }

  // Stretches between the same two points along the same curve (exact copies, or the halves
  // of a long edge that two neighbours draw) are one edge, drawn once per stretch and copy.
  std::vector<Edge> edges_of(const Group& g) const {
    std::vector<std::uint32_t> subs = g.subs;
    auto key = [&](std::uint32_t s) {
      const std::size_t a = point(s, false), b = point(s, true);
      return std::pair<std::size_t, std::size_t>(std::min(a, b), std::max(a, b));
    };
    std::sort(subs.begin(), subs.end(), [&](std::uint32_t a, std::uint32_t b) {
      return std::pair(key(a), a) < std::pair(key(b), b);
    });
    std::vector<Edge> edges;
    for (std::size_t i = 0; i < subs.size();) {
      std::size_t j = i;
      while (j < subs.size() && key(subs[j]) == key(subs[i])) ++j;
      const std::size_t first_edge = edges.size();
      for (std::size_t x = i; x < j; ++x) {
        const std::uint32_t s = subs[x];
        const Contour& c = sub_path(s);
        const Vec2 mid = point_at_length(c, length(c) / 2);
        Edge* same = nullptr;
        for (std::size_t e = first_edge; e < edges.size() && same == nullptr; ++e) {
          const Contour& r = sub_path(edges[e].rep);
          if (norm2(point_at_length(r, length(r) / 2) - mid) <= snap_ * snap_) same = &edges[e];
        }
        if (same == nullptr) {
          edges.emplace_back();
          same = &edges.back();
          same->rep = s;
        }
        const std::uint32_t k = subs_[s].parent;
        same->drawings.push_back({s, open_[k]});
        for (std::uint32_t copy : copies_[k]) same->drawings.push_back({s, copy});
      }
      i = j;
    }
    for (Edge& e : edges) {
      std::sort(e.drawings.begin(), e.drawings.end(),
                [](const Drawing& a, const Drawing& b) { return std::tie(a.piece, a.sub) < std::tie(b.piece, b.sub); });
    }
    return edges;
  }

  void trace(const Group& g, FaceChains& out) {
    std::vector<Edge> edges = edges_of(g);
    const std::size_t n = edges.size();
    // Half-edge 2i runs along edge i's stretch `rep` in its direction, 2i + 1 against it.
    auto tail = [&](std::uint32_t h) { return point(edges[h / 2].rep, (h & 1) != 0); };
    auto head = [&](std::uint32_t h) { return tail(h ^ 1u); };
    std::vector<std::size_t> degree(g.points.size(), 0);
    for (const Edge& e : edges) {
      if (e.drawings.size() > 3 || point(e.rep, false) == point(e.rep, true)) return;
      degree[point(e.rep, false)] += e.drawings.size();
      degree[point(e.rep, true)] += e.drawings.size();
    }
    bool junction = false;
    for (std::size_t d : degree) {
      if (d % 2 != 0) return;
      junction = junction || d > 2;
    }
    if (!junction) return;

    std::vector<std::vector<Leaving>> around(g.points.size());
    for (std::uint32_t h = 0; h < 2 * n; ++h) around[tail(h)].push_back(leaving(sub_path(edges[h / 2].rep), h, (h & 1) == 0));
    std::vector<std::uint32_t> slot(2 * n);
    for (auto& list : around) {
      if (!order_around(list)) return;
      for (std::size_t i = 0; i < list.size(); ++i) slot[list[i].half] = static_cast<std::uint32_t>(i);
    }
    // The next half-edge of a face: at its head, the one just clockwise of the way back. Faces
    // then have their inside on the left: bounded faces run counter-clockwise, the outside clockwise.
    auto next = [&](std::uint32_t h) {
      const auto& list = around[head(h)];
      const std::size_t j = slot[h ^ 1u];
      return list[(j + list.size() - 1) % list.size()].half;
    };
    std::vector<std::int32_t> face_of(2 * n, kUnset);
    std::vector<std::vector<std::uint32_t>> faces;
    for (std::uint32_t h0 = 0; h0 < 2 * n; ++h0) {
      if (face_of[h0] != kUnset) continue;
      faces.emplace_back();
      for (std::uint32_t h = h0; face_of[h] == kUnset; h = next(h)) {
        face_of[h] = static_cast<std::int32_t>(faces.size() - 1);
        faces.back().push_back(h);
      }
      if (next(faces.back().back()) != h0) return;
    }
    std::int32_t outside = kUnset;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      Contour c;
      c.closed = true;
      for (std::uint32_t h : faces[f]) {
        const Contour& p = sub_path(edges[h / 2].rep);
        append(c, (h & 1) ? reversed(p) : p, g.points[tail(h)]);
      }
      const double area = signed_area(c);
      if (area < 0 && outside == kUnset) {
        outside = static_cast<std::int32_t>(f);
      } else if (!(area > snap_ * snap_)) {
        return;
      }
    }
    if (outside == kUnset) return;

    std::vector<std::int8_t> part = parts_of(edges, face_of, faces.size(), static_cast<std::size_t>(outside));
    if (part.empty()) part = parts_without_repeats(edges, face_of, faces, static_cast<std::size_t>(outside));
    if (part.empty()) return;
    // A part whose boundary passes a point twice touches itself: leave that to the end pairing.
    std::vector<std::uint32_t> seen(g.points.size(), 0);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (part[f] == 0) continue;
      for (std::uint32_t h : faces[f]) {
        if (seen[tail(h)] == f + 1) return;
        seen[tail(h)] = static_cast<std::uint32_t>(f + 1);
      }
    }

    // Which part drew which drawing of a shared edge is not in the drawing; parts are usually
    // drawn one after the other, so the first drawing goes to the part whose other edges were
    // drawn nearer to it in the file.
    std::vector<double> mean_index(faces.size(), 0.0);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      for (std::uint32_t h : faces[f]) mean_index[f] += edges[h / 2].drawings.front().piece;
      mean_index[f] /= static_cast<double>(faces[f].size());
    }
    std::vector<Drawing> drawing_of(2 * n);  // for the half-edges of parts
    for (std::size_t i = 0; i < n; ++i) {
      const auto& d = edges[i].drawings;
      const std::size_t a = static_cast<std::size_t>(face_of[2 * i]), b = static_cast<std::size_t>(face_of[2 * i + 1]);
      if (d.size() == 1) {
        drawing_of[part[a] == 1 ? 2 * i : 2 * i + 1] = d[0];
        continue;
      }
      const double p = d[0].piece, q = d[1].piece;
      const bool swap = std::abs(p - mean_index[b]) + std::abs(q - mean_index[a]) <
                        std::abs(p - mean_index[a]) + std::abs(q - mean_index[b]);
      drawing_of[2 * i] = d[swap ? 1 : 0];
      drawing_of[2 * i + 1] = d[swap ? 0 : 1];
    }
    own_cut_pieces(edges, face_of, part, drawing_of);

    // The pieces drawn into contours, to count the copies used (a list: a table over all pieces
    // per group would cost pieces x groups).
    std::vector<std::uint32_t> used;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (part[f] != 1) continue;
      emit(g, edges, faces[f], drawing_of, out);
      for (std::uint32_t h : faces[f]) used.push_back(drawing_of[h].piece);
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    for (std::uint32_t s : g.subs) {
      const std::uint32_t k = subs_[s].parent;
      if (out.taken[k]) continue;  // a cut piece's stretches come one by one
      out.taken[k] = 1;
      for (std::uint32_t copy : copies_[k]) out.copies_used += std::binary_search(used.begin(), used.end(), copy) ? 1 : 0;
    }
  }

  // A piece cut into stretches (the long edge of a T) is one part's edge: on one side all its
  // stretches border that part, on the other its neighbours. Its stretches go to that side, so
  // the part's contour keeps the piece whole instead of taking a neighbour's drawing of a stretch.
  void own_cut_pieces(const std::vector<Edge>& edges, const std::vector<std::int32_t>& face_of,
                      const std::vector<std::int8_t>& part, std::vector<Drawing>& drawing_of) const {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> by_parent;  // (parent, edge) per stretch
    for (std::uint32_t e = 0; e < edges.size(); ++e) {
      for (const Drawing& d : edges[e].drawings) {
        if (d.piece == open_[subs_[d.sub].parent] && subs_of_[subs_[d.sub].parent].size() > 1)
          by_parent.emplace_back(subs_[d.sub].parent, e);
      }
    }
    std::sort(by_parent.begin(), by_parent.end());
    // The half-edge of edge e on the given side of piece k's direction (0: its left).
    auto half_on = [&](std::uint32_t k, std::uint32_t e, int side) {
      std::uint32_t sub = 0;
      for (const Drawing& d : edges[e].drawings) {
        if (d.piece == open_[k]) sub = d.sub;
      }
      const bool same = point(sub, false) == point(edges[e].rep, false);
      return 2 * e + ((side == 0) == same ? 0u : 1u);
    };
    for (std::size_t i = 0; i < by_parent.size();) {
      std::size_t j = i;
      while (j < by_parent.size() && by_parent[j].first == by_parent[i].first) ++j;
      const std::uint32_t k = by_parent[i].first;
      int owner = -1;
      for (int side = 0; side < 2; ++side) {
        const std::int32_t f = face_of[half_on(k, by_parent[i].second, side)];
        bool one_face = part[static_cast<std::size_t>(f)] == 1;
        for (std::size_t x = i; x < j; ++x) one_face = one_face && face_of[half_on(k, by_parent[x].second, side)] == f;
        if (one_face) owner = owner == -1 ? side : 2;  // 2: both sides, undecided
      }
      if (owner == 0 || owner == 1) {
        for (std::size_t x = i; x < j; ++x) {
          const std::uint32_t e = by_parent[x].second;
          const std::uint32_t h = half_on(k, e, owner);
          if (edges[e].drawings.size() == 2 && drawing_of[h].piece != open_[k]) std::swap(drawing_of[h], drawing_of[h ^ 1u]);
        }
      }
      i = j;
    }
  }

  // Appends path p to c without its last vertex, its first vertex moved to `at`.
  static void append(Contour& c, const Contour& p, Vec2 at) {
    const std::size_t first = c.vertices.size();
    c.vertices.insert(c.vertices.end(), p.vertices.begin(), p.vertices.end() - 1);
    c.vertices[first].p = at;
  }

  // A part's face as a contour in chain_contours()'s conventions: one vertex per corner (the
  // stretches of one piece merged back), starting at its lowest-index piece, travelled in that
  // piece's direction.
  void emit(const Group& g, const std::vector<Edge>& edges, const std::vector<std::uint32_t>& face,
            const std::vector<Drawing>& drawing_of, FaceChains& out) const {
    // Stretches in the face's direction, each from the point where the face enters it.
    struct Step {
      Contour path;
      Drawing d;
      bool forward;  // along the stretch's own (its piece's) direction
    };
    std::vector<Step> steps;
    for (std::uint32_t h : face) {
      const Drawing d = drawing_of[h];
      const std::size_t from = point(edges[h / 2].rep, (h & 1) != 0);
      const bool forward = point(d.sub, false) == from;
      Step st{forward ? sub_path(d.sub) : reversed(sub_path(d.sub)), d, forward};
      st.path.vertices.front().p = g.points[from];
      st.path.vertices.back().p = g.points[point(d.sub, forward)];
      steps.push_back(std::move(st));
    }
    auto joins = [&](const Step& a, const Step& b) {
      return a.d.piece == b.d.piece && subs_[a.d.sub].parent == subs_[b.d.sub].parent && a.forward == b.forward &&
             segment_count(a.path) == 1 && segment_count(b.path) == 1;
    };
    // Start at the beginning of a run of one piece. A face made of one piece's stretches only (an
    // arc closing on itself, cut where another piece ends on it) keeps them apart.
    std::size_t begin = 0;
    while (begin < steps.size() && joins(steps[(begin + steps.size() - 1) % steps.size()], steps[begin])) ++begin;
    const bool merge = begin < steps.size();
    if (!merge) begin = 0;
    std::rotate(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(begin), steps.end());
    std::vector<Run> runs;
    for (std::size_t i = 0; i < steps.size();) {
      std::size_t j = i + 1;
      double sweep = steps[i].path.vertices.front().bulge == 0 ? 0 : segment(steps[i].path, 0).sweep();
      while (merge && j < steps.size() && joins(steps[j - 1], steps[j])) {
        sweep += steps[j].path.vertices.front().bulge == 0 ? 0 : segment(steps[j].path, 0).sweep();
        ++j;
      }
      Run r;
      r.piece = steps[i].d.piece;
      if (j == i + 1) {
        r.path = steps[i].path;
      } else {
        r.path = Contour{{{steps[i].path.vertices.front().p, sweep == 0 ? 0.0 : std::tan(sweep / 4)},
                          {steps[j - 1].path.vertices.back().p, 0.0}},
                         false};
      }
      const std::uint32_t k = subs_[steps[i].d.sub].parent;
      const bool same_start = r.piece == open_[k] || pieces_[r.piece].path.vertices.front().p == path(k).vertices.front().p;
      r.along = steps[i].forward == same_start;
      runs.push_back(std::move(r));
      i = j;
    }
    auto lowest = [&] {
      return std::min_element(runs.begin(), runs.end(), [](const Run& a, const Run& b) { return a.piece < b.piece; });
    };
    std::rotate(runs.begin(), lowest(), runs.end());
    if (!runs.front().along) {
      std::reverse(runs.begin(), runs.end());
      for (Run& r : runs) {
        r.path = reversed(r.path);
        r.along = !r.along;
      }
      std::rotate(runs.begin(), lowest(), runs.end());
    }
    ChainedContour c;
    c.group = layer(steps.front().d.sub);
    c.contour.closed = true;
    for (const Run& r : runs) {
      append(c.contour, r.path, r.path.vertices.front().p);
      c.sources.push_back(pieces_[r.piece].source);
    }
    out.first_piece.push_back(runs.front().piece);
    out.contours.push_back(std::move(c));
  }

  const std::vector<ChainPiece>& pieces_;
  const std::vector<std::uint32_t>& open_;
  const std::vector<std::vector<std::uint32_t>>& copies_;
  double snap_;
  std::vector<char> suspect_;                        // per piece of `open`
  std::vector<Sub> subs_;
  std::vector<Contour> owned_;                       // the stretches of cut pieces
  std::vector<std::vector<std::uint32_t>> subs_of_;  // per piece of `open`: its stretches in order
  EndGrid grid_;
  std::vector<std::int32_t> point_of_;      // per end of a stretch: its point in the group being collected
  std::vector<std::uint32_t> end_serial_;   // per end: serial of the group that gave it a point
  std::vector<char> in_group_;              // per stretch: already collected
  std::uint32_t serial_ = 0;
};

}  // namespace

FaceChains chain_faces(const std::vector<ChainPiece>& pieces, const std::vector<std::uint32_t>& open,
                       const std::vector<std::vector<std::uint32_t>>& copies, const std::vector<std::uint8_t>& meeting,
                       double snap) {
  FaceChains out;
  Tracer(pieces, open, copies, meeting, snap).run(out);
  return out;
}

}  // namespace cutroute::geometry::detail
