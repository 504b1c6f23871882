// The report builders: JSON fields and units, CSV layout, SVG content.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include <cutroute/machining/report.hpp>

#include "examples.hpp"

namespace cutroute::machining {
namespace {

TEST(MachiningReport, JsonHasEveryIssueField) {
  const Problem p = test::load_machining_example(test::kE2);
  const OptimizeResult r = optimize(p);
  RunOutput out{&p, &r, optimize_fig5(p, 121, 121), cost_of_accuracy(p, p.K_TZ_sweep)};
  const auto j = report_json(out);
  for (const char* k : {"status", "vc_m_min", "f_mm_rev", "n_rpm", "vf_mm_min", "tm_min", "tool_life_min",
                        "cost", "constraints", "active", "accuracy", "warnings", "valley", "near_optimal",
                        "derived", "fig5_cross_check", "cost_of_accuracy"}) {
    EXPECT_TRUE(j.contains(k)) << k;
  }
  EXPECT_EQ(j["status"], "optimal");
  EXPECT_DOUBLE_EQ(j["vc_m_min"].get<double>(), r.solution->vc);
  EXPECT_NEAR(j["cost"]["total_cu"].get<double>(),
              j["cost"]["cutting_cu"].get<double>() + j["cost"]["tool_cu"].get<double>() +
                  j["cost"]["service_cu"].get<double>() + j["cost"]["fixed_cu"].get<double>(),
              1e-15);
  EXPECT_EQ(j["constraints"].size(), 5u);  // power, roughness, spindle, feedrate, accuracy
  for (const auto& c : j["constraints"]) {
    EXPECT_DOUBLE_EQ(c["slack"].get<double>(), -c["g"].get<double>());
    EXPECT_NEAR(c["g"].get<double>(), c["value"].get<double>() / c["limit"].get<double>() - 1.0, 1e-15);
    EXPECT_EQ(c["active"].get<bool>(), c["name"] == "accuracy");
  }
  EXPECT_NEAR(j["accuracy"]["V_rho_um"].get<double>(), 6.0, 1e-6);
  EXPECT_NEAR(j["accuracy"]["V_rho_cubature_um"].get<double>(), 6.0, 6.0 * 5e-6);
  EXPECT_EQ(j["fig5_cross_check"]["candidate"], 583);
  EXPECT_TRUE(j["fig5_cross_check"]["within_one_cell"].get<bool>());
  EXPECT_EQ(j["cost_of_accuracy"].size(), 6u);
  EXPECT_EQ(j["valley"].size(), 25u);
}

// Pitfall 7: the optimum lies on a boundary. Where it is a search bound, not a constraint (E0: f on
// search.f_max, no limit active), the report names it; where a constraint binds (E2), no bound.
TEST(MachiningReport, SearchBoundsTheAnswerLiesOnAreNamed) {
  const Problem e0 = test::load_machining_example(test::kE0);
  const OptimizeResult r0 = optimize(e0);
  RunOutput out0{&e0, &r0, {}, {}};
  const auto j0 = report_json(out0);
  EXPECT_TRUE(j0["active"].empty());
  EXPECT_EQ(j0["bounds_reached"], nlohmann::json::array({"search.f_max"}));
  EXPECT_NE(report_text(out0).find("on the search bound search.f_max"), std::string::npos) << report_text(out0);
  const Problem e2 = test::load_machining_example(test::kE2);
  const OptimizeResult r2 = optimize(e2);
  RunOutput out2{&e2, &r2, {}, {}};
  EXPECT_TRUE(report_json(out2)["bounds_reached"].empty());
  EXPECT_EQ(report_text(out2).find("on the search bound"), std::string::npos);
}

TEST(MachiningReport, InfeasibleJsonNamesConstraintAndRemedies) {
  Problem p = test::load_machining_example(test::kE2);
  p.accuracy->K_TZ = 0.0005;
  const OptimizeResult r = optimize(p);
  const auto j = report_json(RunOutput{&p, &r, std::nullopt, {}});
  EXPECT_EQ(j["status"], "infeasible");
  EXPECT_EQ(j["infeasible"]["least_violated"], "accuracy");
  EXPECT_GE(j["infeasible"]["suggestions"].size(), 3u);
  EXPECT_FALSE(j.contains("vc_m_min"));
  EXPECT_NE(report_text(RunOutput{&p, &r, std::nullopt, {}}).find("semi-finishing"), std::string::npos);
  EXPECT_TRUE(j["infeasible"]["at"].is_object());
  // An empty search box has no point: "at" is null, not (0, 0).
  Problem e1 = test::load_machining_example(test::kE1);
  e1.quality.Ra_max = 0.1;  // f_Ra = 0.0358 < f_min = 0.05
  const OptimizeResult empty = optimize(e1);
  const auto k = report_json(RunOutput{&e1, &empty, std::nullopt, {}});
  EXPECT_EQ(k["infeasible"]["least_violated"], "bounds");
  EXPECT_TRUE(k["infeasible"]["at"].is_null());
}

TEST(MachiningReport, CsvHasValleyAndGrid) {
  Problem p = test::load_machining_example(test::kE2);
  p.search.grid_vc = 31;
  p.search.grid_f = 21;
  const OptimizeResult r = optimize(p);
  const std::string csv = report_csv(RunOutput{&p, &r, std::nullopt, {}});
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "section,vc_m_min,f_mm_rev,vf_mm_min,ct_cu,tool_life_min,feasible,constraint");
  int valley = 0, valley_feasible = 0, grid = 0, feasible = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 7) << line;
    if (line.rfind("valley,", 0) == 0) ++valley, valley_feasible += line.find(",1,") != std::string::npos;
    if (line.rfind("grid,", 0) == 0) {
      ++grid;
      if (line.find(",1,") != std::string::npos) ++feasible;
    }
  }
  // At f = f_Ra the accuracy limit would need vc ≈ 607 m/min > vc_max: that valley point is infeasible,
  // listed with its feed and no speed, as in the JSON.
  EXPECT_EQ(valley, static_cast<int>(r.valley.size()));
  EXPECT_EQ(valley, 25);
  EXPECT_EQ(valley_feasible,
            std::count_if(r.valley.begin(), r.valley.end(), [](const FeedOptimum& v) { return v.feasible; }));
  EXPECT_EQ(valley_feasible, 24);
  EXPECT_EQ(grid, 31 * 21);
  EXPECT_GT(feasible, 0);
  EXPECT_LT(feasible, grid);  // E2 has infeasible (accuracy) grid points at low speed
}

