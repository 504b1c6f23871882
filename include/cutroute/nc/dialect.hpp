// Dialect: the controller conventions the G-code reader needs (beam on/off M codes, dwell unit,
// M codes that are known to have no effect on the path or the time).
#pragma once

#include <string>
#include <vector>

#include <cutroute/core/result.hpp>

namespace cutroute::nc {

enum class DwellUnit { seconds, milliseconds };

struct Dialect {
  std::string name;
  std::vector<int> beam_on;   // M codes that switch the beam/torch on, e.g. {3, 4}
  std::vector<int> beam_off;  // M codes that switch it off, e.g. {5}; M2/M30 always do
  // G4 P unit. LinuxCNC and RS274/NGC read P in seconds; Fanuc-style controls read an integer
  // P in milliseconds. Default seconds (docs/MACHINE-PROFILE.md).
  DwellUnit dwell_p_unit = DwellUnit::seconds;
  // M codes this control knows that change neither the path nor the time, read without a
  // warning: e.g. the digital outputs M62..M65 with which a plasma post-processor holds and
  // releases the torch-height controller. A program we wrote with a post-processor dialect
  // contains such codes at every contour, and reading our own output must not bury real
  // warnings under them (reader_dialect() in post_dialect.hpp collects them). Codes that
  // are not listed keep their warning: in a foreign program an unknown M code may well change
  // what the machine does. Empty for the built-in dialects.
  std::vector<int> inert = {};

  bool switches_on(int m) const;
  bool switches_off(int m) const;
  bool is_inert(int m) const;
};

// M0, M1 (stops), M2, M30 (program end), M6 (tool change): codes whose meaning the reader fixes,
// which no dialect may use as a beam switch or declare inert.
bool fixed_meaning_m(int m);

// Built-in dialects:
//   "rs274"       M3/M4 beam on, M5 off, G4 P in seconds (the default; what dxf2gcode writes)
//   "rs274-m7m9"  M7/M8 beam on, M9 off (controls that drive the laser/torch from the coolant
//                 outputs), G4 P in seconds
//   "fanuc-ms"    M3/M4 on, M5 off, G4 P in milliseconds
Result<Dialect> builtin_dialect(const std::string& name);
std::vector<std::string> builtin_dialect_names();

// A dialect from explicit lists; checks that no code is both on and off and that none of them
// is a code with another fixed meaning (M2, M30, M6). `field` names the source for messages.
Result<Dialect> make_dialect(std::string name, std::vector<int> on, std::vector<int> off, DwellUnit unit,
                             const std::string& field);

}  // namespace cutroute::nc
