// chain_faces(): the face tracing described in chain_faces.hpp.
#include "chain_faces.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

namespace cutroute::geometry::detail {

namespace {

constexpr std::int32_t kUnset = -1;
// More ends than this in one snap cell is a crowd (a fan of lines), not a corner of parts.
constexpr std::size_t kMaxEndsPerCell = 64;

// The ends of all open pieces in a grid of cell `snap`, to find the ends that meet an end.
struct EndGrid {
  struct Cell {
    std::int64_t ix, iy;
    std::uint32_t end;
  };
  std::vector<Cell> cells;
  double snap;

  // Calls f(end) for the ends in the 3 × 3 cells around p; false when a cell is crowded.
  template <class F>
  bool for_near(Vec2 p, F&& f) const {
    const std::int64_t ix = cell_of(p.x, snap), iy = cell_of(p.y, snap);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const Cell key{ix + dx, iy + dy, 0};
        auto less = [](const Cell& a, const Cell& b) { return std::tie(a.ix, a.iy) < std::tie(b.ix, b.iy); };
        const auto [lo, hi] = std::equal_range(cells.begin(), cells.end(), key, less);
        if (static_cast<std::size_t>(hi - lo) > kMaxEndsPerCell) return false;
        for (auto it = lo; it != hi; ++it) f(it->end);
      }
    }
    return true;
  }
};

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

// One connected group of pieces: its pieces (indices into `open`) and points.
struct Group {
  std::vector<std::uint32_t> pieces;
  std::vector<Vec2> points;
  bool usable = true;
};

class Tracer {
 public:
  Tracer(const std::vector<ChainPiece>& pieces, const std::vector<std::uint32_t>& open,
         const std::vector<std::vector<std::uint32_t>>& copies, double snap)
      : pieces_(pieces), open_(open), copies_(copies), snap_(snap), point_of_(2 * open.size(), kUnset),
        in_group_(open.size(), 0), end_serial_(2 * open.size(), 0) {
    grid_.snap = snap;
    grid_.cells.resize(2 * open.size());
    for (std::size_t e = 0; e < 2 * open.size(); ++e) {
      const Vec2 p = end_pos(e);
      grid_.cells[e] = {cell_of(p.x, snap), cell_of(p.y, snap), static_cast<std::uint32_t>(e)};
    }
    std::sort(grid_.cells.begin(), grid_.cells.end(), [](const EndGrid::Cell& a, const EndGrid::Cell& b) {
      return std::tie(a.ix, a.iy, a.end) < std::tie(b.ix, b.iy, b.end);
    });
  }

  void run(FaceChains& out) {
    out.taken.assign(open_.size(), 0);
    for (std::size_t k = 0; k < open_.size(); ++k) {
      if (copies_[k].empty() || in_group_[k]) continue;
      Group g = collect(static_cast<std::uint32_t>(k));
      if (g.usable) trace(g, out);
    }
  }

 private:
  const Contour& path(std::uint32_t k) const { return pieces_[open_[k]].path; }
  std::int32_t group_id(std::uint32_t k) const { return pieces_[open_[k]].group; }
  Vec2 end_pos(std::size_t e) const { return end_point(path(static_cast<std::uint32_t>(e / 2)), e); }

