#include <cutroute/pipeline/optimize.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <set>
#include <span>
#include <thread>

#include <cutroute/core/drawing_unit.hpp>
#include <cutroute/core/number_format.hpp>
#include <cutroute/core/parallel.hpp>
#include <cutroute/core/text.hpp>
#include <cutroute/core/tolerances.hpp>
#include <cutroute/core/units.hpp>
#include <cutroute/cost/estimate.hpp>
#include <cutroute/cost/machine_profile.hpp>
#include <cutroute/cost/speed_table.hpp>
#include <cutroute/io/estimate_json.hpp>
#include <cutroute/io/inspect_report.hpp>
#include <cutroute/model/chains.hpp>
#include <cutroute/model/common_lines.hpp>
#include <cutroute/model/cut_job.hpp>
#include <cutroute/model/kerf_neighbours.hpp>
#include <cutroute/model/kerf_offset.hpp>
#include <cutroute/model/multi_segment.hpp>
#include <cutroute/nc/compensation_check.hpp>
#include <cutroute/nc/dialect.hpp>
#include <cutroute/nc/frames.hpp>
#include <cutroute/nc/gcode_reader.hpp>
#include <cutroute/nc/post_dialect.hpp>
#include <cutroute/solve/solve.hpp>

#include "compensation_fallback.hpp"
#include "refine.hpp"
#include "shop_rules_steps.hpp"

namespace cutroute::pipeline {

const char* to_string(Technique t) {
  switch (t) {
    case Technique::standard: return "standard";
    case Technique::chain: return "chain";
    case Technique::common: return "common";
    case Technique::automatic: return "auto";
    case Technique::multi: return "multi";
  }
  return "auto";
}

namespace {

struct Setup {
  cost::MachineProfile profile;
  cost::CuttingConditions conditions;
  nc::PostDialect dialect;
  model::EntryOptions entries;
  cost::RoutePrices prices;
  geometry::Vec2 start;
  std::vector<Diagnostic> diagnostics;  // what the set-up changed of what was asked for
};

// The post-processor dialect the machine profile's `dialect` names, for writing (no --dialect): a
// post dialect by name or file (beside the profile first) as it is; a reader dialect (built-in
// name or explicit codes) only where the generic post writes what it reads (M3 on, M5 off, G4 P
// in seconds), else an error: a program whose beam codes or dwell unit the machine reads
// differently does not cut as planned (M3 for a machine switched by M7 never pierces; a pierce
// dwell of 0.3 read in milliseconds pierces nothing).
Result<nc::PostDialect> profile_post_dialect(const cost::MachineProfile& p) {
  const cost::DialectSpec& d = p.dialect;
  if (d.beam_on.empty() && !nc::builtin_dialect(d.name)) {
    auto post = nc::find_post_dialect(d.name, std::filesystem::path(p.file).parent_path().string());
    if (!post) return make_error("field dialect: " + post.error().message, p.file);
    return post;
  }
  auto generic = nc::find_post_dialect("generic");
  if (!generic) return generic.error();
  auto reads = cost::profile_reader_dialect(p);
  if (!reads) return reads.error();
  if (reads->switches_on(3) && reads->switches_off(5) && reads->dwell_p_unit == nc::DwellUnit::seconds) return generic;
  return make_error("the machine profile's dialect '" + d.name +
                        "' reads the beam codes or the dwell unit differently from what the generic post-processor "
                        "writes (M3 on, M5 off, G4 P in seconds): give --dialect with a post-processor dialect JSON file "
                        "that writes them, or name one in the profile's dialect field",
                    p.file);
}

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
  if (!cond) {
    Diagnostic e = cond.error();
    if (o.material.empty()) e.message += " (" + material + " is the machine profile's default material; --material chooses another)";
    return e;
  }
  s.conditions = std::move(cond).value();
  auto dialect = o.dialect.empty() ? profile_post_dialect(s.profile) : nc::find_post_dialect(o.dialect);
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
  // Controller compensation needs leads that are long against half the kerf, r: LinuxCNC refuses
  // an entry move no longer than r, an inside arc of radius r or less, and a move into an inside
  // corner shorter than r tan(θ/2) (a lead-out at a corner turns back by up to 135°: 2.4 r). The
  // profile's leads are sized for its own kerf; a wider one (a plasma kerf with the laser profile:
  // lead-in arcs of the kerf's half, 22 blocks of vrs_Lv10_SHEET_004 refused) scales them up.
  if (o.kerf_mode == nc::KerfMode::controller) {
    const double r = s.entries.kerf_mm / 2;
    model::LeadSpec& lead = s.entries.lead;
    const model::LeadSpec asked = lead;
    lead.in_length_mm = std::max(lead.in_length_mm, 2 * r);
    lead.in_arc_radius_mm = std::max(lead.in_arc_radius_mm, 2 * r);
    lead.out_length_mm = std::max(lead.out_length_mm, 3 * r);
    s.entries.min_lead_mm = r;  // shortened leads of tight spots too
    std::string changed;  // only what was lengthened
    auto note = [&](const char* what, double from, double to) {
      if (to != from) changed += (changed.empty() ? "" : ", ") + std::string(what) + " " + format_fixed(from, 3) + " -> " + format_fixed(to, 3) + " mm";
    };
    note("lead-in", asked.in_length_mm, lead.in_length_mm);
    note("its arc radius", asked.in_arc_radius_mm, lead.in_arc_radius_mm);
    note("lead-out", asked.out_length_mm, lead.out_length_mm);
    if (!changed.empty()) {
      Diagnostic d = make_warning("leads lengthened for controller compensation with a " + format_fixed(s.entries.kerf_mm, 3) +
                                  " mm kerf: " + changed + " (at least the kerf, the kerf, 1.5 kerf)");
      d.code = "leads.kerf";
      s.diagnostics.push_back(std::move(d));
    }
  }
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
  int detours_left = 0;  // shop rules: rapids over freed parts left straight because the run stopped
  OffsetCuts offset_written;  // controller kerf: cuts written on their offset (compensation_fallback.hpp)
};

// Is program a better than program b? The lower objective, but first the fewer rapids left over
// freed parts by a stopped detour pass: those rapids are shorter than their detours, and a program
// whose pass ran out of time must not win for them (0 for both without tip-up detours).
bool better(const Evaluated& a, const Evaluated& b, double a_penalty = 0.0, double b_penalty = 0.0) {
  if (a.detours_left != b.detours_left) return a.detours_left < b.detours_left;
  return a.objective + a_penalty < b.objective + b_penalty - 1e-9;
}

// One entry of the report's lead_alternatives.
nlohmann::json lead_json(const std::string& lead_in, const Evaluated& ev) {
  nlohmann::json j = {{"lead_in", lead_in}, {"frames", ev.frames}, {"t_cut_s", ev.estimate.t_cut_s}, {"objective", ev.objective}};
  if (ev.detours_left > 0) j["tip_up_left_at_time_limit"] = ev.detours_left;  // why a shorter program lost (better())
  return j;
}

// `detour_stop`: where the shop rules' tip-up detour searches stop (see RunLimit). `planner`:
// the nest's entry planner (the shop rules plan lead-ins after micro-joint gaps with it).
Evaluated evaluate(const model::Nest& nest, const model::EntryPlanner& planner, const std::vector<model::EntryCandidate>& seq,
                   const Setup& s, const OptimizeOptions& o, const StopToken& detour_stop) {
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
  if (o.rules.any()) {  // shop rules
    ev.rules = rules::apply_to_toolpath(ev.toolpath, nest, o.rules, detour_stop,
                                        {planner, s.entries, s.dialect, rules::tab_clearance(o.kerf_mode, s.entries.kerf_mm),
                                         o.kerf_mode == nc::KerfMode::controller ? s.entries.kerf_mm : 0.0});
    if (ev.rules.contains("tip_up_program")) ev.detours_left = ev.rules["tip_up_program"]["unavoidable_left_at_time_limit"].get<int>();
  }
  if (o.kerf_mode == nc::KerfMode::controller && o.offset_refused_cuts)
    ev.offset_written = offset_refused_blocks(ev.toolpath, nest, s.entries.kerf_mm, nc::beam_switches_under_compensation(s.dialect),
                                              s.dialect, o.rules.tabs == 0);
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

const char* to_string(nc::KerfMode m) {
  switch (m) {
    case nc::KerfMode::none: return "none";
    case nc::KerfMode::cam: return "cam";
    case nc::KerfMode::controller: return "controller";
  }
  return "none";
}

// The first kerf error, naming how many more there are; overlaps become warnings when allowed.
std::optional<Diagnostic> kerf_errors(Diagnostics& ds, bool allow_overlap) {
  std::optional<Diagnostic> first;
  std::size_t more = 0;
  for (auto& d : ds) {
    if (d.severity != Severity::error) continue;
    if (d.code == "kerf.overlap" && allow_overlap) {
      d.severity = Severity::warning;
      continue;
    }
    if (first) {
      ++more;
    } else {
      first = d;
    }
  }
  if (first && first->code == "kerf.overlap") first->message += " (use --allow-kerf-overlap to cut such a nest anyway)";
  if (first && more > 0) first->message += "; " + std::to_string(more) + " more kerf errors";
  return first;
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
    if (model::is_multi_piece(e)) {
      // A chain or common-line segment: every contour it cuts, in cutting order (a common edge
      // cuts two: its own contour, then the neighbour's), and its pieces.
      auto contours = nlohmann::json::array(), parts = nlohmann::json::array(), pieces = nlohmann::json::array();
      const auto add = [&](model::ContourId id) {
        if (!id.valid()) return;
        for (const auto& listed : contours)
          if (listed == id.value() + 1) return;
        contours.push_back(id.value() + 1);
        const auto& pc = nest.contours[id];
        parts.push_back(pc.part.valid() ? pc.part.value() + 1 : 0);
      };
      for (const auto& p : e.pieces) {
        pieces.push_back(model::to_string(p.kind));
        add(p.contour);
        add(p.other);
      }
      j["contours"] = contours;
      j["parts"] = parts;
      j["pieces"] = pieces;
    }
    arr.push_back(std::move(j));
  }
  return arr;
}

// The leads' fallbacks of the written program, one warning per contour: the entries the program
// uses, not the candidates a job was built with (a common-cut job reuses the standard job's
// candidates without their warnings, and the standard job's name contours the program may enter
// elsewhere). A common line pierced on the line is said by the job itself (common.pierce_on_line).
Diagnostics lead_fallback_diagnostics(const model::Nest& nest, const std::vector<model::EntryCandidate>& seq,
                                      const DrawingUnit& unit) {
  std::vector<const model::EntryCandidate*> fell_back;  // in contour order, as the nest lists them
  std::set<std::int32_t> said;
  for (const auto& e : seq)
    if (e.fallback != model::Fallback::none && said.insert(e.contour.value()).second) fell_back.push_back(&e);
  std::stable_sort(fell_back.begin(), fell_back.end(), [](const auto* a, const auto* b) { return a->contour.value() < b->contour.value(); });
  Diagnostics out;
  for (const auto* entry : fell_back) {
    const model::EntryCandidate& e = *entry;
    const bool multi = model::is_multi_piece(e);
    if (multi && e.fallback == model::Fallback::on_contour) continue;
    const auto& c = nest.contours[e.contour];
    const std::string at = format_position(e.point.x, e.point.y, unit);
    const std::string what = multi ? "the joined cut entered at " + at
                                   : "part " + std::to_string(c.part.valid() ? c.part.value() + 1 : 0) + " " +
                                         (c.role == model::ContourRole::hole ? "hole" : "outer") + " (contour " +
                                         std::to_string(e.contour.value() + 1) + ")";
    Diagnostic d = make_warning(std::string(), std::string(), c.source.line);
    switch (e.fallback) {
      case model::Fallback::short_lead:
        d.message = what + ": no room for the full lead-in; lead-in shortened to " +
                    format_fixed(e.lead_in.vertices.size() >= 2 ? geometry::length(e.lead_in) : 0.0, 2) + " mm";
        d.code = "leads.shortened";
        break;
      case model::Fallback::centre_pierce:
        d.message = what + ": too small for a lead-in; pierced at its centre";
        d.code = "leads.centre_pierce";
        break;
      default:
        d.message = what + ": no admissible lead-in; pierced on the contour";
        d.code = "leads.on_contour";
        break;
    }
    d.handle = c.source.handle;
    d.layer = c.source.layer;
    out.push_back(std::move(d));
  }
  return out;
}

using Clock = std::chrono::steady_clock;

// Wall time of consecutive phases into a report object: lap("x") stores the time since the last lap.
class Laps {
 public:
  explicit Laps(nlohmann::json& out) : out_(out) {}
  void operator()(const char* phase) {
    const auto now = Clock::now();
    out_[phase] = std::chrono::duration<double>(now - mark_).count();
    mark_ = now;
  }

