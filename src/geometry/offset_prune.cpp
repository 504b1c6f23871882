// Invalid-loop removal of the kerf offset (step 3, see offset.hpp and offset_prune.hpp).
#include "geometry/offset_prune.hpp"
#include "geometry/offset_grid.hpp"

#include <algorithm>
#include <cstddef>
#include <numeric>

#include <cutroute/core/tolerances.hpp>

namespace cutroute::geometry::offset_detail {

namespace {

// A point where the path crosses itself, as a position along one of its pieces.
struct Split {
  std::size_t piece = 0;
  double t = 0.0;  // parameter on that piece, [0, 1]
  Vec2 p;          // the crossing point, shared by both pieces that cross there [mm]
};

// One part of the path between two consecutive splits.
struct Slice {
  std::vector<Piece> pieces;
  Vec2 start;
  Vec2 end;
};

bool adjacent_share(const std::vector<Piece>& path, std::size_t k, std::size_t l, Vec2 x) {
  const std::size_t n = path.size();
  if (l == k + 1 && distance(x, path[k].b) <= tol::kOffsetJoinMm) return true;
  if (k == 0 && l == n - 1 && distance(x, path[0].a) <= tol::kOffsetJoinMm) return true;
  return false;
}

// All self-crossings, in path order. Boxes sorted on xmin, so only overlapping pairs are tested.
std::vector<Split> find_splits(const std::vector<Piece>& path) {
  const std::size_t n = path.size();
  std::vector<Box> boxes(n);
  for (std::size_t i = 0; i < n; ++i) boxes[i] = box_of(path[i]).inflated(tol::kOffsetIntersectMm);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return boxes[x].xmin < boxes[y].xmin || (boxes[x].xmin == boxes[y].xmin && x < y);
  });

  std::vector<Split> splits;
  for (std::size_t ii = 0; ii < n; ++ii) {
    const std::size_t i = order[ii];
    for (std::size_t jj = ii + 1; jj < n; ++jj) {
      const std::size_t j = order[jj];
      if (boxes[j].xmin > boxes[i].xmax) break;
      if (!boxes[i].intersects(boxes[j])) continue;
      const std::size_t k = std::min(i, j);
      const std::size_t l = std::max(i, j);
      const Hits hits = intersect(path[k], path[l], tol::kOffsetIntersectMm);
      for (std::size_t h = 0; h < hits.count; ++h) {
        const Vec2 x = hits.points[h];
        if (adjacent_share(path, k, l, x)) continue;
        splits.push_back({k, std::clamp(param_of(path[k], x), 0.0, 1.0), x});
        splits.push_back({l, std::clamp(param_of(path[l], x), 0.0, 1.0), x});
      }
    }
  }
  std::sort(splits.begin(), splits.end(), [](const Split& x, const Split& y) {
    return x.piece < y.piece || (x.piece == y.piece && x.t < y.t);
  });
  // A crossing through a vertex is found on both pieces that meet there: keep one. Splits at
  // the same point with path between them (a loop closing there) are different splits.
  std::vector<double> start_of(n + 1, 0.0);  // arc length where each piece starts [mm]
  for (std::size_t i = 0; i < n; ++i) start_of[i + 1] = start_of[i] + length(path[i]);
  auto along = [&](const Split& s) { return start_of[s.piece] + s.t * length(path[s.piece]); };
  std::vector<Split> unique;
  for (const Split& s : splits)
    if (unique.empty() || along(s) - along(unique.back()) > tol::kOffsetJoinMm) unique.push_back(s);
  while (unique.size() > 1 && start_of[n] - along(unique.back()) + along(unique.front()) <= tol::kOffsetJoinMm)
    unique.pop_back();
  return unique;
}

void add_part(std::vector<Piece>& out, const Piece& p, double t0, double t1, Vec2 q0, Vec2 q1) {
  if ((t1 - t0) * length(p) > tol::kOffsetIntersectMm) out.push_back(sub_piece(p, t0, t1, q0, q1));
}

// The path from split `from` to split `to`, going forward; all the way round when whole.
Slice extract_slice(const std::vector<Piece>& path, const Split& from, const Split& to, bool whole) {
  Slice slice{{}, from.p, to.p};
  const std::size_t n = path.size();
  if (!whole && from.piece == to.piece && to.t > from.t) {
    add_part(slice.pieces, path[from.piece], from.t, to.t, from.p, to.p);
    return slice;
  }
  add_part(slice.pieces, path[from.piece], from.t, 1.0, from.p, path[from.piece].b);
  for (std::size_t k = (from.piece + 1) % n; k != to.piece; k = (k + 1) % n) slice.pieces.push_back(path[k]);
  add_part(slice.pieces, path[to.piece], 0.0, to.t, path[to.piece].a, to.p);
  return slice;
}

