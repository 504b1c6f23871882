// Common-line decomposition: grids of parts sharing edges checked against lengths, coverage and
// precedence computed here from the layout, and the edge cases (point touch, partial overlap,
// near misses, arcs, kerf gap).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <cutroute/geometry/shapes.hpp>
#include <cutroute/model/common_lines.hpp>

namespace cutroute::model {
namespace {

using geometry::Box;
using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;
constexpr double kPi = std::numbers::pi;

SourceContour src(Contour c, std::string layer = "0") {
  SourceContour s;
  s.contour = std::move(c);
  s.layer = std::move(layer);
  return s;
}

Contour rect(double x0, double y0, double x1, double y1, bool ccw = true) {
  return geometry::rectangle(Box{x0, y0, x1, y1}, ccw);
}

Nest make_nest(std::vector<Contour> contours, bool sheet = false) {
  std::vector<SourceContour> in;
  if (sheet) in.push_back(src(rect(-100, -100, 1000, 1000), "sheet"));
  for (auto& c : contours) in.push_back(src(std::move(c)));
  NestOptions o;
  o.detect_sheet = sheet;
  return build_nest(std::move(in), o);
}

double perimeter_sum(const Nest& nest) {
  double s = 0;
  for (const auto& c : nest.contours)
    if (c.role != ContourRole::sheet) s += geometry::length(c.source.contour);
  return s;
}

double cut_length(const CommonLinePlan& plan) {
  double s = 0;
  for (const auto& seg : plan.segments) s += geometry::length(seg.path);
  return s;
}

double dist_to_cuts(const CommonLinePlan& plan, Vec2 p) {
  double best = 1e300;
  for (const auto& seg : plan.segments) best = std::min(best, geometry::distance(seg.path, p));
  return best;
}

// Samples every `step` mm along a contour, by its own vertices (not the library's arc-length code):
// lines by linear interpolation, arcs through centre and angle.
std::vector<Vec2> samples(const Contour& c, double step) {
  std::vector<Vec2> out;
  const std::size_t n = c.closed ? c.vertices.size() : c.vertices.size() - 1;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = c.vertices[i].p, b = c.vertices[(i + 1) % c.vertices.size()].p;
    const double bulge = c.vertices[i].bulge;
    const double chord = geometry::distance(a, b);
    if (std::abs(bulge) < 1e-12) {
      const int k = std::max(1, static_cast<int>(chord / step));
      for (int j = 0; j < k; ++j) out.push_back(a + (b - a) * (static_cast<double>(j) / k));
      continue;
    }
    const double sweep = 4 * std::atan(bulge);
    const double r = chord / (2 * std::sin(std::abs(sweep) / 2));
    const Vec2 m = (a + b) * 0.5;
    const Vec2 u = (b - a) / chord;
    const double h = r * std::cos(sweep / 2);  // centre distance from the chord, signed with the sweep
    const Vec2 centre = m + geometry::perp(u) * (sweep > 0 ? h : -h);
    const double a0 = std::atan2(a.y - centre.y, a.x - centre.x);
    const int k = std::max(2, static_cast<int>(std::abs(sweep) * r / step));
    for (int j = 0; j < k; ++j) {
      const double phi = a0 + sweep * j / k;
      out.push_back(centre + Vec2{std::cos(phi), std::sin(phi)} * r);
    }
  }
  return out;
}

// Every drawn boundary point lies on some cut (within `tol`: half the gap where parts are drawn
// kerf apart): each part is separated from everything around it.
void expect_every_edge_cut(const Nest& nest, const CommonLinePlan& plan, double tol) {
  for (const auto& c : nest.contours) {
    if (c.role == ContourRole::sheet) continue;
    for (const Vec2 p : samples(c.source.contour, 0.5))
      ASSERT_LE(dist_to_cuts(plan, p), tol) << "uncut boundary point (" << p.x << ", " << p.y << ")";
  }
}

// No stretch is cut twice: away from the vertices of all paths, no point of one segment lies on
// another.
void expect_no_double_cut(const CommonLinePlan& plan) {
  std::vector<Vec2> corners;
  for (const auto& s : plan.segments)
    for (const auto& v : s.path.vertices) corners.push_back(v.p);
  for (std::size_t i = 0; i < plan.segments.size(); ++i)
    for (const Vec2 p : samples(plan.segments[i].path, 1.0)) {
      if (std::any_of(corners.begin(), corners.end(), [&](Vec2 q) { return geometry::distance(p, q) < 0.5; })) continue;
      for (std::size_t j = 0; j < plan.segments.size(); ++j)
        if (j != i) {
          ASSERT_GT(geometry::distance(plan.segments[j].path, p), 1e-3) << "segments " << i << " and " << j;
        }
    }
}

// Transitive closure of precedence pairs over n segments: before[a][b] = a must come before b.
// Also: acyclic.
std::vector<std::vector<char>> closure(std::size_t n, const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs) {
  std::vector<std::vector<char>> r(n, std::vector<char>(n, 0));
  for (const auto& [a, b] : pairs) r[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] = 1;
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < n; ++i)
      if (r[i][k])
        for (std::size_t j = 0; j < n; ++j)
          if (r[k][j]) r[i][j] = 1;
  for (std::size_t i = 0; i < n; ++i) EXPECT_FALSE(r[i][i]) << "precedence cycle through segment " << i;
  return r;
}
std::vector<std::vector<char>> closure(const CommonLinePlan& plan) { return closure(plan.segments.size(), plan.precedence); }

