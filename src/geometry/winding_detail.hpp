// Private: the contribution of one segment to the winding number (see winding.cpp).
#pragma once

#include <cutroute/geometry/contour.hpp>

namespace cutroute::geometry::detail {

// Chord crossing of the ray from p towards +x plus the arc's circular-segment term.
int winding_contribution(Vec2 a, Vec2 b, double bulge, Vec2 p);

}  // namespace cutroute::geometry::detail
