// Contours of different parts closer than the kerf without touching: cutting one takes from the other.
#pragma once

#include <cstddef>
#include <optional>

#include <cutroute/geometry/vec2.hpp>
#include <cutroute/model/nest.hpp>

namespace cutroute::model {

struct KerfNeighbours {
  std::size_t pairs = 0;  // pairs of contours of different parts (holes included) closer than the kerf
  ContourId first_a, first_b;  // the first such pair found (for messages), valid when pairs > 0
  geometry::Vec2 near;         // a point of first_a's boundary within the kerf of first_b [mm]
};

// Pairs whose boundaries come closer than kerf_mm but do not meet within touch_tol_mm (touching
// and shared edges are the nest's own diagnostics). Two parts side by side, or a part in a hole,
// less than a kerf apart lose material to each other's cut whatever path the torch follows: the
// cam kerf mode refuses them (kerf.overlap); with the controller's compensation they are only
// said. One boundary test per pair of boxes within the kerf.
KerfNeighbours closer_than_kerf(const Nest& nest, double kerf_mm, double touch_tol_mm);

}  // namespace cutroute::model
