// Test helpers: what solve::validate() finds wrong with a route priced from scratch, and a solve run
// twice that must agree with itself.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <cutroute/solve/solution.hpp>
#include <cutroute/solve/solve.hpp>

namespace cutroute::test {

inline std::vector<std::string> route_errors(const solve::Problem& p, const std::vector<solve::NodeId>& route) {
  solve::Solution s;
  s.route = route;
  s.cost = solve::route_cost(p, route);
  return solve::validate(p, s);
}

// Solves twice and checks that both runs agree (route, iterations) and that the route is valid
// and priced right; returns the first.
inline solve::Solution solve_deterministic(const solve::Problem& p, const solve::SolveParams& sp) {
  const solve::Solution a = solve::solve(p, sp);
  const solve::Solution b = solve::solve(p, sp);
  EXPECT_EQ(a.route, b.route);
  EXPECT_EQ(a.stats.iterations, b.stats.iterations);
  EXPECT_TRUE(solve::validate(p, a).empty());
  EXPECT_EQ(a.cost, solve::route_cost(p, a.route));
  return a;
}

}  // namespace cutroute::test