std::size_t count(const CommonLinePlan& plan, CommonSegmentKind k) {
  return static_cast<std::size_t>(
      std::count_if(plan.segments.begin(), plan.segments.end(), [&](const CommonSegment& s) { return s.kind == k; }));
}

// The loop with the largest area: a group's outer boundary.
std::size_t outer_loop(const CommonLinePlan& plan) {
  std::size_t best = plan.segments.size();
  double area = -1;
  for (std::size_t i = 0; i < plan.segments.size(); ++i)
    if (plan.segments[i].kind == CommonSegmentKind::loop &&
        std::abs(geometry::signed_area(plan.segments[i].path)) > area) {
      area = std::abs(geometry::signed_area(plan.segments[i].path));
      best = i;
    }
  return best;
}

// Each segment's pieces make up its path, lie on the contours they name (connectors: short, at
// most the gap), and pieces_along() cuts the path from any point, both ways, with an overcut.
void expect_pieces_consistent(const Nest& nest, const CommonLinePlan& plan, double tol) {
  for (const auto& seg : plan.segments) {
    ASSERT_FALSE(seg.pieces.empty());
    double len = 0;
    for (std::size_t k = 0; k < seg.pieces.size(); ++k) {
      const auto& p = seg.pieces[k];
      len += geometry::length(p.path);
      if (k > 0) {
        EXPECT_LT(geometry::distance(seg.pieces[k - 1].path.vertices.back().p, p.path.vertices.front().p), 1e-9);
      }
      const Vec2 mid = geometry::point_at_length(p.path, geometry::length(p.path) / 2);
      if (p.connector()) {
        EXPECT_LE(geometry::length(p.path), 2 * tol + 1e-9);
        continue;
      }
      EXPECT_LE(geometry::distance(nest.contours[p.contour].source.contour, mid), tol);
      if (p.stretch >= 0) {
        const auto& st = plan.stretches[static_cast<std::size_t>(p.stretch)];
        EXPECT_EQ(p.contour, st.first);
        EXPECT_LE(geometry::distance(nest.contours[st.second].source.contour, mid), tol);
      }
    }
    EXPECT_NEAR(len, geometry::length(seg.path), 1e-6);
    const double total = geometry::length(seg.path);
    for (const bool fwd : {true, false}) {
      const double s0 = seg.path.closed ? 0.37 * total : (fwd ? 0.0 : total);
      const double extra = seg.path.closed ? 2.0 : 0.0;
      const auto cut = pieces_along(seg, s0, fwd, total + extra);
      ASSERT_FALSE(cut.empty());
      double got = 0;
      for (const auto& p : cut) got += geometry::length(p.path);
      EXPECT_NEAR(got, total + extra, 1e-6);
      EXPECT_LT(geometry::distance(cut.front().path.vertices.front().p, geometry::point_at_length(seg.path, s0)), 1e-6);
      for (std::size_t k = 1; k < cut.size(); ++k)
        EXPECT_LT(geometry::distance(cut[k - 1].path.vertices.back().p, cut[k].path.vertices.front().p), 1e-6);
    }
  }
}

