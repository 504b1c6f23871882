// MACHINING.md 7.1 (U1-U9) and 7.3 (G1-G5): building blocks and closed-form economics.
#include <gtest/gtest.h>

#include <cmath>

#include <cutroute/machining/models.hpp>
#include <cutroute/machining/optimize.hpp>

#include "examples.hpp"

namespace cutroute::machining {
namespace {

TEST(MachiningModels, U1SpindleSpeed) {
  EXPECT_NEAR(spindle_speed_rpm(250, 40), 1989.43679, test::printed(5));
}

TEST(MachiningModels, U2FeedSpeedAndTime) {
  const double Vf = feed_speed_mm_min(0.15, spindle_speed_rpm(250, 40));
  EXPECT_REL(Vf, 298.415518, 2e-9);
  EXPECT_REL(machining_time_min(1, 60, 3, Vf), 0.211115026, 3e-9);
}

TEST(MachiningModels, U3TaylorLife) { EXPECT_REL(taylor_life_min({500, 0.25}, 225.900501), 24.0000, 5e-6); }

TEST(MachiningModels, U4HandbookLife) {
  const HandbookLife h{420, 0.9, 0.2, 0.15, 0.2, 0.0, 0.3};
  EXPECT_REL(handbook_life_min(h, 332.447141, 0.5, 0.1431084), 22.3333, 5e-6);
}

TEST(MachiningModels, U5Kienzle) {
  EXPECT_REL(kienzle_force_n({2220, 0.14}, 1.0, 0.15, 90.0), 434.3016, 2e-7);
  EXPECT_REL(kienzle_force_n({1675, 0.24}, 1.0, 0.15, 90.0), 396.1359, 2e-7);
}

TEST(MachiningModels, U6HandbookForceKeepsTheFactorTen) {
  const double F = handbook_force_n({300, 1.0, 0.75, -0.15, 1.0}, 1.0, 0.15, 250);
  EXPECT_REL(F, 315.8630, 2e-7);
  EXPECT_REL(cutting_power_kw(F, 250), 1.316096, 5e-7);
  // Pitfall 1: a calculator without the kgf -> N factor is off by exactly ten.
  EXPECT_GT(F, 300.0);
}

TEST(MachiningModels, U7Roughness) {
  EXPECT_REL(roughness_ra_um(0.2, 0.8, 1.0), 1.5625, 1e-12);
  EXPECT_REL(roughness_rz_um(0.2, 0.8, 1.0), 6.25, 1e-12);
}

TEST(MachiningModels, U8FeedFromRoughness) {
  EXPECT_REL(feed_for_ra(1.6, 0.4, 1.0), 0.143108351, 5e-9);
  EXPECT_REL(roughness_ra_um(feed_for_ra(1.6, 0.4, 1.0), 0.4, 1.0), 1.6, 1e-12);
}

TEST(MachiningModels, U9BarStiffness) {
  const double k = bar_stiffness_n_mm(210000, bar_inertia_mm4(25, 0), 100);
  EXPECT_REL(k, 12080.0987, 1e-9);
  EXPECT_NEAR(deflection_mm(200, k), 0.0165562, test::printed(7));
}

TEST(MachiningModels, PowerCurveAndTorque) {
  EXPECT_DOUBLE_EQ(available_power_kw(11, 500, 0), 11);
  EXPECT_DOUBLE_EQ(available_power_kw(11, 500, 1000), 5.5);
  EXPECT_DOUBLE_EQ(available_power_kw(11, 2000, 1000), 11);
  EXPECT_DOUBLE_EQ(torque_nm(1000, 40), 20);
}

// ---- 7.3 closed-form economics ----

TEST(MachiningEconomics, G1GilbertTaylor) {
  const double T = gilbert_tool_life(0.25, 0.5, 2.0, 3.0, 0.5);
  EXPECT_REL(T, 24.0, 1e-12);
  const double vc = speed_for_tool_life(500, 0.25, T);
  EXPECT_REL(vc, 225.900501, 3e-9);
  // Numeric optimum over vc at fixed f agrees with the closed form to 1e-8 (E0 is G1 as a problem).
  auto p = test::load_machining_example(test::kE0);
  const auto grid = log_grid(30, 600, 241);
  const FeedOptimum fo = best_vc_at_feed(p, 0, 0.15, grid);
  ASSERT_TRUE(fo.feasible);
  EXPECT_REL(fo.vc, vc, 1e-8);
  EXPECT_TRUE(fo.binding.empty());
  // tm and CT at vc* with f = 0.15, D = 40, L + l_extra = 63, t_load·r1 = 0.5, R_H = 0.5.
  const PointEval e = evaluate(p, vc, 0.15);
  EXPECT_REL(e.tm, 0.233637, 2e-6);
  EXPECT_REL(e.cost.total, 1.155758, 5e-7);
  EXPECT_REL(e.T, 24.0, 1e-8);
}

TEST(MachiningEconomics, G2MaximumProductionRate) {
  const double T = max_production_tool_life(0.25, 2.0);
  EXPECT_REL(T, 6.0, 1e-12);
  EXPECT_REL(speed_for_tool_life(500, 0.25, T), 319.4716, 2e-7);
}

TEST(MachiningEconomics, G3HighSpeedSteel) {
  const double T = gilbert_tool_life(0.125, 0.5, 2.0, 3.0, 0.5);
  EXPECT_REL(T, 56.0, 1e-12);
  EXPECT_REL(speed_for_tool_life(70, 0.125, T), 42.3228, 2e-6);
}

TEST(MachiningEconomics, G4TextbookMaximumProduction) {
  EXPECT_REL(speed_for_tool_life(75, 0.25, max_production_tool_life(0.25, 2.0)), 47.9207, 2e-6);
}

TEST(MachiningEconomics, G5UnequalRates) {
  const double T = gilbert_tool_life(0.25, 0.68, 1.5, 3.0, 0.72);
  EXPECT_REL(T, 16.75, 1e-12);
  EXPECT_REL(speed_for_tool_life(500, 0.25, T), 247.153236, 3e-9);
}

TEST(MachiningEconomics, RatesAndBreakdownAddUp) {
  const Rates r = combine_rates({0.25, 0.35, 0.04, 0.02, 0.06});
  EXPECT_NEAR(r.r1, 0.60, 1e-15);
  EXPECT_NEAR(r.r2, 0.68, 1e-15);
  EXPECT_NEAR(r.r30, 0.72, 1e-15);
  CostInputs c{r, RateMap::physical, 3.0, 1.5, 1.0, 0.5};
  const CostBreakdown b = cost_per_part(c, 0.2, 20.0);
  EXPECT_NEAR(b.total, b.cutting + b.tool + b.service + b.fixed, 1e-15);
  EXPECT_NEAR(b.cutting, 0.2 * 0.72, 1e-15);
  EXPECT_NEAR(b.fixed, 1.1, 1e-15);
  EXPECT_NEAR(b.edges_per_part * b.parts_per_edge, 1.0, 1e-15);
  // The second formula line: CT = tm·r30 + (tm/T)·(r2·t_change + C_edge) + t_load·r1 + R_H.
  EXPECT_NEAR(b.total, 0.2 * 0.72 + 0.01 * (0.68 * 1.5 + 3.0) + 0.6 + 0.5, 1e-15);
  c.map = RateMap::listed_order;
  const CostBreakdown l = cost_per_part(c, 0.2, 20.0);
  EXPECT_NEAR(l.cutting, 0.2 * 0.60, 1e-15);
  EXPECT_NEAR(l.fixed, 0.72 + 0.5, 1e-15);
}

TEST(MachiningEconomics, CoupledToolLifeFormula) {
  // E2 hand check: β = 0.5 from n_r/y_r = 0.3/0.6, y = 0.2, m = 0.2.
  EXPECT_REL(coupled_tool_life(0.2, 0.2, 0.5, 0.68, 1.5, 3.0, 0.72), 14.888889, 1e-7);
  // β = 0 reduces to Gilbert.
  EXPECT_REL(coupled_tool_life(0.2, 0.2, 0.0, 0.68, 1.5, 3.0, 0.72),
             gilbert_tool_life(0.2, 0.68, 1.5, 3.0, 0.72), 1e-14);
}

}  // namespace
}  // namespace cutroute::machining