 private:
  nlohmann::json& out_;
  Clock::time_point mark_ = Clock::now();
};

// The time limit as the shop rules' steps after the route solver see it. The solver of a large nest
// runs to its deadline, so with --time-limit it would leave the rules' re-ordering search and the
// tip-up detours nothing (before, both ignored the limit: 400 circles with a tip-up margin of a
// metre took 3.6 s under --time-limit 1, 3 010 took 10 s, and SIGTERM waited for the detours).
// With these rules on, the solver leaves them their shares of the limit (rules::time_shares(): a
// fifth for the search, a tenth each for the tip-up refinement and the detours), and each stops
// at its own deadline:
//  - the search (an improvement of the order) at the run's deadline less the refinement's and
//    the detours' shares and less the estimate of the evaluation and lead comparison after it
//    (the estimate the solver's budget keeps): ending at the detours' share alone, it left the
//    steps after it 0.5 s where they took 1.2 s (10 000 circles, every rule on, --time-limit 5
//    ended at 6.2 s);
//  - the entry refinement (with tip-up priced by the rule) at the deadline less the detours'
//    share and the time of the programs after it (RunLimit::refine());
//  - the detours at the run's deadline, but never before a tenth of the limit from their start,
//    as the solver's own floor: they are what makes the program safe to run (a rapid over a part
//    cut free can catch it tipped up), and a deadline already spent by an earlier step (a cut job
//    that took long on a big nest) should not cost an ordinary nest the few milliseconds they
//    take there. The detours of an alternative's programs (its lead types) share one deadline.
// Rapids whose detour was not found in time are left straight, counted in the report and warned
// about. Without a limit nothing changes; without these rules the solver gets what it got before,
// and only the refinement keeps to the limit.
// A stop request (SIGINT/SIGTERM) ends them all at once, like the solver.
// Each alternative (technique) has its own: `limit_s` is its part of --time-limit (the shares are
// taken of it) and `deadline` where its time ends (the run's deadline for the last one), so that
// the first alternative's search does not run into the time of the others.
class RunLimit {
 public:
  RunLimit(double limit_s, std::optional<Clock::time_point> deadline, const ShopRules& r)
      : limit_s_(limit_s), shares_(rules::time_shares(r)), deadline_(deadline) {}
  // [s] kept from each solver for the rules' steps after it.
  double rules_reserve_s() const { return (shares_.search + shares_.refine + shares_.detours) * limit_s_; }
  StopToken search(const StopToken& stop) const {
    return deadline_ ? stop.with_time_limit(seconds_left() - (shares_.refine + shares_.detours) * limit_s_ - post_s_) : stop;
  }
  void set_post_estimate(double post_s) { post_s_ = post_s; }
  // The entry refinement: at the deadline less the detours' share and `evaluate_s`, the time of
  // the programs after it, but never before a tenth of the limit from its start, as the solver's
  // floor (a search that ended late should not leave it nothing: with tip-up on 400 circles that
  // took the rapids over freed parts from 10 to 42).
  StopToken refine(const StopToken& stop, double evaluate_s) const {
    return deadline_ ? stop.with_time_limit(std::max(seconds_left() - shares_.detours * limit_s_ - evaluate_s, 0.1 * limit_s_))
                     : stop;
  }
  StopToken detours(const StopToken& stop) const {
    return deadline_ ? stop.with_time_limit(std::max(seconds_left(), 0.1 * limit_s_)) : stop;
  }

