// MACHINING.md 7.6 property tests and optimizer behaviour beyond the worked examples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/random.hpp>
#include <cutroute/machining/optimize.hpp>
#include <cutroute/machining/report.hpp>

#include "examples.hpp"

namespace cutroute::machining {
namespace {

double uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rng.uniform01(); }

// A random boring problem around E2 (fixed seed), with or without the accuracy limit.
Problem random_problem(Rng& rng, bool with_accuracy) {
  Problem p = test::load_machining_example(test::kE2);
  auto& s = p.life.sets[0];
  s.Cv = uniform(rng, 250, 500);
  s.m = uniform(rng, 0.12, 0.35);
  s.x = uniform(rng, 0.05, 0.3);
  s.y = uniform(rng, 0.1, 0.9);
  s.f_hi = 1.0;
  p.op.ap = uniform(rng, 0.3, 2.5);
  p.tool.r_eps = uniform(rng, 0.4, 1.6);
  p.tool.C_edge = uniform(rng, 1, 8);
  p.tool.t_change = uniform(rng, 0.5, 3);
  p.tangential.handbook.y = uniform(rng, 0.6, 0.9);
  p.radial->handbook.n = -uniform(rng, 0.1, 0.4);
  p.machine.P_motor = uniform(rng, 3, 15);
  p.search.f_max = 0.6;
  p.search.grid_vc = p.search.grid_f = 121;
  p.K_TZ_sweep.clear();
  if (with_accuracy)
    p.accuracy->K_TZ = uniform(rng, 0.004, 0.02);
  else
    p.accuracy.reset();
  return p;
}

TEST(MachiningProperties, ValleyCostDecreasesWithFeed) {
  Rng rng(20261121);
  for (int trial = 0; trial < 20; ++trial) {
    Problem p = random_problem(rng, false);
    p.machine.P_motor = 1e6;  // only the Gilbert valley: nothing binds in vc
    p.quality.Ra_max = 1e3;
    const auto vcg = log_grid(p.search.vc_min, p.search.vc_max, 121);
    double prev = std::numeric_limits<double>::infinity();
    for (double f : log_grid(0.05, 0.6, 15)) {
      const FeedOptimum fo = best_vc_at_feed(p, 0, f, vcg);
      if (!fo.feasible) continue;
      const bool on_bound =
          std::abs(fo.vc / vcg.front() - 1) < 1e-12 || std::abs(fo.vc / vcg.back() - 1) < 1e-12;
      if (fo.binding.empty() && !on_bound) {
        // On the Gilbert speed T = T*, to the golden section's resolution (CT is flat there: a
        // relative step δ in vc moves CT by O(δ²), so vc is only resolved to ~1e-8).
        const auto& s = p.life.sets[0];
        EXPECT_NEAR(fo.T / gilbert_tool_life(s.m, 0.68, p.tool.t_change, p.tool.C_edge, 0.72), 1.0, 1e-6);
      }
      EXPECT_LT(fo.CT, prev) << "trial " << trial << " f = " << f << " y = " << p.life.sets[0].y;
      prev = fo.CT;
    }
  }
}

TEST(MachiningProperties, RefinedNeverWorseThanGridAndFeasible) {
  Rng rng(7);
  std::vector<Problem> ps = {test::load_machining_example(test::kE0), test::load_machining_example(test::kE1),
                             test::load_machining_example(test::kE2),
                             test::load_machining_example(test::kE3)};
  for (int trial = 0; trial < 12; ++trial) ps.push_back(random_problem(rng, trial % 2 == 0));
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const OptimizeResult r = optimize(ps[k]);
    if (!r.solution) {
      EXPECT_EQ(r.status, Status::infeasible);
      EXPECT_FALSE(r.grid_best);
      continue;
    }
    ASSERT_TRUE(r.grid_best);
    EXPECT_LE(r.solution->cost.total, r.grid_best->cost.total) << k;
    // Feasible to 1e-9, recomputed from scratch.
    const PointEval e = evaluate(ps[k], r.solution->vc, r.solution->f, r.set);
    EXPECT_LE(e.max_violation(), 1e-9) << k;
    EXPECT_DOUBLE_EQ(e.cost.total, r.solution->cost.total);
    // At least one active constraint or bound: no interior optimum in (vc, f) (3.3).
    const bool on_f_bound = std::abs(r.solution->f / r.f_bounds[1] - 1) < 1e-9;
    const bool on_vc_bound = std::abs(r.solution->vc / r.vc_bounds[1] - 1) < 1e-9 ||
                             std::abs(r.solution->vc / r.vc_bounds[0] - 1) < 1e-9;
    EXPECT_TRUE(!r.active.empty() || on_f_bound || on_vc_bound) << k;
    // Local optimality: small feasible moves never beat it.
    for (double dv : {-1e-4, 1e-4}) {
      for (double df : {-1e-4, 0.0, 1e-4}) {
        const PointEval q = evaluate(ps[k], r.solution->vc * (1 + dv), r.solution->f * (1 + df), r.set);
        if (q.feasible() && q.f <= r.f_bounds[1] && q.vc <= r.vc_bounds[1]) {
          EXPECT_GE(q.cost.total, r.solution->cost.total * (1 - 1e-12))
              << k << std::setprecision(17) << " q " << q.vc << " " << q.f << " " << q.cost.total << " sol "
              << r.solution->vc << " " << r.solution->f << " " << r.solution->cost.total << " bounds "
              << r.f_bounds[1] << " active " << r.active.size();
        }
      }
    }
  }
}

