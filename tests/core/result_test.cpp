#include <gtest/gtest.h>

#include <string>

#include <cutroute/core/result.hpp>
#include <cutroute/core/units.hpp>

namespace cutroute {
namespace {

Result<int> parse_positive(int v) {
  if (v <= 0) return make_error("not positive", "in.txt", 3);
  return v;
}

TEST(Result, HoldsValueOrError) {
  auto ok = parse_positive(5);
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(*ok, 5);
  auto bad = parse_positive(-1);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(format(bad.error()), "in.txt:3: error: not positive");
}

TEST(Diagnostic, FormatNamesEntityAndLayer) {
  Diagnostic d = make_warning("open contour", "a.dxf", 120);
  d.handle = "1F";
  d.layer = "CUT";
  EXPECT_EQ(format(d), "a.dxf:120: warning: open contour (entity 1F, layer CUT)");
}

TEST(Units, ConversionsRoundTrip) {
  EXPECT_DOUBLE_EQ(units::m_per_s_to_mm_per_min(0.1), 6000.0);
  EXPECT_DOUBLE_EQ(units::mm_per_min_to_m_per_s(6000.0), 0.1);
  EXPECT_EQ(units::seconds_to_ticks(1.5), 1'500'000);
  EXPECT_DOUBLE_EQ(units::ticks_to_seconds(2'500'000), 2.5);
}

}  // namespace
}  // namespace cutroute