 private:
  double seconds_left() const { return std::chrono::duration<double>(*deadline_ - Clock::now()).count(); }
  double limit_s_;
  double post_s_ = 0.0;  // [s] refinement and evaluation after the search (estimate)
  rules::TimeShares shares_;
  std::optional<Clock::time_point> deadline_;
};

// As many threads as the solver gets (0: one per core): the cut jobs and the lead comparison use them too.
int solver_threads(const OptimizeOptions& o) {
  return o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// The basic segments of one technique (SCCP); an error when the technique cannot be built here.
// `standard`: the standard job when already built (other techniques start from its candidates).
Result<model::CutJob> build_job(const model::Nest& nest, const model::EntryPlanner& planner, const model::EntryOptions& entries,
                                const OptimizeOptions& o, Technique t, const model::CutJob* standard) {
  const int threads = solver_threads(o);
  switch (t) {
    case Technique::standard: return model::make_cut_job(nest, planner, threads);
    case Technique::chain: return model::make_chain_job(nest, entries, o.chain, standard, &planner, threads);
    case Technique::common:
      // Common lines are cut on the centre line between two parts, uncompensated; the cam offset
      // would move each part's side of it away from the other.
      if (o.kerf_mode == nc::KerfMode::cam)
        return make_error("common-line cutting runs on the centre line between parts: not with --kerf-mode cam (use controller)");
      return model::make_common_job(nest, entries, model::CommonLineOptions{}, standard);
    case Technique::multi: return model::make_multi_job(nest, entries, o.multi, standard);
    case Technique::automatic: break;
  }
  return make_error("no cut job for technique 'auto'");
}

// Why the shop rules cannot be written into a technique's program (nullopt: they can). Part
// rigidity picks the corner each outer contour is entered at: only the standard technique enters
// every contour by its own lead-in (a chain enters its later contours where a bridge lands). Tabs
// go on the edges that hold a part to the skeleton, with every technique: its whole loop
// (standard, chain), its stretches of a group's outline (common lines) or its pieces (multi-segment
// cutting), away from where pieces meet. The order rules (heat, tip-up, sheet rigidity) price any
// technique's segments.
std::optional<std::string> rules_exclude(const ShopRules& r, Technique t) {
  if (r.part_rigidity && t != Technique::standard) return "--part-rigidity works with --technique standard only";
  return std::nullopt;
}

// Does the job cut every contour on its own (nothing joined: the standard set again)?
bool one_contour_each(const model::CutJob& job) {
  for (const auto& seg : job.segments)
    if (seg.contours.size() != 1 || seg.candidates.empty() || model::is_multi_piece(seg.candidates.front())) return false;
  return true;
}

// One solved alternative: the route, its refinement and the program with the best lead type.
struct Alternative {
  solve::Solution solution;
  std::vector<model::EntryCandidate> sequence;
  int moved = 0;
  bool refine_stopped = false;  // the entry refinement ended at the time limit (or a stop request)
  Evaluated best;
  std::string lead_name;
  nlohmann::json leads_json;
  nlohmann::json rules_json;  // shop rules: the history-dependent re-ordering's search and effects
  double rules_penalty = 0.0; // shop rules: their price of the route [objective unit] (heat, tip-up, sheet)
  int rigid_corners = 0;      // shop rules: outer contours entered at a rigid corner
};

// The entries of `seq` planned again with another lead-in type (`other`), each at the same place
// on its contour; `planned[i]` says whether entry i was (fallbacks and entries the other type does
// not fit stay as they are).
std::vector<model::EntryCandidate> with_lead(const model::EntryPlanner& other, const std::vector<model::EntryCandidate>& seq,
                                             std::vector<char>& planned) {
  std::vector<model::EntryCandidate> out = seq;
  planned.assign(out.size(), 0);
  for (std::size_t i = 0; i < out.size(); ++i) {
    auto& e = out[i];
    if (e.fallback != model::Fallback::none) continue;
    auto moved_e = other.entry_at(e.contour, e.s_mm, e.clockwise);
    if (!moved_e) continue;
    // A multi-piece segment keeps its pieces and lead-out: only its lead-in changes, and only
    // when the new one ends where its first piece starts (a common line's end may lie off
    // the contour it is named after, in the middle of a kerf gap).
    if (model::is_multi_piece(e)) {
      if (geometry::distance(moved_e->point, e.pieces.front().path.vertices.front().p) > tol::kSamePointMm) continue;
      e.lead_in = std::move(moved_e->lead_in);
      e.pierce = moved_e->pierce;
    } else {
      e = std::move(*moved_e);
    }
    planned[i] = 1;
  }
  return out;
}

// Frees the memory of a job's entry candidates (its segments stay): on huge nests they are most
// of the memory.
void release_candidates(model::CutJob& job) {
  for (auto& segment : job.segments) std::vector<model::EntryCandidate>().swap(segment.candidates);
}

// A floor under an alternative's route price (s.prices' unit): each basic segment is entered by one
// rapid (its fixed part, the head time) and cut by its cheapest candidate. Picks the alternative
// solved when the time limit is spent (24 000 parts with two holes each: chain, whose program is
// 1.7 % faster than the standard one).
double route_price_floor(const model::CutJob& job, const cost::RoutePrices& prices) {
  double sum = 0.0;
  for (const auto& segment : job.segments) {
    double cheapest = std::numeric_limits<double>::infinity();
    for (const auto& e : segment.candidates) cheapest = std::min(cheapest, cost::inner_price(e, prices));
    sum += cheapest + prices.rapid_price(0.0);
  }
  return sum;
}

// Steps 3-6 for one set of basic segments.
// The entry refinement keeps to the time limit, less `reserve_s` for the programs that follow it:
// it is the one step after the solver that can stop anywhere, so a nest whose geometry takes
// longer than the solver's budget foresaw still ends near the limit (before, it ran to its end:
// 72 000 holes at the default 10 s ended at 12.1 s). The lead types are then judged on the refined
// entries, each re-planned at the same places and evaluated on the solver's threads. Refining each
// type with its own leads instead was 0.02 % slower on the corpus nests (arc leads refined as arcs
// moved fewer entries: deepnestsharp_part_6 14.48 s against 14.44 s re-planned from the line-arc
// refinement), and judging the types before the refinement picked line leads where arcs ended
// 0.1-0.2 % faster.
Result<Alternative> solve_alternative(const model::Nest& nest, model::CutJob& job, const model::EntryPlanner& planner,
                                      const Setup& s, const OptimizeOptions& o, double time_limit_s, const RunLimit& run,
                                      double reserve_s, const StopToken& stop, const ProgressFn& progress,
                                      nlohmann::json& timing) {
  Laps lap(timing);
  // 3. Sequencing. The routing problem is dropped once the route is known (on a plate of 72 000
  // holes it held about as much memory as a lead type's entries).
  Alternative alt;
  auto& seq = alt.sequence;
  {
    cost::RouteProblemOptions rpo;
    rpo.start = s.start;
    auto rp = cost::build_route_problem(job, s.prices, rpo);
    if (!rp) return rp.error();
    lap("route_problem");
    solve::SolveParams params;
    params.solver = o.solver;
    params.seed = o.seed;
    params.threads = o.threads;
    params.time_limit_s = time_limit_s;
    params.work_budget = o.work_limit;
    alt.solution = solve::solve(rp->problem, params, stop, progress);
    if (alt.solution.route.empty()) return make_error("the route solver stopped before it found any route");
    // Shop rules: history-dependent re-ordering of the solver's route.
    const std::vector<solve::NodeId> route =
        o.rules.orders()
            ? rules::reorder(nest, job, *rp, alt.solution.route, o.rules, run.search(stop), alt.rules_json, alt.rules_penalty)
            : alt.solution.route;
    for (const auto* e : cost::route_entries(job, *rp, route)) seq.push_back(*e);
  }
  // The other candidates are not needed any more (but by part rigidity's corners): on a plate of
  // 72 000 holes they were most of the memory, held through the refinement and the programs.
  if (!o.rules.part_rigidity) release_candidates(job);
  lap("sequence");

  // 4. Continuous refinement of the entries for the fixed order.
  const StopToken refine_stop = run.refine(stop, reserve_s);
  if (o.refine_entries) {
    if (progress) progress({"refine", -1, {}});
    const auto penalty = rules::tip_up_entry_penalty(nest, seq, o.rules);
    const Refined refined = refine_entries(planner, s.prices, s.start, s.start, seq, 2, refine_stop, penalty);
    alt.moved = refined.moved;
    alt.refine_stopped = refined.stopped;
  }
  alt.rigid_corners = rules::place_rigid_entries(nest, job, seq, o.rules);  // shop rules: part rigidity
  lap("refine");

  // 5-6. The program of each lead type, its frames and V_on*(n); the best is written.
  const model::LeadKind asked = s.entries.lead.in_kind;
  std::vector<model::LeadKind> kinds = {asked};
  // After Ctrl-C the asked type alone: each other type's program took about a second on a nest of
  // 72 000 contours.
  if (o.compare_leads && !stop.cancelled())
    for (model::LeadKind kind : {model::LeadKind::line, model::LeadKind::arc})
      if (kind != asked) kinds.push_back(kind);
  // Each type's entries where it fits, elsewhere the previous type's (the asked type's lead-in
  // where neither line nor arc fits: a line where an arc does not fit costs one block, the
  // line-arc lead two). Planned on the solver's threads, then evaluated there.
  std::vector<std::vector<model::EntryCandidate>> seqs(kinds.size());
  std::vector<std::vector<char>> planned(kinds.size());
  std::vector<std::unique_ptr<model::EntryPlanner>> planners(kinds.size());
  const int threads = solver_threads(o);
  if (progress && kinds.size() > 1) progress({"leads", -1, {}});
  deal(kinds.size() - 1, threads, 1, [&](std::size_t i) {
    model::EntryOptions kind_opt = s.entries;
    kind_opt.lead.in_kind = kinds[i + 1];
    planners[i + 1] = std::make_unique<model::EntryPlanner>(planner, kind_opt);
    seqs[i + 1] = with_lead(*planners[i + 1], seq, planned[i + 1]);
  });
  for (std::size_t k = 2; k < kinds.size(); ++k)
    for (std::size_t i = 0; i < seq.size(); ++i)
      if (!planned[k][i]) seqs[k][i] = seqs[k - 1][i];
  // Only the best program so far is kept (the others' figures go to the report): with all three
  // kept, the plate of 72 000 holes peaked at 629 MB instead of 574 MB.
  std::vector<nlohmann::json> figures(kinds.size());
  std::optional<Evaluated> best;
  std::size_t win = 0;
  std::mutex best_mutex;
  const StopToken detour_stop = run.detours(stop);
  deal(kinds.size(), threads, 1, [&](std::size_t k) {
    // With tip-up each type's entries are refined again under the rule's price: another lead moves
    // pierce and tool-off points (400 circles 8 mm across, --time-limit 5: the arc lead's program
    // passed over freed parts 73-77 times where the refined default-lead route did 42 times;
    // refined again under the rule, 8-10 times).
    if (k > 0 && o.refine_entries)
      if (const auto penalty = rules::tip_up_entry_penalty(nest, seqs[k], o.rules))
        refine_entries(*planners[k], s.prices, s.start, s.start, seqs[k], 2, refine_stop, penalty);
    Evaluated ev = evaluate(nest, planner, k == 0 ? seq : seqs[k], s, o, detour_stop);
    figures[k] = lead_json(model::to_string(kinds[k]), ev);
    const std::lock_guard lock(best_mutex);
    // The lower objective, ties to the earlier type: the same choice in any order of completion.
    if (!best || better(ev, *best) || (k < win && !better(*best, ev))) {
      best = std::move(ev);
      win = k;
    }
  });
  alt.leads_json = figures;
  alt.best = std::move(*best);
  if (win > 0) seq = std::move(seqs[win]);
  alt.lead_name = model::to_string(kinds[win]);
  lap("evaluate");
  return alt;
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
  const auto t_begin = Clock::now();
  nlohmann::json timing;
  Laps lap(timing);
  if (nest.parts.empty()) return make_error("the nest has no closed contour to cut", loaded.file);

  if (const auto bad = check(o.rules); !bad.empty()) return make_error(bad.front());
  // 1. Conditions.
  auto st = setup(o);
  if (!st) return st.error();
  Setup s = std::move(st).value();
  // Each cut's kerf reaches half its width past the cut's end, into the gap on either side: a
  // tab is w - kerf wide, and one no wider than the kerf is no tab at all.
  if (o.rules.tabs > 0 && o.rules.tab_width_mm <= s.entries.kerf_mm)
    return make_error("--tab-width " + format_fixed(o.rules.tab_width_mm, 3) + " mm is not wider than the kerf (" +
                      format_fixed(s.entries.kerf_mm, 3) + " mm): the beam would cut every tab away");
  OptimizeResult result;
  for (const auto& w : s.conditions.warnings) {
    result.diagnostics.push_back(make_warning(w));
    result.diagnostics.back().code = "material.conditions";  // interpolated or extrapolated rows
  }
  for (const auto& d : s.diagnostics) result.diagnostics.push_back(d);
  // A part no wider than the kerf is burnt away, not cut out (a drawing in the wrong unit, a stray
  // dot of a few micrometres drawn closed): said, as no compensation or offset check sees it.
  if (s.entries.kerf_mm > 0)
    for (const auto& part : nest.parts) {
      const auto& c = nest.contours[part.outer];
      const double kerf = s.entries.kerf_mm;
      const std::string box = format_fixed(c.box.width(), 3) + " x " + format_fixed(c.box.height(), 3) + " mm";
      std::string size;
      if (std::min(c.box.width(), c.box.height()) <= kerf) {
        size = box;
      } else if (c.area_mm2 <= kerf * std::hypot(c.box.width(), c.box.height())) {
        // Drawn at an angle, a thin strip's box is as wide as the strip is long: its width across
        // its own edges, for the parts whose area leaves room for it (area <= width x diameter).
        const double w = geometry::narrowest_width(c.source.contour, kerf / 1000);
        if (w <= kerf) size = format_fixed(w, 3) + " mm wide at its narrowest (its box " + box + ")";
      }
      if (size.empty()) continue;
      Diagnostic w = make_warning("part " + std::to_string(&part - nest.parts.data() + 1) + " is " + size + ", no wider than the kerf (" +
                                      format_fixed(kerf, 3) + " mm): the beam burns it away",
                                  loaded.file, c.source.line);
      w.handle = c.source.handle;
      w.layer = c.source.layer;
      w.code = "nest.smaller_than_kerf";
      result.diagnostics.push_back(std::move(w));
    }
  if (progress) progress({"entries", -1, {}});

  // 2. Cut job, on the path the torch centre follows: with cam kerf the offset contours.
  model::KerfNest kerf;
  if (o.kerf_mode == nc::KerfMode::cam) {
    kerf = model::offset_for_kerf(nest, s.entries.kerf_mm);
    if (auto e = kerf_errors(kerf.diagnostics, o.allow_kerf_overlap)) {
      if (e->file.empty()) e->file = loaded.file;
      return *e;
    }
    for (const auto& d : kerf.diagnostics) result.diagnostics.push_back(d);
    s.entries.drawn = &nest;  // leads keep clear of the drawing where toolpaths cannot follow it
    lap("kerf");
  }
  const model::Nest& cut_nest = o.kerf_mode == nc::KerfMode::cam ? kerf.nest : nest;
  // 2-6 for each alternative set of basic segments (GSCCP), the best kept.
  std::vector<Technique> wanted;
  // Asked for explicitly, a technique the rules cannot be written into is an error, not a silent
  // change; `auto` builds only the ones they can.
  if (o.technique != Technique::automatic)
    if (auto why = rules_exclude(o.rules, o.technique)) return make_error(*why + ", not " + to_string(o.technique));
  if (o.multi_segment)
    if (auto why = rules_exclude(o.rules, Technique::multi)) return make_error(*why + ", not with --multi-segment");
  if (o.multi_segment && o.technique != Technique::automatic && o.technique != Technique::multi)
    return make_error(std::string("--multi-segment adds multi-segment cutting to --technique auto; not with --technique ") +
                      to_string(o.technique) + " (use --technique multi to cut with it alone)");
  if (o.technique == Technique::automatic) wanted = {Technique::standard, Technique::chain, Technique::common};
  else wanted = {o.technique};
  if (o.technique == Technique::automatic && o.multi_segment) wanted.push_back(Technique::multi);  // ECP only when asked for
  // One planner (the per-contour geometry of the nest) for every job, the refinement and the leads.
  const model::EntryPlanner planner(cut_nest, s.entries);
  std::vector<model::CutJob> jobs;
  std::vector<Technique> built;
  std::vector<std::size_t> slot;  // per built job: its place in `alternatives` (the order of `wanted`)
  auto alternatives = nlohmann::json::array();
  double standard_job_s = 0;  // [s] building the standard job: a measure of this nest's geometric work
  std::vector<std::string> interrupted;  // left out after Ctrl-C / SIGTERM
  for (Technique t : wanted) {
    if (auto why = rules_exclude(o.rules, t)) {  // under auto only: asked for, it was refused above
      alternatives.push_back({{"name", to_string(t)}, {"available", false}, {"reason", *why}});
      continue;
    }
    // After Ctrl-C only the first alternative built is solved, so the others are not built: each
    // costs seconds on a huge nest (24 000 parts with two holes: the chain job 1.3-3.4 s).
    if (!jobs.empty() && stop.cancelled()) {
      alternatives.push_back({{"name", to_string(t)}, {"available", false}, {"reason", "not solved (interrupted)"}});
      interrupted.push_back(to_string(t));
      continue;
    }
    const auto t_job = Clock::now();
    auto job = build_job(cut_nest, planner, s.entries, o, t, built.empty() || built.front() != Technique::standard ? nullptr : &jobs.front());
    const double job_s = std::chrono::duration<double>(Clock::now() - t_job).count();
    timing[to_string(t)]["job"] = job_s;
    if (t == Technique::standard) standard_job_s = job_s;
    if (!job) {
      if (o.technique != Technique::automatic) return job.error();
      alternatives.push_back({{"name", to_string(t)}, {"available", false}, {"reason", job.error().message}});
      continue;
    }
    // A chain or common job that found nothing to join is the standard job again: not solved twice.
    if (t != Technique::standard && o.technique == Technique::automatic && one_contour_each(*job)) {
      alternatives.push_back({{"name", to_string(t)}, {"available", false}, {"reason", "nothing to join: same basic segments as standard"}});
      continue;
    }
    if (t == Technique::standard) rules::restrict_candidates(*job, cut_nest, o.rules);  // shop rules: part rigidity
    jobs.push_back(std::move(job).value());
    built.push_back(t);
    slot.push_back(alternatives.size());
    alternatives.push_back(nullptr);
  }
  // The chosen job's diagnostics go here, once the choice is made: a common-cut job has its own
  // (common.pierce_on_line, common.open_loop), which the standard job's would have hidden.
  const std::size_t job_diagnostics_at = result.diagnostics.size();
  lap("entries");

  // --time-limit is the budget of the whole optimisation from here on: the solvers get what the
  // refinement and evaluation (lead types) of every alternative leave. Before the first
  // alternative has been measured, its post-processing is guessed from the time the standard job
  // took (the same kind of geometric work over the same contours); the refinement keeps to the
  // deadline where the guess was short.
  const auto deadline = t_begin + std::chrono::duration<double>(o.time_limit_s);
  double post_s = 2.0 * standard_job_s;  // [s] refinement and evaluation of one alternative (estimate)
  // [s] the programs of one alternative's lead types (estimate: on the plates of 40 000 and 72 000
  // holes they took 0.3 and 0.5 times as long as the standard job)
  double evaluate_s = standard_job_s;
  std::optional<Alternative> best;
  std::size_t chosen = 0;
  // When building the cut jobs alone used up the time limit, only the alternative with the lowest
  // route_price_floor() is solved: each costs seconds before any search on a huge nest (24 000
  // parts with two holes each at --time-limit 2: the jobs took 2.3 s, and each alternative about
  // 2 s more for its route problem, candidate lists, first route and programs; with both solved the
  // run ended at 7.6 s). Otherwise every alternative is solved, in their order.
  // Fixed buffers (at most four techniques), not vectors: a few bytes allocated here, between the
  // jobs' large blocks and the solver's, raised the peak memory of a plate of 72 000 holes from
  // 416 to 449 MB (measured; the heap could not reuse the space around them).
  std::array<std::size_t, 8> order_buf{};
  std::span<std::size_t> order(order_buf.data(), std::min(jobs.size(), order_buf.size()));
  std::iota(order.begin(), order.end(), std::size_t{0});
  // Nor is there time for every alternative when what is left would not cover each one's fixed
  // work: before any search, its route problem, candidate lists and first route take about as
  // long as the standard job did, and its refinement and programs about post_s. 24 000 parts at
  // --time-limit 10: 7.5 s left after the jobs, two alternatives of about 4.3 s each; both solved,
  // the run ended at 11.4 s.
  const double left_s = std::chrono::duration<double>(deadline - Clock::now()).count();
  const bool spent = o.time_limit_s > 0 && jobs.size() > 1 &&
                     left_s < static_cast<double>(jobs.size()) * (standard_job_s + post_s);
  if (spent) {
    std::array<double, 8> floor{};
    for (std::size_t k : order) floor[k] = route_price_floor(jobs[k], s.prices);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return floor[a] < floor[b]; });
    for (std::size_t at = 1; at < order.size(); ++at) release_candidates(jobs[order[at]]);  // not solved
  }
  std::vector<std::string> unsolved;     // left out at the time limit
  for (std::size_t at = 0; at < order.size(); ++at) {
    const std::size_t k = order[at];
    // Alternatives still to be solved, this one included (one alone when the time is spent).
    const std::size_t solving = spent ? 1 : jobs.size();
    const double left_alts = static_cast<double>(solving - std::min(at, solving - 1));
    // Shop rules: their steps after this alternative's solver keep to an even share of what is left.
    std::optional<Clock::time_point> alt_deadline;
    if (o.time_limit_s > 0)
      alt_deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>((deadline - Clock::now()) / left_alts);
    RunLimit run(o.time_limit_s / static_cast<double>(solving), alt_deadline, o.rules);
    // No limit asked stays no limit (0). A limit already spent still leaves each solver a tenth of
    // an even share, never 0 (which the solver reads as "no limit").
    double budget = 0.0;
    if (o.time_limit_s > 0) {
      const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
      budget = std::max((left - left_alts * (post_s + run.rules_reserve_s())) / left_alts,
                        0.1 * o.time_limit_s / static_cast<double>(solving));
    }
    // After Ctrl-C the alternative solved so far is written; the others are not started.
    if (best && stop.stop_requested()) {
      alternatives[slot[k]] = {{"name", to_string(built[k])}, {"available", false}, {"reason", "not solved (interrupted)"}};
      interrupted.push_back(to_string(built[k]));
      continue;
    }
    if (best && spent) {
      alternatives[slot[k]] = {{"name", to_string(built[k])}, {"available", false},
                               {"reason", "not solved: the time limit was spent"}};
      unsolved.push_back(to_string(built[k]));
      continue;
    }
    run.set_post_estimate(post_s);
    auto& alt_timing = timing[to_string(built[k])];
    // The progress line: the route's price in seconds (the solver counts integer ticks), under the
    // technique's name when several are solved one after the other (each search starts afresh).
    const std::string technique = to_string(built[k]);
    const bool named = order.size() > 1 && !spent;
    const ProgressFn shown = !progress ? ProgressFn{} : ProgressFn([&progress, &technique, named](const ProgressEvent& e) {
      ProgressEvent f = e;
      const std::string stage = named ? technique + " " + std::string(e.stage) : std::string(e.stage);
      f.stage = stage;
      if (f.best) f.best = units::ticks_to_seconds(static_cast<std::int64_t>(*f.best));
      progress(f);
    });
    auto alt = solve_alternative(cut_nest, jobs[k], planner, s, o, budget, run, evaluate_s, stop, shown, alt_timing);
    if (!alt && best) {
      alternatives[slot[k]] = {{"name", to_string(built[k])}, {"available", false}, {"reason", alt.error().message}};
      continue;
    }
    if (!alt) return alt.error();
    post_s = alt_timing.value("refine", 0.0) + alt_timing.value("evaluate", 0.0);
    evaluate_s = alt_timing.value("evaluate", 0.0);
    nlohmann::json j;
    j["name"] = to_string(built[k]);
    j["available"] = true;
    j["basic_segments"] = jobs[k].segments.size();
    j["pierces"] = alt->best.program.pierces;
    j["cut_length_mm"] = alt->best.program.cut_length_mm;
    j["rapid_length_mm"] = alt->best.program.rapid_length_mm;
    j["frames"] = alt->best.frames;
    j["t_cut_s"] = alt->best.estimate.t_cut_s;
    j["objective"] = alt->best.objective;
    // With shop rules on, techniques are compared by the objective plus the rules' price of their
    // route (the price the order was optimised for): a faster program that cuts next to the last
    // cut does not win against one that keeps the rules, unless it saves more than their weights.
    if (o.rules.orders()) j["rules_penalty"] = alt->rules_penalty;
    if (alt->best.detours_left > 0) j["tip_up_left_at_time_limit"] = alt->best.detours_left;  // why it lost (better())
    alternatives[slot[k]] = std::move(j);
    // Parts drawn edge to edge: common-line cutting cuts each shared stretch once, taking half a
    // kerf from each part; cut one by one, each loses a whole kerf there (nest.kerf_loss). The
    // common-line program is kept whatever the times: a faster program that cuts the parts short
    // is not a better one.
    const auto spares_parts = [&](std::size_t i) { return !nest.shared_edges.empty() && built[i] == Technique::common; };
    const bool wins = !best || (spares_parts(k) != spares_parts(chosen)
                                    ? spares_parts(k)
                                    : better(alt->best, best->best, alt->rules_penalty, best->rules_penalty));
    if (wins) {
      best = std::move(alt).value();
      chosen = k;
    }
  }
  lap("solve");
  if (best) {
    Diagnostics said;
    for (const auto& d : jobs[chosen].diagnostics)
      if (!d.code.starts_with("leads.")) said.push_back(d);
    for (auto& d : lead_fallback_diagnostics(cut_nest, best->sequence, loaded.unit)) said.push_back(std::move(d));
    result.diagnostics.insert(result.diagnostics.begin() + static_cast<std::ptrdiff_t>(job_diagnostics_at), said.begin(), said.end());
  }
  // Parts drawn edge to edge and cut one by one (not by common lines): each shared stretch is cut
  // twice, and each cut takes its kerf from the neighbour (TopsNest, --technique standard: 44
  // stretches, every part a kerf short there). --kerf-mode cam refuses such a nest; here the
  // program stands, so the loss is said where it cannot be missed.
  if (best && built[chosen] != Technique::common && !nest.shared_edges.empty() && o.kerf_mode != nc::KerfMode::cam) {
    Diagnostic w = make_warning(std::to_string(nest.shared_edges.size()) +
                                " pair(s) of contours share a boundary stretch (nest.common_edge) and are cut one by one (" +
                                to_string(built[chosen]) + "): each shared stretch is cut twice and both parts lose up to a kerf (" +
                                format_fixed(s.entries.kerf_mm, 3) + " mm) along it; common-line cutting (--technique common or auto) "
                                "cuts it once");
    w.code = "nest.kerf_loss";
    result.diagnostics.push_back(std::move(w));
  }
  // Parts less than a kerf apart (side by side, or in a hole) lose material to each other's cut
  // whatever the toolpath; the cam kerf mode refuses them (kerf.overlap), common-line cutting
  // cuts such a gap once. With the controller's compensation the program stands, so it is said.
  if (best && built[chosen] != Technique::common && o.kerf_mode != nc::KerfMode::cam) {
    const model::KerfNeighbours close = model::closer_than_kerf(nest, s.entries.kerf_mm, tol::kSamePointMm);
    if (close.pairs > 0) {
      const auto name = [&](model::ContourId id) {
        const auto& c = nest.contours[id];
        return "part " + std::to_string(c.part.value() + 1) + (c.role == model::ContourRole::hole ? " hole" : " outer");
      };
      Diagnostic w = make_warning(std::to_string(close.pairs) + " pair(s) of contours lie closer than the kerf (" +
                                  format_fixed(s.entries.kerf_mm, 3) + " mm) without touching (first: " + name(close.first_a) +
                                  " and " + name(close.first_b) + " near " + format_position(close.near.x, close.near.y, loaded.unit) +
                                  "): cutting one takes material from the other; --kerf-mode cam refuses such a nest");
      w.code = "nest.closer_than_kerf";
      result.diagnostics.push_back(std::move(w));
    }
  }
  if (!unsolved.empty()) {
    const std::string names = join(unsolved, ", ");
    Diagnostic w = make_warning("the time limit was spent before the " + names + " alternative" +
                                (unsolved.size() > 1 ? "s" : "") +
                                " could be solved (a longer --time-limit compares every technique)");
    w.code = "technique.time_limit";
    result.diagnostics.push_back(std::move(w));
  }
  // A program written after Ctrl-C or SIGTERM is admissible but may be far from the route the run
  // would have found (TopsNest stopped at 2.5 s: chain, 498.5 s, against common, 398.9 s).
  if (stop.cancelled()) {
    const std::string names = join(interrupted, ", ");
    Diagnostic w = make_warning("the run was interrupted (Ctrl-C, SIGTERM or a closed terminal): the program holds the best route found before "
                                "the stop" + (names.empty() ? std::string() : ", and the " + names + " alternative" +
                                                                                  (interrupted.size() > 1 ? "s were" : " was") +
                                                                                  " not solved"));
    w.code = "run.interrupted";
    result.diagnostics.push_back(std::move(w));
  }
  Alternative& win = *best;
  const solve::Solution& sol = win.solution;
  std::vector<model::EntryCandidate>& seq = win.sequence;
  const int moved = win.moved;
  const std::string& lead_name = win.lead_name;
  auto& leads_json = win.leads_json;
  Evaluated& best_ev = win.best;

