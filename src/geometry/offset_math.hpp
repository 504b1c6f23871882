// Private line/arc primitives of the kerf offset: a segment that carries its exact circle,
// points by parameter, distances, boxes, areas and line/arc intersections.
#pragma once

// Self-contained on purpose: the offset must not depend on how contour.hpp's Segment derives
// centres from bulges, because a raw offset arc keeps the exact centre of its source arc and a
// join arc is centred exactly on the source vertex; re-deriving them from a bulge would add
// rounding at every step.

#include <array>
#include <cstddef>

#include <cutroute/geometry/box.hpp>
#include <cutroute/geometry/vec2.hpp>

namespace cutroute::geometry::offset_detail {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;

// |bulge| above this is clamped (contour.hpp allows |bulge| <= 1e9).
inline constexpr double kMaxBulge = 1e9;

// One line or arc. Lines have sweep == 0; arcs have 0 < |sweep| < 2π and carry c and r.
struct Piece {
  Vec2 a;              // start [mm]
  Vec2 b;              // end [mm]
  double sweep = 0.0;  // signed sweep [rad]: > 0 counter-clockwise, 0 for a line
  Vec2 c;              // arc centre [mm]; unused for a line
  double r = 0.0;      // arc radius [mm]; 0 for a line

  bool is_arc() const { return sweep != 0.0; }
  double bulge() const;  // tan(sweep / 4)
};

Piece make_line(Vec2 a, Vec2 b);
Piece make_arc(Vec2 c, double r, Vec2 a, Vec2 b, double sweep);
// From a bulge vertex and the next point; a bulge below tol::kStraightBulge is a line.
Piece make_piece(Vec2 a, Vec2 b, double bulge);

double length(const Piece& p);  // exact [mm]
// t in [0, 1]: of the chord for a line, of the sweep for an arc; t = 0 and 1 give a and b exactly.
Vec2 point_at(const Piece& p, double t);
Vec2 start_tangent(const Piece& p);  // unit, direction of travel
Vec2 end_tangent(const Piece& p);    // unit, direction of travel
// Inverse of point_at for a point on the piece's line or circle. Outside the piece it returns
// values below 0 or above 1 (for an arc, whichever end is nearer in angle).
double param_of(const Piece& p, Vec2 q);
// The part of p between parameters t0 < t1, with the given exact end points.
Piece sub_piece(const Piece& p, double t0, double t1, Vec2 q0, Vec2 q1);
double distance_to(const Piece& p, Vec2 q);  // exact [mm]
Box box_of(const Piece& p);                   // exact, arc extremes included
// Contribution to the signed area of a closed path (shoelace term plus circular segment) [mm²].
double area_term(const Piece& p);

// Points where two pieces meet, each within tol_mm of both pieces; duplicates closer than
// tol_mm are merged. Crossings and tangencies give 1 or 2 points; pieces lying on the same line
// or circle give the end points of their common parts (at most 4).
struct Hits {
  std::size_t count = 0;
  std::array<Vec2, 4> points{};
  void add(Vec2 p, double tol_mm);
};
Hits intersect(const Piece& p, const Piece& q, double tol_mm);

}  // namespace cutroute::geometry::offset_detail