TEST(MachiningProperties, Fig5AgreesWithinOneGridCell) {
  const Problem e2 = test::load_machining_example(test::kE2);
  const OptimizeResult r = optimize(e2);
  for (int n : {61, 121, 241}) {
    const Fig5Result f5 = optimize_fig5(e2, n, n);
    ASSERT_TRUE(f5.found);
    const Fig5Agreement a = fig5_agreement(e2, r, f5);
    EXPECT_TRUE(a.within_one_cell_cost) << n;
    EXPECT_GE(f5.CT, r.solution->cost.total) << "the grid never beats the refined optimum";
    // Positionally within one cell on the spec's 121 grid (and the coarser one); on the 241 grid the
    // cheapest accurate grid point is 1.11 cells away in vc: the cost is flat along the accuracy limit.
    if (n <= 121)
      EXPECT_TRUE(a.within_one_cell) << n << ": " << a.cells_vc << " " << a.cells_f;
    else
      EXPECT_LT(std::max(a.cells_vc, a.cells_f), 1.5) << n;
  }
  Rng rng(99);
  int checked = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const Problem p = random_problem(rng, true);
    const OptimizeResult rr = optimize(p);
    const Fig5Result f5 = optimize_fig5(p, 121, 121);
    EXPECT_EQ(rr.solution.has_value(), f5.found) << trial;
    if (!rr.solution || !f5.found) continue;
    ++checked;
    const Fig5Agreement a = fig5_agreement(p, rr, f5);
    EXPECT_TRUE(a.within_one_cell_cost)
        << trial << ": optimize (" << rr.solution->vc << ", " << rr.solution->f << ") fig5 (" << f5.vc << ", "
        << f5.f << ") cells " << a.cells_vc << " " << a.cells_f;
  }
  EXPECT_GE(checked, 5);
}

TEST(MachiningProperties, ScalingRatesScalesCost) {
  const Problem p = test::load_machining_example(test::kE2);
  const OptimizeResult r = optimize(p);
  for (double lambda : {0.5, 3.0}) {
    Problem q = p;
    auto& R = q.econ.rates;
    R.R_AO *= lambda, R.R_Z *= lambda, R.R_Erx *= lambda, R.R_Exx *= lambda, R.R_TR *= lambda;
    q.econ.R_H *= lambda;
    q.tool.C_edge *= lambda;
    const OptimizeResult s = optimize(q);
    EXPECT_REL(s.solution->cost.total, lambda * r.solution->cost.total, 1e-9);
    EXPECT_REL(s.solution->vc, r.solution->vc, 1e-8);
    EXPECT_REL(s.solution->f, r.solution->f, 1e-8);
  }
}

