#include <cutroute/machining/optimize.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <cutroute/core/tolerances.hpp>
#include <cutroute/machining/contours.hpp>

#include "machining/format.hpp"
#include "machining/nlopt_backend.hpp"
#include "machining/search_steps.hpp"

namespace cutroute::machining {

const char* to_string(Status s) {
  switch (s) {
    case Status::optimal:
      return "optimal";
    case Status::infeasible:
      return "infeasible";
    case Status::warning:
      return "warning";
  }
  return "?";
}
const char* to_string(Method m) { return m == Method::grid_golden ? "grid_golden" : "nlopt_cobyla"; }

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<std::string> active_names(const PointEval& e) {
  std::vector<std::string> out;
  for (int k = 0; k < kConstraintCount; ++k) {
    if (e.g[k].enabled && std::abs(e.g[k].g) <= tol::kConstraintSlackRel) {
      out.emplace_back(to_string(static_cast<ConstraintId>(k)));
    }
  }
  return out;
}

// The cheapest feasible point and the least-violated point of one set's grid.
struct GridScan {
  std::optional<PointEval> best;
  std::optional<PointEval> least_violated;
  double least_violation = kInf;
  Surface surface;
};

GridScan scan_grid(const Problem& p, int set, const SearchBox& box, int nx, int ny, bool keep, long& evals) {
  GridScan s;
  s.surface.set = set;
  s.surface.vc = log_grid(box.vc[0], box.vc[1], nx);
  s.surface.f = log_grid(box.f[0], box.f[1], ny);
  if (keep) {
    s.surface.CT.resize(static_cast<std::size_t>(nx) * ny);
    s.surface.feasible.resize(s.surface.CT.size());
    s.surface.worst.resize(s.surface.CT.size());
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const PointEval e = evaluate(p, s.surface.vc[i], s.surface.f[j], set);
      ++evals;
      const double viol = e.max_violation();
      // Values that overflow (a tool life of 1e-300 min, a feed of 1e-160 mm/rev) make no answer: a
      // NaN cost compares false with everything, and became the "optimum" when it came first.
      const bool finite = std::isfinite(viol) && std::isfinite(e.cost.total);
      const bool ok = finite && viol <= tol::kConstraintSlackRel;
      if (keep) {
        const std::size_t at = static_cast<std::size_t>(j) * nx + i;
        s.surface.CT[at] = e.cost.total;
        s.surface.feasible[at] = ok ? 1 : 0;
        s.surface.worst[at] = ok ? static_cast<signed char>(-1) : static_cast<signed char>(e.worst());
      }
      if (ok && (!s.best || e.cost.total < s.best->cost.total)) s.best = e;
      if (finite && viol < s.least_violation) {
        s.least_violation = viol;
        s.least_violated = e;
      }
    }
  }
  return s;
}

// Golden section on f over two grid steps either side of the grid optimum (MACHINING.md 5.1 step 3).
PointEval refine(const Problem& p, int set, const SearchBox& box, const Surface& grid, const PointEval& start,
                 long& evals) {
  const int ny = static_cast<int>(grid.f.size());
  const double step = ny > 1 ? std::pow(box.f[1] / box.f[0], 1.0 / (ny - 1)) : 1.0;
  const double s = step * step;
  const auto score_f = [&](double f) {
    const FeedOptimum fo = best_vc_at_feed(p, set, f, grid.vc, &evals);
    return fo.feasible ? fo.CT : kInf;
  };
  const auto score = [&](double u) { return score_f(std::exp(u)); };
  double centre = start.f;
  double best_f = start.f;
  double best_ct = score_f(start.f);
  // Deviation from the spec's single bracket: when the cost is flat along a diagonal active constraint,
  // the cheapest grid point can lie more than two cells from the optimum, and the golden section then
  // ends on the bracket edge. The bracket is re-centred there until the minimum is inside (or on a bound).
  for (int round = 0; round < 64; ++round) {
    const double fa = std::max(box.f[0], centre / s);
    const double fb = std::min(box.f[1], centre * s);
    double f_round = fb > fa ? std::exp(detail::golden_min(score, std::log(fa), std::log(fb))) : fa;
    double ct_round = score_f(f_round);
    // The optimum often sits on the bracket end (f = f_Ra); the golden section only approaches it.
    // The ends are scored as exact values: exp(log(f_Ra)) may land an ulp outside the roughness limit.
    for (double f : {fa, fb}) {
      const double ct = score_f(f);
      if (ct < ct_round) ct_round = ct, f_round = f;
    }
    if (!(ct_round < best_ct)) break;
    best_ct = ct_round;
    best_f = f_round;
    const bool at_low = f_round <= fa * (1 + 1e-6) && fa > box.f[0];
    const bool at_high = f_round >= fb * (1 - 1e-6) && fb < box.f[1];
    if (!at_low && !at_high) break;
    centre = f_round;
  }
  PointEval out = start;
  const FeedOptimum fo = best_vc_at_feed(p, set, best_f, grid.vc);
  if (fo.feasible && fo.CT <= start.cost.total) out = evaluate(p, fo.vc, fo.f, set);
  return out;
}

