// Private arc helpers shared by the geometry sources: radius directions measured without the centre.
#pragma once

#include <cutroute/geometry/contour.hpp>

namespace cutroute::geometry::detail {

// Angle [rad] of the radius vector (centre → s.a) of the arc s.
double arc_start_radial_angle(const Segment& s);

// Sweep offset φ (same sign as s.sweep(), |φ| in [0, 2π)) from the start of arc s to the radius
// direction `angle` [rad].
double sweep_to_angle(const Segment& s, double angle);

// Treat an arc as its chord in distance and intersection tests when its sagitta (d·|β|/2) is
// below this [mm]: the centre is then farther than d²/8e-6 and circle formulas lose precision
// faster than the chord approximation does.
bool nearly_straight(const Segment& s);

// A box that surely holds the segment, without trigonometry: the chord's box grown by the
// sagitta for minor arcs, the full circle's box for major arcs. For cheap rejections.
Box coarse_box(const Segment& s);

}  // namespace cutroute::geometry::detail
