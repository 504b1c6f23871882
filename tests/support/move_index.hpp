// MoveIndex: a spatial index over probed cut moves, for "is this boundary point cut, and when first?".
#pragma once

#include <cstddef>
#include <vector>

#include <cutroute/geometry/spatial_index.hpp>
#include <cutroute/geometry/vec2.hpp>

#include "support/gcode_probe.hpp"

namespace cutroute::test {

class MoveIndex {
 public:
  // `moves` in the order that counts (program order); queries ask for distances up to `reach` [mm].
  MoveIndex(std::vector<const ProbeMove*> moves, double reach);
  // The position in `moves` of the first move passing within d (<= reach) of q; size() when none.
  std::size_t first_within(geometry::Vec2 q, double d) const;
  std::size_t size() const { return moves_.size(); }

 private:
  std::vector<const ProbeMove*> moves_;
  geometry::StaticSpatialIndex index_;
};

}  // namespace cutroute::test