std::vector<std::string> suggestions_for(ConstraintId c) {
  switch (c) {
    case ConstraintId::accuracy:
      return {"shorten the boring-bar overhang L_o or use a stiffer bar (larger d, solid, carbide)",
              "add a semi-finishing pass: it reduces TA, TB and T_R3 for the finishing pass",
              "use a smaller nose radius r_eps (lower radial force)"};  // MACHINING.md 5.1 step 2; physical, not in the Py models
    case ConstraintId::roughness:
      return {"use a larger nose radius r_eps (or a wiper insert)", "relax Ra_max or lower f_min"};
    case ConstraintId::power:
      return {"split the depth of cut into more passes (smaller ap)",
              "use a machine with more spindle power"};
    case ConstraintId::spindle:
    case ConstraintId::feedrate:
      return {"lower vc_min or f_min: the machine limits n_max / Vf_max exclude the whole search box"};
    case ConstraintId::tool_life_min:
    case ConstraintId::tool_life_max:
      return {"widen the tool-life window T_min..T_max or change the tool grade"};
    case ConstraintId::load:
      return {"reduce ap (more passes) or use a stronger bar/insert (larger F_allow)"};
    case ConstraintId::deflection:
      return {"shorten the overhang or use a stiffer bar", "relax delta_allow"};
  }
  return {};
}

// Why a set's search box is empty, naming the limiting inputs.
std::string empty_box_reason(const Problem& p, int set, const SearchBox& b) {
  std::string msg;
  if (b.vc[0] > b.vc[1]) {
    msg += "cutting-speed range is empty: search.vc_min = " + fmt(p.search.vc_min) +
           " m/min > min(search.vc_max = " + fmt(p.search.vc_max) +
           ", pi*D*n_max/1000 = " + fmt(spindle_speed_limit_vc(p.op.D, p.machine.n_max)) + ") m/min";
  }
  if (b.f[0] > b.f[1]) {
    if (!msg.empty()) msg += "; ";
    const auto range = life_feed_range(p, set);
    msg += "feed range is empty: max(search.f_min = " + fmt(p.search.f_min) + ", set lower end " +
           fmt(range[0]) + ") mm/rev > min(search.f_max = " + fmt(p.search.f_max) +
           ", f_Ra = " + fmt(feed_for_ra(p.quality.Ra_max, p.tool.r_eps, p.quality.k_Ra)) +
           " from quality.Ra_max and tool.r_eps, set upper end " + fmt(range[1]) + ") mm/rev";
  }
  return msg;
}

