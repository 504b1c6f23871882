// Test helper: what solve::validate() finds wrong with a route priced from scratch.
#pragma once

#include <string>
#include <vector>

#include <cutroute/solve/solution.hpp>

namespace cutroute::test {

inline std::vector<std::string> route_errors(const solve::Problem& p, const std::vector<solve::NodeId>& route) {
  solve::Solution s;
  s.route = route;
  s.cost = solve::route_cost(p, route);
  return solve::validate(p, s);
}

}  // namespace cutroute::test