  // Huge nests under a short limit: the program is admissible, but its entries could be placed for
  // shorter rapids with more time.
  if (win.refine_stopped && !stop.cancelled()) {
    Diagnostic w = make_warning("the entry refinement stopped at the time limit after moving " + std::to_string(moved) +
                                " entries (a longer --time-limit lets it finish: shorter rapids)");
    w.code = "refine.time_limit";
    result.diagnostics.push_back(std::move(w));
  }
  if (best_ev.detours_left > 0) {  // shop rules: tip-up detours stopped (report: rules.tip_up_program)
    Diagnostic w = make_warning(
        "tip-up: " + std::to_string(best_ev.detours_left) + " of " +
        std::to_string(best_ev.rules["tip_up_program"]["rapids_over_freed_parts"].get<int>()) +
        " rapids over parts already cut free are left straight: " +
        (stop.cancelled() ? std::string("the run was interrupted before their detours were found")
                          : std::string("the time limit ran out before their detours were found (a longer --time-limit routes them around)")));
    w.code = "tip_up.time_limit";
    result.diagnostics.push_back(std::move(w));
  }

  // Micro-joints: cuts resumed on the part's edge, tabs that hold nothing.
  for (Diagnostic& w : rules::tab_warnings(best_ev.rules, best_ev.toolpath,
                                           !nc::beam_switches_under_compensation(s.dialect) && o.kerf_mode == nc::KerfMode::controller))
    result.diagnostics.push_back(std::move(w));

