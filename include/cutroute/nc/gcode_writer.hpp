// write_gcode(): turns a Toolpath into the text of a G-code program for one post-processor dialect.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

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
// The chords the writer cuts an arc of `sweep` [rad] and `radius_mm` into so that none strays more
// than `sagitta_mm` from it: R (1 - cos(phi / 2)) ~ R phi^2 / 8 (1 to 100 000).
inline int arc_chord_count(double sweep, double radius_mm, double sagitta_mm) {
  const double pieces = std::ceil(std::abs(sweep) * std::sqrt(radius_mm / (8 * sagitta_mm)));
  return static_cast<int>(std::clamp(pieces, 1.0, 100000.0));
}

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
