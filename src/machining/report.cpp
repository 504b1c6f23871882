#include <cutroute/machining/report.hpp>

#include <cmath>
#include <string>

#include <cutroute/core/tolerances.hpp>

#include "machining/format.hpp"

namespace cutroute::machining {

namespace {

using nlohmann::json;

// JSON has no inf/nan: write null for them.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json point_json(const PointEval& e) {
  json j;
  j["vc_m_min"] = num(e.vc);
  j["f_mm_rev"] = num(e.f);
  j["ct_cu"] = num(e.cost.total);
  return j;
}

json constraints_json(const PointEval& e) {
  json rows = json::array();
  for (int k = 0; k < kConstraintCount; ++k) {
    const auto& c = e.g[k];
    if (!c.enabled) continue;
    const auto id = static_cast<ConstraintId>(k);
    rows.push_back({{"name", to_string(id)},
                    {"value", num(c.value)},
                    {"limit", num(c.limit)},
                    {"unit", constraint_unit(id)},
                    {"g", num(c.g)},
                    {"slack", num(-c.g)},
                    {"active", std::abs(c.g) <= tol::kConstraintSlackRel}});
  }
  return rows;
}

// The search bounds the answer lies on (pitfall 7: the optimum always lies on a boundary; where no
// constraint is active it is one of these, and the user should know that widening it may pay):
// the search box's ends in vc and f, named by what sets them.
std::vector<std::string> bounds_reached(const Problem& p, const OptimizeResult& r) {
  std::vector<std::string> out;
  if (!r.solution) return out;
  const PointEval& e = *r.solution;
  auto at = [](double v, double b) { return std::abs(v - b) <= 1e-9 * std::max(1.0, std::abs(b)); };
  if (at(e.vc, r.vc_bounds[0])) out.push_back("search.vc_min");
  if (at(e.vc, r.vc_bounds[1])) out.push_back(at(r.vc_bounds[1], p.search.vc_max) ? "search.vc_max" : "machine.n_max");
  if (at(e.f, r.f_bounds[0])) out.push_back(at(r.f_bounds[0], p.search.f_min) ? "search.f_min" : "tool-life set feed range");
  if (at(e.f, r.f_bounds[1])) {
    const auto range = life_feed_range(p, r.set);
    if (at(r.f_bounds[1], p.search.f_max)) out.push_back("search.f_max");
    else if (at(r.f_bounds[1], range[1])) out.push_back("tool-life set feed range");
  }
  return out;
}

}  // namespace

const char* constraint_unit(ConstraintId c) {
  switch (c) {
    case ConstraintId::power:
      return "kW";
    case ConstraintId::roughness:
      return "um";
    case ConstraintId::spindle:
      return "rpm";
    case ConstraintId::feedrate:
      return "mm/min";
    case ConstraintId::accuracy:
      return "mm";
    case ConstraintId::tool_life_min:
    case ConstraintId::tool_life_max:
      return "min";
    case ConstraintId::load:
      return "N";
    case ConstraintId::deflection:
      return "mm";
  }
  return "";
}

