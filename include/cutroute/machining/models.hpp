// Pure machining models for boring (MACHINING.md 3.1-3.7): kinematics, tool life, forces, power,
// roughness, boring-bar stiffness and the cost-per-part formula with its closed-form optima.
#pragma once

namespace cutroute::machining {

inline constexpr double kPi = 3.14159265358979323846;

// ---- 3.1 Kinematics [std] ----
double spindle_speed_rpm(double vc_m_min, double D_mm);   // n [rev/min]
double feed_speed_mm_min(double f_mm_rev, double n_rpm);  // Vf [mm/min]
// Machining time of `passes` passes over L + l_extra at feed speed Vf [min].
double machining_time_min(int passes, double L_mm, double l_extra_mm, double Vf_mm_min);
double spindle_speed_limit_vc(double D_mm, double n_max_rpm);  // vc_max,spindle [m/min]

// ---- 3.2 Tool life [std] ----
struct TaylorLife {
  double C = 0.0;  // Taylor constant: vc for T = 1 min [m/min]
  double n = 0.0;  // Taylor exponent [-], 0 < n < 1
};
// One handbook (extended Taylor) coefficient set; valid only for f in [f_lo, f_hi].
struct HandbookLife {
  double Cv = 0.0;    // [m/min for ap, f in mm]
  double Kv = 1.0;    // product of correction factors (material, boring, tool) [-]
  double m = 0.0;     // tool-life exponent [-]
  double x = 0.0;     // depth exponent [-]
  double y = 0.0;     // feed exponent [-]
  double f_lo = 0.0;  // lower end of the set's feed range [mm/rev]
  double f_hi = 0.0;  // upper end of the set's feed range [mm/rev]
};
double taylor_life_min(const TaylorLife& t, double vc_m_min);                                     // T [min]
double handbook_life_min(const HandbookLife& h, double vc_m_min, double ap_mm, double f_mm_rev);  // T [min]
// The speed constant C_f of T = (C_f/vc)^(1/m) at fixed ap and f [m/min].
double handbook_speed_constant(const HandbookLife& h, double ap_mm, double f_mm_rev);

// ---- 3.4 Forces [std] ----
// Handbook form F = 10·Cp·ap^x·f^y·vc^n·Kp [N]; the 10 converts kgf to N (pitfall 1).
struct HandbookForce {
  double Cp = 0.0;  // [kgf for ap, f in mm, vc in m/min]
  double x = 0.0;   // depth exponent [-]
  double y = 0.0;   // feed exponent [-]
  double n = 0.0;   // speed exponent [-]
  double Kp = 1.0;  // correction factor [-]
};
struct KienzleForce {
  double kc11 = 0.0;  // specific cutting force for h = b = 1 mm [MPa]
  double mc = 0.0;    // Kienzle exponent [-]
};
double handbook_force_n(const HandbookForce& c, double ap_mm, double f_mm_rev, double vc_m_min);   // [N]
double kienzle_force_n(const KienzleForce& c, double ap_mm, double f_mm_rev, double kappa_r_deg);  // [N]

// ---- 3.5 Power [std] ----
double cutting_power_kw(double Fc_n, double vc_m_min);  // Pc [kW]
// P_motor, or P_motor·min(1, n/n_base) with a power curve (n_base_rpm <= 0: no curve) [kW].
double available_power_kw(double P_motor_kw, double n_rpm, double n_base_rpm);
double torque_nm(double Fc_n, double D_mm);  // M [N·m]

// ---- 3.6 Roughness [std] ----
double roughness_ra_um(double f_mm_rev, double r_eps_mm, double k_Ra);  // Ra [µm]
double roughness_rz_um(double f_mm_rev, double r_eps_mm, double k_Ra);  // Rz [µm]
double feed_for_ra(double Ra_max_um, double r_eps_mm, double k_Ra);     // f_Ra [mm/rev]

// ---- 3.7 Boring bar [std] ----
double bar_inertia_mm4(double d_mm, double d_in_mm);                   // I [mm^4]
double bar_stiffness_n_mm(double E_mpa, double I_mm4, double L_o_mm);  // k = 3EI/L^3 [N/mm]
double deflection_mm(double F_n, double k_n_mm);                       // δ0 = F/k [mm]

// ---- 3.3 Cost per part [paper structure, recon pairing] ----
// Rates per minute of machine work [CU/min] as the seed groups them.
struct RateInputs {
  double R_AO = 0.0;   // equipment depreciation [CU/min]
  double R_Z = 0.0;    // wages [CU/min]
  double R_Erx = 0.0;  // energy, working strokes [CU/min]
  double R_Exx = 0.0;  // energy, idle strokes [CU/min]
  double R_TR = 0.0;   // current repair [CU/min]
};
// The seed's formula (1) is lost. Its symbol order (t_m, t_serv, t_load next to r1, r2, r3) would
// pair r1 with the machining time; physically r3 (which contains the energy of working strokes)
// belongs to cutting. `physical` is the default; `listed_order` keeps the other reading available.
enum class RateMap { physical, listed_order };
struct Rates {
  double r1 = 0.0;   // machine standing (load/unload) [CU/min]
  double r2 = 0.0;   // technical service (tool changes, idle strokes) [CU/min]
  double r30 = 0.0;  // cutting without tool cost [CU/min]
};
Rates combine_rates(const RateInputs& in);

struct CostInputs {
  Rates rates;
  RateMap map = RateMap::physical;
  double C_edge = 0.0;    // cost of one cutting edge [CU]
  double t_change = 0.0;  // time to index/replace and re-offset one edge [min]
  double t_load = 0.0;    // load + unload time t_y + t_c [min]
  double R_H = 0.0;       // set-up cost per part [CU/part]
};
struct CostBreakdown {
  double total = 0.0;           // CT [CU/part]
  double cutting = 0.0;         // tm·r30 [CU]
  double tool = 0.0;            // tm·C_edge/T [CU]
  double service = 0.0;         // t_serv·r2 [CU]
  double fixed = 0.0;           // t_load·r1 + R_H [CU]
  double edges_per_part = 0.0;  // tm/T [-]
  double parts_per_edge = 0.0;  // T/tm [-]
};
CostBreakdown cost_per_part(const CostInputs& c, double tm_min, double T_min);

// ---- Closed forms (tests and hand checks rely on them) ----
// Generalised Gilbert economic tool life T* = (1/m − 1)·(r2·t_change + C_edge)/r30 [min].
double gilbert_tool_life(double m, double r2, double t_change, double C_edge, double r30);
// Maximum production rate tool life T = (1/m − 1)·t_change [min].
double max_production_tool_life(double m, double t_change);
// Tool life at the optimum when an active constraint couples f ∝ vc^β (feed exponent y) [min].
double coupled_tool_life(double m, double y, double beta, double r2, double t_change, double C_edge,
                         double r30);
// vc for a tool life T with T = (C_f/vc)^(1/m) [m/min].
double speed_for_tool_life(double C_f, double m, double T_min);

}  // namespace cutroute::machining
