// history_search(): precedence kept, cost recomputed, never worse, local optimum checked by enumeration;
// order_by_priority(): sorted where precedence allows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/history_search.hpp>
#include <cutroute/solve/solution.hpp>

#include "random_instance.hpp"
#include "route_check.hpp"

namespace cutroute::solve {
namespace {

// A history-dependent rule written independently of the search: a penalty each time a cluster
// follows, within the last two steps, a cluster whose id differs by one ("neighbours").
SequenceCost neighbour_rule(const Problem& p, Cost weight) {
  return [&p, weight](std::span<const NodeId> r) {
    Cost c = route_cost(p, r);
    for (std::size_t i = 1; i < r.size(); ++i)
      for (std::size_t k = 1; k <= 2 && k <= i; ++k)
        if (std::abs(p.cluster_of(r[i]).value() - p.cluster_of(r[i - k]).value()) == 1) c += k == 1 ? weight : weight / 2;
    return c;
  };
}

void expect_valid(const Problem& p, const std::vector<NodeId>& r) {
  const auto errors = test::route_errors(p, r);
  EXPECT_TRUE(errors.empty()) << (errors.empty() ? "" : errors.front());
}

TEST(HistorySearch, KeepsPrecedenceNeverWorsensAndReportsTheTrueCost) {
  Rng rng(7);
  for (int k = 0; k < 40; ++k) {
    test::RandomSpec spec;
    spec.clusters = 4 + static_cast<int>(rng.below(20));
    spec.max_nodes = 1 + static_cast<int>(rng.below(3));
    spec.closed = k % 2 == 0;
    spec.precedence_pairs = k % 3 == 0 ? 0 : static_cast<int>(rng.below(static_cast<std::uint64_t>(spec.clusters)));
    const Problem p = test::random_problem(spec, rng);
    SCOPED_TRACE("instance " + std::to_string(k));
    const SequenceCost cost = neighbour_rule(p, 700);
    const std::vector<NodeId> start = construct_route(p, rng);
    const auto res = history_search(p, cost, {start}, {});
    expect_valid(p, res.route);
    EXPECT_EQ(res.cost, cost(res.route));
    EXPECT_EQ(res.initial_cost, cost(start));
    EXPECT_LE(res.cost, res.initial_cost);
    EXPECT_TRUE(res.local_optimum);
    EXPECT_EQ(p.cluster_of(res.route.front()), p.start_cluster());
  }
}

// At a local optimum no single swap and no single-cluster move improves: enumerated here directly.
TEST(HistorySearch, ResultIsALocalOptimumOfSwapsAndMoves) {
  Rng rng(11);
  for (int k = 0; k < 15; ++k) {
    test::RandomSpec spec;
    spec.clusters = 8;
    spec.precedence_pairs = k % 2 == 0 ? 3 : 0;
    const Problem p = test::random_problem(spec, rng);
    const SequenceCost cost = neighbour_rule(p, 500);
    const auto res = history_search(p, cost, {construct_route(p, rng)}, {});
    const auto& r = res.route;
    for (std::size_t i = 1; i < r.size(); ++i)
      for (std::size_t j = 1; j < r.size(); ++j) {
        if (i == j) continue;
        auto s = r;
        std::swap(s[i], s[j]);
        if (keeps_precedence(p, s)) {
          EXPECT_GE(cost(s), res.cost) << "swap " << i << " " << j;
        }
        auto m = r;
        const NodeId v = m[i];
        m.erase(m.begin() + static_cast<std::ptrdiff_t>(i));
        m.insert(m.begin() + static_cast<std::ptrdiff_t>(j), v);
        if (keeps_precedence(p, m)) {
          EXPECT_GE(cost(m), res.cost) << "move " << i << " -> " << j;
        }
      }
  }
}

// Clusters 1..6 on a line 10 apart (start 0 at the left end): the static optimum cuts them in a
// row, each next to the previous one. Under a rule that forbids consecutive neighbours (huge
// penalty), orders without neighbours exist (e.g. 2 4 6 1 3 5 ... after start 0 next to 1): the
// search must find one, starting from the static optimum.
TEST(HistorySearch, LeavesTheStaticOptimumWhenTheRuleForbidsIt) {
  const int n = 7;
  ProblemBuilder b(n);
  std::vector<Cost> m(static_cast<std::size_t>(n * n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m[static_cast<std::size_t>(i * n + j)] = 10 * std::abs(i - j);
  b.set_cost_matrix(m);
  for (int i = 0; i < n; ++i) b.add_cluster({NodeId(i)});
  b.set_kind(RouteKind::open_path);
  const Problem p = std::move(b.build()).value();
  std::vector<NodeId> line;
  for (int i = 0; i < n; ++i) line.push_back(NodeId(i));
  const Cost huge = 1000000;
  const SequenceCost cost = [&](std::span<const NodeId> r) {
    Cost c = route_cost(p, r);
    for (std::size_t i = 1; i < r.size(); ++i)
      if (std::abs(r[i].value() - r[i - 1].value()) == 1) c += huge;
    return c;
  };
  ASSERT_GE(cost(line), huge);
  const auto res = history_search(p, cost, {line}, {});
  EXPECT_LT(res.cost, huge) << "a neighbour-free order exists";
  for (std::size_t i = 1; i < res.route.size(); ++i) EXPECT_NE(std::abs(res.route[i].value() - res.route[i - 1].value()), 1);
}

TEST(HistorySearch, BudgetStopsTheSearch) {
  Rng rng(3);
  test::RandomSpec spec;
  spec.clusters = 30;
  const Problem p = test::random_problem(spec, rng);
  HistorySearchParams params;
  params.max_evaluations = 50;
  const auto res = history_search(p, neighbour_rule(p, 900), {construct_route(p, rng)}, params);
  EXPECT_LE(res.evaluations, 51);  // + the pricing of the start
  expect_valid(p, res.route);
}

TEST(HistorySearch, TakesTheCheapestStart) {
  Rng rng(5);
  test::RandomSpec spec;
  spec.clusters = 9;
  const Problem p = test::random_problem(spec, rng);
  const SequenceCost cost = neighbour_rule(p, 400);
  const auto a = construct_route(p, rng), b = construct_route(p, rng);
  HistorySearchParams none;
  none.max_evaluations = 0;
  const auto res = history_search(p, cost, {a, b}, none);
  EXPECT_EQ(res.initial_cost, std::min(cost(a), cost(b)));
}

TEST(OrderByPriority, SortsWherePrecedenceAllows) {
  Rng rng(21);
  for (int k = 0; k < 30; ++k) {
    test::RandomSpec spec;
    spec.clusters = 3 + static_cast<int>(rng.below(25));
    spec.precedence_pairs = k % 2 == 0 ? 0 : static_cast<int>(rng.below(static_cast<std::uint64_t>(spec.clusters)));
    const Problem p = test::random_problem(spec, rng);
    std::vector<double> prio(static_cast<std::size_t>(p.cluster_count()));
    for (auto& x : prio) x = static_cast<double>(rng.below(5));
    const auto start = construct_route(p, rng);
    const auto r = order_by_priority(p, start, prio);
    expect_valid(p, r);
    if (spec.precedence_pairs == 0) {
      for (std::size_t i = 2; i < r.size(); ++i)
        EXPECT_LE(prio[p.cluster_of(r[i - 1]).index()], prio[p.cluster_of(r[i]).index()]);
    }
  }
}

// Pairs out of the start cluster (a SOP file makes node 1 precede every other node) release their
// clusters once the start is placed: every cluster comes out exactly once, in priority order.
TEST(OrderByPriority, StartClusterWithSuccessors) {
  ProblemBuilder b(5);
  for (int c = 0; c < 5; ++c) b.add_cluster({NodeId(c)});
  b.set_cost_matrix(std::vector<Cost>(25, 1));
  b.set_kind(RouteKind::open_path);
  b.set_start_cluster(ClusterId(0));
  for (int c = 1; c < 5; ++c) b.add_precedence(ClusterId(0), ClusterId(c));
  b.add_precedence(ClusterId(3), ClusterId(1));
  const Problem p = std::move(b.build()).value();
  const std::vector<NodeId> route{NodeId(0), NodeId(2), NodeId(3), NodeId(4), NodeId(1)};
  const std::vector<double> prio{0, 0, 3, 1, 2};  // wanted: 0 1 3 4 2, but 3 must precede 1
  const auto r = order_by_priority(p, route, prio);
  EXPECT_EQ(r, (std::vector<NodeId>{NodeId(0), NodeId(3), NodeId(1), NodeId(4), NodeId(2)}));
}

}  // namespace
}  // namespace cutroute::solve