json report_json(const RunOutput& out) {
  const Problem& p = *out.problem;
  const OptimizeResult& r = *out.result;
  json j;
  j["problem"] = p.name;
  j["status"] = to_string(r.status);
  j["method"] = to_string(r.method);
  j["warnings"] = r.warnings;
  if (r.solution) {
    const PointEval& e = *r.solution;
    j["vc_m_min"] = num(e.vc);
    j["f_mm_rev"] = num(e.f);
    j["n_rpm"] = num(e.n);
    j["vf_mm_min"] = num(e.Vf);
    j["tm_min"] = num(e.tm);
    j["tool_life_min"] = num(e.T);
    j["tool_life_set"] = r.set;
    j["cost"] = {{"total_cu", num(e.cost.total)},
                 {"cutting_cu", num(e.cost.cutting)},
                 {"tool_cu", num(e.cost.tool)},
                 {"service_cu", num(e.cost.service)},
                 {"fixed_cu", num(e.cost.fixed)},
                 {"edges_per_part", num(e.cost.edges_per_part)},
                 {"parts_per_edge", num(e.cost.parts_per_edge)}};
    j["derived"] = {{"Fc_N", num(e.Fc)},
                    {"Fr_N", num(e.Fr)},
                    {"Pc_kW", num(e.Pc)},
                    {"Pc_over_eta_kW", num(e.P_demand)},
                    {"P_avail_kW", num(e.P_avail)},
                    {"torque_Nm", num(e.M)},
                    {"Ra_um", num(e.Ra)},
                    {"Rz_um", num(e.Rz)}};
    if (e.acc) {
      const AccuracyValues& a = *e.acc;
      j["accuracy"] = {{"k_N_mm", num(a.k)},
                       {"delta0_um", num(a.delta0 * 1000.0)},
                       {"eps", num(a.eps)},
                       {"sigma_e_um", num(a.sigma_e * 1000.0)},
                       {"sigma_A_um", num(a.sigma_A * 1000.0)},
                       {"S_A_um", num(a.S_A * 1000.0)},
                       {"sigma_r_um", num(a.sigma_r * 1000.0)},
                       {"V_rho_um", num(a.V_rho * 1000.0)},
                       {"value_um", num(a.value * 1000.0)},
                       {"K_TZ_um", num(p.accuracy->K_TZ * 1000.0)},
                       {"z_mm", num(a.z)},
                       {"L_o_mm", num(a.L_o)}};
      if (r.V_rho_cubature) j["accuracy"]["V_rho_cubature_um"] = num(*r.V_rho_cubature * 1000.0);
    }
    j["constraints"] = constraints_json(e);
    j["active"] = r.active;
    j["bounds_reached"] = bounds_reached(p, r);
    if (r.grid_best) j["grid_best"] = point_json(*r.grid_best);
    j["search_box"] = {{"vc_m_min", {r.vc_bounds[0], r.vc_bounds[1]}},
                       {"f_mm_rev", {r.f_bounds[0], r.f_bounds[1]}}};
  }
  if (r.infeasible) {
    const Infeasibility& inf = *r.infeasible;
    j["infeasible"] = {{"least_violated", inf.constraint},
                       {"violation_g", num(inf.violation)},
                       // An empty search box has no point to name.
                       {"at", inf.constraint == "bounds" ? json(nullptr) : json{{"vc_m_min", num(inf.vc)}, {"f_mm_rev", num(inf.f)}}},
                       {"message", inf.message},
                       {"suggestions", inf.suggestions}};
  }
  json valley = json::array();
  for (const FeedOptimum& v : r.valley) {
    valley.push_back({{"f_mm_rev", num(v.f)},
                      {"feasible", v.feasible},
                      {"vc_m_min", v.feasible ? num(v.vc) : json(nullptr)},
                      {"ct_cu", v.feasible ? num(v.CT) : json(nullptr)},
                      {"tool_life_min", v.feasible ? num(v.T) : json(nullptr)},
                      {"binding", v.binding}});
  }
  j["valley"] = valley;
  json contours = json::array();
  for (const ContourLine& c : r.near_optimal) {
    json pts = json::array();
    for (const auto& q : c.pts) pts.push_back({q[0], q[1]});
    contours.push_back({{"delta", c.delta}, {"ct_cu", c.level}, {"closed", c.closed}, {"vc_vf", pts}});
  }
  j["near_optimal"] = contours;
  if (out.fig5) {
    const Fig5Result& f = *out.fig5;
    j["fig5_cross_check"] = {{"found", f.found},           {"candidate", f.candidate},
                             {"candidates", f.candidates}, {"vc_m_min", num(f.vc)},
                             {"f_mm_rev", num(f.f)},       {"ct_cu", num(f.CT)}};
    const Fig5Agreement a = fig5_agreement(p, r, f);
    j["fig5_cross_check"]["distance_cells"] = {a.cells_vc, a.cells_f};
    j["fig5_cross_check"]["within_one_cell"] = a.within_one_cell;
    j["fig5_cross_check"]["within_one_cell_cost"] = a.within_one_cell_cost;
  }
  if (!out.sweep.empty()) {
    json s = json::array();
    for (const auto& q : out.sweep) {
      s.push_back({{"K_TZ_um", q.K_TZ * 1000.0},
                   {"status", to_string(q.status)},
                   {"vc_m_min", q.status == Status::infeasible ? json(nullptr) : num(q.vc)},
                   {"f_mm_rev", q.status == Status::infeasible ? json(nullptr) : num(q.f)},
                   {"ct_cu", q.status == Status::infeasible ? json(nullptr) : num(q.CT)},
                   {"active", q.active}});
    }
    j["cost_of_accuracy"] = s;
  }
  j["evaluations"] = r.evaluations;
  return j;
}