  // Controller compensation: details of the path finer than the kerf, which the controller's
  // offset cannot follow (LinuxCNC refuses such blocks; nc/compensation_check.hpp).
  nlohmann::json compensation;
  if (o.kerf_mode == nc::KerfMode::controller) {
    const nc::CompensationHazards h =
        nc::compensation_hazards(best_ev.toolpath, s.entries.kerf_mm / 2, nc::beam_switches_under_compensation(s.dialect),
                                 s.dialect);
    compensation = {{"blocks", h.compensated}, {"at_risk", h.at.size()}, {"at_risk_segments", nlohmann::json::array()},
                    {"written_on_offset", best_ev.offset_written.labels.size()}};
    const auto& written = best_ev.offset_written.labels;
    if (!written.empty()) {
      compensation["offset_deviation_mm"] = best_ev.offset_written.deviation_mm;
      constexpr std::size_t kNamed = 5;
      std::string which;
      for (std::size_t i = 0; i < std::min(kNamed, written.size()); ++i) which += (which.empty() ? "" : ", ") + written[i];
      const double dev = best_ev.offset_written.deviation_mm;
      Diagnostic w = make_warning(
          "cutter compensation: " + std::to_string(written.size()) +
          " cut(s) with details finer than the kerf, which the controller's offset cannot follow, are written on their kerf "
          "offset (" + format_fixed(s.entries.kerf_mm, 3) + " mm) without G41/G42 (" + which + (written.size() > kNamed ? ", ..." : "") +
          "): a kerf changed in the controller's tool table does not apply to them" +
          (dev > 0 ? "; where details were straightened for the offset, the path deviates by up to " + format_fixed(dev, 3) +
                         " mm from kerf/2"
                   : std::string()) +
          " (--keep-compensation keeps them compensated)");
      w.code = "kerf.offset_written";
      result.diagnostics.push_back(std::move(w));
    }
    for (const std::size_t k : h.at) compensation["at_risk_segments"].push_back(k + 1);  // as the picture numbers them
    if (!h.at.empty()) {
      constexpr std::size_t kNamed = 5;
      std::string where;
      for (std::size_t i = 0; i < std::min(kNamed, h.at.size()); ++i)
        where += (where.empty() ? "" : ", ") + best_ev.toolpath.segments[h.at[i]].label;
      Diagnostic w = make_warning(
          "cutter compensation: " + std::to_string(h.at.size()) + " of " + std::to_string(h.compensated) +
          " compensated cuts have details finer than the kerf (" + format_fixed(s.entries.kerf_mm, 3) +
          " mm) that the controller's offset cannot follow: inside corners between moves shorter than the offset needs, "
          "inside arcs tighter than half the kerf, or entry moves shorter than it (" + where +
          (h.at.size() > kNamed ? ", ..." : "") +
          "); LinuxCNC refuses such blocks. --kerf-mode cam writes the offset path itself; "
          "scripts/check-compensation lists what LinuxCNC refuses");
      w.code = "kerf.controller_detail";
      result.diagnostics.push_back(std::move(w));
    }
  }

