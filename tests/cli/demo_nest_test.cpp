// The generated demo sheet matches the source paper's example: 14 parts, 21 contours, 3 chainable pairs.
#include <gtest/gtest.h>

#include <cutroute/geometry/contour.hpp>
#include <cutroute/model/demo_nest.hpp>
#include <cutroute/model/nest.hpp>

namespace cutroute::model {
namespace {

TEST(DemoNest, HasThePaperExampleStructure) {
  auto contours = make_demo_sheet();
  ASSERT_EQ(contours.size(), 22u);
  NestOptions opts;
  const Nest nest = build_nest(contours, opts);
  ASSERT_TRUE(nest.sheet.has_value());
  EXPECT_EQ(nest.parts.size(), 14u);
  std::size_t holes = 0;
  for (const auto& c : nest.contours) holes += c.role == ContourRole::hole ? 1 : 0;
  EXPECT_EQ(holes, 7u);
  EXPECT_FALSE(has_errors(nest.diagnostics));
}

TEST(DemoNest, ExactlyThreePairsOfOuterContoursAreWithinChainingDistance) {
  auto contours = make_demo_sheet();
  const Nest nest = build_nest(contours, NestOptions{});
  // Outer contours whose boxes are closer than 10 mm: the demo places exactly three such pairs,
  // each 5 mm apart; every other pair of parts is at least 30 mm apart.
  int close_pairs = 0;
  for (std::size_t i = 0; i < nest.parts.size(); ++i) {
    for (std::size_t j = i + 1; j < nest.parts.size(); ++j) {
      const auto& a = nest.contours[nest.parts[PartId(static_cast<int>(i))].outer].box;
      const auto& b = nest.contours[nest.parts[PartId(static_cast<int>(j))].outer].box;
      const double dx = std::max({0.0, a.xmin - b.xmax, b.xmin - a.xmax});
      const double dy = std::max({0.0, a.ymin - b.ymax, b.ymin - a.ymax});
      const double gap = std::hypot(dx, dy);
      if (gap < 10) {
        ++close_pairs;
        EXPECT_NEAR(gap, kDemoChainGapMm, 1e-9);
      } else {
        EXPECT_GE(gap, 30 - 1e-9);
      }
    }
  }
  EXPECT_EQ(close_pairs, 3);
}

TEST(DemoNest, OutersCounterClockwiseHolesClockwise) {
  const Nest nest = build_nest(make_demo_sheet(), NestOptions{});
  for (const auto& c : nest.contours) {
    if (c.role == ContourRole::sheet) continue;
    EXPECT_EQ(geometry::orientation(c.source.contour),
              c.role == ContourRole::outer ? geometry::Orientation::ccw : geometry::Orientation::cw);
  }
}

}  // namespace
}  // namespace cutroute::model
