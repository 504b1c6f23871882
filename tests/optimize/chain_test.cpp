// Chain cutting: candidate chains and their basic segments, checked against geometric facts
// recomputed here (containment by winding number, sampled distances), not against chains.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include <cutroute/cost/route_problem.hpp>
#include <cutroute/geometry/shapes.hpp>
#include <cutroute/model/chains.hpp>
#include <cutroute/model/demo_nest.hpp>

namespace cutroute::model {
namespace {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

Contour rect(double x, double y, double w, double h) {
  return Contour{{Vertex{{x, y}, 0}, Vertex{{x + w, y}, 0}, Vertex{{x + w, y + h}, 0}, Vertex{{x, y + h}, 0}}, true};
}
SourceContour src(Contour c) { return SourceContour{std::move(c), "0", {}, {}, {}}; }

bool in_material(const Nest& nest, Vec2 p) {
  int inside = 0;
  for (const auto& c : nest.contours) {
    if (c.role == ContourRole::sheet) continue;
    inside += geometry::locate(c.source.contour, p, 1e-9) == geometry::Location::inside;
  }
  return inside % 2 == 1;
}

// A chain candidate: pieces alternate contour, bridge, contour, ...; continuous; each contour
// piece a whole loop of its contour; each bridge straight, in scrap, within the gap limit.
void check_chain_candidate(const Nest& nest, const BasicSegment& seg, const EntryCandidate& e, double max_gap) {
  ASSERT_EQ(e.pieces.size(), 2 * seg.contours.size() - 1);
  std::vector<ContourId> cut;
  Vec2 at = e.lead_in.vertices.empty() ? e.pierce : e.lead_in.vertices.back().p;
  for (std::size_t i = 0; i < e.pieces.size(); ++i) {
    const auto& p = e.pieces[i];
    ASSERT_GE(p.path.vertices.size(), 2u);
    EXPECT_LT(geometry::distance(p.path.vertices.front().p, at), 1e-9) << "piece " << i << " does not start where the last ended";
    at = p.path.vertices.back().p;
    if (i % 2 == 1) {
      EXPECT_EQ(p.kind, PieceKind::bridge);
      EXPECT_FALSE(p.contour.valid());
      const double len = geometry::length(p.path);
      EXPECT_LE(len, max_gap + 1e-9);
      for (int k = 1; k < 20; ++k) {
        const Vec2 q = geometry::point_at_length(p.path, len * k / 20.0);
        EXPECT_FALSE(in_material(nest, q)) << "bridge through material at " << q.x << ", " << q.y;
      }
      continue;
    }
    EXPECT_EQ(p.kind, PieceKind::contour);
    const auto& c = nest.contours[p.contour].source.contour;
    EXPECT_NEAR(geometry::length(p.path), geometry::length(c), 1e-6);
    EXPECT_LT(geometry::distance(p.path.vertices.front().p, p.path.vertices.back().p), 1e-6) << "not a whole loop";
    for (int k = 0; k < 10; ++k)
      EXPECT_LT(geometry::distance(c, geometry::point_at_length(p.path, geometry::length(p.path) * k / 10.0)), 1e-6);
    cut.push_back(p.contour);
  }
  std::vector<ContourId> want = seg.contours;
  std::sort(want.begin(), want.end());
  std::sort(cut.begin(), cut.end());
  EXPECT_EQ(cut, want);
  if (!e.lead_out.vertices.empty()) {
    EXPECT_LT(geometry::distance(e.lead_out.vertices.front().p, at), 1e-9);
  }
}

TEST(Chains, DemoSheetHasExactlyTheThreeBracketPairs) {
  const Nest nest = build_nest(make_demo_sheet(), NestOptions{});
  const auto links = chain_links(nest, ChainOptions{});
  ASSERT_EQ(links.size(), 3u);
  for (const auto& l : links) {
    EXPECT_NEAR(l.gap_mm, kDemoChainGapMm, 1e-6);
    EXPECT_NE(nest.contours[l.a].part, nest.contours[l.b].part);
  }
  // Below the gap nothing is chainable.
  ChainOptions tight;
  tight.max_gap_mm = kDemoChainGapMm - 0.5;
  EXPECT_TRUE(chain_links(nest, tight).empty());
}

TEST(Chains, DemoChainJobHas18BasicSegments) {
  const Nest nest = build_nest(make_demo_sheet(), NestOptions{});
  EntryOptions entries;
  entries.kerf_mm = 0.15;
  entries.lead.in_length_mm = 2.0;
  entries.lead.in_arc_radius_mm = 1.0;
  entries.lead.out_length_mm = 0.5;
  const ChainOptions opt;
  const CutJob job = make_chain_job(nest, entries, opt);
  ASSERT_EQ(job.segments.size(), 18u);
  std::size_t chains = 0, contours = 0;
  std::vector<int> times_cut(nest.contours.size(), 0);
  for (const auto& seg : job.segments) {
    contours += seg.contours.size();
    for (auto c : seg.contours) ++times_cut[c.index()];
    if (seg.contours.size() == 1) continue;
    ++chains;
    ASSERT_EQ(seg.contours.size(), 2u);
    EXPECT_GE(seg.candidates.size(), 2u) << "several bridge positions or orders";
    bool both_orders[2] = {false, false};
    for (const auto& e : seg.candidates) {
      check_chain_candidate(nest, seg, e, opt.max_gap_mm);
      both_orders[e.contour == seg.contours[0] ? 0 : 1] = true;
      EXPECT_FALSE(in_material(nest, e.pierce));
    }
    EXPECT_TRUE(both_orders[0] && both_orders[1]) << "each order of the pair offered";
  }
  EXPECT_EQ(chains, 3u);
  EXPECT_EQ(contours, 21u);
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    if (nest.contours[ContourId(static_cast<std::int32_t>(i))].role == ContourRole::sheet) continue;
    EXPECT_EQ(times_cut[i], 1) << "contour " << i + 1;
  }
  // Precedence: every hole's segment before its outer's (seven holes), nothing else.
  EXPECT_EQ(job.precedence.size(), 7u);
  for (auto [a, b] : job.precedence) {
    const auto& sa = job.segments[static_cast<std::size_t>(a)];
    const auto& sb = job.segments[static_cast<std::size_t>(b)];
    ASSERT_EQ(sa.contours.size(), 1u);
    EXPECT_EQ(nest.contours[sa.contours[0]].role, ContourRole::hole);
    EXPECT_EQ(nest.contours[sa.contours[0]].parent, sb.contours[0]);
  }
}

TEST(Chains, RouteProblemChargesPiercesLeadsBridgesAndContours) {
  const Nest nest = build_nest(make_demo_sheet(), NestOptions{});
  const CutJob job = make_chain_job(nest, EntryOptions{}, ChainOptions{});
  cost::RoutePrices prices;
  prices.v_on_mm_s = 50;
  prices.pierce_s = 0.3;
  auto rp = cost::build_route_problem(job, prices, cost::RouteProblemOptions{});
  ASSERT_TRUE(rp.ok());
  for (std::size_t v = 1; v < rp->nodes.size(); ++v) {
    const auto& n = rp->nodes[v];
    const auto& e = job.segments[static_cast<std::size_t>(n.segment)].candidates[static_cast<std::size_t>(n.candidate)];
    double mm = geometry::length(e.lead_in) + geometry::length(e.lead_out);
    for (const auto& p : e.pieces) mm += geometry::length(p.path);
    const double want = mm / 50 + 0.3;
    EXPECT_NEAR(static_cast<double>(rp->problem.inner_cost(solve::NodeId(static_cast<std::int32_t>(v)))) * 1e-6, want, 2e-6);
  }
}

TEST(Chains, BridgeMustNotCrossAPartAndKeepsClearance) {
  // A and B 10 mm apart; C, a small part, sits in the gap near y = 20.
  std::vector<SourceContour> cs{src(rect(0, 0, 50, 50)), src(rect(60, 0, 50, 50)), src(rect(54, 18, 2, 4))};
  NestOptions no_sheet;
  no_sheet.detect_sheet = false;
  const Nest nest = build_nest(cs, no_sheet);
  const EntryPlanner planner(nest, EntryOptions{});
  const ContourId a(0), b(1);
  const auto line = [](Vec2 p, Vec2 q) { return Contour{{Vertex{p, 0}, Vertex{q, 0}}, false}; };
  EXPECT_TRUE(planner.bridge_clear(line({50, 40}, {60, 40}), a, b));
  EXPECT_FALSE(planner.bridge_clear(line({50, 20}, {60, 20}), a, b)) << "crosses C";
  EXPECT_FALSE(planner.bridge_clear(line({50, 23}, {60, 23}), a, b)) << "1 mm from C: inside the clearance";
  EXPECT_FALSE(planner.bridge_clear(line({40, 40}, {60, 40}), a, b)) << "runs through A";
  EXPECT_FALSE(planner.bridge_clear(line({50, 0}, {50, 50}), a, a)) << "along A's edge";
}

TEST(Chains, PrecedenceCycleIsDetected) {
  // P with hole H; Q lies inside H. A segment cutting Q and P together would need H both after
  // it (Q before H) and before it (H before P): no order exists.
  std::vector<SourceContour> cs{src(rect(0, 0, 100, 100)), src(rect(20, 20, 60, 60)), src(rect(40, 40, 20, 20))};
  NestOptions no_sheet;
  no_sheet.detect_sheet = false;
  const Nest nest = build_nest(cs, no_sheet);
  ASSERT_EQ(nest.contours[ContourId(2)].parent, ContourId(1));
  std::vector<BasicSegment> segs(2);
  segs[0].contours = {ContourId(0), ContourId(2)};
  segs[1].contours = {ContourId(1)};
  EXPECT_FALSE(segment_precedence(nest, segs).has_value());
  std::vector<BasicSegment> fine(3);
  for (int i = 0; i < 3; ++i) fine[static_cast<std::size_t>(i)].contours = {ContourId(i)};
  const auto prec = segment_precedence(nest, fine);
  ASSERT_TRUE(prec.has_value());
  EXPECT_EQ(prec->size(), 2u);
}

TEST(Chains, NestedPartsChainOnlyWithPartsInTheSameHole) {
  // Two parts 6 mm apart inside a big hole: they chain; neither chains with the frame around them.
  std::vector<SourceContour> cs{src(rect(0, 0, 300, 200)), src(rect(10, 10, 280, 180)), src(rect(20, 20, 100, 100)),
                                src(rect(126, 20, 100, 100))};
  NestOptions no_sheet;
  no_sheet.detect_sheet = false;
  const Nest nest = build_nest(cs, no_sheet);
  const CutJob job = make_chain_job(nest, EntryOptions{}, ChainOptions{});
  ASSERT_EQ(job.segments.size(), 3u);
  int chain = -1, hole = -1, frame = -1;
  for (std::size_t k = 0; k < job.segments.size(); ++k) {
    const auto& c = job.segments[k].contours;
    if (c.size() == 2) chain = static_cast<int>(k);
    else if (c[0] == ContourId(1)) hole = static_cast<int>(k);
    else if (c[0] == ContourId(0)) frame = static_cast<int>(k);
  }
  ASSERT_GE(chain, 0);
  std::vector<std::pair<std::int32_t, std::int32_t>> want{{chain, hole}, {hole, frame}};
  auto got = job.precedence;
  std::sort(want.begin(), want.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, want);
}

}  // namespace
}  // namespace cutroute::model
