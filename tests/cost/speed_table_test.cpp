// Table 1 as shipped in data/materials/bystar3015.json against the paper (PAPERS.md §1):
// every row, the numbers the paper quotes, continuity at n0, lookup, aliases, interpolation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <cutroute/cost/speed_table.hpp>

namespace cutroute::cost {
namespace {

const SpeedTable& table() {
  static const SpeedTable t = [] {
    auto r = load_speed_table(default_speed_table_path());
    if (!r.ok()) {
      ADD_FAILURE() << format(r.error());
      return SpeedTable{};
    }
    return *r;
  }();
  return t;
}

SpeedRow row(const std::string& m, double t) {
  auto q = find_speed(table(), m, t, false);
  EXPECT_TRUE(q.ok()) << m << " " << t;
  return q.ok() ? q->lower : SpeedRow{};
}

// Table 1 retyped from PAPERS.md, independently of the data file.
struct PaperRow {
  const char* material;
  double thickness;
  int n0;
  double a, b, c, d, v_set, k, e;
  bool measured;
};
constexpr PaperRow kPaper[] = {
    {"St10kp", 1, 172, -2e-12, 2e-8, -7e-5, 0.1415, 0.13, 0.6633, -0.317, true},
    {"St10kp", 2, 167, -1e-12, 2e-8, -5e-5, 0.105, 0.0975, 0.49, -0.315, true},
    {"St10kp", 3, 242, -4e-13, 5e-9, -2e-5, 0.066, 0.06, 0.2145, -0.229, true},
    {"St10kp", 3.5, 242, -3e-13, 3e-9, -1e-5, 0.0462, 0.042, 0.1501, -0.229, false},
    {"St10kp", 3.9, 242, -3e-13, 3e-9, -1e-5, 0.0462, 0.042, 0.1501, -0.229, false},
    {"St10kp", 4, 167, -8e-13, 8e-9, -2e-5, 0.0439, 0.04, 0.1945, -0.306, true},
    {"St10kp", 8, 288, -7e-11, 6e-9, -1e-5, 0.031, 0.027, 0.0634, -0.15, false},
    {"St10kp", 10, 288, -6e-11, 5e-9, -1e-5, 0.027, 0.023, 0.054, -0.15, false},
    {"AMg3M", 1, 70, -4e-12, 3e-8, -9e-5, 0.105, 0.1, 0.2572, -0.222, true},
    {"AMg3M", 1.5, 70, -3e-12, 2e-8, -6e-5, 0.07, 0.067, 0.1723, -0.222, false},
    {"AMg3M", 2, 70, -7e-13, 6e-9, -2e-5, 0.0494, 0.048, 0.0734, -0.1, true},
    {"AMg3M", 3, 72, -2e-13, 2e-9, -5e-6, 0.0254, 0.025, 0.0346, -0.075, true},
    {"AMg3M", 5, 105, -7e-14, 7e-10, -2e-6, 0.0152, 0.015, 0.0194, -0.057, true},
};

TEST(SpeedTable, EveryRowOfTable1IsPresentAsPrinted) {
  EXPECT_EQ(table().rows.size(), std::size(kPaper));
  for (const auto& p : kPaper) {
    SCOPED_TRACE(std::string(p.material) + " " + std::to_string(p.thickness));
    const SpeedRow r = row(p.material, p.thickness);
    EXPECT_EQ(r.n0, p.n0);
    EXPECT_DOUBLE_EQ(r.cubic[0], p.a);
    EXPECT_DOUBLE_EQ(r.cubic[1], p.b);
    EXPECT_DOUBLE_EQ(r.cubic[2], p.c);
    EXPECT_DOUBLE_EQ(r.cubic[3], p.d);
    EXPECT_DOUBLE_EQ(r.v_set_m_s, p.v_set);
    EXPECT_DOUBLE_EQ(r.power_k, p.k);
    EXPECT_DOUBLE_EQ(r.power_e, p.e);
    EXPECT_EQ(r.measured, p.measured);
  }
}

TEST(SpeedTable, PaperNumbersForAMg3M1mm) {
  const SpeedRow r = row("AMg3M", 1);
  // n = 19: the paper's eq. 2 gives 0.1033 m/s (4 digits printed).
  const auto v19 = v_on_star(r, 19);
  EXPECT_EQ(v19.regime, Regime::cubic);
  EXPECT_NEAR(v19.v_m_s, 0.1033, 0.00005);
  // n = 70: the set speed; the cubic gives 0.0989 and the power law 0.1000, both within 1 % of 0.1.
  const auto v70 = v_on_star(r, 70);
  EXPECT_EQ(v70.regime, Regime::set);
  EXPECT_DOUBLE_EQ(v70.v_m_s, 0.1);
  const double cubic70 = v_on_star(r, 70 - 1e-9).v_m_s;
  const double power70 = v_on_star(r, 70 + 1e-9).v_m_s;
  // The paper prints 0.0989 and 0.1000; the printed coefficients give 0.098846 and 0.100152, so
  // the paper's last digit is not exact: compare to one unit of it (0.06 % and 0.15 % apart).
  EXPECT_NEAR(cubic70, 0.0989, 0.0001);
  EXPECT_NEAR(power70, 0.1000, 0.0002);
  EXPECT_LT(std::abs(cubic70 / 0.1 - 1.0), 0.012);  // the paper: 0.6 % from the measured 0.09947
  EXPECT_LT(std::abs(power70 / 0.1 - 1.0), 0.01);
  // n = 1962: the power law gives 0.04779 m/s; measured 0.04776 (0.039 % apart).
  const auto v1962 = v_on_star(r, 1962);
  EXPECT_EQ(v1962.regime, Regime::power);
  EXPECT_NEAR(v1962.v_m_s, 0.04779, 0.000005);
  EXPECT_NEAR(v1962.v_m_s / 0.04776 - 1.0, 0.00039, 0.0002);
  // "up to ~5 % above" and "falls by up to ~50 %" (the paper's prose on this row)
  EXPECT_NEAR(v_on_star(r, 1).v_m_s / 0.1, 1.05, 0.001);
  EXPECT_NEAR(v1962.v_m_s / 0.1, 0.478, 0.001);
}

// Deviation of V_on*(n0 - 1) and V_on*(n0 + 1) from the set speed, in %, for the rows where the
// printed coefficients are NOT continuous within 1.5 % (computed separately in Python from the
// printed coefficients; see the notes in the data file). 99 = within 1.5 %, not an exception.
struct Exception {
  const char* material;
  double thickness;
  double below_pct;
  double above_pct;
};
constexpr Exception kDiscontinuous[] = {
    {"St10kp", 3, 2.441, 1.618}, {"St10kp", 3.5, 4.667, 1.585}, {"St10kp", 3.9, 4.667, 1.585},
    {"St10kp", 4, 1.992, 99},    {"AMg3M", 1.5, -1.561, 99},
};

TEST(SpeedTable, ContinuousAtN0OnBothSidesWithin1_5PercentExceptThePaperOwnRoundingCases) {
  for (const auto& p : kPaper) {
    SCOPED_TRACE(std::string(p.material) + " " + std::to_string(p.thickness));
    const SpeedRow r = row(p.material, p.thickness);
    const double below = 100.0 * (v_on_star(r, r.n0 - 1).v_m_s / r.v_set_m_s - 1.0);
    const double above = 100.0 * (v_on_star(r, r.n0 + 1).v_m_s / r.v_set_m_s - 1.0);
    EXPECT_EQ(v_on_star(r, r.n0 - 1).regime, Regime::cubic);
    EXPECT_EQ(v_on_star(r, r.n0 + 1).regime, Regime::power);
    double want_below = 99;
    double want_above = 99;
    for (const auto& e : kDiscontinuous) {
      if (std::string(e.material) == p.material && e.thickness == p.thickness) {
        want_below = e.below_pct;
        want_above = e.above_pct;
      }
    }
    if (want_below == 99)
      EXPECT_LE(std::abs(below), 1.5);
    else
      EXPECT_NEAR(below, want_below, 0.01);
    if (want_above == 99)
      EXPECT_LE(std::abs(above), 1.5);
    else
      EXPECT_NEAR(above, want_above, 0.01);
  }
}

TEST(SpeedTable, SlowerAboveN0FasterBelow) {
  for (const auto& r : table().rows) {
    SCOPED_TRACE(r.material + " " + std::to_string(r.thickness_mm));
    EXPECT_GT(v_on_star(r, 1).v_m_s, r.v_set_m_s);
    EXPECT_LT(v_on_star(r, 5000).v_m_s, r.v_set_m_s);
    // the power law decreases with n
    EXPECT_LT(v_on_star(r, 2000).v_m_s, v_on_star(r, 1000).v_m_s);
  }
  EXPECT_DOUBLE_EQ(v_on_star(row("AMg3M", 1), 0).v_m_s, 0.105);  // empty program: d
}

TEST(SpeedTable, AliasesResolve) {
  for (const char* a : {"AMg3M", "amg3m", "AMg3", "5754", "EN AW-5754", "АМг3М"})
    EXPECT_EQ(table().resolve_material(a).ok() ? *table().resolve_material(a) : "", "AMg3M") << a;
  for (const char* a : {"St10kp", "st10", "AISI 1010", "Ст10кп"})
    EXPECT_EQ(table().resolve_material(a).ok() ? *table().resolve_material(a) : "", "St10kp") << a;
}

TEST(SpeedTable, UnknownMaterialListsMaterials) {
  auto q = find_speed(table(), "Inconel", 1, false);
  ASSERT_FALSE(q.ok());
  EXPECT_NE(q.error().message.find("unknown material 'Inconel'"), std::string::npos);
  EXPECT_NE(q.error().message.find("AMg3M"), std::string::npos);
  EXPECT_NE(q.error().message.find("St10kp"), std::string::npos);
}

TEST(SpeedTable, UnknownThicknessListsThicknesses) {
  auto q = find_speed(table(), "AMg3M", 2.5, false);
  ASSERT_FALSE(q.ok());
  EXPECT_NE(q.error().message.find("1, 1.5, 2, 3, 5 mm"), std::string::npos) << q.error().message;
  EXPECT_NE(q.error().message.find("--interpolate"), std::string::npos);
  // outside the table there is nothing to interpolate between
  EXPECT_FALSE(find_speed(table(), "AMg3M", 6, true).ok());
  EXPECT_FALSE(find_speed(table(), "St10kp", 0.5, true).ok());
}

TEST(SpeedTable, InterpolationIsLinearInThicknessAndWarns) {
  auto q = find_speed(table(), "AMg3M", 2.5, true);
  ASSERT_TRUE(q.ok());
  EXPECT_TRUE(q->interpolated);
  ASSERT_FALSE(q->warnings.empty());
  for (double n : {19.0, 70.0, 71.0, 120.0, 1962.0}) {
    const double a = v_on_star(row("AMg3M", 2), n).v_m_s;
    const double b = v_on_star(row("AMg3M", 3), n).v_m_s;
    EXPECT_NEAR(q->at(n).v_m_s, 0.5 * (a + b), 1e-15) << n;
  }
  EXPECT_NEAR(q->v_set_m_s(), 0.0365, 1e-15);
  auto q4 = find_speed(table(), "AMg3M", 1.25, true);  // between a measured and an extrapolated row
  ASSERT_TRUE(q4.ok());
  EXPECT_FALSE(q4->measured);
  EXPECT_NEAR(q4->v_set_m_s(), 0.5 * 0.1 + 0.5 * 0.067, 1e-15);
  auto q5 = find_speed(table(), "AMg3M", 1.125, true);
  ASSERT_TRUE(q5.ok());
  EXPECT_NEAR(q5->v_set_m_s(), 0.75 * 0.1 + 0.25 * 0.067, 1e-15);
}

TEST(SpeedTable, ExtrapolatedRowsSaySo) {
  for (double t : {3.5, 3.9, 8.0, 10.0}) {
    auto q = find_speed(table(), "St10kp", t, false);
    ASSERT_TRUE(q.ok());
    EXPECT_FALSE(q->measured) << t;
    ASSERT_EQ(q->warnings.size(), 1u);
    EXPECT_NE(q->warnings[0].find("extrapolation"), std::string::npos);
  }
  auto m = find_speed(table(), "AMg3M", 1, false);
  ASSERT_TRUE(m.ok());
  EXPECT_TRUE(m->measured);
  EXPECT_TRUE(m->warnings.empty());
}

std::string write_temp(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / name;
  std::ofstream(p) << text;
  return p.string();
}

TEST(SpeedTable, BrokenTableFilesNameTheField) {
  struct Case {
    const char* text;
    const char* expect;
  };
  const Case cases[] = {
      {"[1]", "top level"},
      {"{", "not valid JSON"},
      {R"({"materials": []})", "materials must be a non-empty array"},
      {R"({"materials": [{"rows": []}]})", "materials[0].name is missing"},
      {R"({"materials": [{"name": "A", "rows": [{"thickness_mm": [1], "n0": 5, "cubic": [1,2,3],
          "v_set_m_s": 1, "power": {"k": 1, "e": -0.1}, "measured": true}]}]})",
       "materials[0].rows[0].cubic"},
      {R"({"materials": [{"name": "A", "rows": [{"thickness_mm": [1], "n0": 5.5, "cubic": [1,2,3,4],
          "v_set_m_s": 1, "power": {"k": 1, "e": -0.1}, "measured": true}]}]})",
       "materials[0].rows[0].n0 must be a whole number"},
      {R"({"materials": [{"name": "A", "rows": [{"thickness_mm": [1], "n0": 5, "cubic": [1,2,3,4],
          "v_set_m_s": -1, "power": {"k": 1, "e": -0.1}, "measured": true}]}]})",
       "materials[0].rows[0].v_set_m_s must be > 0"},
      {R"({"materials": [{"name": "A", "rows": [{"thickness_mm": [1, 1], "n0": 5, "cubic": [1,2,3,4],
          "v_set_m_s": 1, "power": {"k": 1, "e": -0.1}, "measured": true}]}]})",
       "appears twice"},
      {R"({"materials": [{"name": "A", "rows": [{"thickness_mm": [1], "n0": 5, "cubic": [1,2,3,4],
          "v_set_m_s": 1, "power": {"k": 1, "e": -0.1}}]}]})",
       "materials[0].rows[0].measured is missing"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string path = write_temp("cutroute-bad-table-" + std::to_string(i++) + ".json", c.text);
    auto t = load_speed_table(path);
    ASSERT_FALSE(t.ok()) << c.text;
    EXPECT_EQ(t.error().file, path);
    EXPECT_NE(t.error().message.find(c.expect), std::string::npos) << t.error().message;
    std::filesystem::remove(path);
  }
}

}  // namespace
}  // namespace cutroute::cost
