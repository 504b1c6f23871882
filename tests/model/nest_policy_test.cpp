// What the nest lets through to cutting: crossings are errors unless within the curve tolerance.
#include <gtest/gtest.h>

#include <cutroute/geometry/shapes.hpp>
#include <cutroute/model/nest.hpp>

namespace cutroute::model {
namespace {

SourceContour part(geometry::Contour c) { return SourceContour{std::move(c), "0", {}, {}, {}}; }

// Two squares 10 mm wide, the right one shifted left by `overlap` into the left one.
Nest two_squares(double overlap, double crossing_tol) {
  NestOptions o;
  o.crossing_tol_mm = crossing_tol;
  return build_nest({part(geometry::rectangle({0, 0, 10, 10})), part(geometry::rectangle({10 - overlap, 2, 20, 8}))}, o);
}

TEST(NestPolicy, ShallowCrossingWithinTheCurveToleranceIsTouching) {
  const Nest n = two_squares(0.004, 0.01);
  ASSERT_EQ(n.diagnostics.size(), 1u);
  EXPECT_EQ(n.diagnostics[0].severity, Severity::warning);
  EXPECT_EQ(n.diagnostics[0].code, "nest.touch");
  EXPECT_NE(n.diagnostics[0].message.find("within the curve tolerance"), std::string::npos);
  EXPECT_EQ(n.parts.size(), 2u);  // neither contains the other
}

TEST(NestPolicy, DeeperCrossingIsAnErrorNamingTheDepth) {
  for (double tol : {0.0, 0.01}) {
    const Nest n = two_squares(0.5, tol);
    ASSERT_FALSE(n.diagnostics.empty());
    EXPECT_EQ(n.diagnostics[0].severity, Severity::error);
    EXPECT_EQ(n.diagnostics[0].code, "nest.crossing");
    EXPECT_NE(n.diagnostics[0].message.find("by at least 0.5"), std::string::npos) << n.diagnostics[0].message;
  }
}

TEST(NestPolicy, WithoutToleranceEvenAHairlineCrossingIsAnError) {
  const Nest n = two_squares(0.004, 0.0);
  ASSERT_FALSE(n.diagnostics.empty());
  EXPECT_EQ(n.diagnostics[0].code, "nest.crossing");
}

TEST(NestPolicy, DuplicateOutlineIsCutOnceWithAWarning) {
  const Nest n = build_nest({part(geometry::rectangle({0, 0, 10, 10})), part(geometry::rectangle({0, 0, 10, 10}))}, {});
  EXPECT_EQ(n.contours.size(), 1u);
  ASSERT_EQ(n.diagnostics.size(), 1u);
  EXPECT_EQ(n.diagnostics[0].severity, Severity::warning);
  EXPECT_EQ(n.diagnostics[0].code, "nest.duplicate");
}

}  // namespace
}  // namespace cutroute::model
