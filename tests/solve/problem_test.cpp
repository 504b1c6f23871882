// ProblemBuilder checks, precedence closure, route cost and validate() on hand-made cases.
#include <gtest/gtest.h>

#include <cutroute/solve/problem.hpp>
#include <cutroute/solve/solution.hpp>

namespace cutroute::solve {
namespace {

// 4 nodes on a line at x = 0, 1, 3, 6; clusters {0}, {1, 2}, {3}.
ProblemBuilder line_builder() {
  const int x[4] = {0, 1, 3, 6};
  std::vector<Cost> m(16);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m[static_cast<std::size_t>(i * 4 + j)] = std::abs(x[i] - x[j]);
  ProblemBuilder b(4);
  b.set_cost_matrix(m);
  b.add_cluster({NodeId(0)});
  b.add_cluster({NodeId(1), NodeId(2)});
  b.add_cluster({NodeId(3)});
  return b;
}

TEST(ProblemBuilder, BuildsAndAnswersAccessors) {
  auto r = line_builder().build();
  ASSERT_TRUE(r.ok()) << r.error().message;
  const Problem& p = *r;
  EXPECT_EQ(p.node_count(), 4);
  EXPECT_EQ(p.cluster_count(), 3);
  EXPECT_EQ(p.cluster_of(NodeId(2)), ClusterId(1));
  EXPECT_EQ(p.cluster_size(ClusterId(1)), 2);
  EXPECT_TRUE(p.symmetric());
  EXPECT_EQ(p.arc_cost(NodeId(0), NodeId(3)), 6);
}

TEST(ProblemBuilder, RejectsBadInput) {
  {
    auto b = line_builder();
    b.add_cluster({});
    EXPECT_NE(b.build().error().message.find("empty"), std::string::npos);
  }
  {
    auto b = line_builder();
    b.add_cluster({NodeId(1)});
    EXPECT_NE(b.build().error().message.find("clusters 1 and 3"), std::string::npos);
  }
  {
    ProblemBuilder b(3);
    b.set_cost_matrix(std::vector<Cost>(9, 1));
    b.add_cluster({NodeId(0)});
    b.add_cluster({NodeId(1)});
    EXPECT_NE(b.build().error().message.find("node 2 is in no cluster"), std::string::npos);
  }
  {
    auto b = line_builder();
    b.add_precedence(ClusterId(1), ClusterId(2)).add_precedence(ClusterId(2), ClusterId(1));
    EXPECT_NE(b.build().error().message.find("cycle"), std::string::npos);
  }
  {
    auto b = line_builder();
    b.add_precedence(ClusterId(2), ClusterId(0));
    EXPECT_NE(b.build().error().message.find("start cluster"), std::string::npos);
  }
  {
    ProblemBuilder b(2);
    b.set_cost_matrix({0, -5, 1, 0});
    b.add_cluster({NodeId(0)});
    b.add_cluster({NodeId(1)});
    EXPECT_NE(b.build().error().message.find("negative"), std::string::npos);
  }
  {
    ProblemBuilder b(2);
    b.add_cluster({NodeId(0), NodeId(1)});
    EXPECT_NE(b.build().error().message.find("no costs"), std::string::npos);
  }
}

TEST(ProblemBuilder, PrecedenceClosureIsTransitive) {
  ProblemBuilder b(5);
  b.set_cost_matrix(std::vector<Cost>(25, 1));
  for (int c = 0; c < 5; ++c) b.add_cluster({NodeId(c)});
  b.add_precedence(ClusterId(1), ClusterId(2)).add_precedence(ClusterId(2), ClusterId(3)).add_precedence(ClusterId(2), ClusterId(4));
  auto r = b.build();
  ASSERT_TRUE(r.ok());
  const Problem& p = *r;
  EXPECT_TRUE(p.must_precede(ClusterId(1), ClusterId(4)));
  EXPECT_TRUE(p.must_precede(ClusterId(1), ClusterId(3)));
  EXPECT_FALSE(p.must_precede(ClusterId(3), ClusterId(4)));
  EXPECT_FALSE(p.must_precede(ClusterId(4), ClusterId(1)));
  EXPECT_EQ(p.all_after(ClusterId(1)).size(), 3u);
  EXPECT_EQ(p.all_before(ClusterId(3)).size(), 2u);
}

// Found by fuzzing (session 39): a chain of 8 000 clusters took 1.2 GB of closure lists.
TEST(ProblemBuilder, RefusesAPrecedenceClosureBeyondItsLimit) {
  auto chain = [](int m) {
    ProblemBuilder b(m);
    PlanarCosts pc;
    pc.per_unit = 1.0;
    for (int c = 0; c < m; ++c) pc.out.push_back({static_cast<double>(c), 0.0});
    pc.in = pc.out;
    b.set_planar_costs(pc);
    for (int c = 0; c < m; ++c) b.add_cluster({NodeId(c)});
    for (int c = 1; c + 1 < m; ++c) b.add_precedence(ClusterId(c), ClusterId(c + 1));
    return b.build();
  };
  // m - 2 chained clusters: (m - 2)(m - 3) / 2 ordered pairs, 2^24 = 16 777 216 allowed.
  EXPECT_TRUE(chain(5000).ok());  // 12.5 million pairs
  auto r = chain(6000);           // 18 million
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("more than 16777216 ordered pairs"), std::string::npos) << r.error().message;
}

// The heuristics price a forbidden arc at 2^41: four allowed arcs of 2^40 cost more, and the
// heuristic returned "no route without forbidden arcs" on a problem with one.
TEST(ProblemBuilder, RefusesCostsARouteOfWhichWouldOutpriceAForbiddenArc) {
  auto ring = [](Cost w) {
    ProblemBuilder b(4);
    std::vector<Cost> m(16, kForbiddenCost);
    for (int i = 0; i < 4; ++i) m[static_cast<std::size_t>(i * 4 + i)] = 0, m[static_cast<std::size_t>(i * 4 + (i + 1) % 4)] = w;
    b.set_cost_matrix(m);
    for (int c = 0; c < 4; ++c) b.add_cluster({NodeId(c)});
    return b.build();
  };
  EXPECT_TRUE(ring((kForbiddenCost - 1) / 4).ok());
  auto r = ring(kMaxCost);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("costs up to 549755813887 are supported"), std::string::npos) << r.error().message;
}

