// Segment and contour intersections per kind, with tolerance; distances.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/core/tolerances.hpp>

#include <cutroute/geometry/arc.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/shapes.hpp>

namespace cutroute::geometry {
namespace {

using Kind = SegmentIntersection::Kind;
constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-6;

void expect_point(const SegmentIntersection& x, int i, Vec2 want, double tol = 1e-9) {
  ASSERT_LT(i, x.count);
  EXPECT_NEAR(x.points[i].x, want.x, tol);
  EXPECT_NEAR(x.points[i].y, want.y, tol);
}

// Order-independent check of a two-point answer.
void expect_points(const SegmentIntersection& x, Vec2 p, Vec2 q, double tol = 1e-9) {
  ASSERT_EQ(x.count, 2);
  const bool straight = distance(x.points[0], p) < tol && distance(x.points[1], q) < tol;
  const bool swapped = distance(x.points[0], q) < tol && distance(x.points[1], p) < tol;
  EXPECT_TRUE(straight || swapped) << x.points[0].x << "," << x.points[0].y << " " << x.points[1].x << "," << x.points[1].y;
}

TEST(IntersectLineLine, CrossParallelCollinearTouch) {
  const Segment a{{0, 0}, {4, 4}}, b{{0, 4}, {4, 0}};
  auto x = intersect(a, b, kTol);
  EXPECT_EQ(x.kind, Kind::points);
  expect_point(x, 0, {2, 2});
  EXPECT_EQ(intersect(Segment{{0, 0}, {4, 0}}, Segment{{0, 1}, {4, 1}}, kTol).kind, Kind::none);
  x = intersect(Segment{{0, 0}, {4, 0}}, Segment{{6, 0}, {2, 0}}, kTol);
  EXPECT_EQ(x.kind, Kind::overlap);
  expect_points(x, {2, 0}, {4, 0});
  // Collinear, sharing only an end point: one point.
  x = intersect(Segment{{0, 0}, {4, 0}}, Segment{{4, 0}, {9, 0}}, kTol);
  EXPECT_EQ(x.kind, Kind::points);
  EXPECT_EQ(x.count, 1);
  // T-junction short by half the tolerance: touching counts; short by twice: it does not.
  EXPECT_EQ(intersect(Segment{{0, 0}, {4, 0}}, Segment{{2, 5}, {2, 0.5 * kTol}}, kTol).kind, Kind::points);
  EXPECT_EQ(intersect(Segment{{0, 0}, {4, 0}}, Segment{{2, 5}, {2, 2 * kTol}}, kTol).kind, Kind::none);
  // A zero-length segment is a point.
  EXPECT_EQ(intersect(Segment{{2, 0}, {2, 0}}, Segment{{0, 0}, {4, 0}}, kTol).kind, Kind::points);
}

TEST(IntersectLineArc, TwoOneNone) {
  const Segment top{{1, 0}, {-1, 0}, 1};  // upper half of the unit circle
  auto x = intersect(Segment{{-2, 0.5}, {2, 0.5}}, top, kTol);
  EXPECT_EQ(x.kind, Kind::points);
  expect_points(x, {-std::sqrt(0.75), 0.5}, {std::sqrt(0.75), 0.5});
  // Below the chord: the line meets the circle but not the upper arc.
  EXPECT_EQ(intersect(Segment{{-2, -0.5}, {2, -0.5}}, top, kTol).kind, Kind::none);
  // Tangent at the top.
  x = intersect(Segment{{-2, 1}, {2, 1}}, top, kTol);
  EXPECT_EQ(x.kind, Kind::points);
  EXPECT_EQ(x.count, 1);
  expect_point(x, 0, {0, 1}, 1e-6);
  // Passing 2·tol above: none; tol/2 above: touch.
  EXPECT_EQ(intersect(Segment{{-2, 1 + 2 * kTol}, {2, 1 + 2 * kTol}}, top, kTol).kind, Kind::none);
  EXPECT_EQ(intersect(Segment{{-2, 1 + 0.5 * kTol}, {2, 1 + 0.5 * kTol}}, top, kTol).kind, Kind::points);
  // Line ending inside the circle: one crossing.
  x = intersect(Segment{{0, 0.5}, {3, 0.5}}, top, kTol);
  EXPECT_EQ(x.count, 1);
  expect_point(x, 0, {std::sqrt(0.75), 0.5});
  // Arguments swapped: same answer.
  EXPECT_EQ(intersect(top, Segment{{0, 0.5}, {3, 0.5}}, kTol).count, 1);
}

TEST(IntersectArcArc, CrossSameCircleNone) {
  const Segment a{{1, 0}, {-1, 0}, 1};          // unit circle, upper half, centre (0,0)
  const Segment b{{2, 0}, {0, 0}, 1};           // circle r=1 about (1,0), upper half
  auto x = intersect(a, b, kTol);
  EXPECT_EQ(x.kind, Kind::points);
  // The circles meet at (0.5, ±√0.75); only the upper point lies on both upper halves.
  ASSERT_EQ(x.count, 1);
  expect_point(x, 0, {0.5, std::sqrt(0.75)});
  // Same circle, overlapping sweeps: overlap from 45° to 90°.
  const double s45 = std::sqrt(0.5);
  const Segment q1{{1, 0}, {0, 1}, std::tan(kPi / 8)};         // 0°..90°
  const Segment q2{{s45, s45}, {-s45, s45}, std::tan(kPi / 8)}; // 45°..135°
  x = intersect(q1, q2, kTol);
  EXPECT_EQ(x.kind, Kind::overlap);
  expect_points(x, {s45, s45}, {0, 1});
  // Same circle, disjoint sweeps.
  const Segment q3{{-1, 0}, {0, -1}, std::tan(kPi / 8)};        // 180°..270°
  EXPECT_EQ(intersect(q1, q3, kTol).kind, Kind::none);
  // Concentric, different radii: none.
  EXPECT_EQ(intersect(a, Segment{{2, 0}, {-2, 0}, 1}, kTol).kind, Kind::none);
  // External near-tangency: right half about (-1,0) and left half about (1+δ,0), gap δ.
  const Segment right_half{{-1, -1}, {-1, 1}, 1};
  auto left_half = [](double delta) { return Segment{{1 + delta, 1}, {1 + delta, -1}, 1}; };
  EXPECT_EQ(intersect(right_half, left_half(0.5 * kTol), kTol).kind, Kind::points);
  EXPECT_EQ(intersect(right_half, left_half(2 * kTol), kTol).kind, Kind::none);
  EXPECT_NEAR(distance(right_half, left_half(0.25)), 0.25, 1e-12);
}

TEST(SegmentDistance, InteriorMinimaOfLineArcAndArcArc) {
  const Segment top{{1, 0}, {-1, 0}, 1};
  EXPECT_NEAR(distance(top, Segment{{-3, 3}, {3, 3}}), 2.0, 1e-12);
  EXPECT_NEAR(distance(top, Segment{{1, 0}, {-1, 0}, 1}), 0.0, 1e-12);
  // Lower halves about (0,0) and (4,0): closest at their end points (1,0) and (3,0).
  EXPECT_NEAR(distance(Segment{{1, 0}, {-1, 0}, -1}, Segment{{3, 0}, {5, 0}, -1}), 2.0, 1e-12);
  // Concave sides facing: arcs about the same centre.
  EXPECT_NEAR(distance(top, Segment{{2, 0}, {-2, 0}, 1}), 1.0, 1e-12);
}

// Brute-force truth for distance(): the closest pair among dense samples of both segments is at
// least the true distance and at most the true distance plus the sample spacing.
TEST(SegmentDistance, AgreesWithDenseSamplingOnRandomPairs) {
  Rng rng(77);
  auto random_segment = [&]() {
    const Vec2 a{rng.uniform01() * 10, rng.uniform01() * 10}, b{rng.uniform01() * 10, rng.uniform01() * 10};
    const double kind = rng.uniform01();
    const double sign = rng.chance(0.5) ? 1 : -1;
    double bulge = 0.0;  // lines, minor arcs, major arcs, nearly straight and nearly full arcs
    if (kind >= 0.25 && kind < 0.6) bulge = 2 * rng.uniform01() - 1;
    if (kind >= 0.6 && kind < 0.8) bulge = sign * (1 + 3 * rng.uniform01());
    if (kind >= 0.8 && kind < 0.9) bulge = sign * 1e-7 * rng.uniform01();
    if (kind >= 0.9) bulge = sign * (10 + 40 * rng.uniform01());
    return Segment{a, b, bulge};
  };
  constexpr int kSamples = 250;
  for (int trial = 0; trial < 400; ++trial) {
    const Segment s = random_segment(), t = random_segment();
    std::vector<Vec2> ps, pt;
    for (int i = 0; i <= kSamples; ++i) {
      ps.push_back(s.point_at(static_cast<double>(i) / kSamples));
      pt.push_back(t.point_at(static_cast<double>(i) / kSamples));
    }
    double sampled = 1e300;
    for (Vec2 p : ps) for (Vec2 q : pt) sampled = std::min(sampled, distance(p, q));
    const double spacing = std::max(s.length(), t.length()) / kSamples;
    const double exact = distance(s, t);
    // Arcs with a sagitta below tol::kCollinearMm are measured as their chord (intersect.hpp).
    ASSERT_LE(exact, sampled + 1e-9 + tol::kCollinearMm) << trial << " s " << s.a.x << "," << s.a.y << " " << s.b.x << "," << s.b.y << " b " << s.bulge
                                     << " t " << t.a.x << "," << t.a.y << " " << t.b.x << "," << t.b.y << " b " << t.bulge
                                     << " diff " << exact - sampled;
    ASSERT_GE(exact, sampled - spacing) << trial;
    EXPECT_NEAR(distance(t, s), exact, 1e-9);
    // Reported intersection points lie on both segments; symmetric in kind.
    const SegmentIntersection x = intersect(s, t, kTol);
    EXPECT_EQ(x.kind == Kind::none, intersect(t, s, kTol).kind == Kind::none) << trial;
    EXPECT_EQ(x.kind != Kind::none, exact <= kTol) << trial;
    for (int i = 0; i < x.count; ++i) {
      EXPECT_LE(closest_point(s, x.points[i]).distance, 1e-6) << trial;
      EXPECT_LE(closest_point(t, x.points[i]).distance, 1e-6) << trial;
    }
  }
}

TEST(ContourIntersects, TouchCrossNestAndShareEdge) {
  const Contour c1 = circle({0, 0}, 2), c2 = circle({3, 0}, 2), inner = circle({0, 0}, 1);
  EXPECT_TRUE(intersects(c1, c2, kTol));
  EXPECT_FALSE(intersects(c1, inner, kTol));
  EXPECT_TRUE(intersects(c1, circle({4, 0}, 2), kTol));                  // touching from outside
  EXPECT_FALSE(intersects(c1, circle({4 + 1e-3, 0}, 2), kTol));          // a hair apart
  EXPECT_TRUE(intersects(rectangle({0, 0, 1, 1}), rectangle({1, 0, 2, 1}), kTol));  // shared edge
  EXPECT_TRUE(intersects(rectangle({0, 0, 4, 4}), circle({2, 2}, 2), kTol));          // inscribed: 4 touches
  // 4 touch points; at (0,2) and (4,2) both half arcs end, so 2 segment pairs each: 6.
  EXPECT_EQ(count_close_segment_pairs(rectangle({0, 0, 4, 4}), circle({2, 2}, 2), kTol, 100), 6u);
  // Many segments (a fine polygon) against a circle: still exact and consistent.
  std::vector<Vec2> pts;
  for (int i = 0; i < 2000; ++i) pts.push_back({10 * std::cos(i * 2 * kPi / 2000), 10 * std::sin(i * 2 * kPi / 2000)});
  const Contour ring = polygon(pts);
  EXPECT_FALSE(intersects(ring, circle({0, 0}, 9.9), kTol));
  EXPECT_TRUE(intersects(ring, circle({0, 0}, 9.99999), 1e-3));
  EXPECT_TRUE(intersects(ring, circle({10, 0}, 0.5), kTol));
}

}  // namespace
}  // namespace cutroute::geometry
