// The assignment bound behind the node-set search: against brute force, re-solved incrementally
// against from scratch, and the search's result against single changes; the solver on the problems
// where it applies.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/solve.hpp>

#include "random_instance.hpp"
#include "route_check.hpp"

namespace cutroute::solve {
namespace {

Problem asymmetric(std::uint64_t seed, int clusters, int forbidden = 0) {
  Rng rng(seed);
  test::RandomSpec spec;
  spec.clusters = clusters;
  spec.max_nodes = 4;
  spec.symmetric = false;
  spec.forbidden_arcs = forbidden;
  spec.scatter_nodes = true;
  return test::random_problem(spec, rng);
}

std::vector<NodeId> random_nodes(const Problem& p, Rng& rng) {
  std::vector<NodeId> nodes;
  for (int c = 0; c < p.cluster_count(); ++c) {
    const auto members = p.nodes_of(ClusterId(c));
    nodes.push_back(members[rng.below(members.size())]);
  }
  return nodes;
}

// Every successor permutation without a fixed point, priced; the cheapest.
Cost brute_force_bound(const Problem& p, const std::vector<NodeId>& nodes) {
  const int m = static_cast<int>(nodes.size());
  std::vector<int> succ(static_cast<std::size_t>(m));
  std::iota(succ.begin(), succ.end(), 0);
  Cost best = std::numeric_limits<Cost>::max();
  do {
    Cost c = 0;
    bool ok = true;
    for (int i = 0; i < m && ok; ++i) {
      const int j = succ[static_cast<std::size_t>(i)];
      ok = j != i;
      if (ok) c += p.arc_cost(nodes[static_cast<std::size_t>(i)], nodes[static_cast<std::size_t>(j)]);
    }
    if (ok) best = std::min(best, c);
  } while (std::next_permutation(succ.begin(), succ.end()));
  return best;
}

TEST(NodeSets, AssignmentBoundIsTheCheapestCycleCover) {
  Rng rng(5);
  for (int trial = 0; trial < 60; ++trial) {
    const int m = 2 + trial % 6;
    const Problem p = asymmetric(100 + static_cast<std::uint64_t>(trial), m, trial % 3 == 0 ? 4 : 0);
    const auto nodes = random_nodes(p, rng);
    EXPECT_EQ(assignment_bound(p, nodes), brute_force_bound(p, nodes)) << "trial " << trial;
  }
}

TEST(NodeSets, IncrementalBoundsMatchFreshSolves) {
  Rng rng(7);
  for (int trial = 0; trial < 4; ++trial) {
    const Problem p = asymmetric(200 + static_cast<std::uint64_t>(trial), 25, trial == 1 ? 40 : 0);
    auto nodes = random_nodes(p, rng);
    std::vector<std::pair<ClusterId, NodeId>> changes;
    for (int k = 0; k < 80; ++k) {
      const ClusterId c(static_cast<int>(rng.below(25)));
      const auto members = p.nodes_of(c);
      changes.emplace_back(c, members[rng.below(members.size())]);
    }
    const auto got = assignment_bounds_after(p, nodes, changes);
    ASSERT_EQ(got.size(), changes.size());
    for (std::size_t k = 0; k < changes.size(); ++k) {
      nodes[changes[k].first.index()] = changes[k].second;
      EXPECT_EQ(got[k].second, assignment_bound(p, nodes)) << "trial " << trial << " change " << k;
      EXPECT_LE(got[k].first, got[k].second) << "the skip bound must be a lower bound";
    }
  }
}

TEST(NodeSets, SearchEndsInALocalOptimumOfTheBound) {
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    const Problem p = asymmetric(300 + seed, 10 + static_cast<int>(seed % 8), seed % 4 == 2 ? 10 : 0);
    Rng rng(seed);
    const auto start = construct_route(p, rng);
    std::vector<NodeId> start_nodes(static_cast<std::size_t>(p.cluster_count()));
    for (NodeId v : start) start_nodes[p.cluster_of(v).index()] = v;
    const NodeSetResult r = node_set_search(p, start, seed, 5);
    ASSERT_EQ(r.nodes.size(), start_nodes.size());
    for (int c = 0; c < p.cluster_count(); ++c)
      EXPECT_EQ(p.cluster_of(r.nodes[static_cast<std::size_t>(c)]), ClusterId(c));
    EXPECT_EQ(r.bound, assignment_bound(p, r.nodes));
    EXPECT_LE(r.bound, assignment_bound(p, start_nodes));
    for (int c = 0; c < p.cluster_count(); ++c)
      for (NodeId v : p.nodes_of(ClusterId(c))) {
        auto other = r.nodes;
        other[static_cast<std::size_t>(c)] = v;
        EXPECT_GE(assignment_bound(p, other), r.bound) << "cluster " << c;
      }
  }
}

// Where the node-set search applies (closed tour, asymmetric matrix, clusters of several nodes): the
// route is valid and priced right, never below the bound of its own nodes, and the same per seed.
TEST(NodeSets, SolverStartsFromThemDeterministically) {
  const Problem p = asymmetric(400, 30, 20);
  SolveParams sp;
  sp.solver = SolverKind::heuristic;
  sp.seed = 3;
  sp.threads = 2;
  sp.time_limit_s = 0;
  sp.min_stagnation_work = 10000;
  const Solution a = test::solve_deterministic(p, sp);
  std::vector<NodeId> nodes(static_cast<std::size_t>(p.cluster_count()));
  for (NodeId v : a.route) nodes[p.cluster_of(v).index()] = v;
  EXPECT_GE(a.cost, assignment_bound(p, nodes));
}

}  // namespace
}  // namespace cutroute::solve