void add_solution_warnings(const Problem& p, const OptimizeResult& r, std::vector<std::string>& w) {
  const PointEval& e = *r.solution;
  if (e.T < p.life.warn_T_min || e.T > p.life.warn_T_max) {
    w.push_back("tool life T = " + fmt(e.T) + " min is outside the window [" + fmt(p.life.warn_T_min) + ", " +
                fmt(p.life.warn_T_max) + "] min where the tool-life model is trusted");
  }
  if (p.life.kind == ToolLifeKind::handbook) {
    const auto range = life_feed_range(p, r.set);
    const double fr = std::abs(e.f / range[1] - 1.0);
    if (fr <= 1e-9 && range[1] < std::min(p.search.f_max, kInf)) {
      w.push_back("the feed sits on the upper end of its tool-life coefficient set (" + fmt(range[1]) +
                  " mm/rev); the next set was solved separately and is not better");
    }
  }
  if (p.accuracy) {
    const Bar& bar = p.accuracy->bar;
    const double L_o = bar.mode == OverhangMode::constant ? bar.L_o : bar.L_o0 + p.op.L;
    const double limit = bar.E < 300000.0 ? 4.0 : 6.0;
    if (L_o / bar.d > limit) {
      w.push_back("boring-bar overhang L_o/d = " + fmt(L_o / bar.d) + " exceeds " + fmt(limit) + " for a " +
                  (bar.E < 300000.0 ? "steel" : "carbide") + " bar: expect chatter");
    }
    if (r.V_rho_cubature && e.acc && std::abs(*r.V_rho_cubature / e.acc->V_rho - 1.0) > 1e-4) {
      w.push_back("the cubature V_rho (" + fmt(*r.V_rho_cubature * 1000.0) +
                  " um) differs from the closed form (" + fmt(e.acc->V_rho * 1000.0) +
                  " um) by more than 1e-4: raise integration.simpson_m/n");
    }
  }
}

// The cheapest point that meets every limit at a fixed cutting speed, over the feed range of `set`
// (n_f log-spaced samples; detail::cheapest_on_line).
std::optional<PointEval> best_feed_at_vc(const Problem& p, int set, double vc, int n_f, long& evals) {
  const SearchBox box = search_box(p, set);
  if (box.f[0] > box.f[1]) return std::nullopt;
  const auto at = [&](double f) {
    ++evals;
    return evaluate(p, vc, f, set);
  };
  const auto u = detail::cheapest_on_line(at, log_grid(box.f[0], box.f[1], std::max(n_f, 2)));
  if (!u) return std::nullopt;
  return at(std::exp(*u));
}

// Deviation from MACHINING.md 5.1 step 2, which returns Infeasible when no grid point is feasible:
// a feasible band narrower than a grid cell (a tool-life window of 0.001 min, two limits nearly
// meeting) passes between the samples. Each grid line is searched as in the refinement (the line
// search minimises the largest violation around its least-violated sample, so it finds a sliver the
// line crosses); the cheapest point found, or nullopt when the region is really empty.
std::optional<PointEval> sliver_on_grid_lines(const Problem& p, int set, const Surface& grid, long& evals) {
  std::optional<PointEval> best;
  for (double f : grid.f) {
    const FeedOptimum fo = best_vc_at_feed(p, set, f, grid.vc, &evals);
    if (fo.feasible && (!best || fo.CT < best->cost.total)) best = evaluate(p, fo.vc, fo.f, set);
  }
  for (double vc : grid.vc)
    if (auto e = best_feed_at_vc(p, set, vc, static_cast<int>(grid.f.size()), evals); e && (!best || e->cost.total < best->cost.total))
      best = e;
  return best;
}

