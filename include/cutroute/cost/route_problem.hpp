// build_route_problem(): a CutJob's sequencing problem as a solve::Problem (GTSP with precedence).
#pragma once

#include <cstdint>
#include <vector>

#include <cutroute/core/result.hpp>
#include <cutroute/model/cut_job.hpp>
#include <cutroute/solve/problem.hpp>

namespace cutroute::cost {

enum class Objective { time, cost };

// Per-unit prices of one job. Time form: everything in seconds; cost form (eq. 3): C_on per mm
// of cut, C_off per mm of rapid, C_pt per pierce. Both are scaled to int64 ticks with
// units::kTicksPerSecond (1 tick = 1 µs, or 1e-6 cost unit).
struct RoutePrices {
  Objective objective = Objective::time;
  double v_on_mm_s = 100.0;        // working speed used while sequencing [mm/s]
  double v_off_mm_s = 500.0;       // rapid speed [mm/s]
  double pierce_s = 0.5;           // t_pt [s]
  double head_s = 0.0;             // head lift + lower per rapid between segments [s]
  double c_on_per_mm = 0.0;        // cost form [unit/mm]
  double c_off_per_mm = 0.0;       // cost form [unit/mm]
  double c_pt = 0.0;               // cost form [unit/pierce]

  double cut_price(double mm) const;     // seconds or cost of cutting mm
  double rapid_price(double mm) const;   // seconds or cost of a rapid of mm, head time included
  double pierce_price() const;
};

// Node v of the problem: node 0 is the start (its own cluster 0); node v >= 1 is candidate
// `candidate` of basic segment `segment` (cluster segment + 1).
struct RouteNode {
  std::int32_t segment = -1;     // index into CutJob::segments, -1 for the start node
  std::int32_t candidate = -1;   // index into that segment's candidates
};

struct RouteProblem {
  solve::Problem problem;
  std::vector<RouteNode> nodes;
  std::vector<geometry::Vec2> pierce;    // per node [mm] (start node: the start point)
  std::vector<geometry::Vec2> tool_off;  // per node [mm]
  bool returns_to_start = true;          // closed tour: the rapid back to the park point counts
};

struct RouteProblemOptions {
  geometry::Vec2 start;                 // machine position before the first pierce [mm]
  bool return_to_start = true;          // park at the start point after the last cut
  int matrix_max_nodes = 3000;          // above: costs on demand (a matrix would be too big)
};

// The price of cutting one candidate, as the route's inner cost of its node: its pierce, lead-in,
// every piece (contours with overcut, bridges, common edges) and lead-out [s or cost unit].
double inner_price(const model::EntryCandidate& e, const RoutePrices& prices);

// Arc cost a -> b: the rapid from a's tool-off point to b's pierce point. Inner cost of b: its
// pierce, lead-in, every piece (contours with overcut, bridges, common edges) and lead-out. Precedence (a before b) maps to clusters.
Result<RouteProblem> build_route_problem(const model::CutJob& job, const RoutePrices& prices,
                                         const RouteProblemOptions& options);

// The job's chosen candidate per basic segment, in route order (the start node left out).
std::vector<const model::EntryCandidate*> route_entries(const model::CutJob& job, const RouteProblem& rp,
                                                         const std::vector<solve::NodeId>& route);

}  // namespace cutroute::cost
