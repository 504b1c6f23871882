// optimize_nest(): the main job: a loaded nest -> the fastest admissible cutting program + report.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include <cutroute/core/result.hpp>
#include <cutroute/core/stop.hpp>
#include <cutroute/cost/route_problem.hpp>
#include <cutroute/io/nest_loader.hpp>
#include <cutroute/model/chains.hpp>
#include <cutroute/model/multi_segment.hpp>
#include <cutroute/nc/build_toolpath.hpp>
#include <cutroute/nc/gcode_writer.hpp>
#include <cutroute/pipeline/shop_rules.hpp>
#include <cutroute/solve/params.hpp>

namespace cutroute::pipeline {

// Which alternative sets of basic segments to build (GSCCP, source paper §2): standard = one per
// contour; chain = neighbouring outer contours joined by bridges; common = edges shared by
// neighbouring parts cut once; automatic = every one available, solved each, the best kept;
// multi = long contours cut in several pieces (ECP, model/multi_segment.hpp): only when asked for,
// explicitly or with `multi_segment` added to `automatic`.
enum class Technique { standard, chain, common, automatic, multi };
const char* to_string(Technique t);

// The options of `cutroute optimize` that are not about reading the nest. Defaults are sensible
// without any option: the built-in machine profile's default material and thickness.
struct OptimizeOptions {
  std::string machine_file;                  // empty: the built-in profile
  std::string material;                      // empty: the profile's default job
  std::optional<double> thickness_mm;        // [mm]
  bool interpolate = false;                  // thickness between Table 1 rows
  cost::Objective objective = cost::Objective::time;
  double time_limit_s = 10.0;                // wall-clock budget of optimize_nest [s] (0: none), see below
  // Work budget of each route search (solve::SolveParams::work_budget; 0: automatic). Unlike the
  // time limit it does not depend on the machine: with time_limit_s 0 a run is bounded and
  // reproducible on large nests too.
  double work_limit = 0.0;
  std::uint64_t seed = 1;
  int threads = 0;                           // 0: hardware threads (at most 8)
  solve::SolverKind solver = solve::SolverKind::automatic;
  std::optional<geometry::Vec2> start;       // default (0, 0) [mm]
  std::optional<double> kerf_mm;             // default: the profile's for this material
  // controller: the drawn contours with G41/G42 on the scrap side; cam: the toolpath offset by
  // kerf / 2 to the scrap side with exact arcs (model::offset_for_kerf), entries and leads planned
  // on it; none: the drawn contours as they are.
  nc::KerfMode kerf_mode = nc::KerfMode::controller;
  // With kerf_mode controller: cuts whose drawing has details finer than the kerf, which the
  // controller's compensation refuses, are written on their kerf offset without compensation
  // (pipeline/compensation_fallback.hpp); false keeps them compensated (and warned of).
  bool offset_refused_cuts = true;
  // With kerf_mode cam, toolpaths of neighbouring contours that meet (parts closer than the kerf,
  // code "kerf.overlap") are an input error by default: one cut would cut into the other part.
  // With this set they are cut anyway, with a warning per pair.
  bool allow_kerf_overlap = false;
  // Post-processor dialect, name or JSON file; empty: the machine profile's (generic for the
  // built-in profile), see docs/MACHINE-PROFILE.md.
  std::string dialect;
  double entry_step_mm = 0.0;                // 0: adaptive
  int max_candidates = 12;                   // entry candidates per contour
  bool refine_entries = true;                // continuous entry refinement after sequencing
  bool compare_leads = true;                 // evaluate lead types by the frame-corrected objective
  std::string title;                         // first comment of the program
  // Contours whose boundaries cross (code "nest.crossing") are an input error by default: parts
  // drawn over each other would be ruined. With this set they are cut anyway, each once, with a
  // warning; crossing contours get no order between them.
  bool allow_crossing = false;
  Technique technique = Technique::automatic;
  model::ChainOptions chain;                 // chain technique: gap limit, run length
  bool multi_segment = false;                // automatic also builds and compares the multi technique
  model::MultiSegmentOptions multi;          // multi technique: which contours are split, in how many pieces
  ShopRules rules;                           // shop rules (pipeline/shop_rules.hpp): all off by default
};

struct OptimizeResult {
  nc::Toolpath toolpath;
  nc::WrittenProgram program;
  nlohmann::json report;     // the --report JSON
  Diagnostics diagnostics;   // entry fallbacks, extrapolated speeds, ...; code "tip_up.time_limit":
                             // tip-up detours left straight because the time limit ran out or the run
                             // was interrupted (the CLI prints this one)
};

// Steps (each a function in src/pipeline/):
//  1. cutting conditions from the machine profile and Table 1 (material, thickness);
//  2. the cut job of each technique asked for (standard: model::make_cut_job; chain:
//     model::make_chain_job; common: model::make_common_job; multi: model::make_multi_job, only when
//     asked for): basic segments with entry candidates,
//     leads in scrap, precedence. With `automatic`, a chain/common job that joins nothing is not
//     solved again, and one that cannot be built is reported as not available;
//  then for each job (the solver gets what is left of time_limit_s after the work measured or
//  estimated for the steps that follow it and the shares of the shop rules' steps after it,
//  split evenly over the jobs left; at least a tenth of an even share; when building the jobs
//  spent the whole limit, only the job with the lowest floor under its route price is solved, the
//  others reported as not solved, with warning "technique.time_limit"):
//  3. the routing problem in integer time or cost (cost::build_route_problem) and solve::solve();
//  4. continuous refinement of each one-contour entry along its contour for the fixed order;
//  5. toolpath -> G-code in the dialect; frames n counted on the written program;
//  6. T_cut with V_on*(n) (eq. 10); lead types that change n compared by that corrected objective;
//  the job whose program has the lowest corrected objective (T_cut, or eq. 3 cost) is kept;
//  7. the report: `alternatives` (name, basic_segments, pierces, cut_length_mm, rapid_length_mm,
//     frames, t_cut_s, objective; or available: false with a reason) and `chosen`.
//  (with kerf_mode cam, step 2 plans on model::offset_for_kerf(nest): the torch centre's path)
// Errors: unknown material/thickness, invalid profile or dialect, crossing contours in the nest,
// a technique asked for explicitly that is not available; with kerf_mode cam: a contour too small
// for the kerf ("kerf.collapsed", "kerf.split") and, unless allowed, toolpaths that meet
// ("kerf.overlap").
Result<OptimizeResult> optimize_nest(const io::LoadedNest& nest, const OptimizeOptions& options,
                                     const StopToken& stop = {}, const ProgressFn& progress = {});

}  // namespace cutroute::pipeline
