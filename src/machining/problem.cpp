#include <cutroute/machining/problem.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <cutroute/core/tolerances.hpp>

namespace cutroute::machining {

const char* to_string(ConstraintId c) {
  switch (c) {
    case ConstraintId::power:
      return "power";
    case ConstraintId::roughness:
      return "roughness";
    case ConstraintId::spindle:
      return "spindle";
    case ConstraintId::feedrate:
      return "feedrate";
    case ConstraintId::accuracy:
      return "accuracy";
    case ConstraintId::tool_life_min:
      return "tool_life_min";
    case ConstraintId::tool_life_max:
      return "tool_life_max";
    case ConstraintId::load:
      return "load";
    case ConstraintId::deflection:
      return "deflection";
  }
  return "?";
}

double PointEval::max_violation() const {
  double worst_g = -std::numeric_limits<double>::infinity();
  for (const auto& c : g) {
    if (c.enabled)
      worst_g = std::max(worst_g, std::isnan(c.g) ? std::numeric_limits<double>::infinity() : c.g);
  }
  return worst_g;
}
bool PointEval::feasible() const { return max_violation() <= tol::kConstraintSlackRel; }
ConstraintId PointEval::worst() const {
  int best = 0;
  double worst_g = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < kConstraintCount; ++i) {
    if (g[i].enabled && g[i].g > worst_g) {
      worst_g = g[i].g;
      best = i;
    }
  }
  return static_cast<ConstraintId>(best);
}

int life_set_count(const Problem& p) {
  return p.life.kind == ToolLifeKind::taylor ? 1 : static_cast<int>(p.life.sets.size());
}
std::array<double, 2> life_feed_range(const Problem& p, int set) {
  if (p.life.kind == ToolLifeKind::taylor) return {0.0, std::numeric_limits<double>::infinity()};
  const auto& s = p.life.sets.at(static_cast<std::size_t>(set));
  return {s.f_lo, s.f_hi};
}

namespace {

double tangential_force(const Problem& p, double f, double vc) {
  switch (p.tangential.kind) {
    case ForceKind::handbook:
      return handbook_force_n(p.tangential.handbook, p.op.ap, f, vc);
    case ForceKind::kienzle:
      return kienzle_force_n(p.tangential.kienzle, p.op.ap, f, p.tool.kappa_r);
    case ForceKind::ratio:
      break;
  }
  return 0.0;
}

double radial_force(const Problem& p, double Fc, double f, double vc) {
  if (!p.radial) return 0.0;
  switch (p.radial->kind) {
    case ForceKind::handbook:
      return handbook_force_n(p.radial->handbook, p.op.ap, f, vc);
    case ForceKind::ratio:
      return p.radial->k_r * Fc;
    case ForceKind::kienzle:
      break;
  }
  return 0.0;
}

void set_upper(ConstraintValue& c, double value, double limit) {
  c.enabled = true;
  c.value = value;
  c.limit = limit;
  c.g = value / limit - 1.0;
}
void set_lower(ConstraintValue& c, double value, double limit) {
  c.enabled = true;
  c.value = value;
  c.limit = limit;
  c.g = limit / value - 1.0;
}

// The scatter chain of MACHINING.md 3.8 at every section z; keeps the worst section.
AccuracyValues accuracy_chain(const Problem& p, const Accuracy& a, double Fr, AccuracyMethod method) {
  const double I = bar_inertia_mm4(a.bar.d, a.bar.d_in);
  const double x_r = radial_depth_exponent(p);
  const double z_p = z_two_sided(a.P);
  const double r = p.op.D / 2.0;
  const int nz = std::max(1, a.n_z);
  AccuracyValues worst;
  worst.value = -1.0;
  for (int j = 0; j < nz; ++j) {
    // With one section the longest overhang (z = L) is the conservative choice.
    const double z = nz == 1 ? p.op.L : p.op.L * j / (nz - 1);
    AccuracyValues v;
    v.z = z;
    v.L_o = a.bar.mode == OverhangMode::constant ? a.bar.L_o : a.bar.L_o0 + z;
    v.k = bar_stiffness_n_mm(a.bar.E, I, v.L_o);
    v.delta0 = deflection_mm(Fr, v.k);
    v.eps = error_copying(x_r, Fr, p.op.ap, v.k);
    v.sigma_e = eccentricity_sigma(a.TA, a.TB);
    v.sigma_A = v.eps * v.sigma_e;
    v.S_A = kRayleighSdFactor * v.sigma_A;
    v.sigma_r = v.eps * a.T_R3 / 6.0;
    const double max_var = method == AccuracyMethod::closed_form
                               ? v.sigma_A * v.sigma_A
                               : max_rho_variance(r, v.sigma_A, a.n_phi, a.cubature);
    v.V_rho = scatter_field(z_p, max_var, v.sigma_r);
    v.value = v.V_rho + (a.compensate_static_deflection ? 0.0 : std::abs(v.delta0));
    if (v.value > worst.value) worst = v;
    // Nothing varies along z in Constant mode: one section is the whole answer.
    if (a.bar.mode == OverhangMode::constant) break;
  }
  return worst;
}

}  // namespace

