// The boring problem (MACHINING.md 2 and 4): input structs with units, and the evaluation of cost,
// derived quantities and every constraint g_k = value/limit − 1 at one (vc, f).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <cutroute/machining/accuracy.hpp>
#include <cutroute/machining/models.hpp>

namespace cutroute::machining {

struct Operation {
  double D = 0.0;        // finished bore diameter [mm]
  double L = 0.0;        // bore length [mm]
  double l_extra = 3.0;  // approach + overrun [mm]
  int passes = 1;        // number of passes [-]
  double ap = 0.0;       // radial depth of cut per pass [mm]
};

struct Tool {
  double r_eps = 0.0;             // nose radius [mm]
  double kappa_r = 90.0;          // entering angle [deg]
  double C_edge = 0.0;            // cost per cutting edge [CU]
  double t_change = 0.0;          // time to index/replace and re-offset one edge [min]
  std::optional<double> F_allow;  // allowed cutting force on bar/insert; load check 0.9·F_allow [N]
};

enum class ToolLifeKind { taylor, handbook };
struct ToolLife {
  ToolLifeKind kind = ToolLifeKind::taylor;
  TaylorLife taylor;               // used when kind == taylor
  std::vector<HandbookLife> sets;  // used when kind == handbook: never mixed within one optimisation
  double warn_T_min = 5.0;         // warning below this tool life [min]
  double warn_T_max = 120.0;       // warning above this tool life [min]
  std::string source;              // provenance of the coefficients (reported only)
};

enum class ForceKind { handbook, kienzle, ratio };
struct ForceModel {
  ForceKind kind = ForceKind::handbook;
  HandbookForce handbook;  // kind == handbook
  KienzleForce kienzle;    // kind == kienzle (tangential only)
  double k_r = 0.0;        // kind == ratio (radial only): F_r = k_r·F_c [-]
};

struct Machine {
  double P_motor = 0.0;               // motor power [kW]
  double eta = 1.0;                   // drive efficiency [-]
  double n_max = 0.0;                 // spindle speed limit [rev/min]
  double Vf_max = 0.0;                // feed speed limit [mm/min]
  double n_base = 0.0;                // base speed of the power curve; 0 = constant power [rev/min]
  std::vector<double> spindle_steps;  // available speeds of a stepped spindle; empty = stepless [rev/min]
};

struct Economics {
  RateInputs rates;  // R_AO, R_Z, R_Erx, R_Exx, R_TR [CU/min]
  RateMap rate_map = RateMap::physical;
  double t_load = 0.0;  // t_y + t_c, load and unload [min]
  double R_H = 0.0;     // set-up cost per part [CU/part]
};

struct Quality {
  double Ra_max = 0.0;  // roughness limit [µm]
  double k_Ra = 1.0;    // theory-to-reality factor [-]
};

enum class OverhangMode { constant, quill };
struct Bar {
  double E = 0.0;     // Young's modulus [MPa]
  double d = 0.0;     // outer diameter [mm]
  double d_in = 0.0;  // bore of a hollow bar, 0 = solid [mm]
  double L_o = 0.0;   // overhang (Constant mode) [mm]
  OverhangMode mode = OverhangMode::constant;
  double L_o0 = 0.0;  // overhang at z = 0 (Quill mode: L_o(z) = L_o0 + z) [mm]
};
struct Accuracy {
  Bar bar;
  double TA = 0.0;    // tolerance field of the pre-hole position, coordinate A [mm]
  double TB = 0.0;    // tolerance field of the pre-hole position, coordinate B [mm]
  double T_R3 = 0.0;  // tolerance field of the pre-hole radius [mm]
  int waves = 1;      // harmonic number m of the wavy axis [-]
  double P = 0.9973;  // confidence level [-]
  double K_TZ = 0.0;  // allowed scatter field of the radius vector [mm]
  bool compensate_static_deflection = true;
  int n_phi = 36;                     // angular positions of the radius vector [-]
  int n_z = 1;                        // sections along the bore (used when L_o varies with z) [-]
  CubatureParams cubature;            // Simpson m, n (64, 64) over (A, θ)
  std::optional<double> delta_allow;  // optional static-deflection limit [mm]
};

struct Search {
  double vc_min = 0.0;          // [m/min]
  double vc_max = 0.0;          // [m/min]
  double f_min = 0.0;           // [mm/rev]
  double f_max = 0.0;           // [mm/rev]
  int grid_vc = 241;            // grid points along vc [-]
  int grid_f = 241;             // grid points along f [-]
  std::optional<double> T_min;  // tool-life window, lower end (a hard constraint when given) [min]
  std::optional<double> T_max;  // tool-life window, upper end [min]
};

struct Problem {
  std::string name;
  Operation op;
  Tool tool;
  ToolLife life;
  ForceModel tangential;
  std::optional<ForceModel> radial;  // required when accuracy is given
  Machine machine;
  Economics econ;
  Quality quality;
  std::optional<Accuracy> accuracy;
  Search search;
  std::vector<double> K_TZ_sweep;  // optional cost-of-accuracy sweep values [mm]
};

// Every constraint of MACHINING.md 4; the optional ones are disabled unless their input is present.
enum class ConstraintId {
  power,
  roughness,
  spindle,
  feedrate,
  accuracy,
  tool_life_min,
  tool_life_max,
  load,
  deflection
};
inline constexpr int kConstraintCount = 9;
const char* to_string(ConstraintId c);

struct ConstraintValue {
  bool enabled = false;
  double value = 0.0;  // the constrained quantity (unit of the row: kW, µm, rpm, mm/min, mm, min, N, mm)
  double limit = 0.0;  // its limit, same unit
  double g = 0.0;      // value/limit − 1 (limit/value − 1 for lower bounds); feasible when <= tol
};

// Accuracy chain at the worst section z (MACHINING.md 3.8).
struct AccuracyValues {
  double k = 0.0;        // bar tip stiffness [N/mm]
  double delta0 = 0.0;   // static deflection F_r/k [mm]
  double eps = 0.0;      // error-copying coefficient [-]
  double sigma_e = 0.0;  // Rayleigh parameter of the pre-hole eccentricity [mm]
  double sigma_A = 0.0;  // Rayleigh parameter of the bored-axis displacement [mm]
  double S_A = 0.0;      // standard deviation of the amplitude [mm]
  double sigma_r = 0.0;  // radius scatter copied from the pre-hole radius [mm]
  double V_rho = 0.0;    // scatter field of the radius vector [mm]
  double value = 0.0;    // V_rho (+ |δ0| when not compensated): what K_TZ limits [mm]
  double z = 0.0;        // section where the value is largest [mm]
  double L_o = 0.0;      // overhang at that section [mm]
};

// Everything known at one (vc, f) for one tool-life set.
struct PointEval {
  double vc = 0.0;        // cutting speed [m/min]
  double f = 0.0;         // feed [mm/rev]
  double n = 0.0;         // spindle speed [rev/min]
  double Vf = 0.0;        // feed speed [mm/min]
  double tm = 0.0;        // machining time [min]
  double T = 0.0;         // tool life [min]
  CostBreakdown cost;     // CT and its parts [CU]
  double Fc = 0.0;        // tangential force [N]
  double Fr = 0.0;        // radial force [N] (0 without a radial model)
  double Pc = 0.0;        // cutting power [kW]
  double P_demand = 0.0;  // Pc/η [kW]
  double P_avail = 0.0;   // available power at n [kW]
  double M = 0.0;         // torque [N·m]
  double Ra = 0.0;        // [µm]
  double Rz = 0.0;        // [µm]
  std::optional<AccuracyValues> acc;
  std::array<ConstraintValue, kConstraintCount> g{};

