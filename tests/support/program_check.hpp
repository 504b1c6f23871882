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
  // Kerf offset of the toolpath (--kerf-mode cam: kerf / 2): a contour's cut moves lie this far
  // (± on_contour_mm) from the drawn contour, on its scrap side (outside an outer contour, inside
  // a hole). 0: on the drawn contour.
  double kerf_offset_mm = 0.0;
  // --kerf-mode controller with cuts written on their offset (details finer than the kerf): cut
  // moves made outside G41/G42 lie this far from the drawn contour, as with kerf_offset_mm; those
  // under G41/G42 on it. 0: every cut move as kerf_offset_mm says.
  double uncompensated_offset_mm = 0.0;
  // Micro-joints: every outer contour is cut in tabs + 1 runs and left uncut over tabs gaps of
  // tab_width_mm in total tabs * tab_width_mm (0: no tabs, each contour in one run, whole); one
  // shorter than 2 · tabs · tab_width_mm is cut whole.
  int tabs = 0;
  double tab_width_mm = 0.0;      // [mm]
  // Multi-segment cutting: a contour may be cut in up to this many runs (pieces), which together
  // cover it: every boundary point (sampled every 0.5 mm) lies on a cut move of one of them, and
  // their cut is no longer than the contour plus one overcut per run. 1: one run, whole.
  int max_runs_per_contour = 1;
};

struct ProgramCheck {
  std::vector<std::string> failures;   // empty when the program is admissible
  int runs = 0;                        // beam-on runs (= pierces)
  int contours_cut = 0;
  double cut_length = 0;               // [mm]
  double rapid_length = 0;             // [mm]
  std::vector<int> arc_moves;          // per cut contour (nest order, sheet left out): G2/G3 moves on it
  int bridges = 0;                     // moves through scrap from one contour of a run to the next
  int split_contours = 0;              // contours cut in more than one run (multi-segment cutting)
  std::vector<int> runs_per_contour;   // per cut contour (nest order, sheet left out)
  double bridge_length = 0;            // [mm]
  ProbeResult probe;
};

// Independently of the route data: every closed cut contour of the nest (the sheet excluded) is
// covered by cut moves of exactly one beam-on run, over its whole length and not more than once
// (plus the overcut) (with max_runs_per_contour > 1: by up to that many runs together); every run
// of a contour comes before every run of the contour that contains it (holes before any piece of
// their outer contour, inner parts before the hole around them); moves that lie on
// no contour (leads) stand only at the start and end of a run and are short; no lead comes closer
// than the clearance to any other contour, and none touches its own contour before its end;
// every pierce point lies in scrap; no feed move is made with the beam off. With a kerf offset,
// "whole" means: wherever a tool of radius kerf_offset_mm fits against the drawn contour on its
// scrap side (sampled at three points per drawn segment), the contour's cut passes within
// kerf_offset_mm + on_contour_mm + 1 µm; and "not more than once": its cut is no longer than the offset curve can
// be (drawn length ± 2π · offset, + for outer contours, - for holes, plus the overcut). A run may cut several
// contours (chain cutting) joined by bridges: moves off the contours between a move on one contour
// and a move on another, which must stay in scrap and keep the clearance from every other
// contour (counted in `bridges`; a test of the standard technique expects none).
ProgramCheck check_program(const model::Nest& nest, const std::string& gcode, const ProgramCheckOptions& options);

}  // namespace cutroute::test
