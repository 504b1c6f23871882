// validate(): every validity rule of the input schema (docs/MACHINING-SCHEMA.md), messages name the
// JSON path of the offending field.
#include <cmath>
#include <string>
#include <vector>

#include <cutroute/machining/problem.hpp>

#include "machining/format.hpp"

namespace cutroute::machining {

namespace {

constexpr double kMaxCubatureWork = 2.0e8;
constexpr double kMaxLengthMm = 1.0e5;   // bore diameter and length: 100 m
constexpr std::size_t kMaxSweep = 100;   // K_TZ_sweep values
constexpr double kMaxGridWork = 5.0e7;   // grid points evaluated in all (4.4 million a second)
constexpr double kMaxMotorKw = 1000.0;   // spindle power: machining centres have 5-100 kW

struct Checker {
  std::vector<std::string> out;
  void positive(const char* path, double v) {
    if (!(std::isfinite(v) && v > 0.0))
      out.push_back(std::string(path) + " must be a positive number, got " + fmt_exact(v));
  }
  // Also no larger than `most`: beyond it the model's values overflow (a bore of 1e300 mm turned at
  // 0 rpm for an infinite time) long before any machining centre could take the part.
  void positive_upto(const char* path, double v, double most, const char* unit) {
    positive(path, v);
    if (std::isfinite(v) && v > most) out.push_back(std::string(path) + " must be at most " + fmt(most) + " " + unit + ", got " + fmt_exact(v));
  }
  void non_negative(const char* path, double v) {
    if (!(std::isfinite(v) && v >= 0.0)) out.push_back(std::string(path) + " must be >= 0, got " + fmt_exact(v));
  }
  void finite(const char* path, double v) {
    if (!std::isfinite(v)) out.push_back(std::string(path) + " must be a finite number, got " + fmt_exact(v));
  }
  void open_unit(const char* path, double v) {
    if (!(v > 0.0 && v < 1.0)) out.push_back(std::string(path) + " must lie in (0, 1), got " + fmt_exact(v));
  }
  void rule(bool ok, std::string msg) {
    if (!ok) out.push_back(std::move(msg));
  }
};

void check_force(Checker& c, const ForceModel& m, const std::string& path, bool radial) {
  switch (m.kind) {
    case ForceKind::handbook:
      c.positive((path + ".Cp").c_str(), m.handbook.Cp);
      c.finite((path + ".x").c_str(), m.handbook.x);
      c.finite((path + ".y").c_str(), m.handbook.y);
      c.finite((path + ".n").c_str(), m.handbook.n);
      c.positive((path + ".Kp").c_str(), m.handbook.Kp);
      break;
    case ForceKind::kienzle:
      c.rule(
          !radial,
          path + ".model: 'kienzle' is a tangential model; use 'handbook' or 'ratio' for the radial force");
      c.positive((path + ".kc11").c_str(), m.kienzle.kc11);
      c.rule(m.kienzle.mc >= 0.0 && m.kienzle.mc < 1.0,
             path + ".mc must lie in [0, 1), got " + fmt_exact(m.kienzle.mc));
      break;
    case ForceKind::ratio:
      c.rule(radial, path + ".model: 'ratio' is a radial model (F_r = k_r*F_c)");
      c.positive((path + ".k_r").c_str(), m.k_r);
      break;
  }
}

}  // namespace

std::vector<std::string> validate(const Problem& p) {
  Checker c;
  c.positive_upto("operation.D", p.op.D, kMaxLengthMm, "mm");
  c.positive_upto("operation.L", p.op.L, kMaxLengthMm, "mm");
  c.non_negative("operation.l_extra", p.op.l_extra);
  c.rule(!(p.op.l_extra > kMaxLengthMm), "operation.l_extra must be at most " + fmt(kMaxLengthMm) + " mm, got " + fmt_exact(p.op.l_extra));
  c.rule(p.op.passes >= 1, "operation.passes must be >= 1, got " + std::to_string(p.op.passes));
  c.positive("operation.ap", p.op.ap);
  c.rule(!(p.op.ap >= p.op.D / 2.0), "operation.ap must be smaller than the radius D/2");

  c.positive("tool.r_eps", p.tool.r_eps);
  // Unit slips (a value in µm or W where the schema wants mm or kW) give numbers no bore or machine
  // can have; they are refused by name rather than solved (r_eps = 400 on a 40-mm bore was).
  c.rule(!(p.tool.r_eps >= p.op.D / 2.0), "tool.r_eps must be smaller than the bore radius D/2 = " + fmt(p.op.D / 2.0) +
                                              " mm, got " + fmt_exact(p.tool.r_eps) + " (r_eps is in mm: 0.4 mm, not 400 um)");
  // At 180 degrees the edge lies along the feed: sin(kappa_r) is 1e-16, the chip 1e-16 times the
  // feed and the Kienzle force beyond any machine (found by fuzzing, session 39).
  c.rule(p.tool.kappa_r > 0.0 && p.tool.kappa_r < 180.0,
         "tool.kappa_r must lie in (0, 180) degrees, got " + fmt_exact(p.tool.kappa_r));
  c.non_negative("tool.C_edge", p.tool.C_edge);
  c.non_negative("tool.t_change", p.tool.t_change);
  if (p.tool.F_allow) c.positive("tool.F_allow", *p.tool.F_allow);

  if (p.life.kind == ToolLifeKind::taylor) {
    c.positive("tool_life.C", p.life.taylor.C);
    c.open_unit("tool_life.n", p.life.taylor.n);
  } else {
    c.rule(!p.life.sets.empty(), "tool_life.sets must hold at least one coefficient set");
    for (std::size_t i = 0; i < p.life.sets.size(); ++i) {
      const auto& s = p.life.sets[i];
      const std::string at = "tool_life.sets[" + std::to_string(i) + "]";
      c.positive((at + ".Cv").c_str(), s.Cv);
      c.positive((at + ".Kv").c_str(), s.Kv);
      c.open_unit((at + ".m").c_str(), s.m);
      c.finite((at + ".x").c_str(), s.x);
      c.rule(s.y >= 0.0 && s.y < 1.0, at + ".y must lie in [0, 1), got " + fmt_exact(s.y));
      c.rule(s.f_lo >= 0.0 && s.f_lo < s.f_hi, at + ".f_range must be [lo, hi] with 0 <= lo < hi");
    }
  }
  c.rule(p.life.warn_T_min < p.life.warn_T_max, "tool_life.warn_window must be [lo, hi] with lo < hi");

  check_force(c, p.tangential, "force.tangential", false);
  if (p.radial) check_force(c, *p.radial, "force.radial", true);

  c.positive("machine.P_motor", p.machine.P_motor);
  c.rule(!(p.machine.P_motor > kMaxMotorKw), "machine.P_motor must be at most " + fmt(kMaxMotorKw) + " kW, got " +
                                                 fmt_exact(p.machine.P_motor) + " (P_motor is in kW: 7.5 kW, not 7500 W)");
  c.rule(p.machine.eta > 0.0 && p.machine.eta <= 1.0,
         "machine.eta must lie in (0, 1], got " + fmt_exact(p.machine.eta));
  c.positive("machine.n_max", p.machine.n_max);
  c.positive("machine.Vf_max", p.machine.Vf_max);
  c.non_negative("machine.n_base", p.machine.n_base);
  // Available spindle speeds; one of 1e-300 rpm rounded the optimum down to a cost of 1e302.
  for (double s : p.machine.spindle_steps)
    c.rule(std::isfinite(s) && s >= 1.0, "machine.spindle_steps[] are spindle speeds of at least 1 rpm, got " + fmt_exact(s));

  c.non_negative("rates.R_AO", p.econ.rates.R_AO);
  c.non_negative("rates.R_Z", p.econ.rates.R_Z);
  c.non_negative("rates.R_Erx", p.econ.rates.R_Erx);
  c.non_negative("rates.R_Exx", p.econ.rates.R_Exx);
  c.non_negative("rates.R_TR", p.econ.rates.R_TR);
  c.non_negative("rates.t_load", p.econ.t_load);
  c.non_negative("rates.R_H", p.econ.R_H);
  c.rule(combine_rates(p.econ.rates).r30 > 0.0, "rates: r30 = R_AO + R_Z + R_Erx + R_Exx + R_TR must be > 0");

  c.positive("quality.Ra_max", p.quality.Ra_max);
  c.positive("quality.k_Ra", p.quality.k_Ra);

  if (p.accuracy) {
    const Accuracy& a = *p.accuracy;
    c.rule(p.radial.has_value(), "force.radial is required when accuracy is given");
    c.positive("accuracy.bar.E", a.bar.E);
    c.positive("accuracy.bar.d", a.bar.d);
    c.rule(a.bar.d_in >= 0.0 && a.bar.d_in < a.bar.d, "accuracy.bar.d_in must lie in [0, d)");
    if (a.bar.mode == OverhangMode::constant)
      c.positive("accuracy.bar.L_o", a.bar.L_o);
    else
      c.positive("accuracy.bar.L_o0", a.bar.L_o0);
    c.non_negative("accuracy.blank.TA", a.TA);
    c.non_negative("accuracy.blank.TB", a.TB);
    c.non_negative("accuracy.blank.T_R3", a.T_R3);
    c.rule(a.waves >= 1, "accuracy.waves must be >= 1");
    c.open_unit("accuracy.P", a.P);
    c.positive("accuracy.K_TZ", a.K_TZ);
    c.rule(!(a.K_TZ >= p.op.D / 10.0), "accuracy.K_TZ must be below D/10 = " + fmt(p.op.D / 10.0) +
                                           " mm, coarser than any ISO tolerance grade, got " + fmt_exact(a.K_TZ) +
                                           " (K_TZ is in mm: 6 um is 0.006)");
    c.rule(a.n_phi >= 1 && a.n_phi <= 3600, "accuracy.integration.n_phi must lie in [1, 3600]");
    c.rule(a.n_z >= 1 && a.n_z <= 1000, "accuracy.integration.n_z must lie in [1, 1000]");
    c.rule(a.cubature.m >= 2 && a.cubature.m % 2 == 0 && a.cubature.m <= 4096,
           "accuracy.integration.simpson_m must be even and in [2, 4096]");
    c.rule(a.cubature.n >= 2 && a.cubature.n % 2 == 0 && a.cubature.n <= 4096,
           "accuracy.integration.simpson_n must be even and in [2, 4096]");
    // Each field alone may be large; together they set the cubature's work (the default 36 * 1 * 64 * 64
    // takes milliseconds). 3600 * 1000 * 4096 * 4096 ran for minutes and did not stop on SIGTERM.
    c.rule(static_cast<double>(a.n_phi) * a.n_z * a.cubature.m * a.cubature.n <= kMaxCubatureWork,
           "accuracy.integration: n_phi * n_z * simpson_m * simpson_n must be at most 2e8");
    if (a.delta_allow) c.positive("accuracy.delta_allow", *a.delta_allow);
  }

  c.positive("search.vc_min", p.search.vc_min);
  c.positive("search.vc_max", p.search.vc_max);
  c.positive("search.f_min", p.search.f_min);
  c.positive("search.f_max", p.search.f_max);
  c.rule(!(p.search.vc_min > p.search.vc_max), "search.vc_min must not exceed search.vc_max");
  c.rule(!(p.search.f_min > p.search.f_max), "search.f_min must not exceed search.f_max");
  c.rule(p.search.grid_vc >= 3 && p.search.grid_vc <= 4001 && p.search.grid_f >= 3 && p.search.grid_f <= 4001,
         "search.grid must be [n_vc, n_f] with 3 <= n <= 4001");
  if (p.search.T_min) c.positive("search.T_window[0]", *p.search.T_min);
  if (p.search.T_max) c.positive("search.T_window[1]", *p.search.T_max);
  if (p.search.T_min && p.search.T_max) {
    c.rule(*p.search.T_min < *p.search.T_max, "search.T_window must be [lo, hi] with lo < hi");
  }
  for (double K : p.K_TZ_sweep) {
    c.positive("accuracy.K_TZ_sweep[]", K);
    c.rule(!(K >= p.op.D / 10.0), "accuracy.K_TZ_sweep[] must be below D/10 = " + fmt(p.op.D / 10.0) + " mm, got " + fmt_exact(K) +
                                      " (K_TZ is in mm)");
  }
  c.rule(p.K_TZ_sweep.size() <= kMaxSweep, "accuracy.K_TZ_sweep holds at most " + std::to_string(kMaxSweep) + " values, got " +
                                               std::to_string(p.K_TZ_sweep.size()));
  // Each sweep value repeats the whole grid search: a 4001 x 4001 grid with 12 values took 47 s
  // and 0.9 GB, with 40 values and two transitions more than 6 minutes.
  const double sets = p.life.kind == ToolLifeKind::taylor ? 1.0 : static_cast<double>(std::max<std::size_t>(1, p.life.sets.size()));
  c.rule(static_cast<double>(p.search.grid_vc) * p.search.grid_f * sets * (1.0 + static_cast<double>(p.K_TZ_sweep.size())) <= kMaxGridWork,
         "search.grid: n_vc * n_f * (tool-life sets) * (1 + K_TZ_sweep values) must be at most " + fmt(kMaxGridWork) +
             " grid points (about 10 s)");
  c.rule(p.K_TZ_sweep.empty() || p.accuracy.has_value(), "accuracy.K_TZ_sweep needs the accuracy section");
  return c.out;
}

}  // namespace cutroute::machining
