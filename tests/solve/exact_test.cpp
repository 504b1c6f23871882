// Exact DP beyond brute-force sizes: agrees with the heuristic's bound, limits give a valid lower bound.
#include <gtest/gtest.h>

#include <algorithm>

#include <cutroute/solve/exact_dp.hpp>
#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/solve.hpp>

#include "random_instance.hpp"

namespace cutroute::solve {
namespace {

Problem medium(std::uint64_t seed, int clusters, int nodes, int pairs) {
  Rng rng(seed);
  test::RandomSpec spec;
  spec.clusters = clusters;
  spec.max_nodes = nodes;
  spec.symmetric = false;
  spec.precedence_pairs = pairs;
  return test::random_problem(spec, rng);
}

// Found by fuzzing: routes of valid arcs near kMaxCost cost more than kForbiddenCost in all, and both
// solvers reported "no route without forbidden arcs" for them. Arcs of 2^40 - 0..6 on 6 clusters:
// every tour costs about 6 * 2^40 = 3 * kForbiddenCost.
TEST(ExactDp, RoutesDearerThanTheForbiddenSentinelAreSolutions) {
  const int n = 6;
  std::vector<Cost> m(static_cast<std::size_t>(n * n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m[static_cast<std::size_t>(i * n + j)] = i == j ? 0 : kMaxCost - (i + j) % 7;
  ProblemBuilder b(n);
  b.set_cost_matrix(m);
  for (int i = 0; i < n; ++i) b.add_cluster({NodeId(i)});
  auto built = b.build();
  ASSERT_TRUE(built.ok()) << built.error().message;
  const Problem& p = *built;
  const Solution ex = solve_exact(p, std::size_t{1} << 30, StopToken{});
  ASSERT_EQ(ex.status, SolveStatus::optimal);
  EXPECT_GT(ex.cost, kForbiddenCost);
  EXPECT_TRUE(validate(p, ex).empty());
  SolveParams hp;
  hp.solver = SolverKind::heuristic;
  hp.threads = 1;
  const Solution h = solve(p, hp);
  ASSERT_EQ(h.status, SolveStatus::feasible);
  EXPECT_TRUE(validate(p, h).empty());
  EXPECT_EQ(h.cost, ex.cost);
  // The heuristic's route as the DP's incumbent is kept, not discarded as infeasible.
  const Solution ex2 = solve_exact(p, std::size_t{1} << 30, StopToken{}, &h);
  EXPECT_EQ(ex2.status, SolveStatus::optimal);
  EXPECT_EQ(ex2.cost, ex.cost);
}

TEST(ExactDp, ProvesOptimumBelowEveryHeuristicRun) {
  const Problem p = medium(3, 11, 5, 6);
  const Solution ex = solve_exact(p, std::size_t{1} << 30, StopToken{});
  ASSERT_EQ(ex.status, SolveStatus::optimal);
  ASSERT_TRUE(validate(p, ex).empty());
  EXPECT_EQ(ex.lower_bound, ex.cost);
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    SolveParams hp;
    hp.solver = SolverKind::heuristic;
    hp.seed = seed;
    hp.threads = 1;
    const Solution h = solve(p, hp);
    EXPECT_GE(h.cost, ex.cost);
  }
  // With the heuristic's route as incumbent the DP proves the same optimum (pruning keeps it exact).
  SolveParams hp;
  hp.solver = SolverKind::heuristic;
  hp.threads = 1;
  const Solution h = solve(p, hp);
  const Solution ex2 = solve_exact(p, std::size_t{1} << 30, StopToken{}, &h);
  EXPECT_EQ(ex2.status, SolveStatus::optimal);
  EXPECT_EQ(ex2.cost, ex.cost);
}

TEST(ExactDp, StoppedRunKeepsIncumbentAndAValidLowerBound) {
  const Problem p = medium(4, 13, 6, 4);
  const Solution opt = solve_exact(p, std::size_t{1} << 30, StopToken{});
  ASSERT_EQ(opt.status, SolveStatus::optimal);
  SolveParams hp;
  hp.solver = SolverKind::heuristic;
  hp.threads = 1;
  hp.stagnation_rounds = 1;
  const Solution h = solve(p, hp);
  StopToken stopped;
  stopped.request_stop();
  const Solution cut = solve_exact(p, std::size_t{1} << 30, stopped, &h);
  EXPECT_EQ(cut.status, SolveStatus::feasible);
  EXPECT_EQ(cut.cost, h.cost);
  ASSERT_TRUE(cut.lower_bound.has_value());
  EXPECT_LE(*cut.lower_bound, opt.cost);
  EXPECT_GT(*cut.lower_bound, 0);
}

TEST(ExactDp, MemoryLimitIsRespected) {
  const Problem p = medium(5, 13, 6, 0);
  EXPECT_GT(estimate_exact_memory(p), std::size_t{1} << 20);
  const Solution s = solve_exact(p, std::size_t{1} << 20, StopToken{});
  EXPECT_EQ(s.status, SolveStatus::no_solution);
  EXPECT_TRUE(s.stats.stopped_by_limit);
  ASSERT_TRUE(s.lower_bound.has_value());
  const Solution opt = solve_exact(p, std::size_t{1} << 30, StopToken{});
  EXPECT_LE(*s.lower_bound, opt.cost);
}

// The progress it reports follows the work, not the count of layers: layer k holds C(m', k) sets,
// so on 16 single-node clusters (no incumbent, nothing pruned) the first four of the 14 layers it
// expands are about 3 % of the work. Counted by layers, the display said 33 % after them and then
// crept through the middle layers, where the time goes.
TEST(ExactDp, ProgressFollowsTheWorkNotTheLayers) {
  Rng rng(16);
  test::RandomSpec spec;
  spec.clusters = 16;
  spec.max_nodes = 1;
  spec.symmetric = false;
  const Problem p = test::random_problem(spec, rng);
  std::vector<double> seen;
  const ProgressFn progress = [&](const ProgressEvent& e) {
    if (e.stage == "exact" && e.fraction >= 0.0) seen.push_back(e.fraction);
  };
  const Solution s = solve_exact(p, std::size_t{1} << 30, StopToken{}, nullptr, progress);
  ASSERT_EQ(s.status, SolveStatus::optimal);
  ASSERT_GE(seen.size(), 14u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_LT(seen[3], 0.05);
  EXPECT_GT(seen[seen.size() - 4], 0.95);
  EXPECT_LE(seen.back(), 1.0);
  EXPECT_GT(seen.back(), 0.999);
}

TEST(SolveParams, PresetsAreValidAndCheckNamesTheField) {
  EXPECT_TRUE(check(SolveParams::fast()).empty());
  EXPECT_TRUE(check(SolveParams::standard()).empty());
  EXPECT_TRUE(check(SolveParams::thorough()).empty());
  SolveParams bad;
  bad.threads = -1;
  bad.max_removal_fraction = 2.0;
  const auto msgs = check(bad);
  ASSERT_EQ(msgs.size(), 2u);
  EXPECT_NE(msgs[0].find("threads"), std::string::npos);
  EXPECT_NE(msgs[1].find("max_removal_fraction"), std::string::npos);
}

}  // namespace
}  // namespace cutroute::solve
