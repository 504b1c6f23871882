// Private path operations for entry planning: tangent at an arc length, sub-paths of closed contours.
#pragma once

#include <vector>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::model::detail {

struct PathPoint {
  geometry::Vec2 point;
  geometry::Vec2 tangent;       // unit, direction of travel
  std::size_t segment = 0;
  double t = 0.0;               // fraction of that segment's length
};

// A contour's segment lengths and their running sums (cum[i] = length before segment i, cum[n] =
// geometry::length): entry planning asks for hundreds of points per contour, and walking a spline
// outline of thousands of arcs (an atan each) per point dominated it.
struct Measured {
  std::vector<double> seg_len;
  std::vector<double> cum;
};
Measured measure(const geometry::Contour& c);

// The point and tangent at arc length s of a contour (s wraps on closed contours).
PathPoint at_length(const geometry::Contour& c, double s);
PathPoint at_length(const geometry::Contour& c, const Measured& m, double s);  // O(log n)

// The open path along contour c from arc length s0 for `length` millimetres. On a closed contour
// it wraps past the start (length may exceed one loop by an overcut); on an open one it stops at
// the end. Arcs are split exactly.
geometry::Contour sub_path(const geometry::Contour& c, double s0, double length);
geometry::Contour sub_path(const geometry::Contour& c, const Measured& m, double s0, double length);

// Splits the arc/line a->b (bulge) at fraction u of its length: bulges of the two parts.
void split_bulge(double bulge, double u, double& first, double& second);

}  // namespace cutroute::model::detail