// Everything a grid's decomposition must satisfy, with the shared length computed by the caller.
void check_grid(const Nest& nest, const CommonLinePlan& plan, double shared, double gap_crossings, double tol) {
  EXPECT_NEAR(plan.shared_length_mm, shared, 1e-6);
  EXPECT_NEAR(cut_length(plan), perimeter_sum(nest) - shared + gap_crossings, 1e-6);
  expect_every_edge_cut(nest, plan, tol);
  expect_no_double_cut(plan);
  expect_pieces_consistent(nest, plan, tol);
  const auto before = closure(plan);
  const std::size_t outer = outer_loop(plan);
  ASSERT_LT(outer, plan.segments.size());
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    if (i == outer) continue;
    EXPECT_TRUE(before[i][outer]) << to_string(plan.segments[i].kind) << " " << i << " not before the outer loop";
  }
  for (const auto& s : plan.segments)
    if (s.kind == CommonSegmentKind::trail) {
      EXPECT_TRUE(s.enter_at_start || s.enter_at_end);
    }
}

TEST(CommonLines, TwoSideBySide) {
  const Nest nest = make_nest({rect(0, 0, 100, 50), rect(100, 0, 250, 50)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  ASSERT_EQ(plan.stretches.size(), 1u);
  EXPECT_EQ(plan.groups, 1);
  EXPECT_EQ(count(plan, CommonSegmentKind::loop), 1u);
  EXPECT_EQ(count(plan, CommonSegmentKind::trail), 1u);
  EXPECT_EQ(count(plan, CommonSegmentKind::contour), 0u);
  check_grid(nest, plan, 50, 0, 1e-6);
  for (const auto& s : plan.segments) {
    if (s.kind == CommonSegmentKind::trail) {
      EXPECT_TRUE(s.start_on_loop && s.end_on_loop);
      EXPECT_NEAR(s.shared_mm, 50, 1e-9);
      EXPECT_EQ(s.contours.size(), 2u);
    } else {
      // The outer loop runs counter-clockwise around both parts.
      EXPECT_NEAR(geometry::signed_area(s.path), 250 * 50, 1e-6);
    }
  }
}

// 2 x 2: the two common lines cross at a 4-way junction and go straight through it.
TEST(CommonLines, TwoByTwoStraightThrough) {
  const Nest nest = make_nest({rect(0, 0, 100, 60), rect(100, 0, 200, 60), rect(0, 60, 100, 120), rect(100, 60, 200, 120)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  EXPECT_EQ(plan.stretches.size(), 4u);
  EXPECT_EQ(count(plan, CommonSegmentKind::loop), 1u);
  ASSERT_EQ(count(plan, CommonSegmentKind::trail), 2u);
  check_grid(nest, plan, 2 * 60 + 2 * 100, 0, 1e-6);
  for (const auto& s : plan.segments) {
    if (s.kind != CommonSegmentKind::trail) continue;
    const Vec2 a = s.path.vertices.front().p, b = s.path.vertices.back().p;
    // Straight: from one side of the group to the opposite one.
    EXPECT_TRUE((std::abs(a.x - b.x) < 1e-9 && std::abs(std::abs(a.y - b.y) - 120) < 1e-9) ||
                (std::abs(a.y - b.y) < 1e-9 && std::abs(std::abs(a.x - b.x) - 200) < 1e-9));
    EXPECT_EQ(s.contours.size(), 4u);
  }
}

// 3 x 2 parts with a round hole each (drawn clockwise) and holes unchanged and first.
TEST(CommonLines, ThreeByTwoWithHoles) {
  std::vector<Contour> cs;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) {
      cs.push_back(rect(80.0 * c, 50.0 * r, 80.0 * (c + 1), 50.0 * (r + 1), (r + c) % 2 == 0));
      cs.push_back(geometry::circle(Vec2{80.0 * c + 40, 50.0 * r + 25}, 10));
    }
  const Nest nest = make_nest(std::move(cs));
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  // 2 vertical lines of 100 mm, 1 horizontal of 240 mm.
  EXPECT_EQ(count(plan, CommonSegmentKind::trail), 3u);
  EXPECT_EQ(count(plan, CommonSegmentKind::loop), 1u);
  EXPECT_EQ(count(plan, CommonSegmentKind::contour), 6u);
  check_grid(nest, plan, 2 * 100 + 240, 0, 1e-6);
  const auto before = closure(plan);
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    if (plan.segments[i].kind != CommonSegmentKind::contour) continue;
    EXPECT_EQ(nest.contours[plan.segments[i].contours.front()].role, ContourRole::hole);
    // Every hole before the loop that frees its part; no trail waits for a hole.
    EXPECT_TRUE(before[i][outer_loop(plan)]);
  }
}

// The middle part of 3 x 3 touches no edge of the group's outline: the last of its four common
// lines cuts it free, whichever that is. In the cut job every hole must come before some segment
// that cuts a piece of its part (a common edge counts for both parts it separates): then, in any
// order the pairs allow, the hole is cut before its part is free. A part on the outline may wait
// for the outline alone (after every line of the group); the middle part's hole comes before all
// four of its lines, so it is cut while the part is held on every side.
TEST(CommonLines, JobPutsEachHoleBeforeThePartIsCutFree) {
  std::vector<Contour> cs;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      cs.push_back(rect(60.0 * c, 40.0 * r, 60.0 * (c + 1), 40.0 * (r + 1)));
      cs.push_back(geometry::circle(Vec2{60.0 * c + 30, 40.0 * r + 20}, 8));
    }
  const Nest nest = make_nest(std::move(cs), true);
  const auto job = make_common_job(nest, EntryOptions{}, CommonLineOptions{});
  ASSERT_TRUE(job.ok()) << job.error().message;
  const std::size_t n = job->segments.size();
  const auto before = closure(n, job->precedence);
  int holes = 0;
  for (std::size_t h = 0; h < n; ++h) {
    const auto& hc = job->segments[h].contours;
    if (hc.size() != 1 || nest.contours[hc.front()].role != ContourRole::hole) continue;
    ++holes;
    const ContourId part = nest.contours[hc.front()].parent;
    int around = 0, after_hole = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const auto touched = touched_contours(job->segments[k]);
      if (k == h || std::find(touched.begin(), touched.end(), part) == touched.end()) continue;
      ++around;
      after_hole += before[h][k];
    }
    EXPECT_GE(around, 2);
    EXPECT_GE(after_hole, 1) << "hole segment " << h << " may come after every cut around its part";
    const Vec2 c = nest.contours[hc.front()].box.center();
    if (std::abs(c.x - 90) < 1e-6 && std::abs(c.y - 60) < 1e-6) {
      EXPECT_EQ(around, 4);  // the four common lines, no piece of the outline
      EXPECT_EQ(after_hole, 4);
    } else {
      EXPECT_EQ(after_hole, 1) << "a part on the outline waits for the outline alone";
    }
  }
  EXPECT_EQ(holes, 9);
}

