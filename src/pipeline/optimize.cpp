#include <cutroute/pipeline/optimize.hpp>

#include <chrono>
#include <cmath>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/units.hpp>
#include <cutroute/cost/estimate.hpp>
#include <cutroute/cost/machine_profile.hpp>
#include <cutroute/cost/speed_table.hpp>
#include <cutroute/io/inspect_report.hpp>
#include <cutroute/model/cut_job.hpp>
#include <cutroute/nc/frames.hpp>
#include <cutroute/nc/post_dialect.hpp>
#include <cutroute/solve/solve.hpp>

#include "refine.hpp"
#include "shop_rules_steps.hpp"

namespace cutroute::pipeline {
namespace {

struct Setup {
  cost::MachineProfile profile;
  cost::CuttingConditions conditions;
  nc::PostDialect dialect;
  model::EntryOptions entries;
  cost::RoutePrices prices;
  geometry::Vec2 start;
};

Result<Setup> setup(const OptimizeOptions& o) {
  Setup s;
  auto profile = cost::load_machine_profile(o.machine_file.empty() ? cost::default_machine_profile_path() : o.machine_file);
  if (!profile) return profile.error();
  s.profile = std::move(profile).value();
  auto table = cost::load_speed_table(s.profile.speed_table);
  if (!table) return table.error();
  const std::string material = !o.material.empty() ? o.material : s.profile.default_material.value_or("");
  const double thickness = o.thickness_mm.value_or(s.profile.default_thickness_mm.value_or(0.0));
  if (material.empty() || thickness <= 0)
    return make_error("no material/thickness given and the machine profile has no default job (--material, --thickness)");
  auto cond = cost::make_conditions(s.profile, *table, material, thickness, o.interpolate);
  if (!cond) return cond.error();
  s.conditions = std::move(cond).value();
  auto dialect = nc::find_post_dialect(o.dialect);
  if (!dialect) return dialect.error();
  s.dialect = std::move(dialect).value();

  // Leads and kerf from the profile's technology row for this material and thickness.
  const cost::CuttingParams* tech = nullptr;
  for (const auto& c : s.profile.cutting) {
    auto canon = table->resolve_material(c.material);
    if (canon && *canon == s.conditions.material && std::abs(c.thickness_mm - thickness) < 1e-9) tech = &c;
  }
  s.entries.kerf_mm = o.kerf_mm.value_or(tech ? tech->kerf_mm : 0.2);
  if (tech && tech->lead_in_mm > 0) {
    s.entries.lead.in_length_mm = tech->lead_in_mm;
    s.entries.lead.in_arc_radius_mm = tech->lead_in_mm / 2;
  }
  if (tech && tech->lead_out_mm > 0) s.entries.lead.out_length_mm = tech->lead_out_mm;
  s.entries.entry_step_mm = o.entry_step_mm;
  s.entries.max_candidates = o.max_candidates;
  s.entries.outer_clockwise = s.dialect.outer_clockwise;
  s.entries.hole_clockwise = s.dialect.hole_clockwise;

  s.prices.objective = o.objective;
  s.prices.v_on_mm_s = units::m_per_s_to_mm_per_s(s.conditions.v_set_m_s);
  s.prices.v_off_mm_s = units::m_per_s_to_mm_per_s(s.conditions.rapid_speed_m_s);
  s.prices.pierce_s = s.conditions.pierce_time_s;
  s.prices.head_s = s.conditions.head_lift_lower_s;
  if (o.objective == cost::Objective::cost) {
    if (!s.conditions.costs) return make_error("--objective cost needs costs (C_on, C_off, C_pt) in the machine profile", s.profile.file);
    s.prices.c_on_per_mm = s.conditions.costs->c_on_per_m / units::kMmPerM;
    s.prices.c_off_per_mm = s.conditions.costs->c_off_per_m / units::kMmPerM;
    s.prices.c_pt = s.conditions.costs->c_pt;
  }
  s.start = o.start.value_or(geometry::Vec2{0, 0});
  return s;
}

// Program text and its frame-corrected evaluation for one sequence of entries.
struct Evaluated {
  nc::Toolpath toolpath;
  nc::WrittenProgram program;
  std::size_t frames = 0;
  cost::TimeEstimate estimate;
  double objective = 0;  // t_cut_s (time) or cost (cost form)
  nlohmann::json rules;  // shop rules applied to the toolpath (detours, tabs)
};

Evaluated evaluate(const model::Nest& nest, const std::vector<model::EntryCandidate>& seq, const Setup& s,
                   const OptimizeOptions& o) {
  std::vector<const model::EntryCandidate*> ptrs;
  ptrs.reserve(seq.size());
  for (const auto& e : seq) ptrs.push_back(&e);
  nc::ToolpathOptions to;
  to.start = s.start;
  to.end = s.start;
  to.feed_mm_min = units::m_per_s_to_mm_per_min(s.conditions.v_set_m_s);
  to.pierce_time_s = s.conditions.pierce_time_s;
  to.kerf = o.kerf_mode;
  Evaluated ev;
  ev.toolpath = nc::build_toolpath(nest, ptrs, to);
  if (o.rules.any()) ev.rules = rules::apply_to_toolpath(ev.toolpath, nest, o.rules);  // shop rules
  ev.program = nc::write_gcode(ev.toolpath, s.dialect, nc::GcodeWriteOptions{o.title, true});
  ev.frames = nc::count_frames(ev.program.text);
  cost::ProgramTotals totals;
  totals.cut_length_mm = ev.program.cut_length_mm;
  totals.rapid_length_mm = ev.program.rapid_length_mm;
  totals.pierces = ev.program.pierces;
  totals.frames = ev.frames;
  ev.estimate = cost::estimate_time(totals, s.conditions);
  ev.objective = o.objective == cost::Objective::time ? ev.estimate.t_cut_s : ev.estimate.cost;
  return ev;
}

nlohmann::json sequence_json(const model::Nest& nest, const std::vector<model::EntryCandidate>& seq) {
  auto arr = nlohmann::json::array();
  for (const auto& e : seq) {
    const auto& c = nest.contours[e.contour];
    nlohmann::json j;
    j["contour"] = e.contour.value() + 1;
    j["part"] = c.part.valid() ? c.part.value() + 1 : 0;
    j["kind"] = c.role == model::ContourRole::hole ? "hole" : "outer";
    j["pierce"] = {e.pierce.x, e.pierce.y};
    j["direction"] = e.clockwise ? "cw" : "ccw";
    if (e.fallback != model::Fallback::none) j["fallback"] = model::to_string(e.fallback);
    arr.push_back(std::move(j));
  }
  return arr;
}

}  // namespace

Result<OptimizeResult> optimize_nest(const io::LoadedNest& loaded, const OptimizeOptions& o, const StopToken& stop,
                                     const ProgressFn& progress) {
  for (const auto& d : loaded.diagnostics) {
    if (d.severity != Severity::error) continue;
    if (d.code == "nest.crossing" && o.allow_crossing) continue;
    Diagnostic e = d;
    if (d.code == "nest.crossing") e.message += " (use --allow-crossing to cut such a drawing anyway)";
    return e;  // never cut a nest whose parts are drawn over each other unless told to
  }
  const model::Nest& nest = loaded.nest;
  using Clock = std::chrono::steady_clock;
  auto t_mark = Clock::now();
  nlohmann::json timing;
  auto lap = [&](const char* phase) {
    const auto now = Clock::now();
    timing[phase] = std::chrono::duration<double>(now - t_mark).count();
    t_mark = now;
  };
  if (nest.parts.empty()) return make_error("the nest has no closed contour to cut", loaded.file);

  if (const auto bad = check(o.rules); !bad.empty()) return make_error(bad.front());
  // 1. Conditions.
  auto st = setup(o);
  if (!st) return st.error();
  Setup s = std::move(st).value();
  OptimizeResult result;
  for (const auto& w : s.conditions.warnings) result.diagnostics.push_back(make_warning(w));
  if (progress) progress({"entries", -1, {}});

  // 2. Cut job.
  model::CutJob job = model::make_cut_job(nest, s.entries);
  rules::restrict_candidates(job, nest, o.rules);  // shop rules: part rigidity
  for (const auto& d : job.diagnostics) result.diagnostics.push_back(d);
  lap("entries");

  // 3. Sequencing.
  cost::RouteProblemOptions rpo;
  rpo.start = s.start;
  auto rp = cost::build_route_problem(job, s.prices, rpo);
  if (!rp) return rp.error();
  lap("problem");
  solve::SolveParams params;
  params.solver = o.solver;
  params.seed = o.seed;
  params.threads = o.threads;
  params.time_limit_s = o.time_limit_s;
  const solve::Solution sol = solve::solve(rp->problem, params, stop, progress);
  if (sol.route.empty()) return make_error("the route solver stopped before it found any route", loaded.file);
  lap("solve");
  nlohmann::json rules_json;  // shop rules: history-dependent re-ordering
  const std::vector<solve::NodeId> route =
      o.rules.orders() ? rules::reorder(nest, job, *rp, sol.route, o.rules, stop, rules_json) : sol.route;
  if (o.rules.orders()) rules_json["route"] = rules::route_effects(nest, job, *rp, route, o.rules);
  std::vector<model::EntryCandidate> seq;
  for (const auto* e : cost::route_entries(job, *rp, route)) seq.push_back(*e);

  // 4. Continuous refinement of the entries for the fixed order.
  model::EntryPlanner planner(nest, s.entries);
  int moved = 0;
  if (o.refine_entries) {
    if (progress) progress({"refine", -1, {}});
    moved = refine_entries(planner, s.prices, s.start, s.start, seq, 2, stop);
  }
  const int rigid_corners = rules::place_rigid_entries(nest, job, seq, o.rules);  // shop rules: part rigidity
  lap("refine");

  // 5-6. Program, frames, V_on*(n); lead types compared by the corrected objective.
  Evaluated best = evaluate(nest, seq, s, o);
  std::string lead_name = model::to_string(s.entries.lead.in_kind);
  auto leads_json = nlohmann::json::array();
  leads_json.push_back({{"lead_in", lead_name}, {"frames", best.frames}, {"t_cut_s", best.estimate.t_cut_s},
                        {"objective", best.objective}});
  if (o.compare_leads) {
    for (model::LeadKind kind : {model::LeadKind::line, model::LeadKind::arc}) {
      if (kind == s.entries.lead.in_kind) continue;
      model::EntryOptions alt_opt = s.entries;
      alt_opt.lead.in_kind = kind;
      model::EntryPlanner alt(nest, alt_opt);
      std::vector<model::EntryCandidate> alt_seq = seq;
      for (auto& e : alt_seq) {
        if (e.fallback != model::Fallback::none) continue;
        if (auto moved_e = alt.entry_at(e.contour, e.s_mm, e.clockwise)) e = std::move(*moved_e);
      }
      Evaluated ev = evaluate(nest, alt_seq, s, o);
      leads_json.push_back({{"lead_in", model::to_string(kind)}, {"frames", ev.frames}, {"t_cut_s", ev.estimate.t_cut_s},
                            {"objective", ev.objective}});
      if (ev.objective < best.objective - 1e-9) {
        best = std::move(ev);
        seq = std::move(alt_seq);
        lead_name = model::to_string(kind);
      }
    }
  }

  lap("program");

  // 7. Report.
  nlohmann::json r;
  r["file"] = loaded.file;
  r["material"] = s.conditions.material;
  r["thickness_mm"] = s.conditions.thickness_mm;
  r["measured_speed_row"] = s.conditions.speed.measured;
  r["objective_kind"] = o.objective == cost::Objective::time ? "time" : "cost";
  r["pierces"] = best.program.pierces;
  r["cut_length_mm"] = best.program.cut_length_mm;
  r["rapid_length_mm"] = best.program.rapid_length_mm;
  r["frames"] = best.frames;
  r["v_on_set_m_s"] = best.estimate.v_on_set_m_s;
  r["v_on_m_s"] = best.estimate.v_on_m_s;
  r["v_on_regime"] = cost::to_string(best.estimate.regime);
  r["t_cut_s"] = best.estimate.t_cut_s;
  r["t_cut_const_speed_s"] = best.estimate.t_cut_const_speed_s;
  r["cost"] = best.estimate.cost;
  r["cost_unit"] = best.estimate.cost_unit;
  r["breakdown_s"] = {{"cutting", best.estimate.cutting_s}, {"rapid", best.estimate.rapid_s},
                      {"pierce", best.estimate.pierce_s}, {"head", best.estimate.head_s}};
  r["lead_in"] = lead_name;
  r["lead_alternatives"] = leads_json;
  r["entries_refined"] = moved;
  nlohmann::json solver;
  solver["name"] = sol.stats.solver;
  solver["status"] = solve::to_string(sol.status);
  solver["objective"] = units::ticks_to_seconds(sol.cost);
  solver["lower_bound"] = sol.lower_bound ? nlohmann::json(units::ticks_to_seconds(*sol.lower_bound)) : nlohmann::json();
  solver["time_s"] = sol.stats.seconds;
  solver["threads"] = sol.stats.threads;
  solver["seed"] = o.seed;
  r["solver"] = solver;
  r["timing_s"] = timing;  // wall times: with solver.time_s the only fields that vary run to run
  r["sequence"] = sequence_json(nest, seq);
  auto diags = nlohmann::json::array();
  for (const auto& d : loaded.diagnostics) diags.push_back(io::to_json(d));
  for (const auto& d : result.diagnostics) diags.push_back(io::to_json(d));
  r["diagnostics"] = diags;
  if (o.rules.any()) r["rules"] = rules::report(o.rules, rules_json, best.rules, rigid_corners);  // shop rules

  result.toolpath = std::move(best.toolpath);
  result.program = std::move(best.program);
  result.report = std::move(r);
  return result;
}

}  // namespace cutroute::pipeline
