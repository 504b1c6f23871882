// The metaheuristic: deterministic per seed and thread count, honours stop token and target.
#include <gtest/gtest.h>

#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/solve.hpp>

#include "random_instance.hpp"
#include "route_check.hpp"

namespace cutroute::solve {
namespace {

Problem instance(std::uint64_t seed, bool precedence) {
  Rng rng(seed);
  test::RandomSpec spec;
  spec.clusters = 40;
  spec.max_nodes = 4;
  spec.symmetric = !precedence;
  spec.precedence_pairs = precedence ? 25 : 0;
  spec.inner_costs = precedence;
  return test::random_problem(spec, rng);
}

// Heuristic on two threads, stopped by stagnation only (no clock), short also under sanitizers.
SolveParams short_run(std::uint64_t seed) {
  SolveParams sp;
  sp.solver = SolverKind::heuristic;
  sp.seed = seed;
  sp.threads = 2;
  sp.time_limit_s = 0;
  sp.min_stagnation_work = 10000;
  return sp;
}

using test::solve_deterministic;

TEST(Heuristic, SameSeedAndThreadsGiveTheSameRoute) {
  for (bool prec : {false, true}) {
    const Problem p = instance(11, prec);
    const SolveParams sp = short_run(42);
    const Solution a = solve(p, sp);
    const Solution b = solve(p, sp);
    EXPECT_EQ(a.route, b.route);
    EXPECT_EQ(a.cost, b.cost);
    EXPECT_EQ(a.stats.iterations, b.stats.iterations);
    EXPECT_TRUE(validate(p, a).empty());
  }
}

// 120 clusters of at most 4 nodes without precedence: the "wide" automatic settings (30 % destroys,
// repair next to candidate neighbours, docs/SOLVER.md) with two threads sharing the Ops.
TEST(Heuristic, WideRoutesAreDeterministicAndBeatLocalSearch) {
  Rng rng(21);
  test::RandomSpec spec;
  spec.clusters = 120;
  spec.max_nodes = 4;
  spec.symmetric = true;
  const Problem p = test::random_problem(spec, rng);
  SolveParams sp;
  sp.solver = SolverKind::heuristic;
  sp.seed = 7;
  sp.threads = 2;
  sp.time_limit_s = 0;
  sp.stagnation_rounds = 3;  // short, also under sanitizers
  sp.min_stagnation_work = 0;
  const Solution a = solve_deterministic(p, sp);
  // Destroy/repair rounds improve on a plain construction + local search from the same seed.
  Rng r2(7);
  std::vector<NodeId> start = construct_route(p, r2);
  local_search(p, start);
  EXPECT_LT(a.cost, route_cost(p, start));
  // That was the population mode (automatic on such problems); the single-trajectory search gives
  // another route, deterministic as well.
  sp.population_size = -1;
  const Solution c = solve_deterministic(p, sp);
  EXPECT_NE(a.route, c.route);
}

// An explicit population size applies to any problem without precedence and is ignored with
// precedence (the crossover would break it): the route is then the single-trajectory one.
TEST(Heuristic, PopulationSizeAppliesWithoutPrecedenceOnly) {
  for (bool prec : {false, true}) {
    const Problem p = instance(14, prec);
    SolveParams sp = short_run(3);
    sp.population_size = -1;
    const Solution off = solve(p, sp);
    sp.population_size = 8;
    const Solution on = solve_deterministic(p, sp);
    if (prec)
      EXPECT_EQ(on.route, off.route);
    else
      EXPECT_NE(on.stats.iterations, off.stats.iterations);
  }
}

TEST(Heuristic, CancelledTokenStillReturnsAValidRoute) {
  const Problem p = instance(12, true);
  StopToken stop;
  stop.request_stop();
  SolveParams sp;
  sp.solver = SolverKind::heuristic;
  const Solution s = solve(p, sp, stop);
  EXPECT_EQ(s.status, SolveStatus::feasible);
  EXPECT_TRUE(validate(p, s).empty());
  EXPECT_TRUE(s.stats.stopped_by_limit);
}

// A run stopped before its first route inserts each cluster, once the route is longer than 2 048,
// only next to its candidate neighbours (O(24 k), not O(L k)): still every cluster once and every
// pair kept. On compact clusters (one node each, like small parts) it is about as cheap as the
// full cheapest insertion (10 000 circles: the same T_cut). Clusters whose nodes lie far apart
// fare worse, a price paid only when the run is out of time anyway: only validity is checked there.
TEST(Heuristic, StoppedConstructionIsValidAndCloseToTheFullOne) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    Rng rng(seed);
    test::RandomSpec spec;
    spec.clusters = 2600;
    spec.max_nodes = seed <= 3 ? 1 : 2;
    spec.closed = seed % 2 == 0;
    spec.precedence_pairs = seed == 2 ? 0 : 500;
    const Problem p = test::random_problem(spec, rng);
    StopToken stop;
    stop.request_stop();
    SolveParams sp;
    sp.solver = SolverKind::heuristic;
    sp.threads = 1;
    sp.seed = seed;
    const Solution s = solve(p, sp, stop);
    ASSERT_EQ(s.status, SolveStatus::feasible);
    EXPECT_TRUE(validate(p, s).empty()) << "seed " << seed;
    if (spec.max_nodes > 1) continue;
    Rng crng(seed);
    const double full = static_cast<double>(route_cost(p, construct_route(p, crng)));
    EXPECT_LE(static_cast<double>(s.cost), 1.1 * full) << "seed " << seed;  // measured 0.965-1.014
  }
}

