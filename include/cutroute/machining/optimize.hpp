// The machining-conditions optimizer (MACHINING.md 5): log grid + bisected feasible vc-interval +
// golden section (default), the seed's two-stage Fig. 5 search, the optional NLopt COBYLA back end,
// the valley vc*(f), near-optimal contours and the cost-of-accuracy sweep.
//
// optimize() per tool-life set (sets are never mixed, 3.2):
//   1. bounds: vc in [vc_min, min(vc_max, vc_spindle)], f in [f_min, min(f_max, f_Ra, set range)];
//   2. grid: evaluate CT and every constraint on a log grid, keep the cheapest feasible point;
//   3. refine: golden section on f over [f0/s, f0·s] (s = two grid steps), where each f is scored by
//      best_vc_at_feed() (feasible vc-interval by bisection, then golden section on CT);
//   4. report: the better set's point, the constraint table, the valley and the contours.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <cutroute/machining/problem.hpp>

namespace cutroute::machining {

enum class Status { optimal, infeasible, warning };
const char* to_string(Status s);

enum class Method { grid_golden, nlopt_cobyla };
const char* to_string(Method m);
bool nlopt_available();  // true when built with CUTROUTE_WITH_NLOPT

struct OptimizeParams {
  int grid_vc = 0;     // grid points along vc; 0 = problem.search.grid_vc [-]
  int grid_f = 0;      // grid points along f; 0 = problem.search.grid_f [-]
  bool refine = true;  // golden-section refinement after the grid
  Method method = Method::grid_golden;
  int valley_points = 25;  // samples of vc*(f) across the feed range (0 = none) [-]
  std::vector<double> near_optimal_deltas{0.01, 0.02, 0.05};  // contour levels CT*·(1 + δ) [-]
  bool keep_surface = true;         // return the cost surface on the grid (for plots and CSV)
  bool cubature_at_optimum = true;  // full Simpson cubature for the reported accuracy
};

// The constrained best cutting speed at one feed (a point of the valley vc*(f)).
struct FeedOptimum {
  bool feasible = false;
  double f = 0.0;                    // [mm/rev]
  double vc = 0.0;                   // [m/min]
  double CT = 0.0;                   // [CU/part]
  double T = 0.0;                    // [min]
  std::vector<std::string> binding;  // active constraints there (empty: the Gilbert speed)
  int set = 0;                       // tool-life set
};

struct ContourLine {
  double delta = 0.0;                      // CT = CT*·(1 + delta) [-]
  double level = 0.0;                      // [CU/part]
  std::vector<std::array<double, 2>> pts;  // (vc [m/min], Vf [mm/min])
  bool closed = false;
};

// CT and feasibility on the search grid of one tool-life set.
struct Surface {
  int set = 0;
  std::vector<double> vc;               // [m/min], size nx
  std::vector<double> f;                // [mm/rev], size ny
  std::vector<double> CT;               // [CU/part], CT[j·nx + i] at (vc[i], f[j])
  std::vector<unsigned char> feasible;  // same layout
  std::vector<signed char> worst;       // worst constraint id at infeasible points, −1 when feasible
};

struct Infeasibility {
  std::string constraint;                // least-violated constraint at its best point
  double violation = 0.0;                // its g there [-]
  double vc = 0.0;                       // that point [m/min]
  double f = 0.0;                        // [mm/rev]
  std::string message;                   // readable summary, names the limiting inputs
  std::vector<std::string> suggestions;  // remedies (MACHINING.md 5.1 step 2)
};

struct OptimizeResult {
  Status status = Status::infeasible;
  Method method = Method::grid_golden;
  std::vector<std::string> warnings;
  std::optional<PointEval> solution;      // constraint table from the closed-form accuracy used in the search
  int set = 0;                            // tool-life set of the solution
  std::vector<std::string> active;        // names of the active constraints (|g| <= kConstraintSlackRel)
  std::optional<double> V_rho_cubature;   // accuracy at the optimum by the full cubature [mm]
  std::optional<PointEval> grid_best;     // cheapest feasible grid point
  std::array<double, 2> vc_bounds{};      // search box of the solution's set [m/min]
  std::array<double, 2> f_bounds{};       // [mm/rev]
  std::vector<FeedOptimum> valley;        // vc*(f) across the feed range
  std::vector<ContourLine> near_optimal;  // CT*·(1 + δ) iso-lines in (vc, Vf)
  std::optional<Surface> surface;
  std::optional<Infeasibility> infeasible;
  long evaluations = 0;  // point evaluations spent [-]
};

OptimizeResult optimize(const Problem& p, const OptimizeParams& params = {});

// Search box of tool-life set `set` ([lo, hi] pairs; lo > hi when empty).
struct SearchBox {
  std::array<double, 2> vc{};  // [m/min]
  std::array<double, 2> f{};   // [mm/rev]
};
SearchBox search_box(const Problem& p, int set);
// Log-spaced samples lo·(hi/lo)^(i/(n−1)), i = 0..n−1.
std::vector<double> log_grid(double lo, double hi, int n);

// The constrained optimum over vc at fixed f, searching the vc grid `vc_grid` of `set`.
// `evals`, when given, is increased by the number of point evaluations spent.
FeedOptimum best_vc_at_feed(const Problem& p, int set, double f, const std::vector<double>& vc_grid,
                            long* evals = nullptr);

// The seed's two-stage search (Fig. 5): grid points feasible for all but accuracy, sorted by CT, and
// the first one that also meets accuracy.
struct Fig5Result {
  bool found = false;
  long candidate = -1;  // 0-based position of the answer in the CT-sorted candidate list
  long candidates = 0;  // size of that list
  double vc = 0.0;      // [m/min]
  double f = 0.0;       // [mm/rev]
  double CT = 0.0;      // [CU/part]
  int set = 0;
  double vc_lo = 0.0;    // first grid speed [m/min]
  double f_lo = 0.0;     // first grid feed [mm/rev]
  double vc_step = 1.0;  // ratio between neighbouring grid speeds (one grid cell) [-]
  double f_step = 1.0;   // ratio between neighbouring grid feeds [-]
};
// The grid covers the raw box [vc_min, vc_max] × [f_min, f_max] (∩ the set's feed range): in the seed,
// power and roughness cut the search region as constraints, not as bounds.
Fig5Result optimize_fig5(const Problem& p, int grid_vc, int grid_f);

// How the Fig. 5 answer compares with the optimum.
struct Fig5Agreement {
  bool within_one_cell = false;  // |ln(vc5/vc*)| <= ln(vc step) and |ln(f5/f*)| <= ln(f step)
  // CT* <= CT5 <= the dearest feasible corner of the Fig. 5 grid cell that holds the optimum: the
  // grid answer costs no more than one cell's worth. This form also holds when the cost is flat
  // along a diagonal active constraint and the cheapest grid point sits several cells away.
  bool within_one_cell_cost = false;
  double cells_vc = 0.0;  // distance in grid cells along vc [-]
  double cells_f = 0.0;   // distance in grid cells along f [-]
};
Fig5Agreement fig5_agreement(const Problem& p, const OptimizeResult& r, const Fig5Result& f5);

// Cost of accuracy: CT*(K_TZ) over a list of K_TZ values (the Pareto front, 5.4).
struct AccuracyCostPoint {
  double K_TZ = 0.0;  // [mm]
  Status status = Status::infeasible;
  double vc = 0.0;  // [m/min]
  double f = 0.0;   // [mm/rev]
  double CT = 0.0;  // [CU/part]
  std::vector<std::string> active;
};
std::vector<AccuracyCostPoint> cost_of_accuracy(const Problem& p, const std::vector<double>& K_TZ_mm,
                                                const OptimizeParams& params = {});

}  // namespace cutroute::machining
