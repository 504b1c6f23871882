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
};

struct ChainResult {
  std::vector<ChainedContour> closed;   // closed contours (closed inputs pass through)
  std::vector<ChainedContour> open;     // chains whose ends found no partner
  std::size_t dropped_zero_length = 0;  // pieces shorter than tol::kSamePointMm
  std::size_t dropped_duplicates = 0;   // pieces identical to another (either direction)
};

// Joins pieces whose end points lie within snap_mm, in any input order and direction.
// Where an end point meets several others, the nearest unused partner is taken.
// Snapped end points are moved to their common midpoint so closed contours close exactly.
ChainResult chain_contours(const std::vector<ChainPiece>& pieces, double snap_mm);

}  // namespace cutroute::geometry
