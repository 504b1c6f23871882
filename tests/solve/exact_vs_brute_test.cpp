// 300 random tiny instances: exact DP == brute force, heuristic >= exact and == on >= 98 %, all valid.
#include <gtest/gtest.h>

#include <limits>

#include <cutroute/solve/exact_dp.hpp>
#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/solve.hpp>

#include "random_instance.hpp"

namespace cutroute::solve {
namespace {

TEST(ExactVsBruteForce, ThreeHundredRandomInstances) {
  Rng rng(20261121);
  int heuristic_equal = 0, feasible = 0, infeasible = 0;
  constexpr int kInstances = 300;
  for (int k = 0; k < kInstances; ++k) {
    const test::RandomSpec spec = test::mixed_spec(k, rng);
    const Problem p = test::random_problem(spec, rng);
    SCOPED_TRACE("instance " + std::to_string(k) + ": " + std::to_string(p.cluster_count()) + " clusters, " +
                 std::to_string(p.node_count()) + " nodes");
    const Cost truth = test::brute_force(p);

    const Solution ex = solve_exact(p, std::size_t{1} << 30, StopToken{});
    if (truth == std::numeric_limits<Cost>::max()) {
      ++infeasible;
      EXPECT_EQ(ex.status, SolveStatus::infeasible);
      SolveParams hp;
      hp.solver = SolverKind::heuristic;
      hp.threads = 1;
      hp.min_stagnation_work = 30000;
      const Solution h = solve(p, hp);
      EXPECT_EQ(h.status, SolveStatus::no_solution);
      continue;
    }
    ++feasible;
    ASSERT_EQ(ex.status, SolveStatus::optimal);
    EXPECT_EQ(ex.cost, truth);
    EXPECT_TRUE(validate(p, ex).empty()) << validate(p, ex).front();

    SolveParams hp;
    hp.solver = SolverKind::heuristic;
    hp.seed = static_cast<std::uint64_t>(k) + 1;
    hp.threads = 1;
    hp.min_stagnation_work = 30000;  // three thousandths of the default: tiny instances, fast under sanitizers
    const Solution h = solve(p, hp);
    if (h.status == SolveStatus::no_solution) continue;  // counted as not equal
    EXPECT_TRUE(validate(p, h).empty()) << validate(p, h).front();
    EXPECT_GE(h.cost, truth);
    heuristic_equal += h.cost == truth;
    if (h.cost != truth)
      std::printf("miss %d: m=%d n=%d sym=%d closed=%d prec=%d inner=%d forb=%d: %ld vs %ld\n", k, p.cluster_count(), p.node_count(),
                  spec.symmetric, spec.closed, spec.precedence_pairs, spec.inner_costs, spec.forbidden_arcs, static_cast<long>(h.cost),
                  static_cast<long>(truth));

    SolveParams ap;  // automatic: the DP on instances this small, with its proof
    const Solution a = solve(p, ap);
    EXPECT_EQ(a.status, SolveStatus::optimal);
    EXPECT_EQ(a.cost, truth);
  }
  EXPECT_GT(infeasible, 0);  // the generator does produce infeasible cases (forbidden arcs)
  EXPECT_GE(heuristic_equal * 100, 98 * feasible) << heuristic_equal << " of " << feasible;
  RecordProperty("heuristic_equal", heuristic_equal);
  RecordProperty("feasible", feasible);
  std::printf("heuristic == optimum on %d of %d feasible instances (%d infeasible)\n", heuristic_equal, feasible, infeasible);
}

// Pure enumeration of node choices too, on the smallest instances: checks the reference itself.
TEST(ExactVsBruteForce, ReferenceAgreesWithFullEnumeration) {
  Rng rng(7);
  for (int k = 0; k < 40; ++k) {
    test::RandomSpec spec;
    spec.clusters = 2 + static_cast<int>(rng.below(3));
    spec.max_nodes = 3;
    spec.symmetric = k % 2 == 0;
    spec.closed = k % 3 != 0;
    spec.precedence_pairs = k % 4;
    spec.inner_costs = true;
    const Problem p = test::random_problem(spec, rng);
    // Enumerate every route: one node per cluster in every order, keep the valid ones.
    Cost best = std::numeric_limits<Cost>::max();
    std::vector<int> order(static_cast<std::size_t>(p.cluster_count()));
    for (int c = 0; c < p.cluster_count(); ++c) order[static_cast<std::size_t>(c)] = c;
    do {
      std::vector<std::size_t> pick(order.size(), 0);
      while (true) {
        Solution s;
        for (std::size_t i = 0; i < order.size(); ++i) s.route.push_back(p.nodes_of(ClusterId(order[i]))[pick[i]]);
        s.cost = route_cost(p, s.route);
        if (validate(p, s).empty()) best = std::min(best, s.cost);
        std::size_t i = 0;
        while (i < pick.size() && ++pick[i] == p.nodes_of(ClusterId(order[i])).size()) pick[i++] = 0;
        if (i == pick.size()) break;
      }
    } while (std::next_permutation(order.begin(), order.end()));
    EXPECT_EQ(test::brute_force(p), best) << "instance " << k;
  }
}

}  // namespace
}  // namespace cutroute::solve
