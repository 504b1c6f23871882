// A motion model of the cutting head (acceleration, corner speed, block time) that times one
// move sequence block by block, to explain the frame effect of Table 1 per contour.
#pragma once

#include <cstddef>
#include <vector>

#include <cutroute/core/result.hpp>

namespace cutroute::cost {

// One programmed move as the motion model sees it.
struct MotionMove {
  double length_mm = 0.0;  // path length [mm]
  double feed_mm_s = 0.0;  // programmed speed for this move [mm/s], > 0
  double radius_mm = 0.0;  // arc radius [mm]; 0 for a straight move
  double turn_rad = 0.0;   // direction change from the previous move's end tangent to this
                           // move's start tangent [rad, 0..pi]; ignored when it starts from rest
  bool from_rest = false;  // the head stands still before this move (after a pierce or a stop)
};

// Controller limits. Junction speed: the "junction deviation" rule used by GRBL-type planners,
// v_j^2 = a * delta * s / (1 - s) with s = sin(turn / 2), capped by both moves' feeds; arc speed:
// v^2 <= a * r (centripetal acceleration). block_time_s is the least time a block can take
// (block processing/look-ahead rate); it is what makes many short blocks slow.
struct MotionParams {
  double accel_mm_s2 = 0.0;            // path and centripetal acceleration limit [mm/s^2], > 0
  double junction_deviation_mm = 0.0;  // corner rounding allowance [mm], >= 0 (0: stop at every corner)
  double block_time_s = 0.0;           // minimum time per block [s], >= 0
};

struct MotionTime {
  double time_s = 0.0;            // total time of the moves [s]
  double length_mm = 0.0;         // total length [mm]
  double mean_speed_mm_s = 0.0;   // length / time [mm/s]
  std::size_t block_limited = 0;  // blocks whose time was raised to block_time_s
};

// Times the sequence: junction limits, then a forward and a backward pass so that every
// block can reach its exit speed with the given acceleration (v_out^2 <= v_in^2 + 2 a L), then a
// trapezoid or triangle per block, raised to block_time_s when shorter. The sequence ends at
// rest. O(number of moves). Errors: non-positive accel or feed, negative lengths.
Result<MotionTime> time_moves(const std::vector<MotionMove>& moves, const MotionParams& params);

}  // namespace cutroute::cost