TEST(Heuristic, StopsAtTargetCost) {
  const Problem p = instance(13, false);
  SolveParams sp;
  sp.solver = SolverKind::heuristic;
  sp.threads = 1;
  sp.min_stagnation_work = 10000;
  const Solution full = solve(p, sp);
  sp.target_cost = full.cost * 2;  // any route after construction + local search is below this
  const Solution quick = solve(p, sp);
  EXPECT_LE(quick.cost, full.cost * 2);
  EXPECT_LT(quick.stats.iterations, full.stats.iterations);
}

TEST(Solve, AutomaticPicksExactOnSmallAndHeuristicOnLarge) {
  Rng rng(3);
  test::RandomSpec small;
  small.clusters = 7;
  const Problem ps = test::random_problem(small, rng);
  const Solution a = solve(ps, SolveParams{});
  EXPECT_EQ(a.status, SolveStatus::optimal);
  EXPECT_EQ(a.stats.solver, "exact");
  const Problem pl = instance(14, false);
  const Solution b = solve(pl, SolveParams{});
  EXPECT_EQ(b.status, SolveStatus::feasible);
  EXPECT_EQ(b.stats.solver, "heuristic");
}

}  // namespace
}  // namespace cutroute::solve

namespace cutroute::solve {
namespace {

// One and two clusters, open and closed, every solver: the degenerate sizes must not break anything.
TEST(Solve, DegenerateSizes) {
  for (int clusters : {1, 2}) {
    for (RouteKind kind : {RouteKind::closed_tour, RouteKind::open_path}) {
      ProblemBuilder b(2 * clusters);
      std::vector<Cost> m(static_cast<std::size_t>(4 * clusters * clusters), 5);
      b.set_cost_matrix(m);
      for (int c = 0; c < clusters; ++c) b.add_cluster({NodeId(2 * c), NodeId(2 * c + 1)});
      b.set_inner_cost(NodeId(1), 3).set_inner_cost(NodeId(0), 4);
      b.set_kind(kind);
      const Problem p = *b.build();
      for (SolverKind k : {SolverKind::automatic, SolverKind::exact, SolverKind::heuristic}) {
        SolveParams sp;
        sp.solver = k;
        const Solution s = solve(p, sp);
        ASSERT_FALSE(s.route.empty());
        EXPECT_TRUE(validate(p, s).empty());
        const Cost expected = clusters == 1 ? 3 : (kind == RouteKind::closed_tour ? 3 + 5 + 5 : 3 + 5);
        EXPECT_EQ(s.cost, expected) << clusters << " clusters, solver " << to_string(k);
      }
    }
  }
}

}  // namespace
}  // namespace cutroute::solve
