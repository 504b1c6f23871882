// Dialect: the controller conventions the G-code reader needs (beam on/off M codes, dwell unit).
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

  bool switches_on(int m) const;
  bool switches_off(int m) const;
};

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
