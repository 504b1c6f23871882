// check_program(): re-parses a written cutting program and checks it against the nest it was made for.
#pragma once

#include <string>
#include <vector>

#include <cutroute/model/nest.hpp>

#include "support/gcode_probe.hpp"

namespace cutroute::test {

struct ProgramCheckOptions {
  double on_contour_mm = 0.005;   // a cut move lies on a contour when all its samples are this close
  double clearance_mm = 0.5;      // leads must keep this far from other contours
  double max_lead_mm = 20.0;      // lead-in + lead-out length per pierce
  double max_overcut_mm = 2.0;    // extra length cut along a contour past one full loop
  // Micro-joints: every outer contour is cut in tabs + 1 runs and left uncut over tabs gaps of
  // tab_width_mm in total tabs * tab_width_mm (0: no tabs, each contour in one run, whole).
  int tabs = 0;
  double tab_width_mm = 0.0;      // [mm]
};

struct ProgramCheck {
  std::vector<std::string> failures;   // empty when the program is admissible
  int runs = 0;                        // beam-on runs (= pierces)
  int contours_cut = 0;
  double cut_length = 0;               // [mm]
  double rapid_length = 0;             // [mm]
  ProbeResult probe;
};

// Independently of the route data: every closed cut contour of the nest (the sheet excluded) is
// covered by cut moves of exactly one beam-on run, over its whole length and not more than once
// (plus the overcut); a contour's run comes before the run of the contour that contains it
// (holes before their outer contour, inner parts before the hole around them); moves that lie on
// no contour (leads) stand only at the start and end of a run and are short; no lead comes closer
// than the clearance to any other contour, and none touches its own contour before its end;
// every pierce point lies in scrap; no feed move is made with the beam off.
ProgramCheck check_program(const model::Nest& nest, const std::string& gcode, const ProgramCheckOptions& options);

}  // namespace cutroute::test
