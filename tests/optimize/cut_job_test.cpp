// Entry candidates and precedence of a cut job, checked against independent geometric facts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include <cutroute/geometry/contour.hpp>
#include <cutroute/model/cut_job.hpp>
#include <cutroute/model/demo_nest.hpp>

#include "support/nest_facts.hpp"

namespace cutroute::model {
namespace {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

Contour square(double x, double y, double w, bool ccw = true) {
  Contour c{{Vertex{{x, y}, 0}, Vertex{{x + w, y}, 0}, Vertex{{x + w, y + w}, 0}, Vertex{{x, y + w}, 0}}, true};
  return ccw ? c : geometry::reversed(c);
}

Contour circle(Vec2 c, double r) { return Contour{{Vertex{{c.x - r, c.y}, 1}, Vertex{{c.x + r, c.y}, 1}}, true}; }

SourceContour src(Contour c) { return SourceContour{std::move(c), "0", {}, {}, {}}; }

// Minimum distance between a sampled path and a contour (independent of geometry::intersects):
// 100 points along the lead (leads are a few mm long: 0.05 mm spacing).
double sampled_distance(const Contour& path, const Contour& other) {
  double best = 1e300;
  const double len = geometry::length(path);
  for (int k = 0; k <= 100; ++k) {
    best = std::min(best, geometry::distance(other, geometry::point_at_length(path, len * k / 100.0)));
  }
  return best;
}

using test::in_material;

void check_job(const Nest& nest, const CutJob& job, const EntryOptions& opt) {
  const double clearance = opt.clearance_mm >= 0 ? opt.clearance_mm : opt.kerf_mm + 1;
  for (const auto& ce : job.segments) {
    ASSERT_FALSE(ce.candidates.empty());
    ASSERT_EQ(ce.contours.size(), 1u);  // standard: one basic segment per contour
    const auto& own = nest.contours[ce.contours[0]];
    const double len = geometry::length(own.source.contour);
    for (const auto& e : ce.candidates) {
      EXPECT_EQ(e.contour, ce.contours[0]);
      ASSERT_EQ(e.pieces.size(), 1u);
      EXPECT_EQ(e.pieces[0].kind, PieceKind::contour);
      EXPECT_EQ(e.pieces[0].contour, ce.contours[0]);
      // The cut path is the whole contour plus the overcut, starting and ending at the entry point.
      EXPECT_NEAR(geometry::length(entry_path(e)), len + opt.lead.overcut_mm, 1e-6);
      EXPECT_LT(geometry::distance(entry_path(e).vertices.front().p, e.point), 1e-9);
      EXPECT_LT(geometry::distance(own.source.contour, e.point), 1e-6);
      // Direction by the kerf convention.
      Contour loop = entry_path(e);
      loop.closed = true;
      loop.vertices.pop_back();
      const bool want_cw = own.role == ContourRole::outer ? opt.outer_clockwise : opt.hole_clockwise;
      EXPECT_EQ(geometry::orientation(loop) == geometry::Orientation::cw, want_cw);
      EXPECT_EQ(e.clockwise, want_cw);
      if (e.fallback == Fallback::on_contour) continue;
      // Pierce in scrap, lead-in from the pierce to the entry point, clear of every other contour.
      EXPECT_FALSE(in_material(nest, e.pierce)) << "pierce inside material";
      ASSERT_GE(e.lead_in.vertices.size(), 2u);
      EXPECT_LT(geometry::distance(e.lead_in.vertices.front().p, e.pierce), 1e-9);
      EXPECT_LT(geometry::distance(e.lead_in.vertices.back().p, e.point), 1e-9);
      const auto lead_box = geometry::bounding_box(e.lead_in).inflated(clearance);
      for (const auto& other : nest.contours) {
        if (&other == &own || !other.box.intersects(lead_box)) continue;  // farther than the clearance
        EXPECT_GE(sampled_distance(e.lead_in, other.source.contour), clearance - 1e-6);
      }
    }
  }
}

TEST(CutJob, DemoSheetEveryContourHasAdmissibleEntries) {
  const Nest nest = build_nest(make_demo_sheet(), NestOptions{});
  EntryOptions opt;
  const CutJob job = make_cut_job(nest, opt);
  ASSERT_EQ(job.segments.size(), 21u);
  for (const auto& ce : job.segments) {
    EXPECT_GE(ce.candidates.size(), 4u);
    for (const auto& e : ce.candidates) EXPECT_EQ(e.fallback, Fallback::none);
  }
  check_job(nest, job, opt);
  EXPECT_TRUE(job.diagnostics.empty());
  EXPECT_EQ(job.precedence.size(), 7u);  // every hole before its plate or flange
}

TEST(CutJob, PrecedenceFollowsContainmentAtAnyDepth) {
  // outer0 > hole1 > inner part outer2 > its hole3
  std::vector<SourceContour> cs{src(square(0, 0, 100)), src(square(10, 10, 80, false)), src(square(30, 30, 40)),
                                src(circle({50, 50}, 8))};
  const Nest nest = build_nest(cs, NestOptions{});
  const CutJob job = make_cut_job(nest, EntryOptions{});
  ASSERT_EQ(job.segments.size(), 4u);
  // Map job indices back to nest depth and check each pair goes from deeper to its parent.
  ASSERT_EQ(job.precedence.size(), 3u);
  for (auto [a, b] : job.precedence) {
    const auto& ca = nest.contours[job.segments[static_cast<std::size_t>(a)].contours[0]];
    const auto& cb = nest.contours[job.segments[static_cast<std::size_t>(b)].contours[0]];
    EXPECT_EQ(ca.parent, job.segments[static_cast<std::size_t>(b)].contours[0]);
    EXPECT_EQ(ca.depth, cb.depth + 1);
  }
  check_job(nest, job, EntryOptions{});
}

// 3 x 3 squares drawn edge to edge, a hole in each: the middle square's four neighbours cut all of
// its boundary between them, so their cuts can free it before its own. Every hole comes before
// its own square and before each square that shares an edge with it; the nest names the 12 shared
// edges. A chain of the same job keeps the rule (segment_precedence()).
TEST(CutJob, HolesComeBeforeTheCutsOfPartsDrawnEdgeToEdge) {
  std::vector<SourceContour> cs;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      cs.push_back(src(square(40.0 * c, 40.0 * r, 40)));
      cs.push_back(src(circle({40.0 * c + 20, 40.0 * r + 20}, 6)));
    }
  const Nest nest = build_nest(cs, NestOptions{});
  ASSERT_EQ(nest.shared_edges.size(), 12u);
  const CutJob job = make_cut_job(nest, EntryOptions{});
  ASSERT_EQ(job.segments.size(), 18u);
  auto segment_of = [&](ContourId id) {
    for (std::size_t k = 0; k < job.segments.size(); ++k)
      if (job.segments[k].contours.front() == id) return static_cast<std::int32_t>(k);
    return -1;
  };
  const auto standard = job.precedence;
  const auto chained = segment_precedence(nest, job.segments);
  ASSERT_TRUE(chained.has_value());
  for (const auto* pairs : {&standard, &*chained}) {
    std::size_t expected = 0;
    for (std::size_t i = 0; i < nest.contours.size(); ++i) {
      const auto& hole = nest.contours[ContourId(static_cast<std::int32_t>(i))];
      if (hole.role != ContourRole::hole) continue;
      const Vec2 at = hole.box.center();
      for (std::size_t j = 0; j < nest.contours.size(); ++j) {
        const auto& part = nest.contours[ContourId(static_cast<std::int32_t>(j))];
        if (part.role != ContourRole::outer) continue;
        // The hole's own square, or one whose box touches it along an edge (not only at a corner).
        const geometry::Box own = nest.contours[hole.parent].box;
        const double dx = std::max(part.box.xmin - own.xmax, own.xmin - part.box.xmax);
        const double dy = std::max(part.box.ymin - own.ymax, own.ymin - part.box.ymax);
        const bool edge = (std::abs(dx) < 1e-9 && dy < -1e-9) || (std::abs(dy) < 1e-9 && dx < -1e-9);
        if (!part.box.contains(at) && !edge) continue;
        ++expected;
        const std::pair<std::int32_t, std::int32_t> pair{segment_of(ContourId(static_cast<std::int32_t>(i))),
                                                         segment_of(ContourId(static_cast<std::int32_t>(j)))};
        EXPECT_NE(std::find(pairs->begin(), pairs->end(), pair), pairs->end()) << "hole " << i << " before part " << j;
      }
    }
    EXPECT_EQ(expected, 9u + 2u * 12u);  // its own square, and both sides of each shared edge
    EXPECT_EQ(pairs->size(), expected);
  }
}

TEST(CutJob, NoPierceInANarrowGapBetweenParts) {
  // Two squares 1.5 mm apart: with clearance 1.2 mm no pierce fits between them.
  std::vector<SourceContour> cs{src(square(0, 0, 50)), src(square(51.5, 0, 50))};
  const Nest nest = build_nest(cs, NestOptions{});
  EntryOptions opt;
  opt.clearance_mm = 1.2;
  opt.max_candidates = 24;
  const CutJob job = make_cut_job(nest, opt);
  for (const auto& ce : job.segments) {
    for (const auto& e : ce.candidates) {
      EXPECT_FALSE(e.pierce.x > 50 && e.pierce.x < 51.5 && e.pierce.y > 0 && e.pierce.y < 50)
          << "pierce in the gap at " << e.pierce.x << "," << e.pierce.y;
    }
  }
  check_job(nest, job, opt);
}

TEST(CutJob, SmallHoleFallsBackAndSaysSo) {
  std::vector<SourceContour> cs{src(square(0, 0, 40)), src(circle({20, 20}, 1.0))};
  const Nest nest = build_nest(cs, NestOptions{});
  EntryOptions opt;  // lead-in 3 mm + arc: does not fit in a Ø2 hole
  const CutJob job = make_cut_job(nest, opt);
  ASSERT_EQ(job.segments.size(), 2u);
  bool found = false;
  for (const auto& ce : job.segments) {
    if (nest.contours[ce.contours[0]].role != ContourRole::hole) continue;
    found = true;
    for (const auto& e : ce.candidates) {
      EXPECT_NE(e.fallback, Fallback::none);
      EXPECT_LE(geometry::distance(e.pierce, {20, 20}), 1.0);  // pierce inside the hole
    }
  }
  EXPECT_TRUE(found);
  EXPECT_FALSE(job.diagnostics.empty());
  check_job(nest, job, opt);
}

// The contours' candidates are found on several threads: the job must be the one a single thread
// makes, candidate for candidate, with the diagnostics in contour order. A plate of 24 x 20 holes,
// every seventh too small for a lead-in (a centre pierce and a warning each).
TEST(CutJob, ThreadsMakeTheSameJob) {
  std::vector<SourceContour> cs{src(square(0, 0, 500))};
  for (int r = 0; r < 20; ++r)
    for (int c = 0; c < 24; ++c) cs.push_back(src(circle({12.0 + 20.0 * c, 12.0 + 24.0 * r}, (r * 24 + c) % 7 == 0 ? 1.0 : 6.0)));
  const Nest nest = build_nest(cs, NestOptions{});
  const EntryOptions opt;
  const EntryPlanner planner(nest, opt);
  const CutJob one = make_cut_job(nest, planner, 1);
  ASSERT_EQ(one.segments.size(), 481u);
  EXPECT_EQ(one.diagnostics.size(), 69u);
  for (const int threads : {2, 5}) {
    const CutJob many = make_cut_job(nest, planner, threads);
    ASSERT_EQ(many.segments.size(), one.segments.size());
    EXPECT_EQ(many.precedence, one.precedence);
    for (std::size_t k = 0; k < one.segments.size(); ++k) {
      const auto& a = one.segments[k].candidates;
      const auto& b = many.segments[k].candidates;
      ASSERT_EQ(many.segments[k].contours, one.segments[k].contours);
      ASSERT_EQ(a.size(), b.size()) << "segment " << k;
      for (std::size_t j = 0; j < a.size(); ++j) {
        EXPECT_EQ(a[j].s_mm, b[j].s_mm);
        EXPECT_EQ(a[j].clockwise, b[j].clockwise);
        EXPECT_EQ(a[j].fallback, b[j].fallback);
        EXPECT_EQ(a[j].pierce.x, b[j].pierce.x);
        EXPECT_EQ(a[j].pierce.y, b[j].pierce.y);
        EXPECT_EQ(a[j].lead_in.vertices.size(), b[j].lead_in.vertices.size());
      }
    }
    ASSERT_EQ(many.diagnostics.size(), one.diagnostics.size());
    for (std::size_t k = 0; k < one.diagnostics.size(); ++k) EXPECT_EQ(many.diagnostics[k].message, one.diagnostics[k].message);
    check_job(nest, many, opt);
  }
}

TEST(CutJob, FreeDirectionOffersBothDirections) {
  std::vector<SourceContour> cs{src(square(0, 0, 50))};
  const Nest nest = build_nest(cs, NestOptions{});
  EntryOptions opt;
  opt.free_direction = true;
  const CutJob job = make_cut_job(nest, opt);
  int cw = 0, ccw = 0;
  for (const auto& e : job.segments[0].candidates) (e.clockwise ? cw : ccw)++;
  EXPECT_GT(cw, 0);
  EXPECT_GT(ccw, 0);
}

TEST(CutJob, EntryAtArcLengthMatchesTheContour) {
  std::vector<SourceContour> cs{src(square(0, 0, 50))};
  const Nest nest = build_nest(cs, NestOptions{});
  EntryPlanner planner(nest, EntryOptions{});
  for (double s : {5.0, 30.0, 70.0, 160.0}) {
    const auto e = planner.entry_at(ContourId(0), s, true);
    ASSERT_TRUE(e.has_value());
    EXPECT_LT(geometry::distance(e->point, geometry::point_at_length(nest.contours[ContourId(0)].source.contour, s)),
              1e-9);
    EXPECT_NEAR(e->s_mm, s, 1e-9);
  }
}

// An entry within half a kerf of a vertex is made at the vertex, as a corner entry where the
// contour turns: else the cut starts (and ends) with a move of a few micrometres, in which a
// controller's cutter compensation cannot turn the corner. Farther away the entry stays put.
TEST(CutJob, EntryAHairFromAVertexIsMadeAtTheVertex) {
  std::vector<SourceContour> cs{src(square(0, 0, 50))};
  const Nest nest = build_nest(cs, NestOptions{});
  EntryOptions opt;
  opt.kerf_mm = 0.2;
  EntryPlanner planner(nest, opt);
  const Contour& c = nest.contours[ContourId(0)].source.contour;
  const double len = geometry::length(c);
  for (double s : {50.0 - 0.004, 50.0 + 0.09, 100.0 + 0.001, len - 0.05, 0.08}) {
    const auto e = planner.entry_at(ContourId(0), s, true);
    ASSERT_TRUE(e.has_value()) << s;
    const double vertex = std::round(s / 50.0) * 50.0;
    EXPECT_NEAR(e->s_mm, std::fmod(vertex, len), 1e-9) << s;
    EXPECT_LT(geometry::distance(e->point, geometry::point_at_length(c, std::fmod(vertex, len))), 1e-9) << s;
    EXPECT_TRUE(e->corner) << s;  // the square turns 90 degrees at every vertex
    // The cut begins and ends on the vertex: its first and last moves are whole edges.
    const Contour path = entry_path(*e);
    EXPECT_NEAR(geometry::distance(path.vertices[0].p, path.vertices[1].p), 50.0, 1e-9) << s;
    EXPECT_NEAR(geometry::distance(path.vertices[path.vertices.size() - 2].p, path.vertices.back().p), 50.0, 1e-9) << s;
  }
  for (double s : {50.0 - 0.2, 50.0 + 0.15, 125.0}) {
    const auto e = planner.entry_at(ContourId(0), s, true);
    ASSERT_TRUE(e.has_value()) << s;
    EXPECT_NEAR(e->s_mm, s, 1e-9) << s;
    EXPECT_FALSE(e->corner) << s;
  }
}

}  // namespace
}  // namespace cutroute::model
