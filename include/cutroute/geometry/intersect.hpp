// Segment–segment intersection (line/line, line/arc, arc/arc) and distances, exact with arcs.
#pragma once

#include <cstddef>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::geometry {

// How two segments meet. Every case:
//   kind == none:     no common point and no two points closer than the tolerance;
//                     count == 0, points unused.
//   kind == points:   count (1 or 2) isolated common points in points[0..count). A touch
//                     within the tolerance (the segments pass closer than tol without meeting)
//                     is reported as one point: the midpoint of the two closest points.
//   kind == overlap:  the segments share a stretch (collinear lines, or arcs on the same
//                     circle whose sweeps overlap); count == 2 and points are the two ends of
//                     the shared stretch (equal when they only share an end point within tol
//                     — that case is reported as `points` with count 1 instead).
struct SegmentIntersection {
  enum class Kind { none, points, overlap };
  Kind kind = Kind::none;
  int count = 0;
  Vec2 points[2];
};

// Arcs whose sagitta is below tol::kCollinearMm are treated as their chord here and in the
// distance functions below (their centre is then so far away that circle formulas would lose
// more precision than the chord approximation): answers are exact to within kCollinearMm.
SegmentIntersection intersect(const Segment& s, const Segment& t, double tol_mm);

// Closest point of one segment to p.
struct SegmentClosest {
  Vec2 point;                 // [mm]
  double distance = 0.0;      // |point - p| [mm]
  double length_along = 0.0;  // arc length from s.a to point [mm]
};
SegmentClosest closest_point(const Segment& s, Vec2 p);

// Smallest distance between any point of s and any point of t (0 when they meet) [mm].
double distance(const Segment& s, const Segment& t);

// Number of segment pairs of a and b (contours) within tol_mm of each other, stopping at
// `limit` (1 answers "do they touch"). Only pairs whose boxes overlap are examined exactly.
std::size_t count_close_segment_pairs(const Contour& a, const Contour& b, double tol_mm, std::size_t limit);

}  // namespace cutroute::geometry