  double max_violation() const;  // max g over enabled constraints (<= tol: feasible)
  bool feasible() const;         // every enabled g <= tol::kConstraintSlackRel
  ConstraintId worst() const;    // the enabled constraint with the largest g
};

// How an accuracy value is computed: the exact closed form max_φ var = σ_A² (search) or the full
// Simpson cubature over n_phi angles (reported optimum, cross-checks).
enum class AccuracyMethod { closed_form, cubature };

// Checks every validity rule of the schema (docs/MACHINING-SCHEMA.md); one readable message per
// defect, each naming the field by its JSON path; empty when valid.
std::vector<std::string> validate(const Problem& p);

// Evaluates cost, forces, power, roughness, accuracy and every constraint at (vc, f) using tool-life
// set `set` (index into life.sets; ignored for Taylor).
PointEval evaluate(const Problem& p, double vc, double f, int set = 0,
                   AccuracyMethod method = AccuracyMethod::closed_form);

// Feed range [f_lo, f_hi] of tool-life set `set` ([0, +inf) for Taylor) [mm/rev].
std::array<double, 2> life_feed_range(const Problem& p, int set);
int life_set_count(const Problem& p);

// Depth exponent x_r of the radial force: dF_r/dap = x_r·F_r/ap.
double radial_depth_exponent(const Problem& p);

}  // namespace cutroute::machining