  // What the beam cuts, leads included: a program whose cuts span more than the machine's axes
  // travel cannot run, wherever its zero is set (a drawing read in the wrong unit is 25.4 times too
  // big). The start and park are left out: they are program coordinates, and where the drawing lies
  // far from its origin the table's zero is set elsewhere.
  geometry::Box extent;
  {
    const nc::Toolpath& tp = best_ev.toolpath;
    for (const auto& seg : tp.segments) {
      extent.add(seg.pierce);
      for (const auto& piece : seg.pieces) extent.add(geometry::bounding_box(piece.path));
    }
  }
  if (const auto& area = s.profile.work_area_mm; area && ((*area)[0] < extent.width() - 1e-6 || (*area)[1] < extent.height() - 1e-6)) {
    Diagnostic w = make_warning("the program spans " + format_fixed(extent.width(), 1) + " x " + format_fixed(extent.height(), 1) +
                                " mm, more than the machine's work area of " + format_fixed((*area)[0], 1) +
                                " x " + format_fixed((*area)[1], 1) + " mm (" + s.profile.name +
                                "): is the drawing's unit right (--units), or the sheet meant for this machine?");
    w.code = "machine.work_area";
    result.diagnostics.push_back(std::move(w));
  } else if (area && o.start) {
    // A --start given is a machine position, not the drawing's origin: the head rapids from it to
    // the cuts and parks there, so that travel must fit on the table wherever its zero is set (a
    // sign slip, -1000000,0 for -1000,0, passed without a word and parked the head 1 km away).
    geometry::Box travel = extent;
    travel.add(*o.start);
    if ((*area)[0] < travel.width() - 1e-6 || (*area)[1] < travel.height() - 1e-6) {
      Diagnostic w = make_warning("--start " + format_fixed(o.start->x, 1) + "," + format_fixed(o.start->y, 1) +
                                  " and the cuts span " + format_fixed(travel.width(), 1) + " x " + format_fixed(travel.height(), 1) +
                                  " mm, more than the machine's work area of " + format_fixed((*area)[0], 1) + " x " +
                                  format_fixed((*area)[1], 1) + " mm (" + s.profile.name +
                                  "): the rapid from the start and the park move leave the table; is --start right?");
      w.code = "machine.work_area";
      result.diagnostics.push_back(std::move(w));
    }
  }

