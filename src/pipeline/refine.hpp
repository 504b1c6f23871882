// refine_entries(): for a fixed cutting order, slide each entry along its contour to shorten rapids.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include <cutroute/core/stop.hpp>
#include <cutroute/cost/route_problem.hpp>
#include <cutroute/model/cut_job.hpp>

namespace cutroute::pipeline {

// The continuous CCP step of the source paper, after the GTSP fixed the order on a finite set of
// candidates: for each contour in turn, with its neighbours' points fixed, the entry arc length s
// minimising rapid(prev tool-off -> pierce(s)) + rapid(tool-off(s) -> next pierce) + lead cut is
// sought by sampling 24 points along the contour and a golden-section search around the best;
// only admissible entries (EntryPlanner::entry_at) are taken and only improvements are kept.
// Multi-piece candidates (chains, common lines) and fallbacks are left as they are.
// Cost: passes × contours × ~40 entry evaluations.
// `penalty`, when set, adds a price (objective units) to the entry of sequence[k] with the given
// pierce and tool-off points, between the previous tool-off point and the next pierce point (the
// park position after the last): shop rules whose price depends on where the rapids run, which
// the refinement must not undo (tip-up: rules::tip_up_entry_penalty()).
using EntryPenalty = std::function<double(std::size_t k, geometry::Vec2 prev_off, geometry::Vec2 pierce, geometry::Vec2 off,
                                          const std::optional<geometry::Vec2>& next)>;
struct Refined {
  int moved = 0;         // entries moved
  bool stopped = false;  // `stop` ended it before its passes were done
};
Refined refine_entries(const model::EntryPlanner& planner, const cost::RoutePrices& prices, geometry::Vec2 start,
                       std::optional<geometry::Vec2> park, std::vector<model::EntryCandidate>& sequence, int passes,
                       const StopToken& stop, const EntryPenalty& penalty = {});

}  // namespace cutroute::pipeline
