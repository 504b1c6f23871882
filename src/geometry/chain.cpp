// chain_contours(): the steps listed in chain.hpp, one function each.
#include <cutroute/geometry/chain.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <numeric>
#include <tuple>
#include <utility>

#include <cutroute/core/tolerances.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>

#include "chain_faces.hpp"

namespace cutroute::geometry {

namespace {

constexpr std::int32_t kNone = -1;

// Open pieces this close to another at every vertex and midpoint are copies of it [mm]: above the
// rounding with which another program writes a copy (1e-9 .. 1e-6 mm), far below the snap. At the
// snap itself, two outlines drawn 0.01 mm apart lost edges to each other (fuzzing, session 49).
constexpr double kNearCopyMm = 1e-4;


bool finite_path(const Contour& c) {
  for (const Vertex& v : c.vertices) {
    if (!is_finite(v.p) || std::isnan(v.bulge)) return false;
  }
  return true;
}

// --- step 1: sort pieces into closed pass-throughs, dropped pieces and open pieces to chain ---

struct Sorted {
  std::vector<std::uint32_t> closed;  // indices into pieces
  std::vector<std::uint32_t> open;
};

Sorted classify(const std::vector<ChainPiece>& pieces, ChainResult& result) {
  Sorted s;
  for (std::uint32_t i = 0; i < pieces.size(); ++i) {
    const Contour& c = pieces[i].path;
    if (!finite_path(c)) {
      ++result.dropped_invalid;
      continue;
    }
    if (segment_count(c) == 0 || !(length(c) >= tol::kSamePointMm)) {
      ++result.dropped_zero_length;
      continue;
    }
    (c.closed ? s.closed : s.open).push_back(i);
  }
  return s;
}

// --- step 2: exact duplicates (same vertices in either direction, same group) ---

// Vertex i of a piece read forwards or backwards, with the bulge that leaves it in that
// direction (0 for the last vertex of an open path), -0.0 folded into +0.0.
Vertex canonical_vertex(const Contour& c, std::size_t i, bool backwards) {
  const std::size_t n = c.vertices.size();
  Vertex v;
  if (!backwards) {
    v = c.vertices[i];
    if (!c.closed && i + 1 == n) v.bulge = 0.0;
  } else if (c.closed) {
    v.p = c.vertices[i == 0 ? 0 : n - i].p;
    v.bulge = -c.vertices[n - 1 - i].bulge;
  } else {
    v.p = c.vertices[n - 1 - i].p;
    v.bulge = i + 1 < n ? -c.vertices[n - 2 - i].bulge : 0.0;
  }
  v.p.x += 0.0;
  v.p.y += 0.0;
  v.bulge += 0.0;
  return v;
}

int compare_vertex(const Vertex& a, const Vertex& b) {
  if (a.p.x != b.p.x) return a.p.x < b.p.x ? -1 : 1;
  if (a.p.y != b.p.y) return a.p.y < b.p.y ? -1 : 1;
  if (a.bulge != b.bulge) return a.bulge < b.bulge ? -1 : 1;
  return 0;
}

// The direction in which the piece reads lexicographically smaller: both copies of a
// duplicated piece read the same in their canonical directions.
bool canonical_backwards(const Contour& c) {
  for (std::size_t i = 0; i < c.vertices.size(); ++i) {
    const int k = compare_vertex(canonical_vertex(c, i, false), canonical_vertex(c, i, true));
    if (k != 0) return k > 0;
  }
  return false;
}

std::uint64_t mix(std::uint64_t h, double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  h ^= bits + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  return h * 0xBF58476D1CE4E5B9ull;
}

bool same_canonical(const Contour& a, bool a_back, const Contour& b, bool b_back) {
  if (a.closed != b.closed || a.vertices.size() != b.vertices.size()) return false;
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    if (compare_vertex(canonical_vertex(a, i, a_back), canonical_vertex(b, i, b_back)) != 0) return false;
  }
  return true;
}

// Removes later copies from `ids` (input order kept); returns how many were removed. With
// `copies`, lists each removed piece under the index into `ids` of the piece it repeats.
std::size_t drop_duplicates(const std::vector<ChainPiece>& pieces, std::vector<std::uint32_t>& ids,
                            std::vector<std::vector<std::uint32_t>>* copies = nullptr) {
  struct Key {
    std::int32_t group;
    std::uint64_t hash;
    std::uint32_t id;
    bool backwards;
  };
  std::vector<Key> keys;
  keys.reserve(ids.size());
  for (std::uint32_t id : ids) {
    const Contour& c = pieces[id].path;
    const bool back = canonical_backwards(c);
    std::uint64_t h = c.closed ? 1 : 2;
    for (std::size_t i = 0; i < c.vertices.size(); ++i) {
      const Vertex v = canonical_vertex(c, i, back);
      h = mix(mix(mix(h, v.p.x), v.p.y), v.bulge);
    }
    keys.push_back({pieces[id].group, h, id, back});
  }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    return std::tie(a.group, a.hash, a.id) < std::tie(b.group, b.hash, b.id);
  });
  std::vector<char> dropped(pieces.size(), 0);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> copy_of;  // (kept, copy) piece indices
  std::size_t count = 0;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j].group == keys[i].group && keys[j].hash == keys[i].hash) ++j;
    for (std::size_t x = i; x < j; ++x) {
      if (dropped[keys[x].id]) continue;
      for (std::size_t y = x + 1; y < j; ++y) {
        if (dropped[keys[y].id]) continue;
        if (same_canonical(pieces[keys[x].id].path, keys[x].backwards, pieces[keys[y].id].path, keys[y].backwards)) {
          dropped[keys[y].id] = 1;
          copy_of.emplace_back(keys[x].id, keys[y].id);
          ++count;
        }
      }
    }
    i = j;
  }
  std::erase_if(ids, [&](std::uint32_t id) { return dropped[id] != 0; });
  if (copies != nullptr) {
    copies->assign(ids.size(), {});
    std::sort(copy_of.begin(), copy_of.end());
    for (const auto& [kept, copy] : copy_of) {
      const auto at = std::lower_bound(ids.begin(), ids.end(), kept) - ids.begin();
      (*copies)[static_cast<std::size_t>(at)].push_back(copy);
    }
  }
  return count;
}

