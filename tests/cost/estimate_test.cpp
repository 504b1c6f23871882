// Eq. 1, eq. 10 and eq. 3 evaluated by hand for given program totals.
#include <gtest/gtest.h>

#include <cmath>

#include <cutroute/cost/estimate.hpp>

namespace cutroute::cost {
namespace {

struct Fixture {
  MachineProfile profile;
  SpeedTable table;
};

const Fixture& fx() {
  static const Fixture f = [] {
    Fixture x;
    auto p = load_machine_profile(default_machine_profile_path());
    EXPECT_TRUE(p.ok());
    if (p.ok()) x.profile = *p;
    auto t = load_speed_table(x.profile.speed_table);
    EXPECT_TRUE(t.ok());
    if (t.ok()) x.table = *t;
    return x;
  }();
  return f;
}

CuttingConditions conditions(const std::string& m, double t, bool interpolate = false) {
  auto c = make_conditions(fx().profile, fx().table, m, t, interpolate);
  EXPECT_TRUE(c.ok()) << (c.ok() ? "" : c.error().message);
  return c.ok() ? *c : CuttingConditions{};
}

ProgramTotals totals(double l_on, double l_off, std::size_t pierces, std::size_t frames) {
  ProgramTotals p;
  p.cut_length_mm = l_on;
  p.rapid_length_mm = l_off;
  p.pierces = pierces;
  p.frames = frames;
  return p;
}

TEST(Estimate, Eq1AndEq10ByHand) {
  const auto c = conditions("AMg3M", 1);
  // Default profile: V_on = 0.1 m/s (table set speed), t_pt = 0.3 s, V_off = 1.0 m/s.
  ASSERT_DOUBLE_EQ(c.v_set_m_s, 0.1);
  ASSERT_DOUBLE_EQ(c.pierce_time_s, 0.3);
  ASSERT_DOUBLE_EQ(c.rapid_speed_m_s, 1.0);
  const auto e = estimate_time(totals(12052.0, 3000.0, 19, 120), c);
  const double v120 = 0.08885722120980512;  // 0.2572 * 120^-0.222, evaluated in Python
  EXPECT_NEAR(e.v_on_m_s, v120, 1e-15);
  EXPECT_EQ(e.regime, Regime::power);
  EXPECT_NEAR(e.t_cut_const_speed_s, 120.52 + 3.0 + 5.7, 1e-9);
  EXPECT_NEAR(e.t_cut_s, 12.052 / v120 + 3.0 + 5.7, 1e-9);
  EXPECT_NEAR(e.cutting_s, 12.052 / v120, 1e-9);
  EXPECT_NEAR(e.rapid_s, 3.0, 1e-12);
  EXPECT_NEAR(e.pierce_s, 5.7, 1e-12);
  EXPECT_NEAR(e.total_s, e.t_cut_s, 1e-12);
  EXPECT_NEAR(e.cost, e.t_cut_s, 1e-12);  // eq. 3 in its time form
  EXPECT_EQ(e.cost_unit, "s");
}

TEST(Estimate, BelowN0TheProgramRunsFaster) {
  const auto c = conditions("AMg3M", 1);
  const auto e = estimate_time(totals(1000.0, 0.0, 1, 19), c);
  EXPECT_NEAR(e.v_on_m_s, -4e-12 * 6859 + 3e-8 * 361 - 9e-5 * 19 + 0.105, 1e-15);
  EXPECT_LT(e.t_cut_s, e.t_cut_const_speed_s);
  const auto at_n0 = estimate_time(totals(1000.0, 0.0, 1, 70), c);
  EXPECT_DOUBLE_EQ(at_n0.t_cut_s, at_n0.t_cut_const_speed_s);
}

TEST(Estimate, Eq3WithCosts) {
  auto c = conditions("St10kp", 2);
  c.costs = Costs{"EUR", 0.8, 0.05, 0.03};
  const auto e = estimate_time(totals(5000.0, 2000.0, 10, 400), c);
  EXPECT_NEAR(e.cost, 2.0 * 0.05 + 5.0 * 0.8 + 10 * 0.03, 1e-12);
  EXPECT_EQ(e.cost_unit, "EUR");
}

TEST(Estimate, TermsOutsideEq10GoToTotalOnly) {
  auto c = conditions("AMg3M", 2);
  c.head_lift_lower_s = 0.25;
  auto p = totals(1000.0, 500.0, 4, 50);
  p.dwell_s = 1.5;
  p.feed_off_time_s = 2.0;
  p.feed_off_length_no_feed_mm = 48.0;  // at V_on = 0.048 m/s: 1 s
  const auto e = estimate_time(p, c);
  EXPECT_NEAR(e.dwell_s, 1.5, 1e-12);
  EXPECT_NEAR(e.feed_off_s, 3.0, 1e-12);
  EXPECT_NEAR(e.head_s, 1.0, 1e-12);
  EXPECT_NEAR(e.total_s, e.t_cut_s + 5.5, 1e-12);
  EXPECT_NEAR(e.t_cut_s, e.cutting_s + e.rapid_s + e.pierce_s, 1e-12);
}

TEST(Estimate, ProgrammedPierceDwellsAreNotCountedTwiceInTotal) {
  const auto c = conditions("AMg3M", 2);
  auto p = totals(1000.0, 500.0, 4, 50);
  p.dwell_s = 4 * 0.3;
  p.pierce_dwells = 3;  // three of the four pierces are programmed as dwells
  const auto e = estimate_time(p, c);
  EXPECT_NEAR(e.pierce_s, 4 * c.pierce_time_s, 1e-12);  // eq. 10 itself is unchanged
  EXPECT_NEAR(e.pierce_replaced_s, 3 * c.pierce_time_s, 1e-12);
  EXPECT_NEAR(e.total_s, e.cutting_s + e.rapid_s + c.pierce_time_s + 4 * 0.3 + e.head_s, 1e-12);
}

TEST(Estimate, ProfileSetSpeedScalesTheTable) {
  MachineProfile p = fx().profile;
  for (auto& c : p.cutting)
    if (c.material == "AMg3M" && c.thickness_mm == 1) c.v_set_m_s = 0.05;
  auto c = make_conditions(p, fx().table, "5754", 1, false);
  ASSERT_TRUE(c.ok());
  EXPECT_DOUBLE_EQ(c->v_set_m_s, 0.05);
  EXPECT_DOUBLE_EQ(c->v_on_star(70).v_m_s, 0.05);
  EXPECT_NEAR(c->v_on_star(1962).v_m_s, 0.5 * 0.2572 * std::pow(1962.0, -0.222), 1e-15);
}

TEST(Estimate, ConditionsNeedAProfileRow) {
  MachineProfile p = fx().profile;
  std::erase_if(p.cutting,
                [](const CuttingParams& c) { return c.material == "AMg3M" && c.thickness_mm == 2; });
  auto c = make_conditions(p, fx().table, "AMg3M", 2, false);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("no cutting row for AMg3M 2 mm"), std::string::npos) << c.error().message;
  EXPECT_NE(c.error().message.find("1, 1.5, 3, 5 mm"), std::string::npos) << c.error().message;
}

TEST(Estimate, InterpolatedConditions) {
  const auto c = conditions("AMg3M", 4, true);
  EXPECT_NEAR(c.pierce_time_s, 0.5 * (1.0 + 2.0), 1e-12);
  EXPECT_NEAR(c.v_set_m_s, 0.5 * (0.025 + 0.015), 1e-15);
  EXPECT_NEAR(c.technology.kerf_mm, 0.5 * (0.2 + 0.25), 1e-15);  // default profile rows 3 and 5 mm
  EXPECT_NEAR(c.technology.lead_in_mm, 0.5 * (3.0 + 4.0), 1e-15);
  EXPECT_NEAR(c.technology.thickness_mm, 4.0, 0.0);
  const auto exact = conditions("St10kp", 10);
  EXPECT_NEAR(exact.technology.kerf_mm, 0.35, 0.0);
  EXPECT_NEAR(exact.technology.pierce_time_s, 3.5, 0.0);
  EXPECT_GE(c.warnings.size(), 2u);
  EXPECT_FALSE(make_conditions(fx().profile, fx().table, "AMg3M", 4, false).ok());
}

}  // namespace
}  // namespace cutroute::cost
