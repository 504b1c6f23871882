// Named tolerances, one per question asked, each with its unit (STYLE.md #4).
#pragma once

namespace cutroute::tol {

// Two entity end points closer than this are joined when chaining contours [mm].
// Default of `--snap`; drawings exported from CAD are typically exact to 1e-6, hand-made
// nests are not, and 0.01 mm is well below any laser's kerf (~0.1 mm).
inline constexpr double kSnapMm = 0.01;

// Chain ends still apart after snapping are joined, with a warning, when closer than this [mm].
// Default of `--close-gaps`: a third of the narrowest laser kerf (~0.15 mm), so the cut across
// such a gap removes it anyway, and above the 0.011-0.015 mm gaps that unit conversion and
// hand-drawn joints leave in the corpus (dxf2gcode closes them too).
inline constexpr double kCloseGapMm = 0.05;

// Two closed contours whose boundaries lie this close to each other everywhere are one outline drawn
// twice (a copy nudged by a CAD snap, or redrawn over the first) [mm]: cutting both would run the
// beam twice along one kerf. A third of the narrowest laser kerf, like kCloseGapMm.
inline constexpr double kNearDuplicateMm = 0.05;

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

// Radius mismatch between an arc's start and end point in G-code before it is warned (the reader)
// or rounded otherwise (the writer) [mm].
inline constexpr double kGcodeArcRadiusMm = 0.01;

// Relative slack under which a machining constraint counts as active [dimensionless].
inline constexpr double kConstraintSlackRel = 1e-9;

// Relative termination width of golden-section searches [dimensionless].
inline constexpr double kGoldenSectionRel = 1e-10;

// A drawn contour is an axis-aligned rectangle (a sheet border candidate) when each edge is
// horizontal or vertical within this and its area equals its box's within this × perimeter [mm].
inline constexpr double kSheetRectangleMm = 1e-3;

// A drawn border matches `--sheet W,H` when each side differs from the given size by less than
// this [mm]: users type nominal sizes, drawings carry them to a few decimals.
inline constexpr double kSheetSizeMm = 0.5;

// Contours may stick out of a drawn sheet border by this much and it still counts as enclosing
// them [mm]: nesting tools place parts flush with the border and some end up a hair outside
// (DeepNest's ReadMeExampleSmall: one part 0.12 mm over its plate). Each such contour gets a
// warning; well below any real clearance between parts and sheet edge (~5 mm).
inline constexpr double kSheetOverhangMm = 0.5;


// A requested sheet thickness equals a table thickness when closer than this [mm].
// Tables list thicknesses to 0.1 mm; 1e-6 only absorbs decimal-to-binary conversion.
inline constexpr double kThicknessMm = 1e-6;


// Radius mismatch of a G-code arc in an inch (G20) program before it is warned [inch].
// Inch programs are usually written to 0.001 in (0.0254 mm); rounding start, end and centre
// moves the end radius by up to about 1.5 of that (0.036 mm seen in dxf2gcode output), which
// kGcodeArcRadiusMm would warn of.
inline constexpr double kGcodeArcRadiusInch = 0.002;

// Kerf offset (geometry/offset.hpp). An offset arc whose radius falls to or below this has
// collapsed (its side of the offset shrinks to nothing) and is dropped [mm].
inline constexpr double kOffsetCollapseRadiusMm = 1e-6;

// Two raw offset segment ends closer than this are joined as they are, without a join arc or
// a trim; also the length under which an offset piece is dropped [mm]. A convex corner turning
// by less than 1e-5 rad at a 0.1 mm offset leaves a gap below this.
inline constexpr double kOffsetJoinMm = 1e-6;

// Two offset pieces meet (touch or cross) when they come closer than this; also the distance
// under which two intersection points are the same point [mm]. Far below kOffsetJoinMm so that
// near-tangent crossings are still told apart, far above the rounding of 1e3 mm coordinates.
inline constexpr double kOffsetIntersectMm = 1e-9;

// A piece of the joined raw offset is kept only if its distance to the source contour is at
// least |offset| minus this slack [mm]; valid pieces sit at exactly |offset| up to rounding.
inline constexpr double kOffsetPruneMm = 1e-6;

// A closed offset loop enclosing less than this is numerical debris and is dropped [mm²].
inline constexpr double kOffsetMinLoopAreaMm2 = 1e-9;

// Relative width to which a feasibility boundary in vc is bisected between two grid samples
// [dimensionless]; well below kConstraintSlackRel so that boundary points count as active.
inline constexpr double kBoundaryBisectRel = 1e-14;

// Kerf offset, invalid-loop removal: a slice of the raw offset is still kept when it comes up to
// this much closer than |offset| to the source [mm]. kOffsetPruneMm (rounding only) is too tight
// for spline-fitted outlines: tiny arcs (radius ~0.002 mm) next to a join arc make the exact
// offset dip by ~1e-5 mm, and dropping such a slice lost a whole side of the contour (the offset
// then "collapsed"). A gouge of 0.1 µm is far below any machine's resolution (G-code: 1 µm).
inline constexpr double kOffsetGougeMm = 1e-4;
// Two edges of adjacent parts run together (common-line cutting) when their distance equals 0 or
// the kerf within this at both ends of the shared stretch [mm]. Nests drawn for common-line
// cutting are exact to ~1e-6; 0.01 mm also accepts hand-made ones and is far below a kerf.
inline constexpr double kCommonLineMm = 0.01;

}  // namespace cutroute::tol