TEST(Validate, AcceptsCorrectRoutesAndNamesEveryDefect) {
  auto b = line_builder();
  b.set_inner_cost(NodeId(3), 10);
  b.forbid_arc(NodeId(3), NodeId(1));
  b.add_precedence(ClusterId(2), ClusterId(1));
  const Problem p = *b.build();
  // 0 -> 3 -> 2 -> 0: 6 + 10 + 3 + 3 = 22.
  Solution s;
  s.route = {NodeId(0), NodeId(3), NodeId(2)};
  s.cost = 22;
  EXPECT_EQ(route_cost(p, s.route), 22);
  EXPECT_TRUE(validate(p, s).empty());

  Solution wrong_cost = s;
  wrong_cost.cost = 21;
  EXPECT_EQ(validate(p, wrong_cost).size(), 1u);

  Solution order = s;  // 0 -> 2 -> 3: cluster 1 before cluster 2
  order.route = {NodeId(0), NodeId(2), NodeId(3)};
  order.cost = route_cost(p, order.route);
  ASSERT_FALSE(validate(p, order).empty());
  EXPECT_NE(validate(p, order).front().find("precedence"), std::string::npos);

  Solution forbidden = s;  // 0 -> 3 -> 1 uses the forbidden arc 3 -> 1
  forbidden.route = {NodeId(0), NodeId(3), NodeId(1)};
  forbidden.cost = route_cost(p, forbidden.route);
  bool named = false;
  for (const auto& e : validate(p, forbidden)) named = named || e.find("forbidden arc 3 -> 1") != std::string::npos;
  EXPECT_TRUE(named);

  Solution twice = s;
  twice.route = {NodeId(0), NodeId(1), NodeId(2)};
  twice.cost = route_cost(p, twice.route);
  EXPECT_FALSE(validate(p, twice).empty());

  Solution wrong_start = s;
  wrong_start.route = {NodeId(3), NodeId(2), NodeId(0)};
  wrong_start.cost = route_cost(p, wrong_start.route);
  EXPECT_FALSE(validate(p, wrong_start).empty());
}

TEST(Validate, OpenPathPaysNoClosingArc) {
  auto b = line_builder();
  b.set_kind(RouteKind::open_path);
  const Problem p = *b.build();
  EXPECT_EQ(route_cost(p, std::vector<NodeId>{NodeId(0), NodeId(1), NodeId(3)}), 6);
}

TEST(ProblemBuilder, CostFunctionWithForbiddenArc) {
  ProblemBuilder b(3);
  b.set_cost_function([](NodeId a, NodeId c) { return static_cast<Cost>(std::abs(a.value() - c.value()) * 7); }, true);
  for (int c = 0; c < 3; ++c) b.add_cluster({NodeId(c)});
  b.forbid_arc(NodeId(2), NodeId(0));
  const Problem p = *b.build();
  EXPECT_FALSE(p.has_matrix());
  EXPECT_FALSE(p.symmetric());  // a forbidden arc breaks the promise
  EXPECT_EQ(p.arc_cost(NodeId(0), NodeId(2)), 14);
  EXPECT_TRUE(p.forbidden(NodeId(2), NodeId(0)));
}

}  // namespace
}  // namespace cutroute::solve
