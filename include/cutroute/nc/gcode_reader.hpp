// read_gcode(): one pass over an RS274/ISO cutting program -> lengths, pierces, frames, dwells.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <cutroute/core/diagnostic.hpp>
#include <cutroute/core/result.hpp>
#include <cutroute/core/tolerances.hpp>
#include <cutroute/geometry/vec2.hpp>
#include <cutroute/nc/dialect.hpp>

namespace cutroute::nc {

// What the reader accepts, in brief (docs/FRAMES.md has the frame rule):
//   G0 G1 G2 G3 (modal), I/J incremental (default, G91.1) or absolute (G90.1), R with sign
//   (R < 0: the arc longer than 180°), I/J full circles, P turns on G2/G3 (LinuxCNC); G4 P dwell
//   (in the dialect's unit; Fanuc-style dialects also G4 X seconds), the block's axis words then
//   moved in the motion mode (RS274/NGC); G17 only (G18/G19 are an error); G20/G21; G90/G91;
//   G40/G41/G42 (noted: lengths are of the programmed path, no compensation); G92 (the origin
//   moved: later absolute X/Y/I/J from it), G92.1/G92.2 cancel it, G92.3 restores; G49, G54..G59, G61,
//   G61.1, G64, G80, G94 accepted without effect; F T N words, O or ':' program numbers; S (modal):
//   S0 after a power above 0 is zero power, the beam's feed moves then travel (GRBL laser programs);
//   M3/M4/M5/M7/M8/M9 with the beam codes taken from the dialect; M0 M1 M6; M2/M30 end the
//   program, as does a '%' line closing a program opened by one; the dialect's inert M codes
//   (Dialect::inert) without effect; comments ( ) and ;; block delete '/'; blanks anywhere
//   outside comments, inside numbers too; any letter case; LF, CRLF, CR.
// Unknown words or codes: a warning with the line number (a block with an unknown G code is not
// moved; G28/G30/G53 are named as travel not counted). Also warned: a program whose feed moves
// are never cut (the beam never switched on by the dialect's codes, naming a built-in dialect
// that reads the codes it uses), a G4 P of 100 or more in a seconds dialect (a Fanuc program's
// milliseconds?), G70/G71 (Fanuc's inch/mm, read in the unit in effect), and blocks LinuxCNC
// refuses: two codes of a modal group that is measured, an R arc short of its chord by more than
// 0.00005 in. Malformed numbers, arcs whose end is not on the circle, missing program end,
// subprograms (M98/M99) and LinuxCNC o-words, whose cutting would be left out: an error.
// One executed XY move, recorded when ReadOptions::moves is set (for motion models and tests).
struct Move {
  enum class Kind { rapid, line, arc_cw, arc_ccw };
  Kind kind = Kind::line;
  bool beam_on = false;        // a cutting move
  bool pierce = false;         // the first cutting move after a pierce (the head starts from rest)
  double x0 = 0, y0 = 0;       // start [mm]
  double x1 = 0, y1 = 0;       // end [mm]
  double length_mm = 0.0;      // [mm]
  double radius_mm = 0.0;      // arcs only [mm]
  double start_dir_rad = 0.0;  // tangent direction at the start [rad]
  double end_dir_rad = 0.0;    // tangent direction at the end [rad]
  double feed_mm_min = 0.0;    // programmed F, 0 when none yet [mm/min]
  std::size_t line = 0;        // 1-based source line
};

struct ReadOptions {
  Dialect dialect = Dialect{"rs274", {3, 4}, {5}, DwellUnit::seconds};
  // |start radius - end radius| of an I/J arc above this is warned (gcode.arc_off_circle): in G21
  // programs [mm], in G20 programs [inch] (their coordinates are rounded to a coarser grid). It is
  // an error only where LinuxCNC refuses it (gcode_codes.hpp).
  double arc_radius_tol_mm = tol::kGcodeArcRadiusMm;
  double arc_radius_tol_inch = tol::kGcodeArcRadiusInch;
  // At most this many warnings are kept; the rest are only counted.
  std::size_t max_warnings = 50;
  // When set, every XY move of non-zero length is appended here (one allocation per move: keep
  // it unset when only totals are needed).
  std::vector<Move>* moves = nullptr;
  // Where the head stands when the program starts [mm]: the first move's length is measured from
  // it (a program made with optimize --start begins with the rapid from that point).
  geometry::Vec2 start_mm{0, 0};
};

// Totals of one program. Lengths are XY path lengths in mm (arcs exact: radius × sweep; Z and
// helical components are not counted); inch programs are converted.
struct ProgramStats {
  std::size_t lines = 0;                    // physical lines read, up to the program end
  std::size_t frames = 0;                   // blocks by the frames.hpp definition (Table 1's n)
  std::size_t pierces = 0;                  // beam-on events: off -> on by a dialect code, plus a re-start of
                                            // cutting after a rapid made with the beam still on
  double cut_length_mm = 0.0;               // L_on: G1/G2/G3 moves with the beam on, not at S0 [mm]
  double rapid_length_mm = 0.0;             // L_off: G0 moves, beam on or off [mm]
  double feed_off_length_mm = 0.0;          // G1/G2/G3 moves with the beam off or at S0 (not L_on, not L_off) [mm]
  double feed_off_time_s = 0.0;             // those moves at their programmed F (moves with a known F) [s]
  double feed_off_length_no_feed_mm = 0.0;  // those moves made before any F was programmed [mm]
  double cut_time_at_feed_s = 0.0;          // L_on at the programmed F, for information [s]
  double cut_length_no_feed_mm = 0.0;       // cutting length before any F was programmed [mm]
  double dwell_s = 0.0;                     // sum of G4 dwells [s]
  std::size_t dwells = 0;
  // The part of dwell_s programmed at a pierce: after a beam-on, before its first cutting move.
  // That dwell is the pierce itself, so a time estimate must not add t_pt for it again.
  double pierce_dwell_s = 0.0;              // [s]
  std::size_t pierce_dwells = 0;            // pierces with such a dwell (several dwells count once)
  std::size_t rapid_moves = 0;     // G0 blocks with XY motion
  std::size_t cut_moves = 0;       // G1/G2/G3 blocks with XY motion and the beam on
  std::size_t arc_moves = 0;       // G2/G3 blocks (beam on or off)
  std::size_t beam_on_rapids = 0;  // G0 moves made while the beam was switched on
  bool inch = false;               // G20 was used somewhere
  std::vector<int> unknown_m_codes;  // M codes neither the dialect nor the reader knows, as first met
  // At most ReadOptions::max_warnings, each with its Diagnostic::code: gcode.unknown_word,
  // gcode.unknown_m_code, gcode.line_number, gcode.never_cut, gcode.after_end,
  // gcode.travel_not_counted (G28/G30/G53), gcode.beam_on_and_off, gcode.dwell_unit,
  // gcode.dwell_axis_words, gcode.arc_word_on_line, gcode.no_feed, gcode.beam_on_rapid,
  // gcode.arc_radius_short, gcode.arc_off_circle, gcode.same_modal_group, gcode.fanuc_units,
  // gcode.zero_power.
  Diagnostics warnings;
  std::size_t suppressed_warnings = 0;
};

// Reads a program held in memory. `file` names the source in diagnostics. The error (first
// problem found) carries file and 1-based line.
Result<ProgramStats> read_gcode(std::string_view program, const std::string& file,
                                const ReadOptions& options);

// Reads the file into one buffer, then read_gcode().
Result<ProgramStats> read_gcode_file(const std::string& path, const ReadOptions& options);

}  // namespace cutroute::nc