// Pitfall 9: a stepped spindle runs at the next lower available speed, which protects tool life;
// the feed is chosen again there, the cheapest that meets every limit (at the old feed a lower
// speed may break one: E2's accuracy). When no speed at or below n* has such a feed, the lowest
// step above it that has one is taken, with a warning; when none has one, there is no solution.
void apply_spindle_steps(const Problem& p, OptimizeResult& r, int n_f) {
  const auto& steps = p.machine.spindle_steps;
  if (steps.empty() || !r.solution) return;
  const double n_opt = r.solution->n;
  std::vector<double> below, above;
  for (double s : steps) (s <= n_opt * (1.0 + 1e-12) ? below : above).push_back(s);
  std::sort(below.rbegin(), below.rend());
  std::sort(above.begin(), above.end());
  std::vector<double> order = below;
  order.insert(order.end(), above.begin(), above.end());
  for (double n_step : order) {
    const double vc = kPi * p.op.D * n_step / 1000.0;
    std::optional<PointEval> at;
    int at_set = 0;
    for (int set = 0; set < life_set_count(p); ++set) {
      // A step outside the search box (search.vc_min / vc_max) is as unavailable as a missing one.
      const SearchBox box = search_box(p, set);
      if (vc < box.vc[0] * (1.0 - 1e-12) || vc > box.vc[1] * (1.0 + 1e-12)) continue;
      if (auto e = best_feed_at_vc(p, set, vc, n_f, r.evaluations); e && (!at || e->cost.total < at->cost.total)) at = e, at_set = set;
    }
    if (!at) continue;
    const bool up = n_step > n_opt * (1.0 + 1e-12);
    r.warnings.push_back("stepped spindle: n " + std::string(up ? "raised" : "rounded down") + " from " + fmt(n_opt) + " to " +
                         fmt(n_step) + " rpm (vc = " + fmt(vc) + " m/min), feed chosen again: f = " + fmt(at->f) + " mm/rev" +
                         (up ? "; no available speed at or below it meets every limit" : ""));
    r.solution = *at;
    r.set = at_set;
    r.active = active_names(*at);
    return;
  }
  Infeasibility inf;
  inf.constraint = "spindle_steps";
  inf.vc = r.solution->vc;  // where the continuous optimum lies
  inf.f = r.solution->f;
  inf.message = "no available spindle speed (machine.spindle_steps) within the search box (search.vc_min, vc_max) has a feed that "
                "meets every limit; the continuous optimum is n = " + fmt(n_opt) + " rpm";
  inf.suggestions = {"add a spindle speed near " + fmt(n_opt) + " rpm, or relax the limit that binds there"};
  r.infeasible = std::move(inf);
  r.solution.reset();
}

}  // namespace

std::vector<double> log_grid(double lo, double hi, int n) {
  std::vector<double> v(static_cast<std::size_t>(std::max(n, 1)));
  if (n <= 1) {
    v[0] = lo;
    return v;
  }
  const double r = std::log(hi / lo);
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = lo * std::exp(r * i / (n - 1));
  v.back() = hi;  // exact end point: f = f_Ra must be representable
  return v;
}

SearchBox search_box(const Problem& p, int set) {
  SearchBox b;
  b.vc = {p.search.vc_min, std::min(p.search.vc_max, spindle_speed_limit_vc(p.op.D, p.machine.n_max))};
  const auto range = life_feed_range(p, set);
  b.f = {std::max(p.search.f_min, range[0]),
         std::min({p.search.f_max, feed_for_ra(p.quality.Ra_max, p.tool.r_eps, p.quality.k_Ra), range[1]})};
  return b;
}

FeedOptimum best_vc_at_feed(const Problem& p, int set, double f, const std::vector<double>& vc_grid,
                            long* evals) {
  long count = 0;
  const auto u = detail::cheapest_on_line(
      [&](double vc) {
        ++count;
        return evaluate(p, vc, f, set);
      },
      vc_grid);
  FeedOptimum out;
  out.f = f;
  out.set = set;
  if (evals) *evals += count;
  if (!u) return out;
  const PointEval e = evaluate(p, std::exp(*u), f, set);
  out.feasible = true;
  out.vc = e.vc;
  out.CT = e.cost.total;
  out.T = e.T;
  out.binding = active_names(e);
  return out;
}