// Does open piece b repeat a within tol, vertex for vertex and segment midpoint for midpoint, in
// either direction?
bool near_copy(const Contour& a, const Contour& b, double tol) {
  if (a.closed || b.closed || a.vertices.size() != b.vertices.size()) return false;
  const std::size_t n = segment_count(a);
  for (const bool back : {false, true}) {
    const Contour& other = back ? reversed(b) : b;
    bool same = true;
    for (std::size_t i = 0; i < n && same; ++i) {
      const Segment x = segment(a, i), y = segment(other, i);
      same = distance(x.a, y.a) <= tol && distance(x.b, y.b) <= tol && distance(x.point_at(0.5), y.point_at(0.5)) <= tol;
    }
    if (same) return true;
  }
  return false;
}

// Open pieces repeating an earlier one within `tol` (kNearCopyMm: a copy written with other
// rounding, 1e-9 mm off): dropped as copies, like the exact repeats. Left in, the copy's ends, nearer to the
// original's than to the neighbours', took them as partners and the part lost its edge (fuzzing,
// session 49). Found through a grid (cell tol) of the kept pieces' end points.
std::size_t drop_near_copies(const std::vector<ChainPiece>& pieces, std::vector<std::uint32_t>& ids,
                             std::vector<std::vector<std::uint32_t>>& copies, double tol) {
  const auto cell = [tol](Vec2 p) {
    return std::pair<std::int64_t, std::int64_t>{detail::cell_of(p.x, tol), detail::cell_of(p.y, tol)};
  };
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>> kept_at;  // cell -> positions in ids
  std::vector<std::int64_t> keeper(ids.size(), -1);
  std::size_t count = 0;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const ChainPiece& piece = pieces[ids[k]];
    const Contour& c = piece.path;
    const auto [cx, cy] = cell(c.vertices.front().p);
    for (std::int64_t dx = -1; dx <= 1 && keeper[k] < 0; ++dx)
      for (std::int64_t dy = -1; dy <= 1 && keeper[k] < 0; ++dy) {
        const auto it = kept_at.find({cx + dx, cy + dy});
        if (it == kept_at.end()) continue;
        for (const std::size_t j : it->second)
          if (pieces[ids[j]].group == piece.group && near_copy(pieces[ids[j]].path, c, tol)) {
            keeper[k] = static_cast<std::int64_t>(j);
            break;
          }
      }
    if (keeper[k] >= 0) {
      ++count;
      continue;
    }
    kept_at[cell(c.vertices.front().p)].push_back(k);
    if (cell(c.vertices.back().p) != cell(c.vertices.front().p)) kept_at[cell(c.vertices.back().p)].push_back(k);
  }
  if (count == 0) return 0;
  std::vector<std::uint32_t> kept_ids;
  std::vector<std::vector<std::uint32_t>> kept_copies;
  std::vector<std::size_t> new_index(ids.size(), 0);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (keeper[k] >= 0) continue;
    new_index[k] = kept_ids.size();
    kept_ids.push_back(ids[k]);
    kept_copies.push_back(std::move(copies[k]));
  }
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (keeper[k] < 0) continue;
    auto& list = kept_copies[new_index[static_cast<std::size_t>(keeper[k])]];
    list.push_back(ids[k]);
    list.insert(list.end(), copies[k].begin(), copies[k].end());
  }
  ids = std::move(kept_ids);
  copies = std::move(kept_copies);
  return count;
}