// A part drawn inside a hole, sharing two edges with it: the common line and the loop each cut a
// piece of both, so neither has to wait for the other (that would be a cycle); both come before
// the frame around the hole.
TEST(CommonLines, JobWithAPartSharingTheEdgeOfItsHole) {
  const Nest nest = make_nest({rect(0, 0, 300, 200), rect(50, 50, 250, 150, false), rect(50, 50, 120, 100)});
  const auto job = make_common_job(nest, EntryOptions{}, CommonLineOptions{});
  ASSERT_TRUE(job.ok()) << job.error().message;
  const std::size_t n = job->segments.size();
  const auto before = closure(n, job->precedence);
  std::size_t frame = n;
  for (std::size_t k = 0; k < n; ++k)
    if (job->segments[k].contours == std::vector<ContourId>{ContourId(0)}) frame = k;
  ASSERT_LT(frame, n);
  for (std::size_t k = 0; k < n; ++k)
    if (k != frame) {
      EXPECT_TRUE(before[k][frame]) << k;
    }
}

// A row drawn kerf apart: the common cuts run on the centre lines of the gaps.
TEST(CommonLines, RowWithKerfGap) {
  const double k = 0.2;
  const Nest nest = make_nest({rect(0, 0, 100, 50), rect(100 + k, 0, 200 + k, 50), rect(200 + 2 * k, 0, 300 + 2 * k, 50)});
  CommonLineOptions o;
  o.kerf_mm = k;
  const auto plan = plan_common_lines(nest, o);
  ASSERT_EQ(plan.stretches.size(), 2u);
  for (const auto& s : plan.stretches) {
    EXPECT_NEAR(s.gap_mm, k, 1e-9);
    const double x = s.centre.a.x;
    EXPECT_TRUE(std::abs(x - (100 + k / 2)) < 1e-9 || std::abs(x - (200 + 3 * k / 2)) < 1e-9) << x;
    EXPECT_NEAR(s.centre.b.x, x, 1e-12);
  }
  // The loop crosses each gap twice (top and bottom): 4 crossings of the kerf.
  check_grid(nest, plan, 2 * 50, 4 * k, k / 2 + 1e-9);
  // Gap 0.2 is common only at kerf 0.2: with another kerf these are separate parts.
  o.kerf_mm = 0.3;
  EXPECT_TRUE(plan_common_lines(nest, o).stretches.empty());
}