  // The written program read back as `estimate` reads it: the report's time breakdown is the
  // estimate's (a dwell the dialect writes for the pierce is counted as `estimate` counts it), and
  // a program that cutroute's own reader refuses or measures otherwise (a writer's fault) is said.
  cost::TimeEstimate quoted = best_ev.estimate;
  if (auto reads = nc::reader_dialect(s.dialect)) {
    nc::ReadOptions ro;
    ro.dialect = *reads;
    ro.start_mm = s.start;
    ro.max_warnings = 0;
    const auto back = nc::read_gcode(best_ev.program.text, "the written program", ro);
    const auto differs = [](double a, double b) { return std::abs(a - b) > 1e-6 * std::max(1.0, std::abs(b)); };
    std::string fault;
    // A park move in the dialect's footer (or a move in its header) is travel the route does not
    // know: the program's rapid length is then the one read back, and so is the quote.
    const bool parks = nc::moves_outside_the_path(s.dialect);
    if (!back) fault = "is refused by cutroute's own reader: " + format(back.error());
    else if (back->pierces != best_ev.program.pierces || differs(back->cut_length_mm, best_ev.program.cut_length_mm) ||
             (!parks && differs(back->rapid_length_mm, best_ev.program.rapid_length_mm)))
      fault = "reads back as " + std::to_string(back->pierces) + " pierces, " + format_fixed(back->cut_length_mm, 3) + " mm cut, " +
              format_fixed(back->rapid_length_mm, 3) + " mm rapid, where it was written with " + std::to_string(best_ev.program.pierces) +
              ", " + format_fixed(best_ev.program.cut_length_mm, 3) + " and " + format_fixed(best_ev.program.rapid_length_mm, 3);
    else {
      quoted = cost::estimate_time(cost::program_totals(*back), s.conditions);
      if (parks) {
        best_ev.program.rapid_length_mm = back->rapid_length_mm;
        best_ev.estimate = quoted;
      }
    }
    if (!fault.empty()) {
      Diagnostic w = make_warning("the written program " + fault + " (a fault of cutroute's writer: please report it)");
      w.code = "program.readback";
      result.diagnostics.push_back(std::move(w));
    }
  }