// --- step 3: match end points, nearest pairs first (step 4 is chain_faces.cpp) ---

// Can an open path close on itself? A single straight line cannot (its ends meet only if it has
// no length); two segments or an arc can.
bool can_close_alone(const Contour& c) { return segment_count(c) >= 2 || segment(c, 0).is_arc(); }

using detail::end_point;

// Why a grid and not nanoflann: the search radius is fixed (the snap), so a uniform grid with
// cell = snap answers each query from 3×3 cells; sorted cell keys make it deterministic and
// allocation-light, where a k-d tree would add a build and still need its results re-sorted.
// With `meeting`: per end, how many ends (itself included, capped at 255) lie within snap of it,
// for step 4, which looks only where other than two meet.
std::vector<std::int32_t> match_ends(const std::vector<ChainPiece>& pieces, const std::vector<std::uint32_t>& open,
                                     double snap, std::vector<std::uint8_t>* meeting = nullptr) {
  const std::size_t n_ends = 2 * open.size();
  if (meeting != nullptr) meeting->assign(n_ends, 1);
  std::vector<Vec2> pos(n_ends);
  for (std::size_t e = 0; e < n_ends; ++e) pos[e] = end_point(pieces[open[e / 2]].path, e);
  const std::vector<detail::EndGrid::Cell> cells = detail::make_grid(n_ends, snap, [&](std::size_t e) { return pos[e]; }).cells;

  struct Candidate {
    double dist;
    std::uint32_t e, f;
  };
  std::vector<Candidate> cand;
  cand.reserve(2 * n_ends);
  auto may_close_alone = [&](std::size_t k) { return can_close_alone(pieces[open[k]].path); };
  // Each end offers only its kMaxPartners nearest ends: where hundreds of ends crowd into one
  // snap circle (a fan of lines from one point) the pair list stays linear in memory; such an
  // end can then only miss a partner that is farther than kMaxPartners others.
  constexpr std::size_t kMaxPartners = 8;
  const double snap2 = snap * snap;
  // Equal distances (ends at one point) are broken by closeness in the sorted grid order, so
  // that a crowd of coincident ends offers different partners to different ends and pairs up.
  std::vector<std::uint32_t> rank(n_ends);
  for (std::size_t r = 0; r < n_ends; ++r) rank[cells[r].end] = static_cast<std::uint32_t>(r);
  struct Near {
    Candidate c;
    std::uint32_t rank_gap;
  };
  std::vector<Near> near;
  std::vector<std::int32_t> group_of(n_ends);
  for (std::size_t e = 0; e < n_ends; ++e) group_of[e] = pieces[open[e / 2]].group;
  // Ends visited in grid order: the first cell of each of the 3 neighbouring columns' 3-cell
  // windows then only moves forward, so three cursors replace binary searches (linear time,
  // cache friendly).
  std::size_t cursor[3] = {0, 0, 0};
  for (std::size_t r = 0; r < n_ends; ++r) {
    const std::size_t e = cells[r].end;
    const std::int64_t ix = cells[r].ix, iy = cells[r].iy;
    const std::int32_t group = group_of[e];
    near.clear();
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      std::size_t& k = cursor[dx + 1];
      const std::int64_t want_x = ix + dx, want_y = iy - 1;
      while (k < n_ends && (cells[k].ix < want_x || (cells[k].ix == want_x && cells[k].iy < want_y))) ++k;
      for (std::size_t it = k; it < n_ends && cells[it].ix == ix + dx && cells[it].iy <= iy + 1; ++it) {
        const std::uint32_t f = cells[it].end;
        if (f == e) continue;
        if (group_of[f] != group) continue;
        if (f / 2 == e / 2 && !may_close_alone(e / 2)) continue;
        const double d2 = norm2(pos[f] - pos[e]);
        if (!(d2 <= snap2)) continue;
        const double d = std::sqrt(d2);
        const std::uint32_t gap = rank[f] > rank[e] ? rank[f] - rank[e] : rank[e] - rank[f];
        near.push_back({{d, static_cast<std::uint32_t>(std::min<std::size_t>(e, f)),
                         static_cast<std::uint32_t>(std::max<std::size_t>(e, f))},
                        gap});
      }
    }
    if (meeting != nullptr) (*meeting)[e] = static_cast<std::uint8_t>(std::min<std::size_t>(near.size() + 1, 255));
    if (near.size() > kMaxPartners) {
      std::partial_sort(near.begin(), near.begin() + kMaxPartners, near.end(), [](const Near& a, const Near& b) {
        return std::tie(a.c.dist, a.rank_gap, a.c.e, a.c.f) < std::tie(b.c.dist, b.rank_gap, b.c.e, b.c.f);
      });
      near.resize(kMaxPartners);
    }
    for (const Near& n : near) cand.push_back(n.c);
  }
  std::sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.dist, a.e, a.f) < std::tie(b.dist, b.e, b.f);
  });
  // Both ends of a pair usually offer it.
  cand.erase(std::unique(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) { return a.e == b.e && a.f == b.f; }),
             cand.end());
  std::vector<std::int32_t> partner(n_ends, kNone);
  for (const Candidate& c : cand) {
    if (partner[c.e] != kNone || partner[c.f] != kNone) continue;
    partner[c.e] = static_cast<std::int32_t>(c.f);
    partner[c.f] = static_cast<std::int32_t>(c.e);
  }
  return partner;
}