// A 2 x 2 grid drawn kerf apart: the four centre lines meet at one junction (where they cross,
// the centroid of their ends) and still go straight through it.
TEST(CommonLines, TwoByTwoKerfGap) {
  const double k = 0.2;
  const Nest nest = make_nest({rect(0, 0, 100, 60), rect(100 + k, 0, 200 + k, 60), rect(0, 60 + k, 100, 120 + k),
                               rect(100 + k, 60 + k, 200 + k, 120 + k)});
  CommonLineOptions o;
  o.kerf_mm = k;
  const auto plan = plan_common_lines(nest, o);
  ASSERT_EQ(count(plan, CommonSegmentKind::trail), 2u);
  // Each trail: 2 stretches + 2 connectors of k/2 through the junction; the loop crosses the 4
  // gap mouths.
  check_grid(nest, plan, 2 * 60 + 2 * 100, 4 * k + 2 * k, k / 2 + 1e-9);
  for (const auto& s : plan.segments)
    if (s.kind == CommonSegmentKind::trail) {
      const Vec2 a = s.path.vertices.front().p, b = s.path.vertices.back().p;
      EXPECT_TRUE(std::abs(a.x - b.x) < 1e-9 || std::abs(a.y - b.y) < 1e-9);
    }
}

// A T of parts drawn kerf apart (two side by side under a long one): the junction lies where the
// centre lines cross, so the through line runs straight through it, its kerf reaching the long
// part's edge across the stem's mouth. That edge is no loop of its own: before, the junction was
// the centroid of the three stretch ends, off the through line, and the edge (one kerf long) was
// a loop narrower than the kerf, entered inside the long part.
TEST(CommonLines, TeeKerfGap) {
  for (const double k : {0.15, 1.5}) {
    SCOPED_TRACE("kerf " + std::to_string(k));
    const Nest nest = make_nest({rect(10, 10, 40, 60), rect(40 + k, 10, 70 + k, 60), rect(10, 60 + k, 70 + k, 80 + k)});
    CommonLineOptions o;
    o.kerf_mm = k;
    const auto plan = plan_common_lines(nest, o);
    EXPECT_EQ(count(plan, CommonSegmentKind::loop), 1u);
    ASSERT_EQ(count(plan, CommonSegmentKind::trail), 2u);
    // The outline crosses 3 gap mouths, the through line the stem's mouth (k), the stem reaches
    // the junction (k / 2); the mouth's edge on the long part (k) is cut by the through line.
    check_grid(nest, plan, 50 + 30 + 30, 3 * k + k + k / 2 - k, k / 2 + 1e-9);
    for (const auto& s : plan.segments)
      if (s.kind == CommonSegmentKind::trail) {
        for (const auto& v : s.path.vertices) {
          const bool through = std::abs(s.path.vertices.front().p.y - s.path.vertices.back().p.y) < 1e-9;
          EXPECT_NEAR(through ? v.p.y : v.p.x, through ? 60 + k / 2 : 40 + k / 2, 1e-9);
        }
      }
  }
}