std::string report_text(const RunOutput& out) {
  const Problem& p = *out.problem;
  const OptimizeResult& r = *out.result;
  std::string s;
  if (!p.name.empty()) s += p.name + "\n";
  s += "status: " + std::string(to_string(r.status)) + "\n";
  if (r.solution) {
    const PointEval& e = *r.solution;
    s += "vc = " + fmt(e.vc, 8) + " m/min, f = " + fmt(e.f, 8) + " mm/rev, n = " + fmt(e.n, 7) +
         " rpm, Vf = " + fmt(e.Vf, 7) + " mm/min\n";
    s += "tm = " + fmt(e.tm, 7) + " min, T = " + fmt(e.T, 7) +
         " min, edges/part = " + fmt(e.cost.edges_per_part, 5) + "\n";
    s += "CT = " + fmt(e.cost.total, 8) + " CU = cutting " + fmt(e.cost.cutting, 6) + " + tool " +
         fmt(e.cost.tool, 6) + " + service " + fmt(e.cost.service, 6) + " + fixed " + fmt(e.cost.fixed, 6) +
         "\n";
    s += "Fc = " + fmt(e.Fc, 6) + " N, Pc = " + fmt(e.Pc, 6) + " kW (Pc/eta " + fmt(e.P_demand, 6) + " of " +
         fmt(e.P_avail, 6) + "), Ra = " + fmt(e.Ra, 5) + " um\n";
    if (e.acc) {
      s += "V_rho = " + fmt(e.acc->V_rho * 1000.0, 6) + " um (limit " + fmt(p.accuracy->K_TZ * 1000.0, 6) +
           " um), delta0 = " + fmt(e.acc->delta0 * 1000.0, 5) + " um, eps = " + fmt(e.acc->eps, 6) + "\n";
    }
    s += "constraints (g = value/limit - 1):\n";
    for (int k = 0; k < kConstraintCount; ++k) {
      const auto& c = e.g[k];
      if (!c.enabled) continue;
      const auto id = static_cast<ConstraintId>(k);
      s += "  " + std::string(to_string(id)) + ": " + fmt(c.value, 7) + " / " + fmt(c.limit, 7) + " " +
           constraint_unit(id) + ", slack " + fmt(-c.g, 3) +
           (std::abs(c.g) <= tol::kConstraintSlackRel ? "  ACTIVE" : "") + "\n";
    }
  }
  if (const auto bounds = bounds_reached(p, r); !bounds.empty()) {
    std::string b;
    for (const auto& n : bounds) b += (b.empty() ? "" : ", ") + n;
    s += "on the search bound" + std::string(bounds.size() > 1 ? "s " : " ") + b + " (not a limit of the process: a wider search may find a cheaper point)\n";
  }
  if (r.infeasible) {
    s += r.infeasible->message + "\n";
    for (const auto& sug : r.infeasible->suggestions) s += "  suggestion: " + sug + "\n";
  }
  for (const auto& w : r.warnings) s += "warning: " + w + "\n";
  return s;
}

std::string report_csv(const RunOutput& out) {
  const Problem& p = *out.problem;
  const OptimizeResult& r = *out.result;
  std::string s = "section,vc_m_min,f_mm_rev,vf_mm_min,ct_cu,tool_life_min,feasible,constraint\n";
  const auto row = [&](const char* sec, double vc, double f, double ct, double T, bool ok,
                       const std::string& c) {
    const double Vf = feed_speed_mm_min(f, spindle_speed_rpm(vc, p.op.D));
    s += std::string(sec) + "," + fmt(vc, 10) + "," + fmt(f, 10) + "," + fmt(Vf, 10) + "," + fmt(ct, 10) +
         "," + fmt(T, 8) + "," + (ok ? "1" : "0") + "," + c + "\n";
  };
  for (const FeedOptimum& v : r.valley) {
    std::string b;
    for (const auto& n : v.binding) b += (b.empty() ? "" : "+") + n;
    if (v.feasible) row("valley", v.vc, v.f, v.CT, v.T, true, b);
    else s += "valley,," + fmt(v.f, 10) + ",,,,0," + b + "\n";  // a feed no speed makes feasible, as the JSON lists it
  }
  if (r.surface) {
    const Surface& g = *r.surface;
    for (std::size_t j = 0; j < g.f.size(); ++j) {
      for (std::size_t i = 0; i < g.vc.size(); ++i) {
        const std::size_t at = j * g.vc.size() + i;
        const PointEval e = evaluate(p, g.vc[i], g.f[j], g.set);
        row("grid", g.vc[i], g.f[j], g.CT[at], e.T, g.feasible[at] != 0,
            g.worst[at] < 0 ? std::string() : std::string(to_string(static_cast<ConstraintId>(g.worst[at]))));
      }
    }
  }
  return s;
}

}  // namespace cutroute::machining
