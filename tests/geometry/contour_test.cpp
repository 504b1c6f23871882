// Contour measures against analytic truths, rerun reversed, translated and rotated 180°.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/geometry/arc.hpp>
#include <cutroute/geometry/contour.hpp>
#include <cutroute/geometry/shapes.hpp>

#include "summary.hpp"

namespace cutroute::geometry {
namespace {

using test::expect_summary;
using test::Summary;
using test::summarize;
constexpr double kPi = std::numbers::pi;

struct Case {
  std::string name;
  Contour contour;
  Summary truth;  // computed by hand from the shape, not by the library
};

std::vector<Case> analytic_cases() {
  std::vector<Case> cases;
  cases.push_back({"unit square", rectangle({0, 0, 1, 1}), {4, 1.0, 4.0, {0, 0, 1, 1}}});
  {
    const double r = 5;
    cases.push_back({"circle r=5 as two half arcs", circle({3, 4}, r), {2, kPi * r * r, 2 * kPi * r, {-2, -1, 8, 9}}});
  }
  {
    // Stadium: 10 x 4 rectangle with half circles (r = 2) on the short sides.
    Contour c{{{{0, 0}, 0}, {{10, 0}, 1}, {{10, 4}, 0}, {{0, 4}, 1}}, true};
    cases.push_back({"stadium", c, {4, 40 + 4 * kPi, 20 + 4 * kPi, {-2, 0, 12, 4}}});
  }
  {
    const double r = 7;
    Contour c{{{{0, 0}, 0}, {{r, 0}, std::tan(kPi / 8)}, {{0, r}, 0}}, true};
    cases.push_back({"quarter disc", c, {3, kPi * r * r / 4, 2 * r + kPi * r / 2, {0, 0, r, r}}});
  }
  {
    // Pac-man: 270° arc from 45° to 315°, through 90°, 180° and 270°.
    const double r = 3, c45 = r * std::cos(kPi / 4);
    Contour c{{{{0, 0}, 0}, {{c45, c45}, std::tan(1.5 * kPi / 4)}, {{c45, -c45}, 0}}, true};
    cases.push_back({"pac-man (major arc)", c, {3, 0.75 * kPi * r * r, 2 * r + 1.5 * kPi * r, {-r, -r, c45, r}}});
  }
  {
    // Square 4 x 4 with its top edge replaced by a clockwise (inward) half circle of r = 2.
    Contour c{{{{0, 0}, 0}, {{4, 0}, 0}, {{4, 4}, -1}, {{0, 4}, 0}}, true};
    cases.push_back({"square with inward half circle", c, {4, 16 - 2 * kPi, 12 + 2 * kPi, {0, 0, 4, 4}}});
  }
  {
    Contour open{{{{0, 0}, 1}, {{2, 0}, 0}, {{2, 5}, 0}}, false};
    cases.push_back({"open: half arc then line", open, {3, 0.0, kPi + 5, {0, -1, 2, 5}}});
  }
  return cases;
}

Box rotate180(const Box& b) { return {-b.xmax, -b.ymax, -b.xmin, -b.ymin}; }

TEST(ContourSummary, AnalyticTruths) {
  for (const Case& c : analytic_cases()) expect_summary(summarize(c.contour), c.truth, c.name.c_str());
}

TEST(ContourSummary, VariantsChangeAsPredicted) {
  for (const Case& c : analytic_cases()) {
    SCOPED_TRACE(c.name);
    const Contour before = c.contour;
    Summary rev = c.truth;
    rev.area = -rev.area;
    expect_summary(summarize(reversed(c.contour)), rev, "reversed");
    expect_summary(summarize(reversed(reversed(c.contour))), c.truth, "reversed twice");
    const Vec2 shift{1234.5, -987.25};
    Summary moved = c.truth;
    moved.box = {c.truth.box.xmin + shift.x, c.truth.box.ymin + shift.y, c.truth.box.xmax + shift.x, c.truth.box.ymax + shift.y};
    expect_summary(summarize(translated(c.contour, shift)), moved, "translated");
    Summary turned = c.truth;
    turned.box = rotate180(c.truth.box);
    expect_summary(summarize(rotated_about(c.contour, {0, 0}, kPi)), turned, "rotated 180");
    Summary mirrored = rev;  // a mirror flips orientation
    mirrored.box = {-c.truth.box.xmax, c.truth.box.ymin, -c.truth.box.xmin, c.truth.box.ymax};
    expect_summary(summarize(mirrored_x(c.contour)), mirrored, "mirrored");
    EXPECT_EQ(c.contour, before) << "input modified";
  }
}

TEST(ContourSummary, OrientationFromArea) {
  EXPECT_EQ(orientation(circle({0, 0}, 1)), Orientation::ccw);
  EXPECT_EQ(orientation(circle({0, 0}, 1, false)), Orientation::cw);
  EXPECT_EQ(orientation(polygon({{0, 0}, {1, 1}, {2, 2}})), Orientation::degenerate);
  EXPECT_EQ(orientation(Contour{{{{0, 0}, 0}, {{1, 0}, 0}}, true}), Orientation::degenerate);
}

TEST(Segment, QuarterArcAnalytic) {
  const double r = 10;
  const Segment s{{r, 0}, {0, r}, std::tan(kPi / 8)};
  EXPECT_TRUE(s.is_arc());
  EXPECT_NEAR(s.sweep(), kPi / 2, 1e-15);
  EXPECT_NEAR(s.radius(), r, 1e-12);
  EXPECT_NEAR(s.center().x, 0, 1e-12);
  EXPECT_NEAR(s.center().y, 0, 1e-12);
  EXPECT_NEAR(s.length(), kPi * r / 2, 1e-12);
  const Vec2 mid = s.point_at(0.5);
  EXPECT_NEAR(mid.x, r / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(mid.y, r / std::sqrt(2.0), 1e-12);
  const Vec2 t0 = s.tangent_at(0), t1 = s.tangent_at(1);
  EXPECT_NEAR(t0.x, 0, 1e-12);
  EXPECT_NEAR(t0.y, 1, 1e-12);
  EXPECT_NEAR(t1.x, -1, 1e-12);
  EXPECT_NEAR(t1.y, 0, 1e-12);
  EXPECT_EQ(s.point_at(0), s.a);
  EXPECT_EQ(s.point_at(1), s.b);
}

TEST(Segment, HalfArcsBothWays) {
  const Segment ccw{{1, 0}, {-1, 0}, 1};  // over the top
  const Segment cw{{1, 0}, {-1, 0}, -1};  // under the bottom
  EXPECT_NEAR(ccw.length(), kPi, 1e-14);
  EXPECT_NEAR(ccw.point_at(0.5).y, 1, 1e-14);
  EXPECT_NEAR(cw.point_at(0.5).y, -1, 1e-14);
  EXPECT_NEAR(ccw.bounding_box().ymax, 1, 1e-14);
  EXPECT_NEAR(ccw.bounding_box().ymin, 0, 1e-14);
  EXPECT_NEAR(cw.bounding_box().ymin, -1, 1e-14);
  EXPECT_NEAR(cw.bounding_box().ymax, 0, 1e-14);
}

TEST(Segment, ArcBoxThroughQuadrantExtremes) {
  // Arc of r = 2 about (1, 1) from 80° to 190° (counter-clockwise): passes 90° and 180°.
  const double r = 2, a0 = 80 * kPi / 180, a1 = 190 * kPi / 180;
  const Vec2 c{1, 1};
  const Vec2 p0 = c + Vec2{std::cos(a0), std::sin(a0)} * r, p1 = c + Vec2{std::cos(a1), std::sin(a1)} * r;
  const Segment ccw{p0, p1, bulge_from_sweep(a1 - a0)};
  const Box b = ccw.bounding_box();
  EXPECT_NEAR(b.ymax, c.y + r, 1e-12);
  EXPECT_NEAR(b.xmin, c.x - r, 1e-12);
  EXPECT_NEAR(b.xmax, p0.x, 1e-12);
  EXPECT_NEAR(b.ymin, p1.y, 1e-12);
  // The same end points clockwise go the long way: through 0° (x max) and 270° (y min) only.
  const Segment cw{p0, p1, bulge_from_sweep(-(2 * kPi - (a1 - a0)))};
  const Box bc = cw.bounding_box();
  EXPECT_NEAR(bc.xmax, c.x + r, 1e-12);
  EXPECT_NEAR(bc.ymin, c.y - r, 1e-12);
  EXPECT_NEAR(bc.ymax, p0.y, 1e-12);
  EXPECT_NEAR(bc.xmin, p1.x, 1e-12);
}

// The box of any arc against a dense sampling of it: every sample inside (within 1e-9), and every
// side reached by a sample or an end point to within the sampling's chord error. Random end points,
// bulges from 1e-3 (a flat arc) to 50 (nearly the full circle), both directions.
TEST(Segment, ArcBoxIsTheSampledArcsBox) {
  Rng rng(12345);
  auto uniform = [&rng] { return rng.uniform01(); };
  for (int k = 0; k < 2000; ++k) {
    const Vec2 a{uniform() * 200 - 100, uniform() * 200 - 100}, b{uniform() * 200 - 100, uniform() * 200 - 100};
    const double bulge = (k % 2 ? 1 : -1) * std::exp(std::log(1e-3) + uniform() * (std::log(50.0) - std::log(1e-3)));
    const Segment s{a, b, bulge};
    if (!s.is_arc()) continue;
    const Box box = s.bounding_box();
    Box sampled;
    constexpr int kSamples = 20000;
    for (int j = 0; j <= kSamples; ++j) sampled.add(s.point_at(static_cast<double>(j) / kSamples));
    // Chord error of the sampling: r (1 - cos(sweep / 2n)), well below 1e-4 here.
    const double slack = s.radius() * (1 - std::cos(std::abs(s.sweep()) / (2.0 * kSamples))) + 1e-9;
    EXPECT_LE(box.xmin, sampled.xmin + 1e-9) << k;
    EXPECT_LE(box.ymin, sampled.ymin + 1e-9) << k;
    EXPECT_GE(box.xmax, sampled.xmax - 1e-9) << k;
    EXPECT_GE(box.ymax, sampled.ymax - 1e-9) << k;
    EXPECT_GE(box.xmin, sampled.xmin - slack) << k;
    EXPECT_GE(box.ymin, sampled.ymin - slack) << k;
    EXPECT_LE(box.xmax, sampled.xmax + slack) << k;
    EXPECT_LE(box.ymax, sampled.ymax + slack) << k;
  }
}

TEST(Segment, DegenerateInputGivesNoNaN) {
  const Segment zero{{1, 1}, {1, 1}, 0.5};
  EXPECT_FALSE(zero.is_arc());
  EXPECT_EQ(zero.length(), 0.0);
  EXPECT_EQ(zero.point_at(0.3), (Vec2{1, 1}));
  const Segment huge{{0, 0}, {1e-3, 0}, 1e12};  // clamped to 1e9: a near-full circle
  EXPECT_TRUE(std::isfinite(huge.length()));
  EXPECT_TRUE(std::isfinite(huge.bounding_box().xmax));
  EXPECT_NEAR(huge.length(), 2 * kPi * huge.radius(), 1e-6 * huge.length());
  const Segment nan_bulge{{0, 0}, {1, 0}, std::nan("")};
  EXPECT_FALSE(nan_bulge.is_arc());
  EXPECT_EQ(nan_bulge.length(), 1.0);
  const Segment inf_bulge{{0, 0}, {1, 0}, std::numeric_limits<double>::infinity()};
  EXPECT_TRUE(std::isfinite(inf_bulge.length()));
  // Tiny bulge on a long chord: length and area stay exact (series), no cancellation garbage.
  const double d = 1000, beta = 1e-8;
  const Segment flat{{0, 0}, {d, 0}, beta};
  const double theta = 4 * std::atan(beta), r = d / (2 * std::sin(theta / 2));
  EXPECT_NEAR(flat.length(), r * theta, 1e-9);
  const Contour lens{{{{0, 0}, beta}, {{d, 0}, 0}}, true};
  // Circular segment area r²/2 (θ - sin θ) ≈ d² θ / 12 for small θ (independent expansion).
  EXPECT_NEAR(signed_area(lens), d * d * theta / 12.0, 1e-9);
  const Contour collinear = polygon({{0, 0}, {1, 0}, {2, 0}, {3, 0}});
  EXPECT_EQ(signed_area(collinear), 0.0);
  EXPECT_TRUE(std::isfinite(closest_point(collinear, {1.5, 1}).distance));
}

TEST(Contour, RandomDegenerateContoursGiveFiniteAnswers) {
  // Repeated vertices, collinear runs, bulges from 1e-12 to 1e9 (and NaN / inf): every measure
  // stays finite, and length / area / winding obey their invariants.
  Rng rng(31);
  const double bulges[] = {0.0, 1e-12, -1e-9, 0.3, -1.0, 1.0, 5.0, -1e6, 1e9, std::nan(""),
                           std::numeric_limits<double>::infinity()};
  for (int trial = 0; trial < 500; ++trial) {
    Contour c;
    c.closed = rng.chance(0.7);
    const int n = 1 + static_cast<int>(rng.below(7));
    for (int i = 0; i < n; ++i) {
      Vec2 p{static_cast<double>(rng.below(4)), static_cast<double>(rng.below(4))};  // many repeats
      c.vertices.push_back({p, bulges[rng.below(std::size(bulges))]});
    }
    const Contour before = c;
    const double len = length(c), area = signed_area(c);
    ASSERT_TRUE(std::isfinite(len) && len >= 0) << trial;
    ASSERT_TRUE(std::isfinite(area)) << trial;
    EXPECT_NEAR(length(reversed(c)), len, 1e-9 * (1 + len));
    if (c.closed) {
      EXPECT_NEAR(signed_area(reversed(c)), -area, 1e-9 * (1 + std::abs(area)));
    }
    const Box box = bounding_box(c);
    ASSERT_TRUE(std::isfinite(box.xmin) && std::isfinite(box.ymax)) << trial;
    for (double s : {0.0, 0.3 * len, len, 2.5 * len}) ASSERT_TRUE(is_finite(point_at_length(c, s))) << trial;
    const Vec2 q{rng.uniform01() * 5 - 1, rng.uniform01() * 5 - 1};
    const ClosestPoint cp = closest_point(c, q);
    ASSERT_TRUE(std::isfinite(cp.distance) && is_finite(cp.point)) << trial;
    (void)winding_number(c, q);
    (void)locate(c, q, 1e-9);
    for (Vec2 p : flatten(c, 0.01)) ASSERT_TRUE(is_finite(p)) << trial;
    // Bitwise: NaN bulges compare unequal to themselves.
    ASSERT_EQ(c.vertices.size(), before.vertices.size());
    EXPECT_EQ(std::memcmp(c.vertices.data(), before.vertices.data(), c.vertices.size() * sizeof(Vertex)), 0);
  }
}

TEST(Contour, PointAtLengthAndClosestPointOnCircle) {
  const double r = 4;
  const Vec2 c{10, -3};
  const Contour circ = circle(c, r);
  const Vec2 top = point_at_length(circ, kPi * r / 2);
  EXPECT_NEAR(top.x, c.x, 1e-12);
  EXPECT_NEAR(top.y, c.y + r, 1e-12);
  const Vec2 wrap = point_at_length(circ, 2 * kPi * r + kPi * r);  // wraps to the far side
  EXPECT_NEAR(wrap.x, c.x - r, 1e-12);
  const Vec2 neg = point_at_length(circ, -kPi * r / 2);  // wraps backwards to the bottom
  EXPECT_NEAR(neg.y, c.y - r, 1e-12);
  Rng rng(7);
  for (int i = 0; i < 200; ++i) {
    const double ang = rng.uniform01() * 2 * kPi, dist = 0.1 + rng.uniform01() * 10;
    const Vec2 p = c + Vec2{std::cos(ang), std::sin(ang)} * dist;
    const ClosestPoint cp = closest_point(circ, p);
    EXPECT_NEAR(cp.distance, std::abs(dist - r), 1e-9);
    EXPECT_NEAR(cp.length_along, ang * r, 1e-9);
    const Vec2 back = point_at_length(circ, cp.length_along);
    EXPECT_NEAR(back.x, cp.point.x, 1e-9);
    EXPECT_NEAR(back.y, cp.point.y, 1e-9);
    EXPECT_NEAR(length_at_point(circ, cp.point), cp.length_along, 1e-9);
  }
}

TEST(Contour, PointAtLengthOpenClampsAndWalksSegments) {
  const Contour open{{{{0, 0}, 0}, {{3, 0}, 0}, {{3, 4}, 0}}, false};
  EXPECT_EQ(point_at_length(open, -5), (Vec2{0, 0}));
  EXPECT_EQ(point_at_length(open, 100), (Vec2{3, 4}));
  const Vec2 p = point_at_length(open, 5);
  EXPECT_NEAR(p.x, 3, 1e-15);
  EXPECT_NEAR(p.y, 2, 1e-15);
  const ClosestPoint cp = closest_point(open, {5, 2});
  EXPECT_EQ(cp.segment, 1u);
  EXPECT_NEAR(cp.distance, 2, 1e-15);
  EXPECT_NEAR(cp.length_along, 5, 1e-15);
}

TEST(Contour, ReversedClosedKeepsStartAndFlipsBulges) {
  const Contour c{{{{0, 0}, 0.2}, {{4, 0}, 0}, {{4, 4}, -0.5}, {{0, 4}, 0}}, true};
  const Contour r = reversed(c);
  ASSERT_EQ(r.vertices.size(), 4u);
  EXPECT_EQ(r.vertices[0].p, (Vec2{0, 0}));
  EXPECT_EQ(r.vertices[1].p, (Vec2{0, 4}));
  EXPECT_EQ(r.vertices[1].bulge, 0.5);  // the arc (4,4)->(0,4) travelled back: (0,4)->(4,4)
  EXPECT_EQ(r.vertices[3].bulge, -0.2);
  // Segment by segment, the reversed contour is the same geometry backwards.
  for (std::size_t i = 0; i < 4; ++i) {
    const Segment a = segment(c, i), b = segment(r, 3 - i);
    EXPECT_EQ(a.a, b.b);
    EXPECT_EQ(a.b, b.a);
    EXPECT_NEAR(a.point_at(0.3).x, b.point_at(0.7).x, 1e-12);
    EXPECT_NEAR(a.point_at(0.3).y, b.point_at(0.7).y, 1e-12);
  }
}

TEST(Flatten, StaysWithinChordToleranceAndKeepsVertices) {
  for (const Case& c : analytic_cases()) {
    SCOPED_TRACE(c.name);
    const double tol = 0.01;
    const std::vector<Vec2> pts = flatten(c.contour, tol);
    const std::size_t expect_min = c.contour.closed ? c.contour.vertices.size() : c.contour.vertices.size();
    EXPECT_GE(pts.size(), expect_min);
    // Every chord midpoint lies within tol of the true contour, every point on it.
    const std::size_t n = pts.size();
    const std::size_t m = c.contour.closed ? n : n - 1;
    for (std::size_t i = 0; i < m; ++i) {
      const Vec2 a = pts[i], b = pts[(i + 1) % n];
      EXPECT_LE(distance(c.contour, a), 1e-9);
      EXPECT_LE(distance(c.contour, (a + b) * 0.5), tol + 1e-9);
    }
    if (c.contour.closed) {
      // Polygon area converges to the exact area from inside for convex arcs.
      double twice = 0;
      for (std::size_t i = 0; i < n; ++i) twice += cross(pts[i], pts[(i + 1) % n]);
      EXPECT_NEAR(0.5 * twice, c.truth.area, 0.01 * length(c.contour));
    }
  }
  // Finer tolerance, more points; a line-only contour is unchanged.
  const Contour circ = circle({0, 0}, 100);
  EXPECT_GT(flatten(circ, 0.001).size(), flatten(circ, 0.1).size());
  EXPECT_EQ(flatten(rectangle({0, 0, 2, 1}), 0.01).size(), 4u);
  EXPECT_GT(flatten(circ, std::nan("")).size(), 2u);  // bad tolerance falls back to the default
}

// narrowest_width(): a bound from above on the least width, exact for convex polygons at any
// angle (where the box is as wide as a thin strip is long).
TEST(Contour, NarrowestWidth) {
  for (const double deg : {0.0, 30.0, 45.0, 77.0}) {
    const double a = deg * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
    const Vec2 u{c, s}, v{-s, c};
    const Contour strip = polygon({Vec2{0, 0}, u * 5.0, u * 5.0 + v * 0.1, v * 0.1});
    EXPECT_NEAR(narrowest_width(strip, 0.001), 0.1, 1e-9) << deg;
  }
  const double w = narrowest_width(circle({3, 4}, 0.08), 0.0001);  // chords inside, plus 2 x tol
  EXPECT_GE(w, 0.16);
  EXPECT_LE(w, 0.16 + 0.0002 + 1e-9);
  // An L of arms 1 mm wide: its least width is the whole L's (7.8 mm across the diagonal), not 1.
  const Contour ell = polygon({Vec2{0, 0}, Vec2{10, 0}, Vec2{10, 1}, Vec2{1, 1}, Vec2{1, 10}, Vec2{0, 10}});
  EXPECT_GT(narrowest_width(ell, 0.001), 1.0);
}

}  // namespace
}  // namespace cutroute::geometry
