// Named tolerances, one per question asked, each with its unit (STYLE.md #4).
#pragma once

namespace cutroute::tol {

// Two entity end points closer than this are joined when chaining contours [mm].
// Default of `--snap`; drawings exported from CAD are typically exact to 1e-6, hand-made
// nests are not, and 0.01 mm is well below any laser's kerf (~0.1 mm).
inline constexpr double kSnapMm = 0.01;

// Two points are the same point (duplicate vertices, zero-length segments) [mm].
inline constexpr double kSamePointMm = 1e-6;

// A bulge whose magnitude is below this is a straight segment [dimensionless, tan(sweep/4)].
// 1e-9 on a 1 m chord is a sagitta of 2.5e-7 mm.
inline constexpr double kStraightBulge = 1e-9;

// A point lies on a line if its distance to it is below this [mm].
inline constexpr double kCollinearMm = 1e-6;

// Maximum chord deviation when a curve (SPLINE, ELLIPSE) is replaced by arcs and lines,
// or when an arc is flattened for a consumer that needs polygons [mm]. Default of the
// DXF reader's curve conversion.
inline constexpr double kArcChordMm = 0.01;

// Radius mismatch between an arc's start and end point in G-code before it is an error [mm].
inline constexpr double kGcodeArcRadiusMm = 0.01;

// Relative slack under which a machining constraint counts as active [dimensionless].
inline constexpr double kConstraintSlackRel = 1e-9;

// Relative termination width of golden-section searches [dimensionless].
inline constexpr double kGoldenSectionRel = 1e-10;

// Relative width to which a feasibility boundary in vc is bisected between two grid samples
// [dimensionless]; well below kConstraintSlackRel so that boundary points count as active.
inline constexpr double kBoundaryBisectRel = 1e-14;

}  // namespace cutroute::tol