double radial_depth_exponent(const Problem& p) {
  if (!p.radial) return 0.0;
  if (p.radial->kind == ForceKind::handbook) return p.radial->handbook.x;
  // Ratio model: F_r follows the tangential force's depth exponent (1 for Kienzle: F_c ∝ ap).
  return p.tangential.kind == ForceKind::handbook ? p.tangential.handbook.x : 1.0;
}

PointEval evaluate(const Problem& p, double vc, double f, int set, AccuracyMethod method) {
  PointEval e;
  e.vc = vc;
  e.f = f;
  e.n = spindle_speed_rpm(vc, p.op.D);
  e.Vf = feed_speed_mm_min(f, e.n);
  e.tm = machining_time_min(p.op.passes, p.op.L, p.op.l_extra, e.Vf);
  e.T = p.life.kind == ToolLifeKind::taylor
            ? taylor_life_min(p.life.taylor, vc)
            : handbook_life_min(p.life.sets.at(static_cast<std::size_t>(set)), vc, p.op.ap, f);
  CostInputs ci;
  ci.rates = combine_rates(p.econ.rates);
  ci.map = p.econ.rate_map;
  ci.C_edge = p.tool.C_edge;
  ci.t_change = p.tool.t_change;
  ci.t_load = p.econ.t_load;
  ci.R_H = p.econ.R_H;
  e.cost = cost_per_part(ci, e.tm, e.T);

  e.Fc = tangential_force(p, f, vc);
  e.Fr = radial_force(p, e.Fc, f, vc);
  e.Pc = cutting_power_kw(e.Fc, vc);
  e.P_demand = e.Pc / p.machine.eta;
  e.P_avail = available_power_kw(p.machine.P_motor, e.n, p.machine.n_base);
  e.M = torque_nm(e.Fc, p.op.D);
  e.Ra = roughness_ra_um(f, p.tool.r_eps, p.quality.k_Ra);
  e.Rz = roughness_rz_um(f, p.tool.r_eps, p.quality.k_Ra);

  auto& g = e.g;
  set_upper(g[static_cast<int>(ConstraintId::power)], e.P_demand, e.P_avail);
  set_upper(g[static_cast<int>(ConstraintId::roughness)], e.Ra, p.quality.Ra_max);
  set_upper(g[static_cast<int>(ConstraintId::spindle)], e.n, p.machine.n_max);
  set_upper(g[static_cast<int>(ConstraintId::feedrate)], e.Vf, p.machine.Vf_max);
  if (p.accuracy) {
    e.acc = accuracy_chain(p, *p.accuracy, e.Fr, method);
    set_upper(g[static_cast<int>(ConstraintId::accuracy)], e.acc->value, p.accuracy->K_TZ);
    if (p.accuracy->delta_allow) {
      set_upper(g[static_cast<int>(ConstraintId::deflection)], std::abs(e.acc->delta0),
                *p.accuracy->delta_allow);
    }
  }
  if (p.search.T_min) set_lower(g[static_cast<int>(ConstraintId::tool_life_min)], e.T, *p.search.T_min);
  if (p.search.T_max) set_upper(g[static_cast<int>(ConstraintId::tool_life_max)], e.T, *p.search.T_max);
  if (p.tool.F_allow) set_upper(g[static_cast<int>(ConstraintId::load)], e.Fc, 0.9 * *p.tool.F_allow);
  return e;
}

}  // namespace cutroute::machining
