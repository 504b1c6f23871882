// The population mode's parts: the ordered crossover (checked against its definition on random
// routes) and survivor selection (sizes, the cheapest route kept, clones dropped, all re-derived
// from the routes themselves).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/solution.hpp>

#include "random_instance.hpp"
#include "route_check.hpp"

namespace cutroute::solve {
namespace {

TEST(Population, OrderCrossoverKeepsTheStretchAndTheOtherParentsOrder) {
  Rng rng(17);
  for (int k = 0; k < 80; ++k) {
    test::RandomSpec spec;
    spec.clusters = 4 + static_cast<int>(rng.below(40));
    spec.max_nodes = 1 + static_cast<int>(rng.below(4));
    spec.symmetric = k % 2 == 0;
    spec.closed = k % 3 != 0;
    const Problem p = test::random_problem(spec, rng);
    const std::vector<NodeId> a = construct_route(p, rng), b = construct_route(p, rng);
    const int L = static_cast<int>(a.size());
    int i = 1 + static_cast<int>(rng.below(static_cast<std::uint64_t>(L - 1)));
    int j = 1 + static_cast<int>(rng.below(static_cast<std::uint64_t>(L - 1)));
    if (i > j) std::swap(i, j);
    const std::vector<NodeId> child = order_crossover(p, a, b, i, j);
    ASSERT_EQ(static_cast<int>(child.size()), L);
    EXPECT_EQ(child[0], a[0]);
    EXPECT_TRUE(test::route_errors(p, child).empty()) << "instance " << k;
    std::set<int> stretch;
    for (int q = i; q <= j; ++q) {
      EXPECT_EQ(child[static_cast<std::size_t>(q)], a[static_cast<std::size_t>(q)]);
      stretch.insert(p.cluster_of(a[static_cast<std::size_t>(q)]).value());
    }
    // The rest, read from after the stretch round positions 1..L-1, is b's order read from after
    // a[j]'s cluster in b, with b's nodes.
    std::vector<NodeId> rest, expected;
    for (int q = j + 1; q < L; ++q) rest.push_back(child[static_cast<std::size_t>(q)]);
    for (int q = 1; q < i; ++q) rest.push_back(child[static_cast<std::size_t>(q)]);
    int start = 0;
    for (int q = 1; q < L; ++q)
      if (p.cluster_of(b[static_cast<std::size_t>(q)]) == p.cluster_of(a[static_cast<std::size_t>(j)])) start = q;
    for (int r = 1; r < L; ++r) {
      const NodeId v = b[static_cast<std::size_t>(1 + (start - 1 + r) % (L - 1))];
      if (!stretch.count(p.cluster_of(v).value())) expected.push_back(v);
    }
    EXPECT_EQ(rest, expected) << "instance " << k << ", stretch " << i << ".." << j;
  }
}

// Cluster-level arcs of a closed route, both orientations.
std::set<std::pair<int, int>> edges_of(const Problem& p, const std::vector<NodeId>& r) {
  std::set<std::pair<int, int>> s;
  for (std::size_t q = 0; q < r.size(); ++q) {
    const int x = p.cluster_of(r[q]).value(), y = p.cluster_of(r[(q + 1) % r.size()]).value();
    s.insert({std::min(x, y), std::max(x, y)});
  }
  return s;
}

TEST(Population, SurvivorSelectionKeepsTheCheapestAndDropsClones) {
  Rng rng(29);
  test::RandomSpec spec;
  spec.clusters = 30;
  spec.max_nodes = 3;
  const Problem p = test::random_problem(spec, rng);
  // Local optima (cheap, often alike) mixed with plain constructions and exact copies.
  std::vector<std::vector<NodeId>> routes;
  for (int k = 0; k < 70; ++k) {
    if (k % 4 == 3) {
      routes.push_back(routes[static_cast<std::size_t>(rng.below(routes.size()))]);
      continue;
    }
    std::vector<NodeId> r = construct_route(p, rng);
    if (k % 2 == 0) local_search(p, r);
    routes.push_back(r);
  }
  const int mu = 5, lambda = 10;
  for (int n = 1; n <= static_cast<int>(routes.size()); ++n) {
    const std::vector<std::vector<NodeId>> prefix(routes.begin(), routes.begin() + n);
    const auto kept = population_survivors(p, prefix, mu, lambda);
    const int expected_size = n < mu + lambda ? n : mu + (n - mu - lambda) % lambda;
    ASSERT_EQ(static_cast<int>(kept.size()), expected_size) << n << " routes added";
    Cost cheapest = kForbiddenCost, kept_cheapest = kForbiddenCost;
    for (const auto& r : prefix) cheapest = std::min(cheapest, route_cost(p, r));
    for (const auto& r : kept) {
      kept_cheapest = std::min(kept_cheapest, route_cost(p, r));
      EXPECT_NE(std::find(prefix.begin(), prefix.end(), r), prefix.end()) << "a survivor that was never added";
    }
    EXPECT_EQ(kept_cheapest, cheapest) << n << " routes added";
    // Right after a selection, no two survivors have the same cluster-level arcs (each prefix holds
    // far more than mu distinct routes).
    if (n >= mu + lambda && (n - mu - lambda) % lambda == 0) {
      for (std::size_t x = 0; x < kept.size(); ++x)
        for (std::size_t y = x + 1; y < kept.size(); ++y)
          EXPECT_NE(edges_of(p, kept[x]), edges_of(p, kept[y])) << n << " routes added: survivors " << x << ", " << y;
    }
  }
}

}  // namespace
}  // namespace cutroute::solve