// --- step 5: walk the matched ends into chains, snapping each joint to its midpoint ---

// One arc that closes on itself (an ARC of 359.9°, a one-bulge polyline): as one vertex it would be
// a loop of no length, and the hole it draws would be left out of the nest. It is the circle round
// the arc's centre through the joint, in two halves. An arc whose ends meet because it is tiny
// (r = 0.003 mm, 110°, in a hatch of d2g_Frontplatte) stays a loop of no length, left out.
bool closes_round(const Segment& arc) { return arc.is_arc() && std::abs(arc.sweep()) > std::numbers::pi; }

Contour circle_through(const Segment& arc, Vec2 joint) {
  const Vec2 c = arc.center();
  const double turn = arc.bulge < 0 ? -1.0 : 1.0;
  return Contour{{{joint, turn}, {c * 2.0 - joint, turn}}, true};
}

struct Walker {
  const std::vector<ChainPiece>& pieces;
  const std::vector<std::uint32_t>& open;
  const std::vector<std::int32_t>& partner;
  // Step 7 walks chains, not entities: a piece's source is then an index into these lists,
  // whose entities the walk takes over (reversed when it enters the chain at its end).
  const std::vector<std::vector<std::int32_t>>* source_lists = nullptr;

  Vec2 end_pos(std::size_t e) const { return end_point(pieces[open[e / 2]].path, e); }
  // Where end e ends up: the midpoint with its partner, or where it is when unmatched.
  Vec2 snapped(std::size_t e) const {
    const std::int32_t f = partner[e];
    return f == kNone ? end_pos(e) : (end_pos(e) + end_pos(static_cast<std::size_t>(f))) * 0.5;
  }