TEST(MachiningReport, SvgShowsMapValleyContoursAndLegend) {
  const Problem p = test::load_machining_example(test::kE2);
  const OptimizeResult r = optimize(p);
  const std::string svg = report_svg(RunOutput{&p, &r, std::nullopt, {}});
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  for (const char* s :
       {"cutting speed vc [m/min]", "feed speed Vf", "valley vc*(f)", "CT = CT*(1 + 0.01)",
        "CT = CT*(1 + 0.05)", "feasible-region boundary", "optimum", "<polygon", "<polyline"}) {
    EXPECT_NE(svg.find(s), std::string::npos) << s;
  }
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf,"), std::string::npos);
  EXPECT_EQ(svg.find(",inf"), std::string::npos);
  EXPECT_EQ(svg.find("\"inf"), std::string::npos);
  EXPECT_LT(svg.size(), 2'000'000u);
}

// Found by fuzzing: a load time of 1e20 min makes every grid cost the same double, the shading
// divided log 1 by log 1, and the NaN indexed the colour ramp (UBSan).
TEST(MachiningReport, SvgOfAFlatCostSurfaceHasNoNan) {
  Problem p = test::load_machining_example(test::kE0);
  p.econ.t_load = 1e20;
  const OptimizeResult r = optimize(p);
  ASSERT_TRUE(r.surface.has_value());
  ASSERT_EQ(*std::min_element(r.surface->CT.begin(), r.surface->CT.end()),
            *std::max_element(r.surface->CT.begin(), r.surface->CT.end()));
  const std::string svg = report_svg(RunOutput{&p, &r, std::nullopt, {}});
  EXPECT_NE(svg.find("<polygon"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

}  // namespace
}  // namespace cutroute::machining