OptimizeResult optimize(const Problem& p, const OptimizeParams& params) {
  OptimizeResult r;
  r.method = params.method;
  if (params.method == Method::nlopt_cobyla && !nlopt_available()) {
    r.method = Method::grid_golden;
    r.warnings.push_back("built without CUTROUTE_WITH_NLOPT: used the grid-and-golden method");
  }
  const int nx = params.grid_vc > 0 ? params.grid_vc : p.search.grid_vc;
  const int ny = params.grid_f > 0 ? params.grid_f : p.search.grid_f;

  // Steps 1-3 per tool-life set; the better feasible answer wins (sets are never mixed).
  std::optional<PointEval> best;
  std::optional<PointEval> least_violated;
  double least_violation = kInf;
  std::string box_reasons;
  std::vector<int> sliver_sets;
  for (int set = 0; set < life_set_count(p); ++set) {
    const SearchBox box = search_box(p, set);
    if (box.vc[0] > box.vc[1] || box.f[0] > box.f[1]) {
      box_reasons += (box_reasons.empty() ? "" : "; ") +
                     std::string(life_set_count(p) > 1 ? "set " + std::to_string(set) + ": " : "") +
                     empty_box_reason(p, set, box);
      continue;
    }
    GridScan scan = scan_grid(p, set, box, nx, ny, params.keep_surface, r.evaluations);
    if (scan.least_violation < least_violation) {
      least_violation = scan.least_violation;
      least_violated = scan.least_violated;
    }
    const bool on_grid = scan.best.has_value();
    if (!on_grid && (scan.best = sliver_on_grid_lines(p, set, scan.surface, r.evaluations))) sliver_sets.push_back(set);
    if (!scan.best) continue;
    PointEval sol = *scan.best;
    if (params.refine) {
      if (r.method == Method::nlopt_cobyla) {
        sol = detail::cobyla_refine(p, set, box, *scan.best, r.evaluations);
      } else {
        sol = refine(p, set, box, scan.surface, *scan.best, r.evaluations);
      }
    }
    if (!best || sol.cost.total < best->cost.total) {
      best = sol;
      r.set = set;
      r.grid_best = on_grid ? scan.best : std::nullopt;
      r.vc_bounds = box.vc;
      r.f_bounds = box.f;
      if (params.keep_surface)
        r.surface = std::move(scan.surface);
      else
        r.surface.reset();
    }
  }

  if (!best) {
    r.status = Status::infeasible;
    Infeasibility inf;
    if (!least_violated) {
      inf.constraint = "bounds";
      inf.message = !box_reasons.empty() ? box_reasons
                                         : "the model gives no finite cost or constraint value at any grid point: an input lies "
                                           "far outside any physical range (a coefficient or limit that overflows)";
      inf.suggestions = {!box_reasons.empty() ? "check search.vc_min/vc_max, search.f_min/f_max, quality.Ra_max and tool.r_eps"
                                              : "check the coefficients and limits for a value many orders of magnitude off (units?)"};
    } else {
      const ConstraintId c = least_violated->worst();
      inf.constraint = to_string(c);
      inf.violation = least_violation;
      inf.vc = least_violated->vc;
      inf.f = least_violated->f;
      inf.message = "no grid point meets every constraint; the least-violated constraint is " +
                    inf.constraint + " (g = " + fmt(least_violation) + " at vc = " + fmt(inf.vc) +
                    " m/min, f = " + fmt(inf.f) + " mm/rev)";
      inf.suggestions = suggestions_for(c);
      // At the spindle's top speed the limit wants a faster spindle, not only the usual remedies:
      // E2 with K_TZ = 3 um and n_max = 800 named accuracy alone, the spindle never.
      const double vc_spindle = kPi * p.op.D * p.machine.n_max / 1000.0;
      if (vc_spindle < p.search.vc_max && std::abs(inf.vc / vc_spindle - 1.0) <= 1e-6) {
        inf.message += "; that point lies at the spindle's top speed n_max = " + fmt(p.machine.n_max) + " rpm (vc = " +
                       fmt(vc_spindle) + " m/min): the " + inf.constraint + " limit needs a higher cutting speed than the spindle gives";
        inf.suggestions.insert(inf.suggestions.begin(), "a spindle with a higher machine.n_max");
      }
    }
    r.infeasible = std::move(inf);
    return r;
  }

  r.solution = best;
  r.active = active_names(*best);
  if (!box_reasons.empty()) r.warnings.push_back("skipped tool-life sets: " + box_reasons);
  if (std::find(sliver_sets.begin(), sliver_sets.end(), r.set) != sliver_sets.end())
    r.warnings.push_back("no grid point meets every limit: the feasible region is narrower than a grid cell and was found by "
                         "line searches along the grid lines; the answer has almost no margin on the limits that bound it");
  // The steps first: the warnings (tool life, cubature) speak of the answer given, not of the
  // continuous optimum it replaced.
  apply_spindle_steps(p, r, ny);
  if (!r.solution) {
    r.status = Status::infeasible;
    return r;
  }
  if (p.accuracy && params.cubature_at_optimum) {
    const PointEval cub = evaluate(p, r.solution->vc, r.solution->f, r.set, AccuracyMethod::cubature);
    r.V_rho_cubature = cub.acc->V_rho;
  }
  add_solution_warnings(p, r, r.warnings);
  // Valley vc*(f) across the feed range of the solution's set.
  if (params.valley_points > 0) {
    const SearchBox box{r.vc_bounds, r.f_bounds};
    const std::vector<double> vcg = log_grid(box.vc[0], box.vc[1], nx);
    for (double f : log_grid(box.f[0], box.f[1], params.valley_points)) {
      r.valley.push_back(best_vc_at_feed(p, r.set, f, vcg, &r.evaluations));
    }
  }
  // Near-optimal contours CT = CT*(1 + δ) on the grid, mapped to (vc, Vf).
  if (r.surface && !params.near_optimal_deltas.empty()) {
    const Surface& s = *r.surface;
    const int sx = static_cast<int>(s.vc.size()), sy = static_cast<int>(s.f.size());
    const auto at_index = [](const std::vector<double>& g, double t) {
      if (g.size() < 2) return g.front();
      return g.front() * std::pow(g.back() / g.front(), t / static_cast<double>(g.size() - 1));
    };
    for (double delta : params.near_optimal_deltas) {
      const double level = best->cost.total * (1.0 + delta);
      for (const IsoLine& line : iso_lines(s.CT, sx, sy, level)) {
        ContourLine c;
        c.delta = delta;
        c.level = level;
        c.closed = line.closed;
        for (const auto& q : line.pts) {
          const double vc = at_index(s.vc, q[0]);
          const double f = at_index(s.f, q[1]);
          c.pts.push_back({vc, feed_speed_mm_min(f, spindle_speed_rpm(vc, p.op.D))});
        }
        r.near_optimal.push_back(std::move(c));
      }
    }
  }
  r.status = r.warnings.empty() ? Status::optimal : Status::warning;
  return r;
}

