#include <cutroute/machining/models.hpp>

#include <algorithm>
#include <cmath>

namespace cutroute::machining {

double spindle_speed_rpm(double vc_m_min, double D_mm) { return 1000.0 * vc_m_min / (kPi * D_mm); }
double feed_speed_mm_min(double f_mm_rev, double n_rpm) { return f_mm_rev * n_rpm; }
double machining_time_min(int passes, double L_mm, double l_extra_mm, double Vf_mm_min) {
  return static_cast<double>(passes) * (L_mm + l_extra_mm) / Vf_mm_min;
}
double spindle_speed_limit_vc(double D_mm, double n_max_rpm) { return kPi * D_mm * n_max_rpm / 1000.0; }

double taylor_life_min(const TaylorLife& t, double vc_m_min) { return std::pow(t.C / vc_m_min, 1.0 / t.n); }

double handbook_speed_constant(const HandbookLife& h, double ap_mm, double f_mm_rev) {
  return h.Cv * h.Kv / (std::pow(ap_mm, h.x) * std::pow(f_mm_rev, h.y));
}
double handbook_life_min(const HandbookLife& h, double vc_m_min, double ap_mm, double f_mm_rev) {
  return std::pow(handbook_speed_constant(h, ap_mm, f_mm_rev) / vc_m_min, 1.0 / h.m);
}

double handbook_force_n(const HandbookForce& c, double ap_mm, double f_mm_rev, double vc_m_min) {
  return 10.0 * c.Cp * std::pow(ap_mm, c.x) * std::pow(f_mm_rev, c.y) * std::pow(vc_m_min, c.n) * c.Kp;
}
double kienzle_force_n(const KienzleForce& c, double ap_mm, double f_mm_rev, double kappa_r_deg) {
  const double s = std::sin(kappa_r_deg * kPi / 180.0);
  const double h = f_mm_rev * s;
  const double b = ap_mm / s;
  return c.kc11 * b * std::pow(h, 1.0 - c.mc);
}

double cutting_power_kw(double Fc_n, double vc_m_min) { return Fc_n * vc_m_min / 60000.0; }
double available_power_kw(double P_motor_kw, double n_rpm, double n_base_rpm) {
  if (n_base_rpm <= 0.0) return P_motor_kw;
  return P_motor_kw * std::min(1.0, n_rpm / n_base_rpm);
}
double torque_nm(double Fc_n, double D_mm) { return Fc_n * D_mm / 2000.0; }

double roughness_ra_um(double f_mm_rev, double r_eps_mm, double k_Ra) {
  return k_Ra * 1000.0 * f_mm_rev * f_mm_rev / (32.0 * r_eps_mm);
}
double roughness_rz_um(double f_mm_rev, double r_eps_mm, double k_Ra) {
  return k_Ra * 1000.0 * f_mm_rev * f_mm_rev / (8.0 * r_eps_mm);
}
double feed_for_ra(double Ra_max_um, double r_eps_mm, double k_Ra) {
  return std::sqrt(32.0 * r_eps_mm * Ra_max_um / (1000.0 * k_Ra));
}

double bar_inertia_mm4(double d_mm, double d_in_mm) {
  return kPi * (std::pow(d_mm, 4) - std::pow(d_in_mm, 4)) / 64.0;
}
double bar_stiffness_n_mm(double E_mpa, double I_mm4, double L_o_mm) {
  return 3.0 * E_mpa * I_mm4 / (L_o_mm * L_o_mm * L_o_mm);
}
double deflection_mm(double F_n, double k_n_mm) { return F_n / k_n_mm; }

Rates combine_rates(const RateInputs& in) {
  Rates r;
  r.r1 = in.R_AO + in.R_Z;
  r.r2 = in.R_AO + in.R_Z + in.R_Exx + in.R_TR;
  r.r30 = in.R_AO + in.R_Z + in.R_Erx + in.R_Exx + in.R_TR;
  return r;
}

CostBreakdown cost_per_part(const CostInputs& c, double tm_min, double T_min) {
  CostBreakdown b;
  b.edges_per_part = tm_min / T_min;
  b.parts_per_edge = T_min / tm_min;
  const double t_serv = c.t_change * b.edges_per_part;
  // The tool cost R_RI = C_edge/T is a rate per minute of cutting in either map.
  b.tool = b.edges_per_part * c.C_edge;
  b.service = t_serv * c.rates.r2;
  if (c.map == RateMap::physical) {
    b.cutting = tm_min * c.rates.r30;
    b.fixed = c.t_load * c.rates.r1 + c.R_H;
  } else {
    b.cutting = tm_min * c.rates.r1;
    b.fixed = c.t_load * c.rates.r30 + c.R_H;
  }
  b.total = b.cutting + b.tool + b.service + b.fixed;
  return b;
}

double gilbert_tool_life(double m, double r2, double t_change, double C_edge, double r30) {
  return (1.0 / m - 1.0) * (r2 * t_change + C_edge) / r30;
}
double max_production_tool_life(double m, double t_change) { return (1.0 / m - 1.0) * t_change; }
double coupled_tool_life(double m, double y, double beta, double r2, double t_change, double C_edge,
                         double r30) {
  return ((1.0 + y * beta) / (m * (1.0 + beta)) - 1.0) * (r2 * t_change + C_edge) / r30;
}
double speed_for_tool_life(double C_f, double m, double T_min) { return C_f / std::pow(T_min, m); }

}  // namespace cutroute::machining