TEST(MachiningProperties, ScatterLinearInToleranceAndCompliance) {
  Problem p = test::load_machining_example(test::kE2);
  p.accuracy->T_R3 = 0.0;
  const double vc = 250, f = 0.2;
  const double v1 = evaluate(p, vc, f).acc->V_rho;
  p.accuracy->TA = p.accuracy->TB = 0.8;
  EXPECT_REL(evaluate(p, vc, f).acc->V_rho, 2.0 * v1, 1e-12);
  p.accuracy->TA = p.accuracy->TB = 0.4;
  p.accuracy->bar.E *= 0.25;  // k -> k/4
  EXPECT_REL(evaluate(p, vc, f).acc->V_rho, 4.0 * v1, 1e-12);
  // Same by cubature (the reported path), to the Simpson accuracy.
  p.accuracy->bar.E *= 4.0;
  const double c1 = evaluate(p, vc, f, 0, AccuracyMethod::cubature).acc->V_rho;
  EXPECT_NEAR(c1 / v1, 1.0, 1e-5);
}

TEST(MachiningProperties, DeterministicReport) {
  const Problem p = test::load_machining_example(test::kE2);
  RunOutput a, b;
  const OptimizeResult ra = optimize(p), rb = optimize(p);
  a.problem = b.problem = &p;
  a.result = &ra;
  b.result = &rb;
  EXPECT_EQ(report_json(a).dump(), report_json(b).dump());
  EXPECT_EQ(report_svg(a), report_svg(b));
}

TEST(MachiningOptimizer, NearOptimalContoursLieOnTheirLevel) {
  const Problem p = test::load_machining_example(test::kE2);
  const OptimizeResult r = optimize(p);
  ASSERT_FALSE(r.near_optimal.empty());
  std::vector<double> seen;
  for (const ContourLine& c : r.near_optimal) {
    seen.push_back(c.delta);
    EXPECT_REL(c.level, r.solution->cost.total * (1 + c.delta), 1e-14);
    for (const auto& q : c.pts) {
      const double f = q[1] / spindle_speed_rpm(q[0], p.op.D);
      // Linear interpolation between grid nodes: the level holds to the grid's resolution.
      EXPECT_NEAR(evaluate(p, q[0], f).cost.total / c.level, 1.0, 2e-4);
    }
  }
  for (double d : {0.01, 0.02, 0.05}) EXPECT_NE(std::find(seen.begin(), seen.end(), d), seen.end()) << d;
}

TEST(MachiningOptimizer, TwoToolLifeSetsAreSolvedSeparately) {
  Problem both = test::load_machining_example(test::kE3);
  both.life.sets = {{420, 0.9, 0.2, 0.15, 0.2, 0.0, 0.3}, {350, 0.9, 0.2, 0.15, 0.35, 0.3, 0.7}};
  both.search.f_min = 0.05;
  Problem low = both, high = both;
  low.life.sets = {both.life.sets[0]};
  high.life.sets = {both.life.sets[1]};
  const OptimizeResult rb = optimize(both), rl = optimize(low), rh = optimize(high);
  ASSERT_TRUE(rb.solution && rl.solution && rh.solution);
  const bool high_wins = rh.solution->cost.total < rl.solution->cost.total;
  EXPECT_EQ(rb.set, high_wins ? 1 : 0);
  EXPECT_DOUBLE_EQ(rb.solution->cost.total, std::min(rh.solution->cost.total, rl.solution->cost.total));
  // Each set's feed stays inside its own range.
  EXPECT_LE(rl.solution->f, 0.3 + 1e-15);
  EXPECT_GE(rh.solution->f, 0.3 - 1e-15);
}