Fig5Result optimize_fig5(const Problem& p, int grid_vc, int grid_f) {
  struct Cand {
    double ct;
    double vc, f;
    int set;
    bool accurate;
  };
  std::vector<Cand> cands;
  for (int set = 0; set < life_set_count(p); ++set) {
    // The seed's search region is the raw box; power and roughness (and the spindle) then cut it
    // down as constraints, so the grid is not clipped to f_Ra or the spindle limit here.
    const auto range = life_feed_range(p, set);
    const SearchBox box{{p.search.vc_min, p.search.vc_max},
                        {std::max(p.search.f_min, range[0]), std::min(p.search.f_max, range[1])}};
    if (box.vc[0] > box.vc[1] || box.f[0] > box.f[1]) continue;
    const auto vcg = log_grid(box.vc[0], box.vc[1], grid_vc);
    const auto fg = log_grid(box.f[0], box.f[1], grid_f);
    for (double f : fg) {
      for (double vc : vcg) {
        const PointEval e = evaluate(p, vc, f, set);
        bool ok = true;
        for (int k = 0; k < kConstraintCount; ++k) {
          if (k == static_cast<int>(ConstraintId::accuracy)) continue;
          if (e.g[k].enabled && !(e.g[k].g <= tol::kConstraintSlackRel)) ok = false;
        }
        if (!ok) continue;
        const auto& ga = e.g[static_cast<int>(ConstraintId::accuracy)];
        cands.push_back({e.cost.total, vc, f, set, !ga.enabled || ga.g <= tol::kConstraintSlackRel});
      }
    }
  }
  std::stable_sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) { return a.ct < b.ct; });
  Fig5Result r;
  r.candidates = static_cast<long>(cands.size());
  for (std::size_t k = 0; k < cands.size(); ++k) {
    if (!cands[k].accurate) continue;  // the seed: "go to other (vc, Vf) of the search region"
    r.found = true;
    r.candidate = static_cast<long>(k);
    r.vc = cands[k].vc;
    r.f = cands[k].f;
    r.CT = cands[k].ct;
    r.set = cands[k].set;
    const auto range = life_feed_range(p, r.set);
    const double f_lo = std::max(p.search.f_min, range[0]), f_hi = std::min(p.search.f_max, range[1]);
    r.vc_lo = p.search.vc_min;
    r.f_lo = f_lo;
    r.vc_step = std::pow(p.search.vc_max / p.search.vc_min, 1.0 / std::max(1, grid_vc - 1));
    r.f_step = std::pow(f_hi / f_lo, 1.0 / std::max(1, grid_f - 1));
    break;
  }
  return r;
}