TEST(CommonLines, PointTouchIsNoCommonLine) {
  const Nest nest = make_nest({rect(0, 0, 100, 50), rect(100, 50, 200, 100)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  EXPECT_TRUE(plan.stretches.empty());
  EXPECT_EQ(plan.groups, 0);
  ASSERT_EQ(plan.segments.size(), 2u);
  EXPECT_EQ(count(plan, CommonSegmentKind::contour), 2u);
  EXPECT_TRUE(plan.precedence.empty());
}

// Edges overlapping for 30 of their 50 and 60 mm: only the overlap is common.
TEST(CommonLines, PartialOverlap) {
  const Nest nest = make_nest({rect(0, 0, 100, 50), rect(100, 20, 200, 80)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  ASSERT_EQ(plan.stretches.size(), 1u);
  const auto& s = plan.stretches.front();
  EXPECT_NEAR(std::min(s.centre.a.y, s.centre.b.y), 20, 1e-9);
  EXPECT_NEAR(std::max(s.centre.a.y, s.centre.b.y), 50, 1e-9);
  check_grid(nest, plan, 30, 0, 1e-6);
  // The trail ends where the boundaries part (both on the outer loop).
  for (const auto& seg : plan.segments)
    if (seg.kind == CommonSegmentKind::trail) {
      EXPECT_TRUE(seg.start_on_loop && seg.end_on_loop);
    }
}

TEST(CommonLines, NearMissesAreNotMerged) {
  // Tilted by 0.001 rad: 0.05 mm apart at the far end, more than the 0.01 mm tolerance.
  const double t = 0.001;
  Contour tilted{{Vertex{{100, 0}, 0}, Vertex{{200, 0}, 0}, Vertex{{200, 50}, 0}, Vertex{{100 + 50 * t, 50}, 0}}, true};
  EXPECT_TRUE(plan_common_lines(make_nest({rect(0, 0, 100, 50), tilted}), CommonLineOptions{}).stretches.empty());
  // Parallel but 0.1 mm apart: neither touching nor a kerf (0.2) apart.
  EXPECT_TRUE(plan_common_lines(make_nest({rect(0, 0, 100, 50), rect(100.1, 0, 200, 50)}), CommonLineOptions{})
                  .stretches.empty());
  // Shared stretch shorter than min_length_mm (0.5 of 1 mm).
  EXPECT_TRUE(plan_common_lines(make_nest({rect(0, 0, 100, 50), rect(100, 49.5, 200, 80)}), CommonLineOptions{})
                  .stretches.empty());
  // Collinear edges that only meet end to end (no overlap): nothing common.
  // (The first two share y = 50; the third meets the second's top edge end to end.)
  EXPECT_EQ(plan_common_lines(make_nest({rect(0, 0, 100, 50), rect(0, 50, 100, 60), rect(100, 60, 200, 70)}),
                              CommonLineOptions{})
                .stretches.size(),
            1u);
}

// A half disc (r = 50) in the cradle of a half annulus (r = 50 .. 80): the arc is common.
Contour half_disc(double r) {
  return Contour{{Vertex{{-r, 0}, 0}, Vertex{{r, 0}, 1}}, true};
}
Contour half_annulus(double r0, double r1) {
  return Contour{{Vertex{{r0, 0}, 0}, Vertex{{r1, 0}, 1}, Vertex{{-r1, 0}, 0}, Vertex{{-r0, 0}, -1}}, true};
}

TEST(CommonLines, Arcs) {
  const Nest nest = make_nest({half_disc(50), half_annulus(50, 80)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  ASSERT_EQ(plan.stretches.size(), 1u);
  EXPECT_NEAR(plan.stretches.front().centre.radius(), 50, 1e-9);
  check_grid(nest, plan, 50 * kPi, 0, 1e-6);
}

TEST(CommonLines, ArcsKerfApart) {
  const double k = 0.2;
  const Nest nest = make_nest({half_disc(50), half_annulus(50 + k, 80)});
  CommonLineOptions o;
  o.kerf_mm = k;
  const auto plan = plan_common_lines(nest, o);
  ASSERT_EQ(plan.stretches.size(), 1u);
  EXPECT_NEAR(plan.stretches.front().centre.radius(), 50 + k / 2, 1e-9);
  // Shared: the overlap measured on the centre line; the loop crosses the gap at both feet.
  check_grid(nest, plan, (50 + k / 2) * kPi, 2 * k, k / 2 + 1e-9);
  // Concentric circles kerf apart with material between them (a ring 0.2 mm wide: the inner
  // circle is its hole) are no common line: the gap is not scrap.
  EXPECT_TRUE(plan_common_lines(make_nest({geometry::circle({0, 0}, 50), geometry::circle({0, 0}, 50 + k)}), o)
                  .stretches.empty());
}

// Middle row of three parts between two wide ones: the short verticals end on the long
// horizontals at both ends, so they are pierced on a junction after a horizontal line.
TEST(CommonLines, TrailWithoutBoundaryEndEntersAtJunction) {
  const Nest nest = make_nest({rect(0, 0, 300, 100), rect(0, 100, 100, 200), rect(100, 100, 200, 200),
                               rect(200, 100, 300, 200), rect(0, 200, 300, 300)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  check_grid(nest, plan, 2 * 300 + 2 * 100, 0, 1e-6);
  const auto before = closure(plan);
  int on_line = 0;
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    const auto& s = plan.segments[i];
    if (s.kind != CommonSegmentKind::trail || !s.pierce_on_line) continue;
    ++on_line;
    EXPECT_FALSE(s.start_on_loop || s.end_on_loop);
    EXPECT_NEAR(geometry::length(s.path), 100, 1e-9);
    bool after_a_horizontal = false;
    for (std::size_t j = 0; j < plan.segments.size(); ++j)
      if (plan.segments[j].kind == CommonSegmentKind::trail && plan.segments[j].start_on_loop && before[j][i])
        after_a_horizontal = true;
    EXPECT_TRUE(after_a_horizontal);
  }
  EXPECT_EQ(on_line, 2);
  EXPECT_EQ(std::count_if(plan.diagnostics.begin(), plan.diagnostics.end(),
                          [](const Diagnostic& d) { return d.code == "common.pierce_on_line"; }),
            2);
}

// Eight parts around an empty square: an outer loop, a loop around the enclosed scrap (cut
// before the outer one) and the radial common lines.
TEST(CommonLines, RingEnclosingScrap) {
  std::vector<Contour> cs;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (r != 1 || c != 1) cs.push_back(rect(50.0 * c, 50.0 * r, 50.0 * (c + 1), 50.0 * (r + 1)));
  const Nest nest = make_nest(std::move(cs));
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  EXPECT_EQ(count(plan, CommonSegmentKind::loop), 2u);
  check_grid(nest, plan, 8 * 50, 0, 1e-6);
  for (const auto& s : plan.segments)
    if (s.kind == CommonSegmentKind::loop && std::abs(geometry::signed_area(s.path)) < 3000) {
      EXPECT_NEAR(geometry::signed_area(s.path), -2500, 1e-6);  // scrap on its left: clockwise
    }
}

// A part drawn inside a hole of another, sharing a stretch with the hole's edge.
TEST(CommonLines, InnerPartSharingHoleEdge) {
  const Nest nest = make_nest({rect(0, 0, 300, 200), rect(50, 50, 250, 150, false), rect(50, 50, 120, 100)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  ASSERT_EQ(plan.stretches.size(), 2u);  // the inner part's left and bottom edges
  EXPECT_NEAR(plan.shared_length_mm, 50 + 70, 1e-9);
  EXPECT_NEAR(cut_length(plan), perimeter_sum(nest) - 120, 1e-6);
  expect_every_edge_cut(nest, plan, 1e-6);
  expect_no_double_cut(plan);
  const auto before = closure(plan);
  // The part's outer contour last: it is the only contour segment left whole.
  std::size_t outer = plan.segments.size();
  for (std::size_t i = 0; i < plan.segments.size(); ++i)
    if (plan.segments[i].kind == CommonSegmentKind::contour) outer = i;
  ASSERT_LT(outer, plan.segments.size());
  for (std::size_t i = 0; i < plan.segments.size(); ++i)
    if (i != outer) {
      EXPECT_TRUE(before[i][outer]) << i;
    }
}

// The contour a loop enters and its direction on it: what the kerf side is taken from.
TEST(CommonLines, EnteredContourAndDirection) {
  const Nest nest = make_nest({rect(0, 0, 100, 50), rect(100, 0, 250, 50, false)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  for (const auto& seg : plan.segments) {
    if (seg.kind != CommonSegmentKind::loop) continue;
    // The loop runs counter-clockwise: on each part's outline it runs counter-clockwise too.
    for (const double s : {10.0, 120.0, 260.0, 380.0}) {
      for (const bool fwd : {true, false}) {
        const auto cut = pieces_along(seg, s, fwd, geometry::length(seg.path));
        const auto e = entered_contour(nest, cut);
        ASSERT_TRUE(e.contour.valid());
        EXPECT_EQ(e.clockwise, !fwd) << s;
        const Vec2 p = geometry::point_at_length(nest.contours[e.contour].source.contour, e.s_mm);
        EXPECT_LT(geometry::distance(p, cut.front().path.vertices.front().p), 1e-6);
        // The part's material lies inside that contour: its first point is on its boundary.
        EXPECT_LT(geometry::distance(nest.contours[e.contour].source.contour, geometry::point_at_length(seg.path, s)),
                  1e-6);
      }
    }
  }
}

// Contours drawn crossing (cut anyway with --allow-crossing): each holds a sample point of the
// other, yet the order stays acyclic (a container is always the larger one).
TEST(CommonLines, CrossingContoursNoCycle) {
  const Nest nest = make_nest({rect(0, 0, 100, 20), rect(40, -40, 60, 60), rect(200, 0, 300, 50), rect(300, 0, 400, 50)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  EXPECT_EQ(plan.stretches.size(), 1u);
  closure(plan);
}

TEST(CommonLines, Deterministic) {
  const auto build = [] {
    return make_nest({rect(0, 0, 100, 60), rect(100, 0, 200, 60), rect(0, 60, 100, 120), rect(100, 60, 200, 120)});
  };
  const Nest n1 = build(), n2 = build();
  const auto a = plan_common_lines(n1, CommonLineOptions{}), b = plan_common_lines(n2, CommonLineOptions{});
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) EXPECT_EQ(a.segments[i].path, b.segments[i].path);
  EXPECT_EQ(a.precedence, b.precedence);
}

}  // namespace
}  // namespace cutroute::model