TEST(MachiningOptimizer, QuillModeTakesTheWorstSection) {
  Problem p = test::load_machining_example(test::kE2);
  Problem q = p;
  q.accuracy->bar.mode = OverhangMode::quill;
  q.accuracy->bar.L_o0 = 40.0;  // L_o(z) = 40 + z, worst at z = L = 60: same as constant 100
  q.accuracy->n_z = 7;
  const PointEval a = evaluate(p, 280, 0.2), b = evaluate(q, 280, 0.2);
  EXPECT_REL(b.acc->V_rho, a.acc->V_rho, 1e-12);
  EXPECT_DOUBLE_EQ(b.acc->z, 60.0);
  EXPECT_DOUBLE_EQ(b.acc->L_o, 100.0);
}

TEST(MachiningOptimizer, UncompensatedDeflectionAddsToAccuracy) {
  Problem p = test::load_machining_example(test::kE2);
  p.accuracy->compensate_static_deflection = false;
  const PointEval e = evaluate(p, 280, 0.2);
  EXPECT_REL(e.acc->value, e.acc->V_rho + e.acc->delta0, 1e-14);
  EXPECT_REL(e.g[static_cast<int>(ConstraintId::accuracy)].value, e.acc->value, 1e-15);
}

TEST(MachiningOptimizer, StepSpindleRoundsDown) {
  Problem p = test::load_machining_example(test::kE1);
  p.machine.spindle_steps = {1000, 1600, 2500, 3150};
  const OptimizeResult r = optimize(p);
  ASSERT_TRUE(r.solution);
  EXPECT_NEAR(r.solution->n, 2500.0, 1e-9);
  EXPECT_EQ(r.status, Status::warning);
  EXPECT_GT(r.solution->T, 22.3333);  // slower than the economic speed: longer tool life
}

// The rounded-down speed gets its feed chosen again: at the old feed E2's accuracy broke (6.243 µm
// against 6 µm, reported as the answer with a cost below the true optimum). Values from an
// independent Python search of each speed (session 47 audit): n = 2000, f = 0.1841389 mm/rev,
// CT = 1.2454700, accuracy on its limit.
TEST(MachiningOptimizer, StepSpindleChoosesTheFeedAgainWithinEveryLimit) {
  Problem p = test::load_machining_example(test::kE2);
  p.machine.spindle_steps = {500, 800, 1000, 1250, 1600, 2000, 2500, 3150, 4000};
  OptimizeResult r = optimize(p);
  ASSERT_TRUE(r.solution);
  EXPECT_EQ(r.status, Status::warning);
  EXPECT_NEAR(r.solution->n, 2000.0, 1e-9);
  EXPECT_REL(r.solution->f, 0.1841389, 1e-6);
  EXPECT_REL(r.solution->cost.total, 1.2454700, 1e-6);
  EXPECT_LE(r.solution->max_violation(), 1e-9);
  EXPECT_EQ(r.active, std::vector<std::string>{"accuracy"});
  // No step at or below n* = 2645.5 (E1): the lowest one above it, at f_Ra, with a warning.
  Problem q = test::load_machining_example(test::kE1);
  q.machine.spindle_steps = {3000, 4000};
  r = optimize(q);
  ASSERT_TRUE(r.solution);
  EXPECT_NEAR(r.solution->n, 3000.0, 1e-9);
  EXPECT_REL(r.solution->f, 0.1431084, 1e-6);
  EXPECT_LE(r.solution->max_violation(), 1e-9);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("raised from"), std::string::npos) << r.warnings.back();
  // A tool-life window no available speed can keep (n = 2500 lasts too long at any feed): none.
  q.machine.spindle_steps = {2500};
  q.search.T_min = 5.0;
  q.search.T_max = 25.0;
  r = optimize(q);
  EXPECT_EQ(r.status, Status::infeasible);
  EXPECT_FALSE(r.solution);
  ASSERT_TRUE(r.infeasible);
  EXPECT_EQ(r.infeasible->constraint, "spindle_steps");
}

