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

// Local optima (cheap, often alike) mixed with plain constructions (every `plain_every`-th) and
// exact copies of earlier routes (every `copy_every`-th, the last of each group).
std::vector<std::vector<NodeId>> mixed_routes(const Problem& p, Rng& rng, int count, int copy_every, int plain_every) {
  std::vector<std::vector<NodeId>> routes;
  for (int k = 0; k < count; ++k) {
    if (k % copy_every == copy_every - 1) {
      routes.push_back(routes[static_cast<std::size_t>(rng.below(routes.size()))]);
      continue;
    }
    std::vector<NodeId> r = construct_route(p, rng);
    if (k % plain_every != 1) local_search(p, r);
    routes.push_back(r);
  }
  return routes;
}

TEST(Population, SurvivorSelectionKeepsTheCheapestAndDropsClones) {
  Rng rng(29);
  test::RandomSpec spec;
  spec.clusters = 30;
  spec.max_nodes = 3;
  const Problem p = test::random_problem(spec, rng);
  const std::vector<std::vector<NodeId>> routes = mixed_routes(p, rng, 70, 4, 2);
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

// Survivor selection written out from its definition (docs/SOLVER.md "Population"), every
// fitness recomputed from scratch before each removal.
std::vector<std::vector<NodeId>> reference_survivors(const Problem& p, const std::vector<std::vector<NodeId>>& routes, int mu,
                                                     int lambda) {
  const int close = 5, elite = 4;
  // Symmetric problems: the share of x's cluster-level edges that y lacks (routes of 8+ clusters,
  // so a route's edges are distinct).
  auto dist = [&](const std::vector<NodeId>& x, const std::vector<NodeId>& y) {
    const auto ex = edges_of(p, x), ey = edges_of(p, y);
    int broken = 0;
    for (const auto& e : ex) broken += ey.count(e) == 0;
    return static_cast<double>(broken) / static_cast<double>(ex.size());
  };
  std::vector<std::vector<NodeId>> pop;
  for (const auto& r : routes) {
    pop.push_back(r);
    if (static_cast<int>(pop.size()) < mu + lambda) continue;
    while (static_cast<int>(pop.size()) > mu) {
      const int n = static_cast<int>(pop.size());
      std::vector<double> div(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) {
        std::vector<double> d;
        for (int j = 0; j < n; ++j)
          if (j != i) d.push_back(dist(pop[static_cast<std::size_t>(i)], pop[static_cast<std::size_t>(j)]));
        std::sort(d.begin(), d.end());
        const int c = std::min(close, n - 1);
        double sum = 0.0;
        for (int q = 0; q < c; ++q) sum += d[static_cast<std::size_t>(q)];
        div[static_cast<std::size_t>(i)] = sum / c;
      }
      std::vector<int> by_cost(static_cast<std::size_t>(n)), by_div(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) by_cost[static_cast<std::size_t>(i)] = by_div[static_cast<std::size_t>(i)] = i;
      auto cost = [&](int i) { return route_cost(p, pop[static_cast<std::size_t>(i)]); };
      std::stable_sort(by_cost.begin(), by_cost.end(), [&](int a, int b) { return cost(a) < cost(b); });
      std::stable_sort(by_div.begin(), by_div.end(),
                       [&](int a, int b) { return div[static_cast<std::size_t>(a)] > div[static_cast<std::size_t>(b)]; });
      std::vector<double> fit(static_cast<std::size_t>(n), 0.0);
      const double w = std::max(0.0, 1.0 - static_cast<double>(elite) / n);
      for (int rk = 0; rk < n; ++rk) {
        fit[static_cast<std::size_t>(by_cost[static_cast<std::size_t>(rk)])] += static_cast<double>(rk) / (n - 1);
        fit[static_cast<std::size_t>(by_div[static_cast<std::size_t>(rk)])] += w * (static_cast<double>(rk) / (n - 1));
      }
      int worst = -1;
      bool worst_clone = false;
      for (int i = 0; i < n; ++i) {
        bool clone = false;
        for (int j = 0; j < n; ++j)
          clone = clone || (j != i && dist(pop[static_cast<std::size_t>(i)], pop[static_cast<std::size_t>(j)]) == 0.0 &&
                            (cost(j) < cost(i) || (cost(j) == cost(i) && j < i)));
        if (worst < 0 || (clone && !worst_clone) ||
            (clone == worst_clone && fit[static_cast<std::size_t>(i)] > fit[static_cast<std::size_t>(worst)])) {
          worst = i;
          worst_clone = clone;
        }
      }
      pop.erase(pop.begin() + worst);
    }
  }
  return pop;
}

// The solver keeps sorted distance lists up to date member by member instead of recomputing them;
// the survivors must be the same routes, in the same order, as the definition gives.
TEST(Population, SurvivorSelectionMatchesTheDefinition) {
  Rng rng(31);
  for (int k = 0; k < 12; ++k) {
    test::RandomSpec spec;
    spec.clusters = 8 + static_cast<int>(rng.below(20));
    spec.max_nodes = 1 + static_cast<int>(rng.below(3));
    spec.symmetric = true;
    const Problem p = test::random_problem(spec, rng);
    const std::vector<std::vector<NodeId>> routes = mixed_routes(p, rng, 60, 5, 3);
    const int mu = 4 + static_cast<int>(rng.below(6)), lambda = 3 + static_cast<int>(rng.below(10));
    EXPECT_EQ(population_survivors(p, routes, mu, lambda), reference_survivors(p, routes, mu, lambda))
        << "instance " << k << ", mu " << mu << ", lambda " << lambda;
  }
}

}  // namespace
}  // namespace cutroute::solve
