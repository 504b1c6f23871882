// build_toolpath(): turns the chosen entries of a cut job, in cutting order, into a Toolpath.
#pragma once

#include <vector>

#include <cutroute/model/cut_job.hpp>
#include <cutroute/model/nest.hpp>
#include <cutroute/nc/toolpath.hpp>

namespace cutroute::nc {

enum class KerfMode { none, cam, controller };

struct ToolpathOptions {
  geometry::Vec2 start;            // head position before the program [mm]
  geometry::Vec2 end;              // park position after it [mm]
  double feed_mm_min = 6000;       // programmed cutting feed [mm/min]
  double pierce_time_s = 0.5;      // dwell after beam on [s]
  KerfMode kerf = KerfMode::none;  // controller: G41/G42 on the scrap side
};

// `sequence` lists the chosen candidate of each basic segment, in cutting order. Each becomes one
// cutting segment: pierce, lead-in, its pieces (contour pieces with overcut and common edges as
// PieceRole::contour, bridges as PieceRole::bridge), lead-out. A chain's label names every
// contour it cuts ("part 3 outer + part 4 outer"). The kerf side is that of the entered contour:
// chains join outer contours cut in the same direction, so it holds for the whole segment.
Toolpath build_toolpath(const model::Nest& nest, const std::vector<const model::EntryCandidate*>& sequence,
                        const ToolpathOptions& options);

}  // namespace cutroute::nc