  // Breadth-first over pieces joined at points (ends within snap of each other, same layer).
  Group collect(std::uint32_t start) {
    Group g;
    ++serial_;
    std::vector<std::uint32_t> queue{start};
    in_group_[start] = 1;
    std::vector<std::uint32_t> cluster;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::uint32_t k = queue[q];
      g.pieces.push_back(k);
      for (std::uint32_t e = 2 * k; e <= 2 * k + 1; ++e) {
        if (point_of_[e] != kUnset) continue;
        const auto id = static_cast<std::int32_t>(g.points.size());
        cluster.assign(1, e);
        point_of_[e] = id;
        end_serial_[e] = serial_;
        for (std::size_t c = 0; c < cluster.size(); ++c) {
          const Vec2 p = end_pos(cluster[c]);
          const bool calm = grid_.for_near(p, [&](std::uint32_t f) {
            if (group_id(f / 2) != group_id(k) || !(norm2(end_pos(f) - p) <= snap_ * snap_)) return;
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

  std::size_t times_drawn(std::uint32_t k) const { return 1 + copies_[k].size(); }

  void trace(const Group& g, FaceChains& out) {
    const std::size_t n = g.pieces.size();
    // Degrees count each drawing of an edge.
    std::vector<std::size_t> degree(g.points.size(), 0);
    for (std::uint32_t k : g.pieces) {
      if (times_drawn(k) > 2 || point_of_[2 * k] == point_of_[2 * k + 1]) return;
      degree[static_cast<std::size_t>(point_of_[2 * k])] += times_drawn(k);
      degree[static_cast<std::size_t>(point_of_[2 * k + 1])] += times_drawn(k);
    }
    bool junction = false;
    for (std::size_t d : degree) {
      if (d % 2 != 0) return;
      junction = junction || d > 2;
    }
    if (!junction) return;

    // Half-edge 2i runs along piece g.pieces[i] in its direction, 2i + 1 against it.
    auto tail = [&](std::uint32_t h) { return static_cast<std::size_t>(point_of_[2 * g.pieces[h / 2] + (h & 1)]); };
    auto head = [&](std::uint32_t h) { return tail(h ^ 1u); };
    std::vector<std::vector<Leaving>> around(g.points.size());
    for (std::uint32_t h = 0; h < 2 * n; ++h) around[tail(h)].push_back(leaving(path(g.pieces[h / 2]), h, (h & 1) == 0));
    std::vector<std::uint32_t> slot(2 * n);
    for (auto& list : around) {
      std::sort(list.begin(), list.end(), [](const Leaving& a, const Leaving& b) {
        return std::tie(a.angle, a.curvature, a.half) < std::tie(b.angle, b.curvature, b.half);
      });
      for (std::size_t i = 0; i < list.size(); ++i) {
        const Leaving& a = list[i];
        const Leaving& b = list[(i + 1) % list.size()];
        double gap = std::abs(b.angle - a.angle);
        gap = std::min(gap, 2 * std::numbers::pi - gap);
        // Two pieces leaving along one curve overlap: the order around the point is unknown.
        if (gap < 1e-9 && std::abs(b.curvature - a.curvature) < 1e-9) return;
        slot[a.half] = static_cast<std::uint32_t>(i);
      }
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
      if (faces.back().front() != h0 || next(faces.back().back()) != h0) return;
    }
    std::int32_t outside = kUnset;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const double area = signed_area(face_contour(g, faces[f]));
      if (area < 0 && outside == kUnset) {
        outside = static_cast<std::int32_t>(f);
      } else if (!(area > snap_ * snap_)) {
        return;
      }
    }
    if (outside == kUnset) return;

    // Which faces are parts: an edge drawn twice has a part on both sides, an edge drawn once on
    // exactly one; the outside is scrap. The faces form one connected dual graph, so the
    // outside and the twice-drawn edges fix every face.
    std::vector<std::int8_t> part(faces.size(), -1);
    part[static_cast<std::size_t>(outside)] = 0;
    std::vector<std::vector<std::size_t>> across(faces.size());
    std::vector<std::size_t> queue{static_cast<std::size_t>(outside)};
    for (std::size_t i = 0; i < n; ++i) {
      const auto a = static_cast<std::size_t>(face_of[2 * i]), b = static_cast<std::size_t>(face_of[2 * i + 1]);
      if (a == b) return;
      if (times_drawn(g.pieces[i]) == 2) {
        for (std::size_t f : {a, b}) {
          if (part[f] == 0) return;
          if (part[f] == -1) queue.push_back(f);
          part[f] = 1;
        }
      } else {
        across[a].push_back(b);
        across[b].push_back(a);
      }
    }
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::size_t f = queue[q];
      for (std::size_t o : across[f]) {
        if (part[o] == -1) {
          part[o] = static_cast<std::int8_t>(1 - part[f]);
          queue.push_back(o);
        } else if (part[o] == part[f]) {
          return;
        }
      }
    }
    // A part whose boundary passes a point twice touches itself: leave that to the end pairing.
    std::vector<std::uint32_t> seen(g.points.size(), 0);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (part[f] == -1) return;
      if (part[f] == 0) continue;
      for (std::uint32_t h : faces[f]) {
        if (seen[tail(h)] == f + 1) return;
        seen[tail(h)] = static_cast<std::uint32_t>(f + 1);
      }
    }

    // Which part drew which copy is not in the drawing; parts are usually drawn one after the
    // other, so each copy goes to the part whose other entities lie nearer to it in the file.
    std::vector<double> mean_index(faces.size(), 0.0);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      for (std::uint32_t h : faces[f]) mean_index[f] += open_[g.pieces[h / 2]];
      mean_index[f] /= static_cast<double>(faces[f].size());
    }
    std::vector<char> swapped(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t k = g.pieces[i];
      if (copies_[k].empty()) continue;
      const double p = open_[k], q = copies_[k].front();
      const double a = mean_index[static_cast<std::size_t>(face_of[2 * i])];
      const double b = mean_index[static_cast<std::size_t>(face_of[2 * i + 1])];
      swapped[i] = std::abs(p - b) + std::abs(q - a) < std::abs(p - a) + std::abs(q - b);
    }
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (part[f] == 1) emit(g, faces[f], swapped, out);
    }
    for (std::uint32_t k : g.pieces) {
      out.taken[k] = 1;
      if (times_drawn(k) == 2) ++out.copies_used;
    }
  }

