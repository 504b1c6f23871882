// chain_faces(): contours of parts drawn edge to edge with their own entities, traced as faces of a planar graph; the grid of end points the chaining steps share.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <vector>

#include <cutroute/geometry/chain.hpp>

namespace cutroute::geometry::detail {

// End e of an open piece: its start when e is even, its end when odd.
inline Vec2 end_point(const Contour& c, std::size_t e) { return (e & 1) ? c.vertices.back().p : c.vertices.front().p; }

// Grid cell index of a coordinate, clamped so that absurd coordinates cannot overflow.
inline std::int64_t cell_of(double v, double cell) {
  const double q = std::floor(v / cell);
  constexpr double kLimit = 4.0e18;
  return static_cast<std::int64_t>(std::clamp(q, -kLimit, kLimit));
}

// The ends of all pieces in a grid of cell `snap`, to find the ends that meet an end.
struct EndGrid {
  struct Cell {
    std::int64_t ix, iy;
    std::uint32_t end;
  };
  std::vector<Cell> cells;
  double snap = 0;

  // Calls f(end) for the ends in the 3 × 3 cells around p; false when a cell is crowded.
  template <class F>
  bool for_near(Vec2 p, F&& f) const {
    // More ends than this in one snap cell is a crowd (a fan of lines), not a corner of parts.
    constexpr std::size_t kMaxEndsPerCell = 64;
    const std::int64_t ix = cell_of(p.x, snap), iy = cell_of(p.y, snap);
    auto less = [](const Cell& a, const Cell& b) { return std::tie(a.ix, a.iy) < std::tie(b.ix, b.iy); };
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto [lo, hi] = std::equal_range(cells.begin(), cells.end(), Cell{ix + dx, iy + dy, 0}, less);
        if (static_cast<std::size_t>(hi - lo) > kMaxEndsPerCell) return false;
        for (auto it = lo; it != hi; ++it) f(it->end);
      }
    }
    return true;
  }
};

// The grid of `ends` end points (pos(e) for e in [0, ends)), sorted by cell then end.
template <class Pos>
EndGrid make_grid(std::size_t ends, double snap, Pos&& pos) {
  EndGrid grid;
  grid.snap = snap;
  grid.cells.resize(ends);
  for (std::size_t e = 0; e < ends; ++e) {
    const Vec2 p = pos(e);
    grid.cells[e] = {cell_of(p.x, snap), cell_of(p.y, snap), static_cast<std::uint32_t>(e)};
  }
  std::sort(grid.cells.begin(), grid.cells.end(), [](const EndGrid::Cell& a, const EndGrid::Cell& b) {
    return std::tie(a.ix, a.iy, a.end) < std::tie(b.ix, b.iy, b.end);
  });
  return grid;
}

// Why faces and not end pairing: where two parts drawn with separate entities share an edge, the
// edge is drawn twice and three or four ends meet at each of its end points. Pairing ends by
// distance there is arbitrary: it walks from one part into the other, and with the second copy
// of the edge dropped as a duplicate one part is always left open. The drawing is a planar graph
// whose bounded faces are the parts; an edge drawn twice bounds two of them, an edge drawn once
// bounds one part and scrap.
//
// Steps:
//  1. suspects: pieces with an exact copy or with an end met by other than one other end (a corner
//     of three or four parts, a T, a free end); none in a clean drawing, which ends here;
//  2. from the suspects, through the points where ends meet, every piece joined to one is visited;
//     a single line or arc is cut where a visited piece of its layer ends on it away from its ends
//     (a T: the long side of one part meets the sides of two neighbours, or neighbours' sides meet
//     partly), at that end's position, and is visited too. Connected groups of the visited
//     pieces' stretches (ends within `snap`) are formed;
//  3. in a group, stretches between the same two points along the same curve (midpoints within
//     `snap`) are one edge, drawn once per stretch and exact copy;
//  4. the group is traced into faces (at each point the next edge is the one turning tightest, by
//     tangent angle then curvature), and faces are chosen so that an edge drawn twice lies between
//     two chosen faces and an edge drawn once between a chosen face and an unchosen one, the
//     outside never chosen;
//  5. each drawing of an edge goes to one of its faces: a piece cut in step 2 to the side where all
//     its stretches border one part, else the earlier drawing to the part whose other edges come
//     nearer to it in the file; stretches of one piece that follow each other are merged back.
// Where no choice fits, a part drawn twice by mistake is looked for (parts_without_repeats(): its
// second outline is dropped as duplicates). A group is left to the end pairing, its copies dropped
// and its pieces uncut, when no choice fits or the group does not look like a planar drawing: an
// odd number of drawings at a point, an edge drawn more than three times, ends crowding more than
// 64 to a snap cell or spread wider than the snap, two edges leaving a point along the same curve,
// an edge whose ends meet, a face of no area, more than one face turning clockwise, a part's face
// passing a point twice. A single edge drawn twice by mistake makes an odd point, and keeps the end
// pairing.
// Cost: nothing more than the end pairing's counts for a clean drawing; else O(n log n) for n open
// pieces (a grid of ends, a packed R-tree of the pieces for the T search).
struct FaceChains {
  std::vector<ChainedContour> contours;       // closed: the faces that are parts
  std::vector<std::uint32_t> first_piece;     // per contour: its lowest piece index (output order)
  std::vector<char> taken;                    // per index into `open`: chained here
  std::size_t copies_used = 0;                // duplicates that bound a second face
};

// open: indices into pieces of the open pieces left after duplicates were removed (ascending);
// copies[k]: the pieces dropped as duplicates of pieces[open[k]]; meeting[e]: how many ends lie
// within snap of end e of open piece e / 2, itself included. Where every end meets one other and
// nothing has a copy there is nothing to trace, and this returns at once.
FaceChains chain_faces(const std::vector<ChainPiece>& pieces, const std::vector<std::uint32_t>& open,
                       const std::vector<std::vector<std::uint32_t>>& copies, const std::vector<std::uint8_t>& meeting,
                       double snap);

}  // namespace cutroute::geometry::detail