Fig5Agreement fig5_agreement(const Problem& p, const OptimizeResult& r, const Fig5Result& f5) {
  Fig5Agreement a;
  if (!r.solution || !f5.found) {
    a.within_one_cell = a.within_one_cell_cost = !r.solution && !f5.found;
    return a;
  }
  const PointEval& x = *r.solution;
  const double lv = std::log(f5.vc_step), lf = std::log(f5.f_step);
  a.cells_vc = std::abs(std::log(f5.vc / x.vc)) / lv;
  a.cells_f = std::abs(std::log(f5.f / x.f)) / lf;
  a.within_one_cell = a.cells_vc <= 1.0 + 1e-9 && a.cells_f <= 1.0 + 1e-9;
  // The cell of the Fig. 5 grid holding the optimum, and its feasible corners.
  const double iv = std::floor(std::log(x.vc / f5.vc_lo) / lv);
  const double jf = std::floor(std::log(x.f / f5.f_lo) / lf);
  double dearest = -kInf;
  for (int di = 0; di <= 1; ++di) {
    for (int dj = 0; dj <= 1; ++dj) {
      const double vc = f5.vc_lo * std::exp((iv + di) * lv), f = f5.f_lo * std::exp((jf + dj) * lf);
      const PointEval e = evaluate(p, vc, f, f5.set);
      if (e.feasible()) dearest = std::max(dearest, e.cost.total);
    }
  }
  const double slack = 1e-12 * x.cost.total;
  a.within_one_cell_cost =
      f5.CT >= x.cost.total - slack && (a.within_one_cell || (dearest > -kInf && f5.CT <= dearest + slack));
  return a;
}

std::vector<AccuracyCostPoint> cost_of_accuracy(const Problem& p, const std::vector<double>& K_TZ_mm,
                                                const OptimizeParams& params) {
  std::vector<AccuracyCostPoint> out;
  OptimizeParams q = params;
  q.valley_points = 0;
  q.near_optimal_deltas.clear();
  q.keep_surface = false;
  q.cubature_at_optimum = false;
  for (double K : K_TZ_mm) {
    Problem pk = p;
    if (pk.accuracy) pk.accuracy->K_TZ = K;
    const OptimizeResult r = optimize(pk, q);
    AccuracyCostPoint pt;
    pt.K_TZ = K;
    pt.status = r.status;
    if (r.solution) {
      pt.vc = r.solution->vc;
      pt.f = r.solution->f;
      pt.CT = r.solution->cost.total;
      pt.active = r.active;
    }
    out.push_back(std::move(pt));
  }
  return out;
}

}  // namespace cutroute::machining