  Contour face_contour(const Group& g, const std::vector<std::uint32_t>& face) const {
    Contour c;
    c.closed = true;
    for (std::uint32_t h : face) {
      const Contour& p = path(g.pieces[h / 2]);
      const Contour piece = (h & 1) ? reversed(p) : p;
      const std::size_t first = c.vertices.size();
      c.vertices.insert(c.vertices.end(), piece.vertices.begin(), piece.vertices.end() - 1);
      c.vertices[first].p = g.points[static_cast<std::size_t>(point_of_[2 * g.pieces[h / 2] + (h & 1)])];
    }
    return c;
  }

  // A part's face as a contour in chain_contours()'s conventions: it starts at its lowest-index
  // piece, travelled in that piece's direction. An edge drawn twice gives its first drawing to the
  // face that runs along it and its copy to the face that runs against it, or the other way
  // round where `swapped`.
  void emit(const Group& g, std::vector<std::uint32_t> face, const std::vector<char>& swapped, FaceChains& out) const {
    // The drawing (piece index) each half-edge of the face takes, fixed before any reversal.
    std::vector<std::uint32_t> drawn(face.size());
    for (std::size_t i = 0; i < face.size(); ++i) {
      const std::uint32_t h = face[i], k = g.pieces[h / 2];
      const bool copy = !copies_[k].empty() && ((h & 1) != 0) != (swapped[h / 2] != 0);
      drawn[i] = copy ? copies_[k].front() : open_[k];
    }
    const auto lowest = std::min_element(drawn.begin(), drawn.end()) - drawn.begin();
    std::rotate(face.begin(), face.begin() + lowest, face.end());
    std::rotate(drawn.begin(), drawn.begin() + lowest, drawn.end());
    // Whether the face runs along its first drawing as drawn (a copy may be drawn reversed).
    const std::uint32_t k0 = g.pieces[face.front() / 2];
    const bool same_start = drawn.front() == open_[k0] || pieces_[drawn.front()].path.vertices.front().p == path(k0).vertices.front().p;
    if (((face.front() & 1) == 0) != same_start) {
      std::reverse(face.begin(), face.end());
      std::reverse(drawn.begin(), drawn.end());
      for (std::uint32_t& h : face) h ^= 1u;  // the same pieces, run the other way
      std::rotate(face.begin(), face.end() - 1, face.end());
      std::rotate(drawn.begin(), drawn.end() - 1, drawn.end());
    }
    ChainedContour c;
    c.group = group_id(k0);
    c.contour = face_contour(g, face);
    for (std::uint32_t piece : drawn) c.sources.push_back(pieces_[piece].source);
    out.first_piece.push_back(drawn.front());
    out.contours.push_back(std::move(c));
  }

  const std::vector<ChainPiece>& pieces_;
  const std::vector<std::uint32_t>& open_;
  const std::vector<std::vector<std::uint32_t>>& copies_;
  double snap_;
  EndGrid grid_;
  std::vector<std::int32_t> point_of_;  // per end: its point in the group being collected
  std::vector<char> in_group_;          // per piece: already collected
  std::vector<std::uint32_t> end_serial_;  // per end: serial of the group that gave it a point
  std::uint32_t serial_ = 0;
};

}  // namespace

FaceChains chain_faces(const std::vector<ChainPiece>& pieces, const std::vector<std::uint32_t>& open,
                       const std::vector<std::vector<std::uint32_t>>& copies, double snap) {
  FaceChains out;
  Tracer(pieces, open, copies, snap).run(out);
  return out;
}

}  // namespace cutroute::geometry::detail
