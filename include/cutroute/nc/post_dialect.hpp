// PostDialect: how one machine family wants its G-code written (codes, formats), loaded from JSON.
#pragma once

#include <string>
#include <vector>

#include <cutroute/core/result.hpp>
#include <cutroute/nc/dialect.hpp>

namespace cutroute::nc {

enum class ArcFormat { ij, r };       // G2/G3 with incremental I J centre, or with radius R
enum class CommentStyle { paren, semicolon, none };

// Every field has a default that LinuxCNC's interpreter accepts (the `generic` dialect).
// Code lists may contain the placeholders {pierce_s} (pierce dwell [s]), {pierce_ms} (the same in
// milliseconds, for controls whose G4 P counts ms; not both in one dialect) and {feed} (feed
// [mm/min or in/min]), replaced when written.
struct PostDialect {
  std::string file;  // the JSON file it came from (messages); "" if made in code
  std::string name = "generic";  // a file without "name": its file name without .json
  std::string description;
  std::string units = "mm";                  // "mm" (G21) or "in" (G20): coordinates converted on output
  int decimals = 3;                          // coordinate decimals (mm: 1 µm)
  int feed_decimals = 0;
  ArcFormat arc_format = ArcFormat::ij;
  bool line_numbers = false;
  int line_number_start = 10;
  int line_number_step = 10;
  CommentStyle comments = CommentStyle::paren;
  std::vector<std::string> header = {"G17 G90 G40 G94"};  // after the units word (G20/G21) the writer emits
  std::vector<std::string> footer = {};
  std::string program_end = "M30";
  std::vector<std::string> beam_on = {"M3 S1"};
  std::vector<std::string> pierce = {"G4 P{pierce_s}"};
  std::vector<std::string> beam_off = {"M5"};
  // Torch height control (plasma): on after the lead-in, off before the lead-out. With controller
  // kerf compensation they are written outside G41/G42 .. G40 instead (right after the pierce and
  // after the tool-off), because LinuxCNC refuses digital outputs while compensation is on.
  std::vector<std::string> thc_on = {};
  std::vector<std::string> thc_off = {};
  std::string kerf_left = "G41";
  std::string kerf_right = "G42";
  std::string kerf_off = "G40";
  // Cut direction convention for the kerf side (with left compensation the tool keeps the part on
  // its right when outer contours run clockwise).
  bool outer_clockwise = true;
  bool hole_clockwise = false;
};

// Reads a dialect JSON file; errors name the file and the field. Unknown fields are errors (a
// typo in a post-processor must not silently fall back to a default), and so is a line the writer
// cannot rely on: not one printable ASCII G-code block of at most 200 characters; a units word
// against `units`; G91, or G90.1 with I J arcs; compensation switched on outside kerf_left /
// kerf_right; a move in the plane in other than header and footer; kerf_left / kerf_right /
// kerf_off without G41 / G42 / G40; program_end without M2 or M30; and a dialect its reader
// (reader_dialect()) cannot read back.
Result<PostDialect> load_post_dialect(const std::string& path);
// "generic", "plasma-thc", ... from <data_dir>/dialects/<name>.json, or a file path.
Result<PostDialect> find_post_dialect(const std::string& name_or_path);
// The same, a relative file name looked for in `folder` first (a machine profile's folder).
Result<PostDialect> find_post_dialect(const std::string& name_or_path, const std::string& folder);
// `line` with the placeholders {pierce_s}, {pierce_ms} and {feed} replaced by the given texts (as
// written; {pierce_ms} by pierce_s when pierce_ms is empty, for checks that need only a number).
std::string fill_placeholders(std::string line, const std::string& pierce_s, const std::string& feed,
                              const std::string& pierce_ms = "");
// Does the dialect dwell Fanuc-style ({pierce_ms}, or G4 X seconds), so that G4 P counts milliseconds?
bool fanuc_dwell(const PostDialect& post);
// Do its header or footer move the head (a park position)? Those moves are not part of the route:
// the written program's rapid length and time then exceed the route's, and are quoted as read.
bool moves_outside_the_path(const PostDialect& post);
// The names of the shipped dialects (<data_dir>/dialects/*.json), sorted.
std::vector<std::string> post_dialect_names();

// Can the beam go off and on again (beam_off, beam_on, pierce lines) while G41/G42 is on? LinuxCNC
// refuses the digital and analog outputs M62-M68 under compensation, and the torch-height codes
// bracket the compensated block; without either (the generic laser dialect) it can. The writer
// then keeps compensation on over micro-joint gaps (gcode_writer.cpp).
bool beam_switches_under_compensation(const PostDialect& post);

// The reader dialect that reads what `post` writes, so that `cutroute estimate` understands the
// programs `cutroute optimize` wrote with it:
//   beam on / off  the M words of the beam_on / beam_off lines;
//   inert          every other M word the dialect writes (header, footer, pierce, thc_on,
//                  thc_off, kerf and program-end lines: torch-height outputs, gas valves ...),
//                  except the codes with a fixed meaning (fixed_meaning_m(): M0 M1 M2 M6 M30);
//   G4 P unit      milliseconds when a line writes {pierce_ms} or a G4 X dwell (Fanuc), else
//                  seconds ({pierce_s}).
// Errors (a line that is no G-code block, no M code in beam_on, a beam code with a fixed meaning
// or in both beam_on and beam_off) name the dialect's file and the field.
Result<Dialect> reader_dialect(const PostDialect& post);

// A reader dialect by name: a built-in one, else a post-processor dialect (shipped name or JSON
// file; a relative file is looked for in `folder` first) read the way it writes, so that the
// programs `optimize --dialect NAME` wrote are understood. `unknown` starts the message when the
// name is neither; `file` is the file that named it (a machine profile), "" for the command line.
Result<Dialect> reader_dialect_named(const std::string& name, const std::string& unknown, const std::string& file = "",
                                     const std::string& folder = "");

}  // namespace cutroute::nc
