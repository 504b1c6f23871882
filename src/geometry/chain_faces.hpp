// chain_faces(): contours of parts drawn edge to edge, one copy of the shared edge per part, traced as faces.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
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

// Why faces and not end pairing: where two parts drawn with separate entities share an edge, the
// edge is drawn twice and three or four ends meet at each of its end points. Pairing ends by
// distance there is arbitrary: it walks from one part into the other, and with the second copy
// of the edge dropped as a duplicate one part is always left open. The drawing is a planar graph
// whose bounded faces are the parts; an edge drawn twice bounds two of them, an edge drawn once
// bounds one part and scrap.
//
// Works on connected groups of open pieces (joined by ends within `snap`) that hold an exact
// duplicate and a point where more than two ends meet. Such a group is traced into faces (at each
// point the next piece is the one turning tightest, by tangent angle then curvature) and its
// faces are chosen so that an edge drawn twice lies between two chosen faces and an edge drawn
// once between a chosen face and an unchosen one, the outside never chosen. A group is left to
// the end pairing, its copies dropped as before, when that choice does not exist or the group
// does not look like a planar drawing: an odd number of ends at a point, an edge drawn three
// times, ends crowding more than 64 to a point or spread wider than the snap, two pieces leaving
// a point along the same curve, a piece whose ends meet, or more than one face turning clockwise.
// A whole outline drawn twice, or a single edge drawn twice by mistake, cannot be chosen so, and
// keeps today's result.
struct FaceChains {
  std::vector<ChainedContour> contours;       // closed: the faces that are parts
  std::vector<std::uint32_t> first_piece;     // per contour: its lowest piece index (output order)
  std::vector<char> taken;                    // per index into `open`: chained here
  std::size_t copies_used = 0;                // duplicates that bound a second face
};

// open: indices into pieces of the open pieces left after duplicates were removed (ascending);
// copies[k]: the pieces dropped as duplicates of pieces[open[k]].
FaceChains chain_faces(const std::vector<ChainPiece>& pieces, const std::vector<std::uint32_t>& open,
                       const std::vector<std::vector<std::uint32_t>>& copies, double snap);

}  // namespace cutroute::geometry::detail
