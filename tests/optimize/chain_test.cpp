// Chain cutting: candidate chains and their basic segments, checked against geometric facts
// recomputed here (containment by winding number, sampled distances), not against chains.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include <cutroute/cost/route_problem.hpp>
#include <cutroute/geometry/shapes.hpp>
#include <cutroute/model/chains.hpp>
#include <cutroute/model/demo_nest.hpp>

#include "support/nest_facts.hpp"
#include <cutroute/nc/build_toolpath.hpp>
#include <cutroute/nc/gcode_writer.hpp>
#include <cutroute/nc/post_dialect.hpp>

#include "support/program_check.hpp"

namespace cutroute::model {
namespace {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

Contour rect(double x, double y, double w, double h) {
  return Contour{{Vertex{{x, y}, 0}, Vertex{{x + w, y}, 0}, Vertex{{x + w, y + h}, 0}, Vertex{{x, y + h}, 0}}, true};
}
SourceContour src(Contour c) { return SourceContour{std::move(c), "0", {}, {}, {}}; }

// Small synthetic nests have no sheet border: none is looked for.
Nest loose_nest(std::vector<SourceContour> cs) {
  NestOptions no_sheet;
  no_sheet.detect_sheet = false;
  return build_nest(std::move(cs), no_sheet);
}

using test::in_material;

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

// 300 plates 20 x 10 mm, 6 mm apart, with a hole each: the links and the chains are found on
// several threads (outers and runs dealt round-robin), and must be what one thread finds.
TEST(Chains, ThreadsMakeTheSameJob) {
  std::vector<SourceContour> cs;
  for (int r = 0; r < 15; ++r)
    for (int c = 0; c < 20; ++c) {
      const double x = 26.0 * c + (r % 2) * 3.0, y = 16.0 * r;
      cs.push_back(src(rect(x, y, 20, 10)));
      cs.push_back(src(geometry::circle({x + 10, y + 5}, 2.0 + 0.1 * (c % 3))));
    }
  const Nest nest = loose_nest(cs);
  const auto links = chain_links(nest, ChainOptions{}, 1);
  ASSERT_GT(links.size(), 500u);
  const CutJob one = make_chain_job(nest, EntryOptions{}, ChainOptions{}, nullptr, nullptr, 1);
  std::size_t chained = 0;
  for (const auto& seg : one.segments) chained += seg.contours.size() > 1 ? 1 : 0;
  ASSERT_GT(chained, 60u);
  for (const int threads : {2, 5}) {
    const auto many_links = chain_links(nest, ChainOptions{}, threads);
    ASSERT_EQ(many_links.size(), links.size());
    for (std::size_t k = 0; k < links.size(); ++k) {
      EXPECT_EQ(many_links[k].a, links[k].a);
      EXPECT_EQ(many_links[k].b, links[k].b);
      EXPECT_EQ(many_links[k].gap_mm, links[k].gap_mm);
    }
    const CutJob many = make_chain_job(nest, EntryOptions{}, ChainOptions{}, nullptr, nullptr, threads);
    ASSERT_EQ(many.segments.size(), one.segments.size());
    EXPECT_EQ(many.precedence, one.precedence);
    for (std::size_t k = 0; k < one.segments.size(); ++k) {
      ASSERT_EQ(many.segments[k].contours, one.segments[k].contours) << "segment " << k;
      const auto& a = one.segments[k].candidates;
      const auto& b = many.segments[k].candidates;
      ASSERT_EQ(a.size(), b.size()) << "segment " << k;
      for (std::size_t j = 0; j < a.size(); ++j) {
        EXPECT_EQ(a[j].pierce.x, b[j].pierce.x);
        EXPECT_EQ(a[j].pierce.y, b[j].pierce.y);
        EXPECT_EQ(a[j].pieces.size(), b[j].pieces.size());
        EXPECT_EQ(tool_off_point(a[j]).x, tool_off_point(b[j]).x);
      }
    }
  }
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

TEST(Chains, RunOfThreeAroundACorner) {
  // A left of B, C below B, all 5 mm apart: B's lower left corner is near both, so one pierce can
  // cut A, bridge to that corner, cut B, bridge down to C, cut C.
  std::vector<SourceContour> cs{src(rect(0, 0, 50, 50)), src(rect(55, 0, 50, 50)), src(rect(55, -55, 50, 50))};
  const Nest nest = loose_nest(cs);
  const ChainOptions opt;
  const CutJob job = make_chain_job(nest, EntryOptions{}, opt);
  ASSERT_EQ(job.segments.size(), 1u);
  const auto& seg = job.segments[0];
  ASSERT_EQ(seg.contours.size(), 3u);
  ASSERT_FALSE(seg.candidates.empty());
  for (const auto& e : seg.candidates) {
    check_chain_candidate(nest, seg, e, opt.max_gap_mm);
    EXPECT_EQ(e.pieces[2].contour, ContourId(1)) << "B is in the middle";
  }
  // Limited to pairs, the same nest gets one pair and one single contour.
  ChainOptions pairs = opt;
  pairs.max_contours = 2;
  EXPECT_EQ(make_chain_job(nest, EntryOptions{}, pairs).segments.size(), 2u);
}

// B sits 0.05 mm lower than A: from A's lower right corner the closest point of B lies 0.05 mm
// above B's corner. The bridge ends on the corner instead (within kerf/2 = 0.1 mm of it): else B's
// cut would start and end with a 0.05 mm move, too short for a controller's compensation to turn
// the corner in. Every bridge end lies on a vertex of B or more than kerf/2 from all of them.
TEST(Chains, BridgeEndsOnAVertexWithinHalfAKerf) {
  std::vector<SourceContour> cs{src(rect(0, 0, 50, 50)), src(rect(55, -0.05, 50, 50))};
  const Nest nest = loose_nest(cs);
  EntryOptions entries;
  entries.kerf_mm = 0.2;
  const ChainOptions opt;
  const CutJob job = make_chain_job(nest, entries, opt);
  ASSERT_EQ(job.segments.size(), 1u);
  const auto& seg = job.segments[0];
  int at_corner = 0;
  for (const auto& e : seg.candidates) {
    check_chain_candidate(nest, seg, e, opt.max_gap_mm);
    const Vec2 q = e.pieces[1].path.vertices.back().p;
    const auto& other = nest.contours[e.pieces[2].contour].source.contour;
    double nearest = 1e300;
    for (const auto& v : other.vertices) nearest = std::min(nearest, geometry::distance(v.p, q));
    EXPECT_TRUE(nearest < 1e-9 || nearest > 0.1 - 1e-9) << "bridge ends " << nearest << " mm from a vertex";
    at_corner += nearest < 1e-9 && geometry::distance(q, {55, -0.05}) < 1e-9;
  }
  EXPECT_GT(at_corner, 0) << "the bridge from A's corner (50, 0) must end on B's corner";
}

TEST(Chains, BridgeMustNotCrossAPartAndKeepsClearance) {
  // A and B 10 mm apart; C, a small part, sits in the gap near y = 20.
  std::vector<SourceContour> cs{src(rect(0, 0, 50, 50)), src(rect(60, 0, 50, 50)), src(rect(54, 18, 2, 4))};
  const Nest nest = loose_nest(cs);
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
  const Nest nest = loose_nest(cs);
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
  const Nest nest = loose_nest(cs);
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

// The program check is the independent judge of chains: it accepts a bridge through scrap and
// rejects one through a part, on the written G-code.
TEST(Chains, ProgramCheckJudgesBridgesOnTheWrittenProgram) {
  std::vector<SourceContour> cs{src(rect(0, 0, 50, 50)), src(rect(60, 0, 50, 50)), src(rect(54, 20, 2, 6))};
  const Nest nest = loose_nest(cs);
  const EntryPlanner planner(nest, EntryOptions{});
  const auto dialect = nc::find_post_dialect("generic");
  ASSERT_TRUE(dialect.ok());
  const auto program_with_bridge_to = [&](double y) {
    // A entered at (50, 30) from outside, cut whole, bridge to (60, y), B cut whole; C alone.
    const double s_a = planner.closest(ContourId(0), {50, 30}).first;
    const double s_b = planner.closest(ContourId(1), {60, y}).first;
    auto e = planner.entry_at(ContourId(0), s_a, true);
    if (!e) throw std::runtime_error("no entry at (50, 30)");
    e->pieces = {SegmentPiece{PieceKind::contour, ContourId(0), planner.whole_loop(ContourId(0), s_a, true, false), ContourId()},
                 SegmentPiece{PieceKind::bridge, ContourId(), Contour{{Vertex{{50, 30}, 0}, Vertex{{60, y}, 0}}, false}, ContourId()},
                 SegmentPiece{PieceKind::contour, ContourId(1), planner.whole_loop(ContourId(1), s_b, true, true), ContourId()}};
    e->lead_out = planner.lead_out_at(ContourId(1), s_b, true);
    Diagnostics diagnostics;
    auto c = planner.candidates(ContourId(2), diagnostics);
    const std::vector<const EntryCandidate*> seq{&c.front(), &*e};
    return nc::write_gcode(nc::build_toolpath(nest, seq, nc::ToolpathOptions{}), *dialect, nc::GcodeWriteOptions{}).text;
  };
  test::ProgramCheckOptions opt;
  opt.clearance_mm = 1.0;
  const auto good = test::check_program(nest, program_with_bridge_to(30), opt);
  EXPECT_TRUE(good.failures.empty()) << good.failures.front();
  EXPECT_EQ(good.runs, 2);
  EXPECT_EQ(good.bridges, 1);
  EXPECT_NEAR(good.bridge_length, 10.0, 1e-3);
  const auto bad = test::check_program(nest, program_with_bridge_to(18), opt);
  bool said = false;
  for (const auto& f : bad.failures) said |= f.find("bridge comes") != std::string::npos || f.find("bridge enters") != std::string::npos;
  EXPECT_TRUE(said) << (bad.failures.empty() ? std::string("no failure") : bad.failures.front());
}

}  // namespace
}  // namespace cutroute::model
