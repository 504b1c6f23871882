// Contour constructors (circle, rectangle, polygon) and rigid transforms (translate, rotate, mirror).
#pragma once

#include <vector>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::geometry {

// A full circle as two half arcs (bulge ±1), starting at centre + (r, 0).
Contour circle(Vec2 center, double radius, bool ccw = true);
// A closed axis-aligned rectangle, counter-clockwise from (xmin, ymin) unless ccw is false.
Contour rectangle(const Box& box, bool ccw = true);
// A closed or open polygon through the points (all bulges 0).
Contour polygon(const std::vector<Vec2>& points, bool closed = true);

// Rigid transforms keep bulges (rotation and translation preserve arc orientation); a mirror
// flips every bulge's sign because it turns counter-clockwise arcs clockwise.
Contour translated(const Contour& c, Vec2 offset);
Contour rotated_about(const Contour& c, Vec2 pivot, double angle_rad);
Contour mirrored_x(const Contour& c);  // (x, y) -> (-x, y)

}  // namespace cutroute::geometry
