// Step 3 of the kerf offset: removal of the invalid loops of a self-intersecting raw offset.
#pragma once

#include <vector>

#include "geometry/offset_math.hpp"

namespace cutroute::geometry::offset_detail {

struct PrunedLoops {
  std::vector<std::vector<Piece>> loops;  // closed loops of kept slices, each end to start
  bool removed = false;                   // some slice (or unclosable chain) was discarded
};

// Splits the closed joined raw offset `path` at its self-intersections, keeps the slices that
// stay at least abs_offset (minus tol::kOffsetGougeMm) away from `source` without crossing it,
// and stitches them into closed loops. Orientation is not checked here.
PrunedLoops prune_invalid_loops(const std::vector<Piece>& path, const std::vector<Piece>& source,
                                double abs_offset);

}  // namespace cutroute::geometry::offset_detail
