// Elite-difference destroy: removes exactly the clusters next to arcs the elite route lacks (checked
// against an independent cluster-level arc set), keeps position 0, and its tracked cost equals the
// shortened route's cost recomputed from scratch.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/solution.hpp>

#include "random_instance.hpp"

namespace cutroute::solve {
namespace {

// Cluster-level arcs of a route (both orientations when `sym`).
std::set<std::pair<int, int>> arcs_of(const Problem& p, const std::vector<NodeId>& r, bool sym) {
  std::set<std::pair<int, int>> s;
  const std::size_t L = r.size();
  for (std::size_t i = 0; i < L; ++i) {
    if (i + 1 == L && !p.closed()) break;
    const int a = p.cluster_of(r[i]).value(), b = p.cluster_of(r[(i + 1) % L]).value();
    s.insert({a, b});
    if (sym) s.insert({b, a});
  }
  return s;
}

TEST(EliteDestroy, RemovesExactlyTheClustersNextToArcsTheEliteLacks) {
  Rng rng(5);
  int nontrivial = 0;
  for (int k = 0; k < 40; ++k) {
    test::RandomSpec spec;
    spec.clusters = 3 + static_cast<int>(rng.below(40));
    spec.max_nodes = 1 + static_cast<int>(rng.below(4));
    spec.symmetric = k % 2 == 0;
    spec.closed = k % 3 != 0;
    spec.inner_costs = k % 4 == 0;
    const Problem p = test::random_problem(spec, rng);
    const std::vector<NodeId> a = construct_route(p, rng);
    const std::vector<NodeId> b = construct_route(p, rng);

    std::vector<NodeId> same = a;
    Cost tracked = -1;
    EXPECT_TRUE(remove_differences(p, same, a, tracked).empty());
    EXPECT_EQ(same, a);

    const auto elite_arcs = arcs_of(p, b, p.symmetric());
    std::set<int> expected;  // positions at an end of an arc of a that b lacks, except 0
    const std::size_t L = a.size();
    for (std::size_t i = 0; i < L; ++i) {
      if (i + 1 == L && !p.closed()) break;
      const std::size_t j = (i + 1) % L;
      if (j == i || elite_arcs.count({p.cluster_of(a[i]).value(), p.cluster_of(a[j]).value()})) continue;
      if (i > 0) expected.insert(static_cast<int>(i));
      if (j > 0) expected.insert(static_cast<int>(j));
    }
    std::vector<NodeId> route = a;
    const std::vector<ClusterId> removed = remove_differences(p, route, b, tracked);
    std::set<int> removed_clusters;
    for (ClusterId c : removed) removed_clusters.insert(c.value());
    std::set<int> expected_clusters;
    for (int i : expected) expected_clusters.insert(p.cluster_of(a[static_cast<std::size_t>(i)]).value());
    EXPECT_EQ(removed_clusters, expected_clusters) << "instance " << k;
    EXPECT_EQ(removed.size(), expected.size());
    // What stays is a's order without the removed clusters, position 0 first.
    std::vector<NodeId> kept;
    for (std::size_t i = 0; i < L; ++i)
      if (!expected.count(static_cast<int>(i))) kept.push_back(a[i]);
    EXPECT_EQ(route, kept);
    EXPECT_EQ(tracked, route_cost(p, route)) << "instance " << k;
    nontrivial += !removed.empty();
  }
  EXPECT_GT(nontrivial, 30);  // two random constructions almost always differ
}

}  // namespace
}  // namespace cutroute::solve
