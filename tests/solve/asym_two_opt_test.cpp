// Reversing moves on nearly symmetric asymmetric matrices (2-opt, reversing segment exchange, LK
// chains): priced exactly, and none that pays is left, checked by making every such move and
// recomputing the cost; LK chains keep routes valid and go beyond the short moves' local optima, also
// on large symmetric routes, where they track their cost incrementally.
#include <gtest/gtest.h>

#include <algorithm>

#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/solution.hpp>

#include "random_instance.hpp"
#include "route_check.hpp"

namespace cutroute::solve {
namespace {

bool valid(const Problem& p, const std::vector<NodeId>& r) { return test::route_errors(p, r).empty(); }

// Instance k of a series: 4 to 3 + max_more clusters, a symmetric matrix plus independent noise of a
// few % of the mean arc on every arc; open or closed, with or without precedence and inner costs.
Problem nearly_symmetric_problem(int k, int max_more, Rng& rng) {
  test::RandomSpec spec;
  spec.clusters = 4 + static_cast<int>(rng.below(static_cast<std::uint64_t>(max_more)));
  spec.max_nodes = 1 + static_cast<int>(rng.below(3));
  spec.symmetric = true;
  spec.asym_noise = 1 + static_cast<int>(rng.below(60));
  spec.closed = k % 3 != 0;
  spec.precedence_pairs = k % 2 == 0 ? 0 : static_cast<int>(rng.below(static_cast<std::uint64_t>(spec.clusters)));
  spec.inner_costs = k % 4 == 1;
  spec.scatter_nodes = k % 5 < 2;
  return test::random_problem(spec, rng);
}

// Applies `pass` until it stops improving, checking after each call that the route is valid and that
// the pass reported exactly whether the cost dropped; returns the number of calls.
template <class Pass>
int descend(const Problem& p, std::vector<NodeId>& r, Pass pass) {
  int passes = 0;
  for (bool improved = true; improved && passes < 1000; ++passes) {
    const Cost before = route_cost(p, r);
    improved = pass(p, r);
    const Cost after = route_cost(p, r);
    EXPECT_TRUE(valid(p, r));
    EXPECT_EQ(improved, after < before);
    EXPECT_LE(after, before);
  }
  return passes;
}

TEST(AsymTwoOpt, LeavesNoImprovingFeasibleReversal) {
  Rng rng(17);
  int improving_runs = 0;
  for (int k = 0; k < 40; ++k) {
    const Problem p = nearly_symmetric_problem(k, 30, rng);
    ASSERT_FALSE(p.symmetric());
    SCOPED_TRACE("instance " + std::to_string(k));
    std::vector<NodeId> r = construct_route(p, rng);
    ASSERT_TRUE(valid(p, r));
    const int passes = descend(p, r, two_opt_pass);
    improving_runs += passes > 1;
    const Cost cost = route_cost(p, r);
    for (std::size_t i = 1; i + 1 < r.size(); ++i)
      for (std::size_t j = i + 1; j < r.size(); ++j) {
        std::vector<NodeId> x = r;
        std::reverse(x.begin() + static_cast<std::ptrdiff_t>(i), x.begin() + static_cast<std::ptrdiff_t>(j) + 1);
        if (valid(p, x)) {
          EXPECT_GE(route_cost(p, x), cost) << "reversing [" << i << ", " << j << "] pays";
        }
      }
  }
  EXPECT_GT(improving_runs, 20);  // most random constructions leave reversals to make (27 of 40)
}

// a [b..c] [d..e] f -> a [d..e] [c..b] f and -> a [e..d] [b..c] f, every i < j < h.
TEST(ReversingExchange, LeavesNoImprovingFeasibleMove) {
  Rng rng(23);
  int improving_runs = 0;
  for (int k = 0; k < 40; ++k) {
    const Problem p = nearly_symmetric_problem(k, 20, rng);
    SCOPED_TRACE("instance " + std::to_string(k));
    std::vector<NodeId> r = construct_route(p, rng);
    const int passes = descend(p, r, reversing_exchange_pass);
    improving_runs += passes > 1;
    const Cost cost = route_cost(p, r);
    const std::size_t L = r.size();
    for (std::size_t i = 0; i + 2 < L; ++i)
      for (std::size_t j = i + 1; j + 1 < L; ++j)
        for (std::size_t h = j + 1; h < L; ++h)
          for (int variant = 0; variant < 2; ++variant) {
            std::vector<NodeId> x(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(i) + 1);
            std::vector<NodeId> left(r.begin() + static_cast<std::ptrdiff_t>(i) + 1, r.begin() + static_cast<std::ptrdiff_t>(j) + 1);
            std::vector<NodeId> right(r.begin() + static_cast<std::ptrdiff_t>(j) + 1, r.begin() + static_cast<std::ptrdiff_t>(h) + 1);
            (variant == 0 ? left : right).assign((variant == 0 ? left : right).rbegin(), (variant == 0 ? left : right).rend());
            x.insert(x.end(), right.begin(), right.end());
            x.insert(x.end(), left.begin(), left.end());
            x.insert(x.end(), r.begin() + static_cast<std::ptrdiff_t>(h) + 1, r.end());
            if (valid(p, x)) {
              EXPECT_GE(route_cost(p, x), cost) << "variant " << variant << " at " << i << ", " << j << ", " << h << " pays";
            }
          }
  }
  EXPECT_GT(improving_runs, 20);
}

// Every LK pass leaves a valid route whose cost only drops, and reports exactly when it dropped;
// without a plain matrix (inner costs) it leaves the route alone.
TEST(LinKernighan, KeepsRoutesValidAndCheaper) {
  Rng rng(29);
  int improving_runs = 0;
  for (int k = 0; k < 60; ++k) {
    const Problem p = nearly_symmetric_problem(k, 40, rng);
    SCOPED_TRACE("instance " + std::to_string(k));
    std::vector<NodeId> r = construct_route(p, rng);
    const std::vector<NodeId> start = r;
    const int passes = descend(p, r, [](const Problem& q, std::vector<NodeId>& x) { return lk_pass(q, x); });
    if (p.has_inner_costs()) {
      EXPECT_EQ(r, start);
    }
    improving_runs += passes > 1;
  }
  EXPECT_GT(improving_runs, 30);
}

// Routes at a local optimum of every shorter move (2-opt, Or-opt, swap, both segment exchanges)
// still hold LK improvements, with and without precedence: its chains reach deeper changes, through
// routes that break precedence on the way.
TEST(LinKernighan, ImprovesOnShortMoveLocalOptima) {
  Rng rng(31);
  int improved_plain = 0, improved_prec = 0, total_plain = 0, total_prec = 0;
  for (int k = 0; k < 120; ++k) {
    test::RandomSpec spec;
    spec.clusters = 30 + static_cast<int>(rng.below(40));
    spec.max_nodes = 1;
    spec.symmetric = true;
    spec.asym_noise = 1 + static_cast<int>(rng.below(20));
    spec.closed = k % 2 == 0;
    spec.precedence_pairs = k % 4 < 2 ? 0 : spec.clusters / 3;
    const Problem p = test::random_problem(spec, rng);
    if (p.symmetric()) continue;
    std::vector<NodeId> r = construct_route(p, rng);
    for (int guard = 0; guard < 1000; ++guard) {
      bool any = two_opt_pass(p, r);
      any = or_opt_pass(p, r) || any;
      any = swap_pass(p, r) || any;
      any = segment_exchange_pass(p, r) || any;
      any = reversing_exchange_pass(p, r) || any;
      if (!any) break;
    }
    const Cost local = route_cost(p, r);
    const bool better = lk_pass(p, r);
    ASSERT_TRUE(valid(p, r));
    EXPECT_EQ(better, route_cost(p, r) < local);
    (p.has_precedence() ? total_prec : total_plain) += 1;
    (p.has_precedence() ? improved_prec : improved_plain) += better;
  }
  EXPECT_GT(total_plain, 40);
  EXPECT_GT(total_prec, 40);
  EXPECT_GT(improved_plain, total_plain / 3) << improved_plain << " of " << total_plain;
  // Measured: 24 of 55 without precedence; precedence (a third of the clusters in pairs) blocks
  // more chains, 9 of 59.
  EXPECT_GT(improved_prec, total_prec / 10) << improved_prec << " of " << total_prec;
}

// LK passes with a tracked cost until one finds nothing (at most 100): each must keep the route
// valid, track its cost exactly and report exactly when it improved. Returns the improving passes.
int tracked_lk_passes(const Problem& p, std::vector<NodeId>& r) {
  int improved = 0;
  for (int pass = 0; pass < 100; ++pass) {
    const Cost before = route_cost(p, r);
    Cost tracked = -1;
    const bool better = lk_pass(p, r, &tracked);
    if (!valid(p, r)) {
      ADD_FAILURE() << "pass " << pass << " left an invalid route";
      break;
    }
    EXPECT_EQ(tracked, route_cost(p, r));
    EXPECT_EQ(better, route_cost(p, r) < before);
    if (!better) break;
    ++improved;
  }
  return improved;
}

// Symmetric closed tours of at least 96 clusters without precedence (GTSPLIB 99-217) get LK chains
// too, priced incrementally: from local optima of 2-opt and Or-opt every pass keeps the route
// valid, the cost it tracks equals the recomputed one, and chains still find improvements. Below
// 96 clusters the pass leaves such routes alone.
TEST(LinKernighan, SymmetricLargeRoutesTrackTheirCost) {
  Rng rng(37);
  int improved = 0;
  for (int k = 0; k < 12; ++k) {
    SCOPED_TRACE("instance " + std::to_string(k));
    test::RandomSpec spec;
    spec.clusters = k < 10 ? 96 + static_cast<int>(rng.below(40)) : 60;
    spec.max_nodes = 1 + static_cast<int>(rng.below(3));
    spec.symmetric = true;
    spec.scatter_nodes = k % 2 == 0;
    const Problem p = test::random_problem(spec, rng);
    ASSERT_TRUE(p.symmetric());
    std::vector<NodeId> r = construct_route(p, rng);
    for (int guard = 0; guard < 1000; ++guard)
      if (!(two_opt_pass(p, r) | or_opt_pass(p, r))) break;
    const int passes = tracked_lk_passes(p, r);
    if (spec.clusters < 96) {
      EXPECT_EQ(passes, 0);
    }
    improved += passes;
  }
  EXPECT_GT(improved, 10);
}

// Matrices symmetric but for forbidden arcs (SOP prob.100: precedence forbids one direction) get
// their chains priced in O(1), with a route priced from scratch only when it would become the
// best: every pass keeps the route valid (no forbidden arc), the cost it tracks equals the
// recomputed one, and chains still find improvements, with and without precedence.
TEST(LinKernighan, SymmetricButForbiddenArcsTrackTheirCost) {
  Rng rng(41);
  int improved = 0;
  for (int k = 0; k < 40; ++k) {
    SCOPED_TRACE("instance " + std::to_string(k));
    test::RandomSpec spec;
    spec.clusters = 30 + static_cast<int>(rng.below(40));
    spec.max_nodes = 1;
    spec.symmetric = true;
    spec.closed = k % 2 == 0;
    spec.forbidden_arcs = 3 * spec.clusters;
    spec.precedence_pairs = k % 4 < 2 ? 0 : spec.clusters / 4;
    const Problem p = test::random_problem(spec, rng);
    ASSERT_FALSE(p.symmetric());
    std::vector<NodeId> r = construct_route(p, rng);
    if (!valid(p, r)) continue;  // a forbidden arc the construction could not avoid
    for (int guard = 0; guard < 1000; ++guard)
      if (!(two_opt_pass(p, r) | or_opt_pass(p, r))) break;
    improved += tracked_lk_passes(p, r);
  }
  EXPECT_GT(improved, 20);
}

// On those matrices with precedence pairs the first four steps of a chain try several alternatives
// (greedy chains rarely get back to a feasible route once they broke pairs): routes at a local
// optimum of chains that branch only at their first step still hold improvements for the default
// chains, which keep them valid and track their cost.
TEST(LinKernighan, BranchingChainsImproveOnFirstStepLocalOptima) {
  Rng rng(43);
  int tried = 0, improved = 0;
  const int first_only[] = {5};
  for (int k = 0; k < 40; ++k) {
    SCOPED_TRACE("instance " + std::to_string(k));
    test::RandomSpec spec;
    spec.clusters = 40 + static_cast<int>(rng.below(30));
    spec.max_nodes = 1;
    spec.symmetric = true;
    spec.closed = false;
    spec.forbidden_arcs = 2 * spec.clusters;
    spec.precedence_pairs = spec.clusters / 3;
    const Problem p = test::random_problem(spec, rng);
    std::vector<NodeId> r = construct_route(p, rng);
    if (!valid(p, r)) continue;
    for (int guard = 0; guard < 1000; ++guard) {
      bool any = two_opt_pass(p, r);
      any = or_opt_pass(p, r) || any;
      any = lk_pass(p, r, nullptr, first_only) || any;
      if (!any) break;
    }
    ASSERT_FALSE(lk_pass(p, r, nullptr, first_only));
    ++tried;
    improved += tracked_lk_passes(p, r) > 0;
  }
  EXPECT_GT(tried, 30);
  // Measured: 32 of 39 (a chain branching at its first step only finds none, by construction).
  EXPECT_GT(improved, tried / 2) << improved << " of " << tried;
}

}  // namespace
}  // namespace cutroute::solve