  // 7. Report.
  nlohmann::json r;
  r["file"] = to_utf8(loaded.file);  // a file name in a legacy encoding: JSON needs UTF-8
  r["material"] = s.conditions.material;
  r["thickness_mm"] = s.conditions.thickness_mm;
  r["measured_speed_row"] = s.conditions.speed.measured;
  r["machine"] = s.profile.name;
  r["dialect"] = s.dialect.name;
  r["kerf_mode"] = to_string(o.kerf_mode);
  r["kerf_mm"] = s.entries.kerf_mm;
  if (!compensation.is_null()) r["compensation"] = compensation;  // controller kerf: blocks at risk
  r["objective_kind"] = o.objective == cost::Objective::time ? "time" : "cost";
  r["extent_mm"] = {extent.width(), extent.height()};  // what the beam cuts, leads included
  r["pierces"] = best_ev.program.pierces;
  r["cut_length_mm"] = best_ev.program.cut_length_mm;
  r["rapid_length_mm"] = best_ev.program.rapid_length_mm;
  r["frames"] = best_ev.frames;
  r["v_on_set_m_s"] = best_ev.estimate.v_on_set_m_s;
  r["v_on_m_s"] = best_ev.estimate.v_on_m_s;
  r["v_on_regime"] = cost::to_string(best_ev.estimate.regime);
  r["t_cut_s"] = best_ev.estimate.t_cut_s;
  r["t_cut_const_speed_s"] = best_ev.estimate.t_cut_const_speed_s;
  // What the machine takes in all, as `estimate` reports it: eq. 10 plus what lies outside it
  // (head lift and lowering per pierce, programmed dwells beyond the pierce times, beam-off feed).
  r["total_s"] = quoted.total_s;
  r["cost"] = best_ev.estimate.cost;
  r["cost_unit"] = best_ev.estimate.cost_unit;
  r["breakdown"] = io::breakdown_json(quoted);  // as `estimate --json` gives it
  r["lead_in"] = lead_name;
  r["lead_alternatives"] = leads_json;
  r["entries_refined"] = moved;
  if (win.refine_stopped) r["entries_refinement_stopped"] = true;
  r["technique"] = to_string(o.technique);
  r["alternatives"] = alternatives;
  r["chosen"] = to_string(built[chosen]);
  r["basic_segments"] = jobs[chosen].segments.size();
  nlohmann::json solver;
  solver["name"] = sol.stats.solver;
  solver["status"] = solve::to_string(sol.status);
  solver["objective"] = units::ticks_to_seconds(sol.cost);
  solver["lower_bound"] = sol.lower_bound ? nlohmann::json(units::ticks_to_seconds(*sol.lower_bound)) : nlohmann::json();
  solver["time_s"] = sol.stats.seconds;
  solver["threads"] = sol.stats.threads;
  solver["seed"] = o.seed;
  solver["work_m"] = sol.stats.work / 1e6;  // millions of work units (--work-limit)
  r["solver"] = solver;
  r["timing_s"] = timing;  // wall times: with solver.time_s the only fields that vary run to run
  r["sequence"] = sequence_json(nest, seq);
  auto diags = nlohmann::json::array();
  for (const auto& d : loaded.diagnostics) diags.push_back(io::to_json(d));
  for (const auto& d : result.diagnostics) diags.push_back(io::to_json(d));
  r["diagnostics"] = diags;
  if (o.rules.any()) r["rules"] = rules::report(o.rules, win.rules_json, best_ev.rules, win.rigid_corners);  // shop rules

  result.toolpath = std::move(best_ev.toolpath);
  result.program = std::move(best_ev.program);
  result.report = std::move(r);
  return result;
}

}  // namespace cutroute::pipeline