// The stepped answer is checked as the answer: a step below search.vc_min is not available (E1
// with one step at 100 rpm gave vc = 12.6 m/min under vc_min = 30), and the tool-life and cubature
// warnings speak of the stepped point, not of the continuous optimum it replaced (session 49 audit).
TEST(MachiningOptimizer, StepSpindleKeepsTheSearchBoxAndWarnsOfItsOwnPoint) {
  Problem p = test::load_machining_example(test::kE1);
  p.machine.spindle_steps = {100};
  p.search.vc_min = 30;
  OptimizeResult r = optimize(p);
  EXPECT_EQ(r.status, Status::infeasible);
  ASSERT_TRUE(r.infeasible);
  EXPECT_EQ(r.infeasible->constraint, "spindle_steps");
  // E1 at 1000 rpm: T = 2894 min, beyond the 120-min window; the warning gives that T.
  p.machine.spindle_steps = {1000};
  p.search.vc_min = 0;
  r = optimize(p);
  ASSERT_TRUE(r.solution);
  EXPECT_NEAR(r.solution->n, 1000.0, 1e-9);
  const std::string life = "tool life T = " + format_fixed(r.solution->T, 2);
  EXPECT_TRUE(std::any_of(r.warnings.begin(), r.warnings.end(), [&](const std::string& w) { return w.rfind(life, 0) == 0; }))
      << life;
  // E2 (accuracy) rounded down: the cubature is taken at the stepped point, so it agrees.
  Problem q = test::load_machining_example(test::kE2);
  q.machine.spindle_steps = {1000};
  r = optimize(q);
  ASSERT_TRUE(r.solution);
  for (const std::string& w : r.warnings) EXPECT_EQ(w.find("cubature"), std::string::npos) << w;
  ASSERT_TRUE(r.V_rho_cubature);
  EXPECT_REL(*r.V_rho_cubature, r.solution->acc->V_rho, 1e-4);
}

// E2 asking 3 um of a spindle capped at 800 rpm: accuracy needs a higher speed than the spindle
// gives, and the answer says so (it named accuracy alone).
TEST(MachiningOptimizer, InfeasibleAtTheSpindlesTopSpeedNamesIt) {
  Problem p = test::load_machining_example(test::kE2);
  p.accuracy->K_TZ = 0.003;
  p.machine.n_max = 800;
  const OptimizeResult r = optimize(p);
  EXPECT_EQ(r.status, Status::infeasible);
  ASSERT_TRUE(r.infeasible);
  EXPECT_EQ(r.infeasible->constraint, "accuracy");
  EXPECT_NE(r.infeasible->message.find("spindle's top speed n_max = 800 rpm"), std::string::npos) << r.infeasible->message;
  ASSERT_FALSE(r.infeasible->suggestions.empty());
  EXPECT_NE(r.infeasible->suggestions.front().find("machine.n_max"), std::string::npos);
}

TEST(MachiningOptimizer, KienzleWithRatioRadialForce) {
  Problem p = test::load_machining_example(test::kE2);
  p.tangential.kind = ForceKind::kienzle;
  p.tangential.kienzle = {2220, 0.14};
  p.radial->kind = ForceKind::ratio;
  p.radial->k_r = 0.4;
  EXPECT_DOUBLE_EQ(radial_depth_exponent(p), 1.0);
  const PointEval e = evaluate(p, 250, 0.15);
  EXPECT_REL(e.Fc, kienzle_force_n({2220, 0.14}, 1.5, 0.15, 90), 1e-15);
  EXPECT_REL(e.Fr, 0.4 * e.Fc, 1e-15);
  EXPECT_REL(e.acc->eps, e.Fr / (1.5 * e.acc->k), 1e-14);
  const OptimizeResult r = optimize(p);
  ASSERT_TRUE(r.solution);
  EXPECT_LE(r.solution->max_violation(), 1e-9);
}