  // Appends piece k entered at end e_in (its start when even), without its last vertex.
  void append(ChainedContour& out, std::size_t e_in) const {
    const std::size_t k = e_in / 2;
    const ChainPiece& piece = pieces[open[k]];
    const Contour path = (e_in & 1) ? reversed(piece.path) : piece.path;
    const std::size_t first = out.contour.vertices.size();
    out.contour.vertices.insert(out.contour.vertices.end(), path.vertices.begin(), path.vertices.end() - 1);
    out.contour.vertices[first].p = snapped(e_in);
    if (source_lists == nullptr) {
      out.sources.push_back(piece.source);
    } else {
      const auto& list = (*source_lists)[static_cast<std::size_t>(piece.source)];
      if (e_in & 1) out.sources.insert(out.sources.end(), list.rbegin(), list.rend());
      else out.sources.insert(out.sources.end(), list.begin(), list.end());
    }
  }

  ChainedContour walk(std::size_t first_piece, std::size_t e_start, bool cycle) const {
    ChainedContour out;
    out.group = pieces[open[first_piece]].group;
    std::size_t e_in = e_start;
    for (;;) {
      append(out, e_in);
      const std::size_t e_out = e_in ^ 1;
      const std::int32_t next = partner[e_out];
      if (next == kNone) {
        out.contour.vertices.push_back({snapped(e_out), 0.0});
        break;
      }
      if (static_cast<std::size_t>(next) / 2 == first_piece && cycle) break;
      e_in = static_cast<std::size_t>(next);
    }
    out.contour.closed = cycle;
    const Segment arc = segment(pieces[open[first_piece]].path, 0);
    if (cycle && out.contour.vertices.size() == 1 && closes_round(arc))
      out.contour.vertices = circle_through(arc, out.contour.vertices[0].p).vertices;
    return out;
  }
};

// Every piece once: chains found from their free end (or from their lowest piece when they close),
// handed to emit(lowest piece, closed?, chain) in order of their lowest piece.
template <class Emit>
void walk_chains(const Walker& walker, Emit&& emit) {
  const auto& partner = walker.partner;
  const std::size_t count = walker.open.size();
  std::vector<char> used(count, 0);
  for (std::size_t k = 0; k < count; ++k) {
    if (used[k]) continue;
    // Walk backwards from k's start to find the chain's free end, or come back round to k.
    std::size_t e = 2 * k;
    bool cycle = false;
    for (;;) {
      const std::int32_t f = partner[e];
      if (f == kNone) break;
      if (static_cast<std::size_t>(f) / 2 == k) {
        cycle = true;
        break;
      }
      e = static_cast<std::size_t>(f) ^ 1;  // the other end of the previous piece
    }
    ChainedContour chain = cycle ? walker.walk(k, 2 * k, true) : walker.walk(e / 2, e, false);
    // Mark the pieces used: they are exactly the chain's pieces (sources are unique per piece
    // only for the caller, so walk the partner links again instead of trusting them).
    std::size_t e_in = cycle ? 2 * k : e;
    const std::size_t first = e_in / 2;
    for (;;) {
      used[e_in / 2] = 1;
      const std::int32_t next = partner[e_in ^ 1];
      if (next == kNone || static_cast<std::size_t>(next) / 2 == first) break;
      e_in = static_cast<std::size_t>(next);
    }
    emit(k, cycle, std::move(chain));
  }
}

// --- step 6: open chains that only repeat closed contours ---

// An open chain that lies wholly on closed contours of its group (a LINE drawn again over an edge
// of a closed polyline) is a repeat, like an exact duplicate: it would only be reported as an
// open path not cut. Tested at its vertices and at the quarter points of its segments, within
// tol::kCollinearMm (a repeat drawn by the same program is exact).
// A closed contour's segments are indexed (SegmentSet) the first time a point is tested against
// it: strokes drawn inside a long outline (marks inside a spline part) each asked all of its
// segments (5 000 strokes in a 20 000-segment outline: 1.9 s, now 0.1 s).
void drop_repeated_strokes(ChainResult& result) {
  if (result.open.empty() || result.closed.empty()) return;
  std::vector<Box> boxes;
  boxes.reserve(result.closed.size());
  for (const ChainedContour& c : result.closed) boxes.push_back(bounding_box(c.contour).inflated(tol::kCollinearMm));
  const StaticSpatialIndex index(boxes);
  std::vector<std::unique_ptr<SegmentSet>> sets(result.closed.size());
  auto on_closed = [&](Vec2 p, std::int32_t group) {
    bool on = false;
    index.visit(Box{p.x, p.y, p.x, p.y}, [&](std::uint32_t k) {
      if (result.closed[k].group != group) return true;
      if (!sets[k]) sets[k] = std::make_unique<SegmentSet>(make_segment_set(result.closed[k].contour));
      sets[k]->index.visit(Box{p.x, p.y, p.x, p.y}.inflated(tol::kCollinearMm), [&](std::uint32_t i) {
        on = closest_point(sets[k]->segments[i], p).distance <= tol::kCollinearMm;
        return !on;
      });
      return !on;
    });
    return on;
  };
  std::erase_if(result.open, [&](const ChainedContour& chain) {
    for (std::size_t i = 0; i < segment_count(chain.contour); ++i) {
      const Segment s = segment(chain.contour, i);
      for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        if (!on_closed(s.point_at(t), chain.group)) return false;
      }
    }
    result.dropped_duplicates += chain.sources.size();
    return true;
  });
}

