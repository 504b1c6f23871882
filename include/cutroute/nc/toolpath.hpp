// Toolpath: the machine-independent cutting program (rapids, pierces, lead-ins, cuts, lead-outs).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::nc {

// What a piece of cutting path is for: the report, the picture and the G-code comments use it,
// and lead pieces may get their own feed or torch-height handling.
enum class PieceRole { lead_in, contour, bridge, lead_out };
const char* to_string(PieceRole r);

enum class KerfSide { none, left, right };  // controller compensation (G41 left / G42 right)

struct CutPiece {
  geometry::Contour path;   // open, in the order of travel [mm]
  PieceRole role = PieceRole::contour;
  std::int32_t contour = -1;  // the nest contour this piece cuts (contour pieces), else -1
  // Common-line cutting: the neighbouring contour whose boundary this piece cuts too (one cut for
  // both parts), else -1.
  std::int32_t shared_with = -1;
};

// One cutting segment of the source paper: pierce -> lead-in -> contour(s) -> lead-out -> tool off.
// The pieces are continuous: each starts where the previous one ends.
struct CutSegment {
  geometry::Vec2 pierce;             // [mm]
  std::vector<CutPiece> pieces;
  KerfSide kerf = KerfSide::none;    // with --kerf-mode controller
  double feed_mm_min = 0.0;          // programmed cutting feed [mm/min]
  std::string label;                 // e.g. "part 3 hole 2", written as a comment
  // Shop rules (nc/rapid_detours.hpp): rapid waypoints before the pierce, so the rapid to this
  // segment goes around parts already cut free; empty: one straight rapid [mm]. After a tab: the
  // corners of the gap, so the rapid follows the contour.
  std::vector<geometry::Vec2> rapid_via;
  // Micro-joints (nc/micro_joints.hpp): this segment resumes the previous one's contour past a tab
  // gap, pierced on the contour with the same kerf side. The writer keeps controller compensation
  // on over the gap where the dialect allows (gcode_writer.hpp), so the cut resumes on the offset
  // path instead of entering the compensation on the contour.
  bool after_tab = false;
};

struct Toolpath {
  geometry::Vec2 start;              // machine position before the program [mm]
  std::vector<CutSegment> segments;  // in cutting order
  geometry::Vec2 end;                // where the head parks after the last cut [mm]
  std::vector<geometry::Vec2> end_via;  // shop rules: rapid waypoints before parking [mm]
  double pierce_time_s = 0.0;        // dwell after beam on [s]
};

// The point where a segment's cutting ends (tool-off point).
geometry::Vec2 tool_off_point(const CutSegment& s);

}  // namespace cutroute::nc