TEST(MachiningOptimizer, EmptyBoxNamesTheLimitingInputs) {
  Problem p = test::load_machining_example(test::kE1);
  p.quality.Ra_max = 0.1;  // f_Ra = 0.0358 < f_min = 0.05
  const OptimizeResult r = optimize(p);
  EXPECT_EQ(r.status, Status::infeasible);
  ASSERT_TRUE(r.infeasible);
  EXPECT_EQ(r.infeasible->constraint, "bounds");
  EXPECT_NE(r.infeasible->message.find("search.f_min"), std::string::npos) << r.infeasible->message;
  EXPECT_NE(r.infeasible->message.find("Ra_max"), std::string::npos) << r.infeasible->message;
}

// Found by fuzzing (session 39). A search box reaching down to 1e-160 (allowed: positive) puts grid
// points where the model overflows: their NaN cost compared false with everything, and the first
// of them became the "optimum" (tm = inf, CT = nan). They are skipped; the optimum is E0's.
TEST(MachiningOptimizer, PointsWhereTheModelOverflowsAreNoAnswer) {
  Problem p = test::load_machining_example(test::kE0);
  const OptimizeResult normal = optimize(p);
  ASSERT_TRUE(normal.solution);
  p.search.vc_min = p.search.f_min = 1e-160;
  const OptimizeResult r = optimize(p);
  ASSERT_TRUE(r.solution);
  EXPECT_TRUE(std::isfinite(r.solution->cost.total));
  EXPECT_NEAR(r.solution->cost.total, normal.solution->cost.total, 1e-6 * normal.solution->cost.total);
  RunOutput out;
  out.problem = &p;
  out.result = &r;
  EXPECT_EQ(report_svg(out).find("nan"), std::string::npos);
  // Nowhere finite (a bar of E = 1e-300 MPa bends without limit): infeasible, and says why.
  Problem q = test::load_machining_example(test::kE2);
  q.accuracy->bar.E = 1e-300;
  const OptimizeResult none = optimize(q);
  EXPECT_EQ(none.status, Status::infeasible);
  ASSERT_TRUE(none.infeasible);
  EXPECT_NE(none.infeasible->message.find("no finite cost or constraint value"), std::string::npos) << none.infeasible->message;
}

TEST(MachiningOptimizer, PowerCurveLimitsLowSpeeds) {
  Problem p = test::load_machining_example(test::kE3);
  p.machine.n_base = 1500;  // full power only above 1500 rpm: 76 % of it at ~1140 rpm
  const OptimizeResult r = optimize(p);
  ASSERT_TRUE(r.solution);
  EXPECT_LE(r.solution->P_demand, p.machine.P_motor * r.solution->n / 1500 * (1 + 1e-9));
  EXPECT_GT(r.solution->cost.total, 1.1866075);
}

TEST(MachiningOptimizer, NloptBackEnd) {
  for (const char* file : {test::kE2, test::kE3}) {
    const Problem p = test::load_machining_example(file);
    OptimizeParams params;
    params.method = Method::nlopt_cobyla;
    const OptimizeResult n = optimize(p, params);
    const OptimizeResult g = optimize(p);
    ASSERT_TRUE(n.solution);
    if (!nlopt_available()) {
      // Built without CUTROUTE_WITH_NLOPT: the reference method answers and says so.
      EXPECT_EQ(n.method, Method::grid_golden);
      ASSERT_FALSE(n.warnings.empty());
      EXPECT_NE(n.warnings.front().find("CUTROUTE_WITH_NLOPT"), std::string::npos);
      continue;
    }
    EXPECT_EQ(n.method, Method::nlopt_cobyla);
    // COBYLA reproduces the reference to 6 digits (MACHINING.md 5.3).
    EXPECT_NEAR(n.solution->vc / g.solution->vc, 1.0, 1e-6) << file;
    EXPECT_NEAR(n.solution->f / g.solution->f, 1.0, 1e-6) << file;
    EXPECT_NEAR(n.solution->cost.total / g.solution->cost.total, 1.0, 1e-7) << file;
    EXPECT_LE(n.solution->max_violation(), 1e-9);
  }
}

}  // namespace
}  // namespace cutroute::machining

