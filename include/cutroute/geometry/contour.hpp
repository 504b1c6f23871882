// Contour: a polyline of bulge vertices (lines and exact circular arcs), open or closed.
#pragma once

#include <cstddef>
#include <vector>

#include <cutroute/geometry/box.hpp>
#include <cutroute/geometry/vec2.hpp>

namespace cutroute::geometry {

// One vertex and the segment that leaves it. bulge = tan(sweep / 4) of the arc from this
// vertex to the next (DXF convention): 0 = straight line, > 0 counter-clockwise arc,
// < 0 clockwise arc, ±1 = half circle. |bulge| <= 1e9 (a full circle is two half arcs).
// Seen along the chord from this vertex to the next, a counter-clockwise arc bulges to the
// right and a clockwise one to the left; |bulge| < 1 is the minor arc, > 1 the major one.
// Radius, centre and length in terms of chord and bulge: geometry/arc.hpp. Below
// tol::kStraightBulge a bulge is a straight line; NaN reads as 0 and larger magnitudes (or ±inf)
// as ±1e9, so no function here returns NaN for finite coordinates.
struct Vertex {
  Vec2 p;               // [mm]
  double bulge = 0.0;   // [1]
  friend bool operator==(const Vertex&, const Vertex&) = default;
};

// A closed contour has vertices.size() segments (the last one returns to vertices[0]; the
// first vertex is not repeated); an open one has vertices.size() - 1 and the last vertex's
// bulge is ignored. Closed contours have at least 1 vertex (a single vertex with bulge
// cannot close; a full circle is 2 vertices with bulge ±1 each).
struct Contour {
  std::vector<Vertex> vertices;
  bool closed = false;
  friend bool operator==(const Contour&, const Contour&) = default;
};

// One segment of a contour, as a value: a line (bulge 0) or an arc.
struct Segment {
  Vec2 a;               // start [mm]
  Vec2 b;               // end [mm]
  double bulge = 0.0;   // [1], as in Vertex

  bool is_arc() const;
  double length() const;       // exact arc length [mm]
  Vec2 center() const;         // arc centre; midpoint for a line [mm]
  double radius() const;       // arc radius; +inf for a line [mm]
  double sweep() const;        // signed sweep angle [rad], 4*atan(bulge)
  Vec2 point_at(double t) const;    // t in [0,1] of arc length
  Vec2 tangent_at(double t) const;  // unit tangent in the direction of travel
  Box bounding_box() const;    // exact, arc extremes included
};

std::size_t segment_count(const Contour& c);
Segment segment(const Contour& c, std::size_t i);

// Lengths and areas are exact with arcs.
double length(const Contour& c);                // [mm]
double signed_area(const Contour& c);           // [mm²], > 0 counter-clockwise; closed only
enum class Orientation { ccw, cw, degenerate };
Orientation orientation(const Contour& c);      // of a closed contour, from its signed area
Box bounding_box(const Contour& c);             // exact, arc extremes included

Contour reversed(const Contour& c);             // same geometry, opposite direction

// Arc-length parametrisation. s is clamped to [0, length]; on a closed contour s wraps
// (negative s counts back from the end). closest_point() takes the first segment on ties.
Vec2 point_at_length(const Contour& c, double s);
struct ClosestPoint {
  Vec2 point;                 // closest point on the contour [mm]
  double distance = 0.0;      // from the query point [mm]
  std::size_t segment = 0;    // index of the segment it lies on
  double length_along = 0.0;  // arc length from the start of the contour to `point` [mm]
};
ClosestPoint closest_point(const Contour& c, Vec2 p);
inline double length_at_point(const Contour& c, Vec2 p) { return closest_point(c, p).length_along; }
inline double distance(const Contour& c, Vec2 p) { return closest_point(c, p).distance; }

// Exact point-in-contour with arcs (winding number), for closed contours; no flattening
// (winding.cpp explains the chord-polygon-plus-circular-segments method). winding_number() is
// +1 inside a counter-clockwise contour, -1 inside a clockwise one, 0 for open contours; its
// value for a point exactly on the boundary is unspecified. locate() first asks whether p is
// within on_tol_mm of the boundary, then uses the non-zero rule. Cost O(segments); for many
// queries against one contour see geometry/segment_set.hpp.
enum class Location { outside, inside, on_boundary };
Location locate(const Contour& c, Vec2 p, double on_tol_mm);
int winding_number(const Contour& c, Vec2 p);

// Do the boundaries of a and b touch or cross (within tol_mm)? Exact with arcs (segment
// intersections in geometry/intersect.hpp). One contour inside the other without touching is
// NOT an intersection: combine with locate() for containment.
bool intersects(const Contour& a, const Contour& b, double tol_mm);

// A polygon approximating the contour within chord_tol_mm (arcs split into equal chords whose
// sagitta is at most the tolerance; at most 65536 chords per arc). Every vertex of the contour
// is kept. For closed contours the first point is not repeated. A tolerance <= 0 or NaN means
// tol::kArcChordMm.
std::vector<Vec2> flatten(const Contour& c, double chord_tol_mm);

// The contour's extent across the narrowest of its edges' normals (arcs flattened within
// chord_tol_mm > 0, plus twice that where it has arcs): never less than its least width, and that
// width exactly for a convex polygon, whose narrowest direction is normal to one of its edges.
// O(n^2): for a few candidates.
double narrowest_width(const Contour& c, double chord_tol_mm);

}  // namespace cutroute::geometry
