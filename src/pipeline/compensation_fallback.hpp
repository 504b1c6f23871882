// offset_refused_blocks(): cuts a controller's compensation would refuse, written on their kerf offset instead.
#pragma once

#include <string>
#include <vector>

#include <cutroute/model/nest.hpp>
#include <cutroute/nc/post_dialect.hpp>
#include <cutroute/nc/toolpath.hpp>

namespace cutroute::pipeline {

// With --kerf-mode controller, a compensated cut whose drawing has details finer than the kerf
// (nc::compensation_hazards: concave corners, tight concave arcs, short entries) is refused by the
// controller (LinuxCNC stops the program there). Each such cut of a contour (whole, a chain's
// contours, or a multi-segment piece) is written instead as --kerf-mode cam writes it: the torch
// centre on the contour's kerf offset, no G41/G42, its leads and bridges ending and starting on
// that path (they move by kerf/2 into scrap). Left compensated: common lines, cuts next to a tab,
// and contours whose offset is not one loop (a feature narrower than the kerf, which no toolpath
// follows).
// `written_with` and `held_over_tabs` as for nc::compensation_hazards().
struct OffsetCuts {
  std::vector<std::string> labels;  // the cuts rewritten
  // The most a rewritten path deviates from kerf/2 where the offset needed a drawing's details
  // shorter than a fraction of the kerf straightened (model::kerf_offset_cut) [mm].
  double deviation_mm = 0.0;
};
// `pieces`: pieces of a contour are rewritten too (false with micro-joints, whose pieces between
// tabs keep the compensation they resume with).
OffsetCuts offset_refused_blocks(nc::Toolpath& path, const model::Nest& nest, double kerf_mm, bool held_over_tabs,
                                 const nc::PostDialect& written_with, bool pieces);

}  // namespace cutroute::pipeline
