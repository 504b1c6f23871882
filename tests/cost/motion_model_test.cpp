// The motion model against closed-form kinematics (trapezoid and triangle profiles, stops at
// corners, the block-time floor that makes many short blocks slow).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <cutroute/cost/motion_model.hpp>

namespace cutroute::cost {
namespace {

MotionMove line(double len, double feed, double turn = 0.0, bool rest = false) {
  MotionMove m;
  m.length_mm = len;
  m.feed_mm_s = feed;
  m.turn_rad = turn;
  m.from_rest = rest;
  return m;
}

double time_of(const std::vector<MotionMove>& moves, const MotionParams& p) {
  auto r = time_moves(moves, p);
  EXPECT_TRUE(r.ok());
  return r.ok() ? r->time_s : -1.0;
}

TEST(MotionModel, TrapezoidFromRestToRest) {
  // L = 1000 mm at 100 mm/s with a = 1000 mm/s^2: t = L/v + v/a.
  EXPECT_NEAR(time_of({line(1000, 100)}, {1000, 0, 0}), 10.0 + 0.1, 1e-12);
}

TEST(MotionModel, TriangleWhenTheFeedIsNotReached) {
  // L = 1 mm < v^2/a = 10 mm: t = 2 sqrt(L/a).
  EXPECT_NEAR(time_of({line(1, 100)}, {1000, 0, 0}), 2.0 * std::sqrt(0.001), 1e-12);
}

TEST(MotionModel, TangentBlocksDoNotSlowDown) {
  const MotionParams p{1000, 0, 0};
  std::vector<MotionMove> split;
  for (int i = 0; i < 10; ++i) split.push_back(line(100, 100));
  EXPECT_NEAR(time_of(split, p), time_of({line(1000, 100)}, p), 1e-9);
}

TEST(MotionModel, SharpCornerWithoutDeviationStops) {
  const MotionParams p{1000, 0, 0};
  const double corner = time_of({line(500, 100), line(500, 100, std::numbers::pi / 2)}, p);
  EXPECT_NEAR(corner, 2.0 * (5.0 + 0.1), 1e-9);
  // A reversal stops whatever the deviation allowance.
  EXPECT_NEAR(time_of({line(500, 100), line(500, 100, std::numbers::pi)}, {1000, 5.0, 0}), 10.2, 1e-9);
}

TEST(MotionModel, JunctionDeviationCornerSpeed) {
  // 90 degrees, delta = 0.05 mm, a = 1000: v_j^2 = a delta s/(1-s), s = sin 45°.
  const double s = std::sin(std::numbers::pi / 4);
  const double vj = std::sqrt(1000.0 * 0.05 * s / (1.0 - s));  // about 10.99 mm/s
  // Each 500 mm block: accelerate/decelerate between rest, 100 mm/s and vj.
  const auto leg = [](double v0, double v1) {
    const double v = 100.0, a = 1000.0;
    const double d = (v * v - v0 * v0) / (2 * a) + (v * v - v1 * v1) / (2 * a);
    return (v - v0) / a + (v - v1) / a + (500.0 - d) / v;
  };
  EXPECT_NEAR(time_of({line(500, 100), line(500, 100, std::numbers::pi / 2)}, {1000, 0.05, 0}),
              leg(0, vj) + leg(vj, 0), 1e-9);
}

TEST(MotionModel, BlockTimeMakesManyShortBlocksSlow) {
  // 1000 tangent blocks of 0.1 mm at 100 mm/s: 1 s of motion by feed (acceleration ample), but
  // a controller that needs 4 ms per block takes 4 s: the frame effect of Table 1.
  std::vector<MotionMove> many(1000, line(0.1, 100));
  const MotionParams fast{1e9, 0, 0};
  EXPECT_NEAR(time_of(many, fast), 1.0, 1e-6);
  auto r = time_moves(many, {1e9, 0, 0.004});
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->time_s, 4.0, 1e-9);
  EXPECT_EQ(r->block_limited, 1000u);
  EXPECT_NEAR(r->mean_speed_mm_s, 25.0, 1e-9);
  // The same 100 mm as 10 blocks is not limited.
  std::vector<MotionMove> few(10, line(10, 100));
  EXPECT_NEAR(time_of(few, {1e9, 0, 0.004}), 1.0, 1e-6);
}

TEST(MotionModel, ArcSpeedIsCentripetalLimited) {
  MotionMove circle = line(2 * std::numbers::pi, 100);  // r = 1 mm full circle
  circle.radius_mm = 1.0;
  // v <= sqrt(a r) = sqrt(1000) mm/s; the circle is long enough to reach it.
  const double v = std::sqrt(1000.0);
  EXPECT_NEAR(time_of({circle}, {1000, 0, 0}), circle.length_mm / v + v / 1000.0, 1e-9);
}

TEST(MotionModel, RestartsAfterAPierceAndRejectsBadInput) {
  const MotionParams p{1000, 1.0, 0};
  EXPECT_NEAR(time_of({line(1000, 100), line(1000, 100, 0.0, true)}, p), 2 * 10.1, 1e-9);
  EXPECT_FALSE(time_moves({line(10, 0)}, p).ok());
  EXPECT_FALSE(time_moves({line(-1, 10)}, p).ok());
  EXPECT_FALSE(time_moves({line(1, 10)}, {0, 0, 0}).ok());
  EXPECT_NEAR(time_of({}, p), 0.0, 0.0);
}

}  // namespace
}  // namespace cutroute::cost
