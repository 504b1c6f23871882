// chain_contours(): join open pieces (lines, arcs, open polylines) into closed contours by end points.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::geometry {

// One input piece: its geometry and the caller's index for it (e.g. the DXF entity), so that
// results can say which entities made them. Pieces join only when their `group` is equal
// (the caller may pass 0 for all to chain across layers).
struct ChainPiece {
  Contour path;              // open or closed
  std::int32_t source = -1;  // caller's id of the entity
  std::int32_t group = 0;
};

struct ChainedContour {
  Contour contour;                    // closed, or open when it could not be closed
  std::vector<std::int32_t> sources;  // the pieces it was made of, in order of travel
  std::int32_t group = 0;
  // Open chains: how far an end of it lies from the nearest end it could join (another free end of
  // its group, or its own other end), when within kGapHintMm; else < 0 (step 8).
  double nearest_end_mm = -1;
};

// Step 8 looks this far for an open chain's nearest free end [mm]: the largest --close-gaps.
inline constexpr double kGapHintMm = 1.0;

// A gap between two chain ends that step 7 closed (the ends moved to `at`, its midpoint).
struct ClosedGap {
  Vec2 at;
  double width_mm = 0;                // the distance the ends were apart
  std::int32_t source_a = -1, source_b = -1;  // the pieces whose ends met there
  std::int32_t group = 0;
  Vec2 end_a, end_b;                  // the two ends as drawn
};

struct ChainResult {
  std::vector<ChainedContour> closed;   // closed contours (closed inputs pass through)
  std::vector<ChainedContour> open;     // chains whose ends found no partner
  std::size_t dropped_zero_length = 0;  // pieces shorter than tol::kSamePointMm
  std::size_t dropped_duplicates = 0;   // pieces identical to another (either direction), less
                                        // the copies kept as the edge of a second part (step 3),
                                        // and pieces of open chains repeating closed ones (step 6)
  std::size_t dropped_invalid = 0;      // pieces with a NaN or infinite coordinate or bulge
  std::vector<ClosedGap> gaps_closed;   // step 7, in order of the chain ends' indices
};

// Joins pieces whose end points lie within snap_mm, in any input order and direction.
// Where an end point meets several others, the nearest unused partner is taken.
// Snapped end points are moved to their common midpoint so closed contours close exactly.
//
// Steps (chain.cpp has one function per step):
//  1. classify: drop pieces with non-finite values and pieces shorter than tol::kSamePointMm;
//     closed pieces pass through unchanged.
//  2. drop exact duplicates: the same vertices (bit-exact, -0 == +0) read forwards or backwards,
//     in the same group; the first in input order is kept. (Closed pieces that repeat another
//     from a different start vertex are not caught here; model::build_nest() reports them.)
//     Then open pieces that repeat an earlier one within 1e-4 mm at every vertex and segment
//     midpoint, either way round (a copy rounded otherwise), are dropped the same way.
//  3. match end points: all pairs of ends (same group) within snap_mm, found through a uniform
//     grid of cell snap_mm, sorted by distance (ties by index) and matched greedily, so each end
//     gets its nearest partner not already taken. Both ends of one piece may match each other
//     (an open polyline or arc that closes itself), a single straight line may not.
//  4. parts drawn edge to edge: where an open piece has an exact copy or an end met by other than
//     one end (a corner of three or four parts, a T), its connected group of pieces is traced as
//     the faces of a planar graph and each face that is a part becomes a contour; an edge drawn
//     twice then bounds two parts, one drawing each, and a long side that neighbours meet in
//     stretches stays one piece of its part; points lie at the mean of the ends that meet there
//     (detail::chain_faces(), src/geometry/chain_faces.hpp, says when a group is left to the end
//     pairing instead, its copies dropped). The ends of the pieces left are matched again (3).
//  5. walk: pieces linked through matched ends form paths (open) and cycles (closed); each
//     joint is moved to the midpoint of its two ends. A cycle thinner than 2 snaps (2 area /
//     length: a V or there-and-back mark whose ends meet) stays an open path.
//  6. an open chain lying wholly on closed contours of its group (within tol::kCollinearMm: a
//     LINE drawn again over an edge of a closed polyline) is dropped, counted as duplicates.
//  7. gaps: when gap_mm > snap_mm, a chain still open whose own ends lie within gap_mm closes on
//     itself, the ends of the others are matched again as in 3 within gap_mm, and all are walked as in 5 (their joints moved to the midpoints), and each such joint
//     is listed in gaps_closed; contours closed there follow the others, in order of their lowest
//     open chain. A loop it would close whose mean width (2 area / length) is under 2 gap_mm (a
//     V-shaped or there-and-back mark) is left open: cut, it would be a slit through a part. Drawings made by hand or converted between units often leave such gaps
//     (0.011-0.015 mm in three files of the corpus), and a part left open is not cut at all.
//  8. each chain still open gets nearest_end_mm, so that a warning can say what would close it.
// When step 7 closed gaps, steps 1-8 run again on the pieces with the ends of those gaps moved to
// their midpoints (no step 7 then): parts drawn edge to edge are traced as faces only where every
// end meets another within the snap, and a gap in one of them left its neighbour open.
// Output is deterministic: contours in input order of their lowest piece; a cycle starts at its
// lowest-index piece, travelled in that piece's direction; an open chain starts at its free end
// reached by walking backwards from its lowest-index piece.
// Cost: O(n log n) for n pieces (plus k² distance checks, not memory, for k ends crowded
// within one snap distance: each end offers only its 8 nearest partners).
// snap_mm below tol::kSamePointMm (or NaN) is raised to it.
ChainResult chain_contours(const std::vector<ChainPiece>& pieces, double snap_mm, double gap_mm = 0.0);

}  // namespace cutroute::geometry