namespace cutroute::machining {
namespace {

TEST(MachiningOptimizer, LongOverhangWarns) {
  Problem p = test::load_machining_example(test::kE2);
  EXPECT_EQ(optimize(p).status, Status::optimal);  // L_o/d = 4 exactly: at the limit, no warning
  p.accuracy->bar.L_o = 120;                       // L_o/d = 4.8 > 4 for a steel bar
  p.accuracy->K_TZ = 0.02;
  const OptimizeResult r = optimize(p);
  EXPECT_EQ(r.status, Status::warning);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("L_o/d"), std::string::npos) << r.warnings.back();
  p.accuracy->bar.E = 580000;  // carbide bar: the limit is 6
  EXPECT_EQ(optimize(p).status, Status::optimal);
}

TEST(MachiningOptimizer, ListedOrderRateMapChangesOnlyThePairing) {
  Problem p = test::load_machining_example(test::kE0);
  p.econ.rates = {0.25, 0.35, 0.04, 0.02, 0.06};
  p.econ.rate_map = RateMap::listed_order;
  const OptimizeResult r = optimize(p);
  ASSERT_TRUE(r.solution);
  // Cutting is charged at r1 = 0.6: Gilbert with r1 in place of r30.
  const double T = gilbert_tool_life(0.25, 0.68, 2.0, 3.0, 0.60);
  EXPECT_NEAR(r.solution->T / T, 1.0, 1e-6);
  EXPECT_NEAR(r.solution->cost.fixed, 1.0 * 0.72 + 0.5, 1e-12);
}

TEST(MachiningOptimizer, ToolLifeWindowIsAHardConstraint) {
  Problem p = test::load_machining_example(test::kE1);
  p.search.T_min = 30.0;  // the economic T* = 22.3 is not allowed: vc drops until T = 30
  const OptimizeResult r = optimize(p);
  ASSERT_TRUE(r.solution);
  EXPECT_NEAR(r.solution->T, 30.0, 30.0 * 1e-9);
  EXPECT_NE(std::find(r.active.begin(), r.active.end(), "tool_life_min"), r.active.end());
}

// A window narrower than a grid cell: no grid point has 40 <= T <= 40.001 min, the band lies
// between the samples. The answer must be the one the wide window [40, 60] gives (T = 40 binds in
// both), with a warning that says how it was found.
TEST(MachiningOptimizer, ToolLifeWindowNarrowerThanAGridCellIsFound) {
  Problem wide = test::load_machining_example(test::kE1);
  wide.search.T_min = 40.0;
  wide.search.T_max = 60.0;
  const OptimizeResult w = optimize(wide);
  ASSERT_TRUE(w.solution);
  Problem narrow = wide;
  narrow.search.T_max = 40.001;
  const OptimizeResult r = optimize(narrow);
  ASSERT_TRUE(r.solution) << (r.infeasible ? r.infeasible->message : "");
  EXPECT_EQ(r.status, Status::warning);
  EXPECT_FALSE(r.grid_best);
  EXPECT_GE(r.solution->T, 40.0 * (1 - 1e-9));
  EXPECT_LE(r.solution->T, 40.001 * (1 + 1e-9));
  EXPECT_NEAR(r.solution->vc / w.solution->vc, 1.0, 1e-6);
  EXPECT_NEAR(r.solution->cost.total / w.solution->cost.total, 1.0, 1e-9);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("narrower than a grid cell"), std::string::npos);
}

}  // namespace
}  // namespace cutroute::machining
