// write_gcode(): turns a Toolpath into the text of a G-code program for one post-processor dialect.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include <cutroute/core/tolerances.hpp>
#include <cutroute/core/units.hpp>
#include <cutroute/nc/post_dialect.hpp>
#include <cutroute/nc/toolpath.hpp>

namespace cutroute::nc {

struct GcodeWriteOptions {
  std::string title;          // first comment line (e.g. the nest file name)
  bool comments = true;       // per-segment comments (labels), when the dialect has comments
};

// What was written, measured on the quantised moves actually emitted.
struct WrittenProgram {
  std::string text;
  std::size_t pierces = 0;
  double cut_length_mm = 0.0;    // beam-on path length, arcs exact [mm]
  double rapid_length_mm = 0.0;  // G0 path length [mm]
};

// Smallest arc radius written as G2/G3 [mm]; smaller arcs are written as chords. LinuxCNC refuses
// arcs below its tolerance (0.005 mm, 0.0005 in = 0.0127 mm in G20) as "zero-radius arc": spline
// fits leave arcs of 1-2 um at cusps (d2g_DRAAK, d2g_Lueftergitter_R14), and the whole program was
// refused.
inline constexpr double kMinArcRadiusMm = 0.02;
// Largest arc radius written as G2/G3 (100 m). Such an arc over a whole 3-m sheet still bows 11 mm,
// so larger ones are written as chords, and no I/J/R word goes beyond 1e5 mm.
inline constexpr double kMaxArcRadiusMm = 1.0e5;
// Arcs below kMinArcRadiusMm are written as chords that stay within this of the arc: one move for
// the arcs of a micrometre or two. Chords within the output resolution took two or three, and the
// frame count sets V_on*(n): d2g_Lueftergitter_R14 got 96 more frames, 1.9 % more T_cut.
inline constexpr double kMicroArcChordMm = 0.004;
// The program's coordinate grid: a length in mm rounded to the dialect's decimals in its unit, back
// in mm. The writer, written_arc() and the compensation check round with this one arithmetic:
// written_arc() picks between centres a grid step apart on differences of 1e-12, and a copy that
// rounded one bit differently read an arc about the other centre.
struct ProgramGrid {
  double scale;   // program units per mm
  double steps;   // grid steps per program unit
  double res_mm;  // one grid step [mm]
  explicit ProgramGrid(const PostDialect& d)
      : scale(d.units == "in" ? 1.0 / units::kMmPerInch : 1.0), steps(std::pow(10.0, d.decimals)),
        res_mm(std::pow(10.0, -d.decimals) / scale) {}
  double operator()(double mm) const { return std::round(mm * scale * steps) / steps / scale; }
  geometry::Vec2 operator()(geometry::Vec2 p) const { return {(*this)(p.x), (*this)(p.y)}; }
};

// How the writer emits an arc of `bulge` between a and b, both already on its grid of step res_mm
// (the compensation check follows the same plan, so that it reads the program as written):
//   line   - one G1: nearly straight, or a chord under two grid steps;
//   chords - `chords` G1 moves through points of the arc, none straying more than res_mm (radius
//            beyond kMaxArcRadiusMm) or kMicroArcChordMm (below kMinArcRadiusMm) from it:
//            R (1 - cos(phi / 2)) ~ R phi^2 / 8, 1 to 100 000 of them;
//   arc    - one G2/G3 (two in the R format beyond 150 degrees).
struct ArcPlan {
  enum class Form { line, chords, arc } form = Form::line;
  double radius_mm = 0.0;
  int chords = 1;
};
inline ArcPlan plan_arc(double chord_mm, double bulge, double res_mm) {
  const double b = std::abs(bulge);
  if (b < tol::kStraightBulge || chord_mm < 2 * res_mm) return {};
  ArcPlan p{ArcPlan::Form::arc, chord_mm * (1 + b * b) / (4 * b), 1};
  if (p.radius_mm > kMaxArcRadiusMm || p.radius_mm < kMinArcRadiusMm) {
    const double sagitta = p.radius_mm > kMaxArcRadiusMm ? res_mm : std::max(res_mm, kMicroArcChordMm);
    const double pieces = std::ceil(4 * std::atan(b) * std::sqrt(p.radius_mm / (8 * sagitta)));
    p.form = ArcPlan::Form::chords;
    p.chords = static_cast<int>(std::clamp(pieces, 1.0, 100000.0));
  }
  return p;
}

// An arc as the writer writes it from `from` to `to` (both on the program's grid) [mm], and so
// where the controller puts its centre: I J rounded to the grid (on a coarse grid the neighbouring
// grid point whose start and end radii differ least), or, with R words, on the chord's bisector at
// the rounded radius. The compensation check reads the arcs with these centres: on an inch grid
// they lie up to 0.0005 in from the drawn ones, enough to move the corners the controller's offset
// must turn. Only for arcs plan_arc() writes as arcs (R arcs beyond 150 degrees are split first).
struct WrittenArc {
  geometry::Vec2 centre;  // [mm]
  double radius = 0.0;    // the written R; with I J the start radius [mm]
  int chords = 0;         // > 0: no grid point makes the radii agree (1 decimal): written as chords
};
WrittenArc written_arc(geometry::Vec2 from, geometry::Vec2 to, double bulge, const PostDialect& d);

// Does the writer keep G41/G42 on from segment `from` into the next one, `to`? When `to` resumes
// `from`'s contour past a micro-joint gap (after_tab) on the same kerf side, and the dialect lets
// the beam switch under compensation (beam_switches_under_compensation()).
bool compensation_held(const CutSegment& from, const CutSegment& to, bool beam_switches);

// Coordinates are rounded to the dialect's resolution before writing and the writer's idea of
// the current position is the rounded one, so what the machine does is what we measured. Arc
// centres are recomputed from the rounded end points (radius consistent to the resolution).
// Arcs of more than 150° are split in two for the R format (R is ill-conditioned near 180°).
// Moves that round to zero length are dropped.
WrittenProgram write_gcode(const Toolpath& path, const PostDialect& dialect, const GcodeWriteOptions& options);

}  // namespace cutroute::nc