// Between two crossings the distance to the source stays on one side of |d|, so a few samples
// per piece decide; the crossing test catches slices that cut through the source itself.
// `near` holds the source boxes grown by |d|.
bool slice_is_valid(const Slice& slice, const std::vector<Piece>& source, const std::vector<Box>& source_boxes,
                    const BoxGrid& near, double abs_offset) {
  const double min_dist = abs_offset - tol::kOffsetGougeMm;
  for (const Piece& q : slice.pieces) {
    for (double t : {0.25, 0.5, 0.75}) {
      const Vec2 x = point_at(q, t);
      Box at;
      at.add(x);
      if (near.any_near(at, [&](std::size_t s) { return distance_to(source[s], x) < min_dist; })) return false;
    }
    const Box qb = box_of(q).inflated(tol::kOffsetIntersectMm);
    if (near.any_near(qb, [&](std::size_t s) {
          return qb.intersects(source_boxes[s]) && intersect(q, source[s], tol::kOffsetIntersectMm).count > 0;
        }))
      return false;
  }
  return true;
}

// Chains kept slices end to start. Each slice starts where another one ended (a crossing);
// a chain that cannot be closed is dropped. Starts are sorted on x so that finding the next
// slice is a binary search.
PrunedLoops stitch(std::vector<Slice> slices, bool removed) {
  PrunedLoops result;
  result.removed = removed;
  const double tol = tol::kSamePointMm;
  std::vector<std::size_t> by_x(slices.size());
  std::iota(by_x.begin(), by_x.end(), std::size_t{0});
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
    return slices[a].start.x < slices[b].start.x || (slices[a].start.x == slices[b].start.x && a < b);
  });
  std::vector<bool> used(slices.size(), false);
  auto next_from = [&](Vec2 end) {
    auto it = std::lower_bound(by_x.begin(), by_x.end(), end.x - tol,
                               [&](std::size_t s, double x) { return slices[s].start.x < x; });
    std::size_t best = slices.size();
    double best_dist = tol;
    for (; it != by_x.end() && slices[*it].start.x <= end.x + tol; ++it) {
      const double dist = distance(slices[*it].start, end);
      if (!used[*it] && dist <= best_dist) {
        best = *it;
        best_dist = dist;
      }
    }
    return best;
  };
  for (std::size_t first = 0; first < slices.size(); ++first) {
    if (used[first]) continue;
    used[first] = true;
    std::vector<Piece> loop = slices[first].pieces;
    const Vec2 start = slices[first].start;
    Vec2 end = slices[first].end;
    bool closed = false;
    for (std::size_t guard = 0; guard <= slices.size(); ++guard) {
      if (distance(end, start) <= tol) {
        closed = true;
        break;
      }
      const std::size_t best = next_from(end);
      if (best == slices.size()) break;
      used[best] = true;
      loop.insert(loop.end(), slices[best].pieces.begin(), slices[best].pieces.end());
      end = slices[best].end;
    }
    if (closed && !loop.empty()) {
      result.loops.push_back(std::move(loop));
    } else {
      result.removed = true;
    }
  }
  return result;
}

}  // namespace

PrunedLoops prune_invalid_loops(const std::vector<Piece>& path, const std::vector<Piece>& source,
                                double abs_offset) {
  if (path.empty()) return {};
  std::vector<Box> source_boxes(source.size());
  for (std::size_t s = 0; s < source.size(); ++s) source_boxes[s] = box_of(source[s]);
  const BoxGrid near(source_boxes, abs_offset);

  const std::vector<Split> splits = find_splits(path);
  std::vector<Slice> kept;
  bool removed = false;
  if (splits.empty()) {
    Slice whole{path, path.front().a, path.front().a};
    if (slice_is_valid(whole, source, source_boxes, near, abs_offset)) {
      kept.push_back(std::move(whole));
    } else {
      removed = true;
    }
    return stitch(std::move(kept), removed);
  }
  for (std::size_t i = 0; i < splits.size(); ++i) {
    Slice slice = extract_slice(path, splits[i], splits[(i + 1) % splits.size()], splits.size() == 1);
    if (slice.pieces.empty()) continue;
    if (slice_is_valid(slice, source, source_boxes, near, abs_offset)) {
      kept.push_back(std::move(slice));
    } else {
      removed = true;
    }
  }
  return stitch(std::move(kept), removed);
}

}  // namespace cutroute::geometry::offset_detail
