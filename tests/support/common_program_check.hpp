// check_common_program(): re-parses a cutting program and checks it against a nest whose parts may share cuts.
#pragma once

#include <string>
#include <vector>

#include <cutroute/model/nest.hpp>

#include "support/gcode_probe.hpp"

namespace cutroute::test {

struct CommonProgramCheck {
  std::vector<std::string> failures;  // empty when the program is admissible
  ProbeResult probe;
  int runs = 0;                       // beam-on runs (= pierces)
  int pierces_on_a_cut = 0;           // runs starting on a drawn boundary (no lead-in)
  double boundary_cut_mm = 0;         // beam-on length lying on drawn part boundaries [mm]
  // The nearest approach of the beam's centre to a part's material where no compensation offsets
  // it: every pierce and every beam-on move outside G41/G42 (common lines, their leads, connectors,
  // cuts written on their kerf offset), measured exactly to the drawn boundaries (0 inside a
  // part), looked for within 10 mm [mm]; `nearest_line` its program line. On parts drawn kerf
  // apart a common line runs exactly half a kerf from both parts, and nothing may come nearer.
  double nearest_uncompensated_mm = 10;
  int nearest_line = 0;
  // With `tab_width_mm` > 0: per drawn contour (the sheet excluded, in nest order), the widths of
  // the stretches of its boundary left uncut (micro-joints), in sampling order [mm].
  std::vector<std::vector<double>> uncut;
};

// Independently of the route data, from the program text alone:
//  - every point of every part boundary (sampled every 0.5 mm) lies within `on_mm` of some
//    beam-on move: every part is cut free of everything around it;
//  - each contour's boundary is complete before that of the contour around it (holes before
//    their part, parts in a hole before the hole);
//  - for parts sharing boundary stretches (a group), every shared stretch is cut before the
//    group's outer boundary is complete (after that the parts are free and may move);
//  - moves lying on no boundary (leads, connectors across a kerf gap) never pass through the
//    material of a part (sampled, away from their ends), and every pierce lies in scrap or on a
//    drawn boundary; no feed move with the beam off; the program ends.
// `on_mm`: 0.005 for parts drawn touching; half the kerf (plus that) for parts drawn kerf apart.
// `group_rule` false: skip the third check. Drawings whose contours touch along stretches that
// are not common lines (cut twice, e.g. d2g_DRAAK) make "a move lying on two boundaries" an
// ambiguous sign of a common line there.
// `tab_width_mm` > 0 (micro-joints): an outer contour's boundary may stay uncut where it lies
// farther than half of `tab_width_mm` from every other contour (its own edges, away from junctions; never
// on a common line or a hole); the boundary is then sampled every 0.02 mm and the uncut stretches
// are measured (`uncut`), an uncut stretch elsewhere is a failure. Its parts count as done when
// the rest of their boundary is.
// `fit_radius_mm` > 0: a boundary point that a disc of that radius cannot touch from scrap (a
// feature narrower than the kerf, which a path on the kerf offset passes by) need not be cut.
CommonProgramCheck check_common_program(const model::Nest& nest, const std::string& gcode, double on_mm,
                                        bool group_rule = true, double tab_width_mm = 0.0, double fit_radius_mm = 0.0);

}  // namespace cutroute::test
