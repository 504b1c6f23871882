// What the G-code reader knows of each word letter and G code: names for messages, the codes
// without effect, the modal groups it checks, LinuxCNC's R-arc limit.
#pragma once

#include <cstdio>
#include <numbers>
#include <string>

#include <cutroute/core/units.hpp>

namespace cutroute::nc::detail {

inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

inline std::string g_name(int tenths) {
  char buf[32];
  if (tenths % 10 != 0)
    std::snprintf(buf, sizeof buf, "G%d.%d", tenths / 10, tenths % 10);
  else
    std::snprintf(buf, sizeof buf, "G%d", tenths / 10);
  return buf;
}

// Letters the reader understands; the others are warned about once per line.
inline bool known_letter(char c) {
  switch (c) {
    case 'G':
    case 'M':
    case 'N':
    case 'O':
    case 'X':
    case 'Y':
    case 'Z':
    case 'I':
    case 'J':
    case 'K':
    case 'R':
    case 'F':
    case 'S':
    case 'T':
    case 'P':
    case 'D':
    case 'H':
    case 'Q':
      return true;
    default:
      return false;
  }
}

// G codes accepted without an effect on lengths or time (see gcode_reader.hpp).
inline bool inert_g(int t) {
  switch (t) {
    case 170:
    case 400:
    case 410:
    case 420:
    case 490:
    case 540:
    case 550:
    case 560:
    case 570:
    case 580:
    case 590:
    case 610:
    case 611:
    case 640:
    case 800:
    case 940:
      return true;
    default:
      return false;
  }
}

// LinuxCNC's RADIUS_TOLERANCE_INCH (0.00005 in; RADIUS_TOLERANCE_MM is the same in mm): an R-form
// arc whose |R| falls short of half its chord by more is refused ("arc radius too small to reach
// end point"), in G20 and G21 programs alike (found by bisection with rs274 2.9) [mm].
inline constexpr double kControllerRadiusShortMm = 0.00005 * units::kMmPerInch;

// LinuxCNC's CENTER_ARC_RADIUS_TOLERANCE_INCH / _MM (2·0.001·√2 in, 2·0.01·√2 mm, in the program's
// unit) and its relative 0.1 % of the start radius: an I/J arc whose end radius differs from its
// start radius by more than both is refused ("radius to end of arc differs from radius to start");
// within either it is run as a spiral. Found by bisection with rs274 2.9 at radii 1-1000 mm and
// 0.1-10 in: refused beyond 0.02828 mm up to a radius of 28 mm, beyond 0.1 % from there.
inline constexpr double kControllerArcRadiusAbsMm = 2.0 * 0.01 * std::numbers::sqrt2;
inline constexpr double kControllerArcRadiusAbsInch = 2.0 * 0.001 * std::numbers::sqrt2;
inline constexpr double kControllerArcRadiusRel = 0.001;

// The modal groups whose codes change what the reader measures: motion, distance mode, arc
// distance mode, units. Two codes of one group in a block are refused by the controller (LinuxCNC:
// "two G codes used from same modal group", the same code twice too); G80, in LinuxCNC's motion
// group, is left out: it accepts "G0 G80", and Fanuc posts write it beside G0 in safety lines.
inline int measured_modal_group(int tenths) {
  switch (tenths) {
    case 0:
    case 10:
    case 20:
    case 30:
      return 1;
    case 900:
    case 910:
      return 3;
    case 901:
    case 911:
      return 4;
    case 200:
    case 210:
      return 6;
    default:
      return 0;
  }
}

}  // namespace cutroute::nc::detail
