// Local-search operators never worsen a route, never break it, and construction is always valid.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <cutroute/solve/heuristic.hpp>
#include <cutroute/solve/solution.hpp>

#include "random_instance.hpp"
#include "route_check.hpp"

namespace cutroute::solve {
namespace {

void expect_valid(const Problem& p, const std::vector<NodeId>& r, const char* what) {
  const auto errors = test::route_errors(p, r);
  EXPECT_TRUE(errors.empty()) << what << ": " << (errors.empty() ? "" : errors.front());
}

TEST(Operators, NeverWorsenAndKeepPrecedence) {
  Rng rng(99);
  for (int k = 0; k < 60; ++k) {
    test::RandomSpec spec;
    spec.clusters = 5 + static_cast<int>(rng.below(60));
    spec.max_nodes = 1 + static_cast<int>(rng.below(4));
    spec.symmetric = k % 2 == 0;
    spec.closed = k % 3 != 0;
    spec.precedence_pairs = k % 4 == 0 ? 0 : static_cast<int>(rng.below(static_cast<std::uint64_t>(spec.clusters)));
    spec.inner_costs = k % 5 == 0;
    spec.scatter_nodes = k % 7 < 3;
    if (k % 6 == 1) spec.symmetric = true, spec.asym_noise = 20;  // nearly symmetric matrix
    const Problem p = test::random_problem(spec, rng);
    SCOPED_TRACE("instance " + std::to_string(k));
    std::vector<NodeId> r = construct_route(p, rng);
    expect_valid(p, r, "construction");
    using Op = bool (*)(const Problem&, std::vector<NodeId>&);
    const std::pair<const char*, Op> ops[] = {{"reinsertion", reinsertion_pass},
                                              {"two_opt", two_opt_pass},
                                              {"or_opt", or_opt_pass},
                                              {"swap", swap_pass},
                                              {"segment_exchange", segment_exchange_pass},
                                              {"reversing_exchange", reversing_exchange_pass},
                                              {"cluster_optimise", [](const Problem& q, std::vector<NodeId>& x) { return cluster_optimise(q, x); }}};
    for (int round = 0; round < 3; ++round)
      for (auto [name, op] : ops) {
        const Cost before = route_cost(p, r);
        const bool improved = op(p, r);
        const Cost after = route_cost(p, r);
        expect_valid(p, r, name);
        EXPECT_LE(after, before) << name;
        EXPECT_EQ(improved, after < before) << name;
      }
    const Cost before = route_cost(p, r);
    local_search(p, r);
    expect_valid(p, r, "local_search");
    EXPECT_LE(route_cost(p, r), before);
  }
}

// A random order that keeps precedence, with random nodes: a bad but valid route on which many moves
// pay and many candidate places would break a pair.
std::vector<NodeId> random_valid_route(const Problem& p, Rng& rng) {
  const int m = p.cluster_count();
  std::vector<int> indeg(static_cast<std::size_t>(m));
  for (int c = 0; c < m; ++c) indeg[static_cast<std::size_t>(c)] = static_cast<int>(p.all_before(ClusterId(c)).size());
  std::vector<NodeId> r{p.nodes_of(p.start_cluster())[0]};
  std::vector<int> avail;
  auto place = [&](ClusterId c) {
    for (ClusterId b : p.all_after(c))
      if (--indeg[b.index()] == 0 && b != p.start_cluster()) avail.push_back(b.value());
  };
  place(p.start_cluster());
  for (int c = 0; c < m; ++c)
    if (ClusterId(c) != p.start_cluster() && indeg[static_cast<std::size_t>(c)] == 0) avail.push_back(c);
  while (!avail.empty()) {
    const std::size_t k = rng.below(avail.size());
    const ClusterId c(avail[k]);
    avail[k] = avail.back(), avail.pop_back();
    const auto nodes = p.nodes_of(c);
    r.push_back(nodes[static_cast<std::size_t>(rng.below(nodes.size()))]);
    place(c);
  }
  return r;
}

// Long routes with sparse precedence (from 200 clusters, as cutting nests) take reinsertion, 2-opt,
// Or-opt and swap only next to candidate neighbours and check the pairs only for improving moves: every
// move must still keep them, never worsen the route, and the operators must find moves. Matrices of
// 200-300 clusters with m/2 random pairs, and plates: a grid of holes with planar costs, every hole
// before the plate's outer contour, a few holes before another hole (parts in holes).
TEST(Operators, LongRoutesWithSparsePrecedenceKeepEveryPair) {
  Rng rng(4242);
  using Op = bool (*)(const Problem&, std::vector<NodeId>&);
  const std::pair<const char*, Op> ops[] = {{"reinsertion", reinsertion_pass}, {"two_opt", two_opt_pass}, {"or_opt", or_opt_pass}, {"swap", swap_pass}};
  int moves[4] = {0, 0, 0, 0};
  for (int k = 0; k < 12; ++k) {
    std::optional<Problem> built;
    if (k % 3 != 2) {  // k % 3 == 0: symmetric (2-opt applies), 1: nearly symmetric
      test::RandomSpec spec;
      spec.clusters = 200 + static_cast<int>(rng.below(100));
      spec.max_nodes = 1 + static_cast<int>(rng.below(3));
      spec.closed = k % 2 == 0;
      spec.precedence_pairs = spec.clusters / 2;
      spec.inner_costs = k % 4 == 1;
      if (k % 3 == 1) spec.asym_noise = 30;
      built.emplace(test::random_problem(spec, rng));
    } else {
      constexpr int kSide = 16;  // 256 holes on a 20-mm grid, each entered at 1-3 points
      PlanarCosts pc;
      std::vector<std::vector<NodeId>> clusters;
      int n = 0;
      auto add = [&](double x, double y, int nodes) {
        clusters.emplace_back();
        for (int j = 0; j < nodes; ++j) {
          const double a = 6.283 * rng.uniform01();
          pc.in.push_back({x + 4 * std::cos(a), y + 4 * std::sin(a)}), pc.out.push_back({x + 4 * std::cos(a + 0.2), y + 4 * std::sin(a + 0.2)});
          clusters.back().push_back(NodeId(n++));
        }
      };
      add(-5, -5, 1);  // the machine's start
      for (int r = 0; r < kSide; ++r)
        for (int c = 0; c < kSide; ++c) add(20.0 * c + 3 * rng.uniform01(), 20.0 * r + 3 * rng.uniform01(), 1 + static_cast<int>(rng.below(3)));
      add(160, 160, 4);  // the outer contour
      pc.base = 0.25, pc.per_unit = 1.0 / 250, pc.scale = 1e6;
      ProblemBuilder pb(n);
      pb.set_planar_costs(pc);
      for (const auto& c : clusters) pb.add_cluster(c);
      const int outer = static_cast<int>(clusters.size()) - 1;
      for (int h = 1; h < outer; ++h) pb.add_precedence(ClusterId(h), ClusterId(outer));
      for (int j = 0; j < 20; ++j) {
        const int a = 1 + static_cast<int>(rng.below(static_cast<std::uint64_t>(outer - 2)));
        pb.add_precedence(ClusterId(a), ClusterId(a + 1));
      }
      pb.set_kind(k % 2 == 0 ? RouteKind::closed_tour : RouteKind::open_path);
      auto r = pb.build();
      ASSERT_TRUE(r.ok()) << r.error().message;
      built.emplace(std::move(r).value());
    }
    const Problem& p = *built;
    SCOPED_TRACE("instance " + std::to_string(k));
    std::vector<NodeId> r = random_valid_route(p, rng);
    expect_valid(p, r, "random order");
    for (int round = 0; round < 4; ++round)
      for (std::size_t o = 0; o < 4; ++o) {
        const Cost before = route_cost(p, r);
        const bool improved = ops[o].second(p, r);
        const Cost after = route_cost(p, r);
        expect_valid(p, r, ops[o].first);
        EXPECT_LE(after, before) << ops[o].first;
        EXPECT_EQ(improved, after < before) << ops[o].first;
        moves[o] += improved ? 1 : 0;
      }
    const Cost before = route_cost(p, r);
    local_search(p, r);
    expect_valid(p, r, "local_search");
    EXPECT_LE(route_cost(p, r), before);
  }
  for (std::size_t o = 0; o < 4; ++o) EXPECT_GE(moves[o], 4) << ops[o].first << " found too few moves";
}

// 2-opt with neighbour optimisation against enumeration: reversing route[i..j] with every choice of
// nodes at its four ends, the move is made exactly when the cheapest choice beats the route, and
// then it yields that cost (recomputed from the matrix, and as the move tracked it).
TEST(Operators, TwoOptNeighbourMoveMatchesEnumeration) {
  Rng rng(2012);
  int moved = 0, refused = 0;
  for (int k = 0; k < 40; ++k) {
    test::RandomSpec spec;
    spec.clusters = 8 + static_cast<int>(rng.below(50));
    spec.max_nodes = 1 + static_cast<int>(rng.below(4));
    spec.closed = k % 3 != 0;
    spec.scatter_nodes = k % 2 == 0;
    const Problem p = test::random_problem(spec, rng);
    SCOPED_TRACE("instance " + std::to_string(k));
    // A random route (random order, random nodes), so that many reversals pay.
    std::vector<NodeId> r = construct_route(p, rng);
    rng.shuffle(r.begin() + 1, r.end());
    for (NodeId& v : r) {
      const auto nodes = p.nodes_of(p.cluster_of(v));
      v = nodes[static_cast<std::size_t>(rng.below(nodes.size()))];
    }
    const int L = static_cast<int>(r.size());
    for (int trial = 0; trial < 30; ++trial) {
      // 2 <= i, i + 2 <= j <= L - 2.
      const int i = 2 + static_cast<int>(rng.below(static_cast<std::uint64_t>(L - 5)));
      const int j = i + 2 + static_cast<int>(rng.below(static_cast<std::uint64_t>(L - 3 - i)));
      std::vector<NodeId> rev = r;
      std::reverse(rev.begin() + i, rev.begin() + j + 1);
      // After the reversal the four end clusters sit at i - 1, i, j, j + 1.
      Cost best = std::numeric_limits<Cost>::max();
      for (NodeId x : p.nodes_of(p.cluster_of(rev[static_cast<std::size_t>(i - 1)])))
        for (NodeId y : p.nodes_of(p.cluster_of(rev[static_cast<std::size_t>(i)])))
          for (NodeId u : p.nodes_of(p.cluster_of(rev[static_cast<std::size_t>(j)])))
            for (NodeId w : p.nodes_of(p.cluster_of(rev[static_cast<std::size_t>(j + 1)]))) {
              std::vector<NodeId> cand = rev;
              cand[static_cast<std::size_t>(i - 1)] = x, cand[static_cast<std::size_t>(i)] = y;
              cand[static_cast<std::size_t>(j)] = u, cand[static_cast<std::size_t>(j + 1)] = w;
              best = std::min(best, route_cost(p, cand));
            }
      const Cost before = route_cost(p, r);
      std::vector<NodeId> out = r;
      Cost tracked = -1;
      const bool did = two_opt_neighbour_move(p, out, i, j, tracked);
      ASSERT_EQ(did, best < before) << "i " << i << " j " << j;
      if (did) {
        ++moved;
        EXPECT_EQ(route_cost(p, out), best);
        EXPECT_EQ(tracked, best);
        expect_valid(p, out, "two_opt_neighbour_move");
        r = out;
      } else {
        ++refused;
        EXPECT_EQ(out, r);
      }
    }
  }
  // Both outcomes occur often enough for the comparison to mean something.
  EXPECT_GT(moved, 100);
  EXPECT_GT(refused, 100);
}

// Cluster optimisation is exact for a fixed order: compare with enumerating every node choice.
TEST(Operators, ClusterOptimiseFindsBestNodesForFixedOrder) {
  Rng rng(5);
  for (int k = 0; k < 60; ++k) {
    test::RandomSpec spec;
    spec.clusters = 1 + static_cast<int>(rng.below(5));  // one cluster: its cheapest node alone
    spec.max_nodes = 3;
    spec.symmetric = k % 2 == 0;
    spec.closed = k % 3 != 0;
    spec.inner_costs = k % 3 != 0;  // without: the solver reads its cluster-blocked matrix copies
    spec.scatter_nodes = k % 4 < 2;  // ... which are then a true permutation of the matrix
    const Problem p = test::random_problem(spec, rng);
    std::vector<NodeId> r = construct_route(p, rng);
    Cost best = route_cost(p, r);
    std::vector<std::size_t> pick(r.size(), 0);
    while (true) {
      std::vector<NodeId> x;
      for (std::size_t i = 0; i < r.size(); ++i) x.push_back(p.nodes_of(p.cluster_of(r[i]))[pick[i]]);
      best = std::min(best, route_cost(p, x));
      std::size_t i = 0;
      while (i < pick.size() && ++pick[i] == p.nodes_of(p.cluster_of(r[i])).size()) pick[i++] = 0;
      if (i == pick.size()) break;
    }
    cluster_optimise(p, r, 1e12);
    EXPECT_EQ(route_cost(p, r), best) << "instance " << k;
  }
}

}  // namespace
}  // namespace cutroute::solve
