#include <gtest/gtest.h>

#include <limits>

#include <cutroute/core/number_format.hpp>

namespace cutroute {
namespace {

TEST(NumberFormat, TrimsZerosAndPoint) {
  EXPECT_EQ(format_fixed(1.5, 3), "1.5");
  EXPECT_EQ(format_fixed(2.0, 3), "2");
  EXPECT_EQ(format_fixed(10.0, 0), "10");
  EXPECT_EQ(format_fixed(100.0, 2), "100");
  EXPECT_EQ(format_fixed(0.1 + 0.2, 4), "0.3");
}

TEST(NumberFormat, RoundsHalfAwayAsToChars) {
  EXPECT_EQ(format_fixed(1.23456, 3), "1.235");
  EXPECT_EQ(format_fixed(-1.23456, 3), "-1.235");
}

TEST(NumberFormat, NeverNegativeZero) {
  EXPECT_EQ(format_fixed(-0.0, 3), "0");
  EXPECT_EQ(format_fixed(-0.0004, 3), "0");
  EXPECT_EQ(format_fixed(0.0004, 3), "0");
}

TEST(NumberFormat, NonFiniteIsVisible) {
  EXPECT_EQ(format_fixed(std::numeric_limits<double>::quiet_NaN(), 3), "nan");
  EXPECT_EQ(format_fixed(std::numeric_limits<double>::infinity(), 3), "inf");
}

TEST(NumberFormat, HugeValuesDoNotOverflowTheBuffer) {
  EXPECT_FALSE(format_fixed(1e300, 3).empty());
}

}  // namespace
}  // namespace cutroute