// --- step 7: gaps in the drawing ---

// The ends still free after steps 3-6 paired again within gap_mm, nearest first, as in step 3, and
// the chains so linked walked into longer chains, closed ones among the closed contours (after
// the others, in order of their lowest chain). A second pass rather than a wider snap: parts drawn
// edge to edge (step 4) and repeated strokes (step 6) are still told at the snap, and every joint
// made across a gap is listed for a warning, where a wider snap would move ends unsaid.
constexpr double kSliverGaps = 2.0;

// Is the closed loop c thinner (mean width 2 area / length) than kSliverGaps joints of gap_mm?
bool is_sliver(const Contour& c, double gap_mm) { return 2 * std::abs(signed_area(c)) < kSliverGaps * gap_mm * length(c); }

// Would the open path c, closed by a straight joint, be such a loop?
bool sliver_if_closed(const Contour& c, double gap_mm) {
  Contour loop = c;
  loop.closed = true;
  loop.vertices.back().bulge = 0;
  return is_sliver(loop, gap_mm);
}

void close_gaps(ChainResult& result, double gap_mm) {
  if (result.open.empty()) return;
  std::vector<ChainPiece> chains;
  std::vector<std::vector<std::int32_t>> lists;
  chains.reserve(result.open.size());
  lists.reserve(result.open.size());
  for (std::size_t i = 0; i < result.open.size(); ++i) {
    ChainedContour& c = result.open[i];
    chains.push_back({std::move(c.contour), static_cast<std::int32_t>(i), c.group});
    lists.push_back(std::move(c.sources));
  }
  std::vector<std::uint32_t> ids(chains.size());
  std::iota(ids.begin(), ids.end(), std::uint32_t{0});
  // A chain whose own ends lie within the gap closes on itself first: the end of a bend line or of
  // a neighbour's gap that happens to lie nearer must not take one of them, leaving the outline
  // open (or joining two outlines into one figure).
  std::vector<std::int32_t> partner(2 * chains.size(), kNone);
  std::vector<std::uint32_t> rest;
  for (std::uint32_t k = 0; k < chains.size(); ++k) {
    const Contour& c = chains[k].path;
    if (can_close_alone(c) && distance(c.vertices.front().p, c.vertices.back().p) <= gap_mm && !sliver_if_closed(c, gap_mm)) {
      partner[2 * k] = static_cast<std::int32_t>(2 * k + 1);
      partner[2 * k + 1] = static_cast<std::int32_t>(2 * k);
    } else {
      rest.push_back(k);
    }
  }
  const std::vector<std::int32_t> among_rest = match_ends(chains, rest, gap_mm);
  for (std::size_t e = 0; e < among_rest.size(); ++e) {
    if (among_rest[e] == kNone) continue;
    const auto f = static_cast<std::size_t>(among_rest[e]);
    partner[2 * rest[e / 2] + (e & 1)] = static_cast<std::int32_t>(2 * rest[f / 2] + (f & 1));
  }
  // A mark drawn as a V or there and back, whose open ends lie close, would close into a sliver
  // and be cut as a slit through the part it marks: a loop whose mean width (2 area / length) is
  // within a few gap widths is no drawn outline, and its joints are undone.
  std::vector<std::size_t> slivers;
  {
    Walker probe{chains, ids, partner};
    walk_chains(probe, [&](std::size_t k, bool cycle, const ChainedContour& chain) {
      if (cycle && is_sliver(chain.contour, gap_mm)) slivers.push_back(k);
    });
  }
  for (const std::size_t k : slivers) {
    std::size_t e_in = 2 * k;
    for (;;) {
      const std::int32_t next = partner[e_in ^ 1];
      partner[e_in ^ 1] = kNone;
      partner[static_cast<std::size_t>(next)] = kNone;
      if (static_cast<std::size_t>(next) / 2 == k) break;
      e_in = static_cast<std::size_t>(next);
    }
  }
  for (std::size_t e = 0; e < partner.size(); ++e) {
    const std::int32_t f = partner[e];
    if (f == kNone || static_cast<std::size_t>(f) < e) continue;
    const Vec2 a = end_point(chains[e / 2].path, e), b = end_point(chains[static_cast<std::size_t>(f) / 2].path, static_cast<std::size_t>(f));
    auto end_source = [&](std::size_t end) {
      const auto& list = lists[end / 2];
      return (end & 1) ? list.back() : list.front();
    };
    result.gaps_closed.push_back({(a + b) * 0.5, distance(a, b), end_source(e), end_source(static_cast<std::size_t>(f)), chains[e / 2].group, a, b});
  }
  result.open.clear();
  Walker walker{chains, ids, partner};
  walker.source_lists = &lists;
  walk_chains(walker, [&](std::size_t, bool cycle, ChainedContour chain) {
    (cycle ? result.closed : result.open).push_back(std::move(chain));
  });
}

