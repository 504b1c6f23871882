// The DP over precedence ideals: equal to brute force on tiny instances, the known optima of TSPLIB SOP
// instances beyond the dense table, valid bounds when memory or time runs out.
#include <gtest/gtest.h>

#include <cutroute/io/instance.hpp>
#include <cutroute/solve/exact_dp.hpp>
#include <cutroute/solve/solve.hpp>

#include "random_instance.hpp"
#include "support/paths.hpp"

namespace cutroute::solve {
namespace {

TEST(ExactIdeals, EqualsBruteForceOnThreeHundredInstances) {
  Rng rng(20261128);
  int optimal = 0, infeasible = 0;
  for (int k = 0; k < 300; ++k) {
    test::RandomSpec spec = test::mixed_spec(k, rng);
    if (k % 4 != 3) spec.precedence_pairs = 1 + static_cast<int>(rng.below(8));  // mostly with precedence
    const Problem p = test::random_problem(spec, rng);
    SCOPED_TRACE("instance " + std::to_string(k));
    const Cost truth = test::brute_force(p);
    const Solution s = solve_exact_ideals(p, std::size_t{1} << 30, StopToken{});
    if (truth == std::numeric_limits<Cost>::max()) {
      ++infeasible;
      EXPECT_EQ(s.status, SolveStatus::infeasible);
      continue;
    }
    ASSERT_EQ(s.status, SolveStatus::optimal);
    EXPECT_EQ(s.cost, truth);
    EXPECT_EQ(s.lower_bound, s.cost);
    EXPECT_TRUE(validate(p, s).empty());
    ++optimal;
    // With a heuristic route as the incumbent, the bound prunes states: still the optimum.
    SolveParams hp = SolveParams::fast();
    hp.solver = SolverKind::heuristic;
    hp.threads = 1;
    const Solution h = solve(p, hp);
    const Solution si = solve_exact_ideals(p, std::size_t{1} << 30, StopToken{}, &h);
    ASSERT_EQ(si.status, SolveStatus::optimal);
    EXPECT_EQ(si.cost, truth);
    EXPECT_TRUE(validate(p, si).empty());
  }
  EXPECT_GE(optimal, 250);
  EXPECT_GE(infeasible, 1);
}

// Known optima (../shared/data/sop/README.md, "optimal per source comment") of instances whose 43-53
// non-start clusters the dense table cannot hold (2^43 subsets); through solve() with the exact solver,
// which hands them to the ideals.
TEST(ExactIdeals, ProvesSopOptimaBeyondTheDenseTable) {
  const std::pair<const char*, Cost> known[] = {{"p43.4", 83005}, {"ry48p.4", 31446}, {"ft53.4", 14425}};
  for (auto [name, opt] : known) {
    auto r = io::read_instance(test::shared(std::string("data/sop/") + name + ".sop"));
    ASSERT_TRUE(r.ok()) << name << ": " << r.error().message;
    SolveParams sp;
    sp.solver = SolverKind::exact;
    sp.threads = 1;
    const Solution s = solve(r->problem, sp);
    EXPECT_EQ(s.status, SolveStatus::optimal) << name;
    EXPECT_EQ(s.cost, opt) << name;
    EXPECT_TRUE(validate(r->problem, s).empty()) << name;
  }
}

// Out of memory, or stopped: the incumbent stays, and the bound lies between the cheapest-entry bound
// and the optimum.
TEST(ExactIdeals, LimitsGiveAValidBound) {
  auto r = io::read_instance(test::shared("data/sop/ft53.4.sop"));
  ASSERT_TRUE(r.ok()) << r.error().message;
  const Problem& p = r->problem;
  constexpr Cost kOptimum = 14425;
  SolveParams hp = SolveParams::fast();
  hp.solver = SolverKind::heuristic;
  hp.threads = 1;
  const Solution h = solve(p, hp);
  ASSERT_FALSE(h.route.empty());
  for (std::size_t limit : {std::size_t{4} << 20, std::size_t{12} << 20}) {
    const Solution s = solve_exact_ideals(p, limit, StopToken{}, &h);
    EXPECT_TRUE(s.stats.stopped_by_limit) << limit;
    EXPECT_EQ(s.status, SolveStatus::feasible) << limit;
    EXPECT_EQ(s.cost, h.cost) << limit;
    ASSERT_TRUE(s.lower_bound.has_value()) << limit;
    EXPECT_LE(*s.lower_bound, kOptimum) << limit;
    EXPECT_GT(*s.lower_bound, 0) << limit;
  }
  StopToken stopped;
  stopped.request_stop();
  const Solution s = solve_exact_ideals(p, std::size_t{1} << 30, stopped, &h);
  EXPECT_TRUE(s.stats.stopped_by_limit);
  EXPECT_EQ(s.cost, h.cost);
  ASSERT_TRUE(s.lower_bound.has_value());
  EXPECT_LE(*s.lower_bound, kOptimum);
}

// A long exact run tells the progress line how far it is: one event a layer, for both DPs.
TEST(ExactIdeals, BothDpsReportEachLayer) {
  auto r = io::read_instance(test::shared("data/sop/p43.4.sop"));
  ASSERT_TRUE(r.ok()) << r.error().message;
  Rng rng(3);
  test::RandomSpec spec;
  spec.clusters = 12;
  spec.max_nodes = 3;
  spec.precedence_pairs = 4;
  const Problem dense = test::random_problem(spec, rng);
  const Problem* const problems[] = {&r->problem, &dense};
  for (const Problem* p : problems) {
    std::vector<ProgressEvent> events;
    std::vector<std::string> stages;
    const Solution s = solve_exact(*p, std::size_t{1} << 30, StopToken{}, nullptr, [&](const ProgressEvent& e) {
      events.push_back(e);
      stages.emplace_back(e.stage);
    });
    ASSERT_EQ(s.status, SolveStatus::optimal);
    ASSERT_GE(events.size(), static_cast<std::size_t>(p->cluster_count() / 2));
    for (std::size_t i = 0; i < events.size(); ++i) {
      EXPECT_EQ(stages[i], "exact");
      EXPECT_GT(events[i].fraction, 0.0);
      EXPECT_LE(events[i].fraction, 1.0);
      if (i > 0) {
        EXPECT_GE(events[i].fraction, events[i - 1].fraction);
      }
    }
  }
}

}  // namespace
}  // namespace cutroute::solve
