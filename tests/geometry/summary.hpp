// Property summary of a contour (vertex count, signed area, length, box) with named tolerances.
#pragma once

#include <cmath>
#include <ostream>

#include <gtest/gtest.h>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::geometry::test {

// Analytic values are compared to within these: double rounding on coordinates of size ~100 mm.
inline constexpr double kLengthTolMm = 1e-9;
inline constexpr double kAreaTolMm2 = 1e-8;
inline constexpr double kBoxTolMm = 1e-9;

struct Summary {
  std::size_t vertices = 0;
  double area = 0.0;    // signed [mm²]
  double length = 0.0;  // [mm]
  Box box;
};

inline Summary summarize(const Contour& c) { return {c.vertices.size(), signed_area(c), length(c), bounding_box(c)}; }

inline void expect_summary(const Summary& got, const Summary& want, const char* what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(got.vertices, want.vertices);
  EXPECT_NEAR(got.area, want.area, kAreaTolMm2);
  EXPECT_NEAR(got.length, want.length, kLengthTolMm);
  EXPECT_NEAR(got.box.xmin, want.box.xmin, kBoxTolMm);
  EXPECT_NEAR(got.box.ymin, want.box.ymin, kBoxTolMm);
  EXPECT_NEAR(got.box.xmax, want.box.xmax, kBoxTolMm);
  EXPECT_NEAR(got.box.ymax, want.box.ymax, kBoxTolMm);
}

}  // namespace cutroute::geometry::test