// --- step 8: how near the chains left open are to closing ---

void measure_open_ends(ChainResult& result) {
  const std::size_t n_ends = 2 * result.open.size();
  if (n_ends == 0) return;
  std::vector<Vec2> pos(n_ends);
  for (std::size_t e = 0; e < n_ends; ++e) pos[e] = end_point(result.open[e / 2].contour, e);
  const detail::EndGrid grid = detail::make_grid(n_ends, kGapHintMm, [&](std::size_t e) { return pos[e]; });
  for (std::size_t k = 0; k < result.open.size(); ++k) {
    ChainedContour& chain = result.open[k];
    bool may_close_alone = can_close_alone(chain.contour);
    // Not when step 7 would refuse that loop as a sliver (a V-shaped mark).
    if (may_close_alone)
      may_close_alone = !sliver_if_closed(
          chain.contour, std::max(distance(chain.contour.vertices.front().p, chain.contour.vertices.back().p), tol::kSamePointMm));
    double best = -1;
    for (const std::size_t e : {2 * k, 2 * k + 1}) {
      // A crowded cell (a fan of strokes) gives no hint rather than a slow one.
      grid.for_near(pos[e], [&](std::uint32_t f) {
        if (f == e || result.open[f / 2].group != chain.group) return;
        if (f / 2 == k && !may_close_alone) return;
        const double d = distance(pos[e], pos[f]);
        if (d <= kGapHintMm && (best < 0 || d < best)) best = d;
      });
    }
    chain.nearest_end_mm = best;
  }
}

