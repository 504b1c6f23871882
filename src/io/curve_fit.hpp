// Private arc math and curve-to-biarc fitting for the DXF reader (SPLINE, ELLIPSE, arcs under
// non-uniform INSERT scale): the geometry module's functions are not used here on purpose, so
// the reader stays self-contained and the conversion tolerance is checked by its own code.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

#include <cutroute/geometry/contour.hpp>
#include <cutroute/geometry/vec2.hpp>

namespace cutroute::io::detail {

using geometry::Vec2;
using geometry::Vertex;

// An arc (or line, bulge 0) from a to b in the DXF bulge convention.
struct ArcSeg {
  Vec2 a;
  Vec2 b;
  double bulge = 0.0;  // [1] tan(sweep / 4)
};

// Centre of an arc with |bulge| > 0 (undefined for lines).
Vec2 arc_center(const ArcSeg& s);
// Exact length of a line or arc [mm].
double arc_length(const ArcSeg& s);
// Distance from p to a line or arc segment [mm].
double distance_to_arc(const ArcSeg& s, Vec2 p);
// Point at fraction t in [0,1] of the sweep (or of the line).
Vec2 arc_point(const ArcSeg& s, double t);

// A 2D affine map p -> [m00 m01; m10 m11] p + t.
struct Affine {
  double m00 = 1, m01 = 0, m10 = 0, m11 = 1;
  Vec2 t;
  Vec2 apply(Vec2 p) const { return {m00 * p.x + m01 * p.y + t.x, m10 * p.x + m11 * p.y + t.y}; }
  Vec2 apply_linear(Vec2 v) const { return {m00 * v.x + m01 * v.y, m10 * v.x + m11 * v.y}; }
  double det() const { return m00 * m11 - m01 * m10; }
  // An upper bound of how far the linear part stretches a vector (its Frobenius norm).
  double stretch_bound() const { return std::sqrt(m00 * m00 + m01 * m01 + m10 * m10 + m11 * m11); }
  // Does the map keep circles circles (rotation, uniform scale, mirror)? [relative tolerance]
  bool is_similarity() const;
  // this ∘ other: first other, then this.
  Affine then_after(const Affine& other) const;
  static Affine translate(Vec2 v);
  static Affine scale(double sx, double sy);
  static Affine rotate(double radians);
};

// A smooth parametric curve on [t0, t1]: position and first derivative.
struct ParamCurve {
  std::function<Vec2(double)> point;
  std::function<Vec2(double)> derivative;
  double t0 = 0.0;
  double t1 = 1.0;
};

// Appends to `out` the vertices of arcs/lines following `curve` within tol_mm (the start point
// is appended; the end point is not, so consecutive pieces chain). Biarcs are tried first; a
// piece whose biarc misses the tolerance is split in two, down to a small limit where a line is
// used. The deviation is checked at sample points of the curve against the fitted arcs.
// Returns the largest deviation measured [mm]. Splitting stops once `out` holds max_vertices
// (a guard against absurd tolerances; the returned deviation then exceeds tol_mm). Returns
// +inf, leaving `out` incomplete, when the curve has non-finite points.
double fit_biarcs(const ParamCurve& curve, double tol_mm, std::vector<Vertex>& out,
                  std::size_t max_vertices = 1'000'000);

// Non-uniform rational B-spline: control points, weights (empty = all 1), knots, degree.
struct Nurbs {
  int degree = 3;
  std::vector<Vec2> control;
  std::vector<double> weights;
  std::vector<double> knots;
};

// Position and derivative at u inside knot span `span` (knots[span] <= u <= knots[span+1]);
// choosing the span picks the one-sided derivative at a knot.
Vec2 nurbs_point(const Nurbs& s, std::size_t span, double u, Vec2* derivative);

// The highest SPLINE degree read: the basis functions are evaluated in fixed arrays of 32.
inline constexpr int kMaxSplineDegree = 30;

// Converts a spline given by control points into bulge vertices within tol_mm; spans are fitted
// separately so that knots of full multiplicity (corners) stay corners. Returns the vertices of
// an open polyline including the end point; empty if the data is unusable.
std::vector<Vertex> nurbs_to_arcs(const Nurbs& s, double tol_mm, double* max_dev);

// A C2 cubic through fit points, chord-length parametrised (periodic when closed; end tangents
// used when given, else natural ends), as a NURBS-free list of cubic pieces fitted to arcs.
std::vector<Vertex> fit_points_to_arcs(const std::vector<Vec2>& pts, bool closed, const Vec2* start_tangent,
                                       const Vec2* end_tangent, double tol_mm, double* max_dev);

}  // namespace cutroute::io::detail
