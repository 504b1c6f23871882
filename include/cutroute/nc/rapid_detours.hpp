// Tip-up avoidance: parts' outer contours as obstacles, and a post-pass that routes rapids around parts already cut free.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include <cutroute/core/stop.hpp>
#include <cutroute/geometry/box.hpp>
#include <cutroute/geometry/spatial_index.hpp>
#include <cutroute/geometry/vec2.hpp>
#include <cutroute/model/nest.hpp>
#include <cutroute/nc/toolpath.hpp>

namespace cutroute::nc {

// The outer contour of every part as a polygon (arcs flattened within tol::kArcChordMm) with a
// grown hull: the 16-gon of its extents in 16 directions pushed out by `margin_mm` (every point of
// its boundary at least margin_mm from the part). A rapid "passes over" a
// part when some stretch of the straight move lies inside the polygon (corner to corner included).
class PartObstacles {
 public:
  PartObstacles(const model::Nest& nest, double margin_mm);

  int part_count() const { return static_cast<int>(parts_.size()); }
  // Does the straight move a -> b pass over part `part` (index into nest.parts)?
  bool crosses(int part, geometry::Vec2 a, geometry::Vec2 b) const;
  // Every part the straight move passes over, in increasing index order.
  std::vector<int> crossed(geometry::Vec2 a, geometry::Vec2 b) const;
  // Does the straight move pass over some part with counts(part) true? Through the spatial
  // index: O(log P + parts near the move), for callers that ask many times (entry refinement).
  bool crosses_any(geometry::Vec2 a, geometry::Vec2 b, const std::function<bool(int)>& counts) const;
  // The shortest polyline a -> b (waypoints only, a and b excluded) through the corners of the
  // grown hulls that passes over none of the parts with freed[part] != 0 and keeps the margin
  // from them (except from a part an end point is already that close to); empty when the straight
  // move passes over no freed part; nullopt when there is none (an end point enclosed by freed
  // parts) or when more than kMaxDetourParts parts would have to be gone around.
  // Visibility graph over the hulls of the parts in the way, grown until no leg crosses a freed
  // part: O(V² · E) per round for V hull corners and E polygon edges near the legs.
  // `tests_left`, when given, bounds the work: each test of a leg against one part spends one, and
  // the search gives up (nullopt) when none is left. `stop`, when given, is polled at the first
  // test and then every kStopPollTests tests (a few milliseconds; no clock read per test): the
  // search gives up (nullopt) when it requests a stop, which then stays requested.
  static constexpr std::size_t kMaxDetourParts = 24;
  static constexpr std::size_t kStopPollTests = 4096;
  std::optional<std::vector<geometry::Vec2>> detour(geometry::Vec2 a, geometry::Vec2 b, const std::vector<char>& freed,
                                                    std::size_t* tests_left = nullptr, const StopToken* stop = nullptr) const;

 private:
  struct Obstacle {
    std::vector<geometry::Vec2> polygon;  // outer contour, flattened [mm]
    std::vector<geometry::Vec2> hull;     // grown hull (16 corners), counter-clockwise [mm]
    geometry::Box box;                    // of the polygon [mm]
    std::vector<geometry::Vec2> guard;    // the hull grown by 0.999 margin: what detour legs avoid [mm]
    geometry::Box guard_box;              // of the guard [mm]
  };
  // Does a detour leg a -> b come closer than the margin to the part (or pass over it, when an
  // end point itself is that close)?
  bool blocks(int part, geometry::Vec2 a, geometry::Vec2 b) const;
  std::vector<Obstacle> parts_;
  geometry::StaticSpatialIndex index_;  // over the guard boxes (the polygon boxes when no margin)
};

struct DetourStats {
  int rapids_over_freed = 0;   // straight rapids that would pass over a part already cut free
  int detours = 0;             // of these, routed around (waypoints written as extra G0 moves)
  int unavoidable = 0;         // no way around found: left straight
  int over_budget = 0;         // of these, left straight because the toolpath's search budget was spent
  int left_at_time_limit = 0;  // of these, left straight because `stop` requested a stop (deadline or
                               // cancel) before or during their search; disjoint from over_budget
  double extra_mm = 0.0;       // added rapid length of the detours [mm]
};

// Post-pass on a finished toolpath: a part is free once the segment that cuts its outer contour is
// done; every later rapid (and the one to the park position) that would pass over a free part gets
// the waypoints of PartObstacles::detour() in CutSegment::rapid_via / Toolpath::end_via.
// The searches of one toolpath share a budget of kDetourTestBudget leg-part tests (under a second).
// `stop` (the run's deadline and cancel flag) is polled before each search and inside it: once it
// requests a stop, no more searches run and every remaining rapid over a freed part is left
// straight (still counted in rapids_over_freed, unavoidable and left_at_time_limit). The toolpath
// stays complete: only waypoints are added, never moves removed.
inline constexpr std::size_t kDetourTestBudget = 5'000'000;
DetourStats route_rapids_around_freed_parts(Toolpath& path, const model::Nest& nest, double margin_mm,
                                            const StopToken& stop);

}  // namespace cutroute::nc