ChainResult chain_once(const std::vector<ChainPiece>& pieces, double snap_mm, double gap_mm) {
  ChainResult result;
  Sorted sorted = classify(pieces, result);
  result.dropped_duplicates += drop_duplicates(pieces, sorted.closed);
  std::vector<std::vector<std::uint32_t>> copies;
  std::size_t open_copies = drop_duplicates(pieces, sorted.open, &copies);
  open_copies += drop_near_copies(pieces, sorted.open, copies, std::min(snap_mm, kNearCopyMm));
  result.dropped_duplicates += open_copies;

  // Ends paired first; parts drawn edge to edge, where the pairing is unsure, then traced as faces
  // and the ends of what is left paired again.
  std::vector<std::uint32_t> open = std::move(sorted.open);
  std::vector<std::uint8_t> meeting;
  std::vector<std::int32_t> partner = match_ends(pieces, open, snap_mm, &meeting);
  detail::FaceChains faces = detail::chain_faces(pieces, open, copies, meeting, snap_mm);
  if (!faces.contours.empty()) {
    result.dropped_duplicates -= faces.copies_used;
    std::size_t kept = 0;
    for (std::size_t k = 0; k < open.size(); ++k) {
      if (!faces.taken[k]) open[kept++] = open[k];
    }
    open.resize(kept);
    partner = match_ends(pieces, open, snap_mm);
  }
  const Walker walker{pieces, open, partner};

  // Output in input order of each contour's lowest piece; closed inputs and faces interleaved likewise.
  std::vector<std::uint32_t> closed_key;
  std::size_t next_closed = 0;
  auto flush_closed_before = [&](std::uint32_t piece_index) {
    while (next_closed < sorted.closed.size() && sorted.closed[next_closed] < piece_index) {
      const ChainPiece& p = pieces[sorted.closed[next_closed]];
      closed_key.push_back(sorted.closed[next_closed++]);
      result.closed.push_back({p.path, {p.source}, p.group});
    }
  };
  walk_chains(walker, [&](std::size_t k, bool cycle, ChainedContour chain) {
    flush_closed_before(open[k]);
    // A mark whose ends meet within the snap (a V, a stroke there and back) closes into a sliver
    // that would be cut as a slit through the part it marks (and a there-and-back stroke with a
    // side trip made the whole drawing fail as a contour touching itself): it stays an open path.
    if (cycle && is_sliver(chain.contour, snap_mm)) {
      chain.contour.closed = false;
      chain.contour.vertices.push_back({chain.contour.vertices.front().p, 0.0});
      cycle = false;
    }
    if (cycle) closed_key.push_back(open[k]);
    (cycle ? result.closed : result.open).push_back(std::move(chain));
  });
  flush_closed_before(std::numeric_limits<std::uint32_t>::max());
  if (!faces.contours.empty()) {
    for (std::size_t i = 0; i < faces.contours.size(); ++i) {
      closed_key.push_back(faces.first_piece[i]);
      result.closed.push_back(std::move(faces.contours[i]));
    }
    std::vector<std::size_t> order(result.closed.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return closed_key[a] < closed_key[b]; });
    std::vector<ChainedContour> sorted_closed;
    sorted_closed.reserve(order.size());
    for (std::size_t i : order) sorted_closed.push_back(std::move(result.closed[i]));
    result.closed = std::move(sorted_closed);
  }
  drop_repeated_strokes(result);
  if (gap_mm > snap_mm && std::isfinite(gap_mm)) close_gaps(result, gap_mm);
  measure_open_ends(result);
  return result;
}

}  // namespace

ChainResult chain_contours(const std::vector<ChainPiece>& pieces, double snap_mm, double gap_mm) {
  if (!(snap_mm >= tol::kSamePointMm) || !std::isfinite(snap_mm)) snap_mm = tol::kSamePointMm;
  ChainResult result = chain_once(pieces, snap_mm, gap_mm);
  if (result.gaps_closed.empty()) return result;
  // The joints made across gaps decided, the drawing is chained again with their ends moved to
  // meet, as if drawn so: parts drawn edge to edge (step 4) are traced only where every end meets
  // another within the snap, and a gap in one of them left its neighbour, whose copy of the shared
  // edge had been dropped, open. A free end keeps its exact coordinates through the steps, so the
  // ends to move are found by position.
  std::map<std::pair<double, double>, Vec2> moved;
  for (const ClosedGap& g : result.gaps_closed) {
    moved[{g.end_a.x, g.end_a.y}] = g.at;
    moved[{g.end_b.x, g.end_b.y}] = g.at;
  }
  std::vector<ChainPiece> met = pieces;
  for (ChainPiece& p : met) {
    if (p.path.closed || p.path.vertices.empty()) continue;
    const auto front = moved.find({p.path.vertices.front().p.x, p.path.vertices.front().p.y});
    const auto back = moved.find({p.path.vertices.back().p.x, p.path.vertices.back().p.y});
    // One arc across its own gap: its ends cannot move without changing its bulge's meaning.
    if (segment_count(p.path) == 1 && front != moved.end() && back != moved.end() && front->second == back->second &&
        closes_round(segment(p.path, 0))) {
      p.path = circle_through(segment(p.path, 0), front->second);
      continue;
    }
    if (front != moved.end()) p.path.vertices.front().p = front->second;
    if (back != moved.end()) p.path.vertices.back().p = back->second;
  }
  ChainResult again = chain_once(met, snap_mm, 0.0);
  again.gaps_closed = std::move(result.gaps_closed);
  return again;
}

}  // namespace cutroute::geometry
