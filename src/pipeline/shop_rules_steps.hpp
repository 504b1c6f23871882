// Private: where optimize_nest() applies the shop rules, one function per pipeline step.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include <cutroute/core/stop.hpp>
#include <cutroute/cost/route_problem.hpp>
#include <cutroute/model/cut_job.hpp>
#include <cutroute/model/nest.hpp>
#include <cutroute/nc/build_toolpath.hpp>
#include <cutroute/nc/post_dialect.hpp>
#include <cutroute/nc/toolpath.hpp>
#include <cutroute/pipeline/shop_rules.hpp>
#include <cutroute/solve/problem.hpp>

#include "refine.hpp"

namespace cutroute::pipeline::rules {

// Shares of --time-limit that optimize_nest() keeps from the route solver for the rules' steps
// after it (0 for a step that does not run with these rules): the re-ordering search (step 3),
// the entry refinement under the tip-up price (step 4) and the tip-up detours of the programs
// (step 5). Why and how they are used: optimize.cpp, RunLimit.
struct TimeShares {
  double search = 0.0;
  double refine = 0.0;
  double detours = 0.0;
};
TimeShares time_shares(const ShopRules& r);

// Step 2 (cut job): with part rigidity, outer contours keep only their corner candidates (those
// without any corner keep all, and are counted in the report).
void restrict_candidates(model::CutJob& job, const model::Nest& nest, const ShopRules& r);

// Step 3 (sequencing): the solver's route re-ordered under the history-dependent rules (heat,
// tip-up, sheet rigidity) by solve::history_search() from three starts: the solver's route, the
// greedy route under the rules, and (with a clamp) the route sorted along the sweep. Returns the
// route and writes what it did into report["search"], and the rules' effects on the returned
// route (heat pairs, rapids over freed parts, steps behind the sweep front) into report["route"];
// `penalty` gets their total price [objective unit], by which alternatives are compared. Every
// technique's segments work: a segment is priced by all the contours it cuts (a chain's parts,
// the contours a common line or a multi-segment piece runs along).
std::vector<solve::NodeId> reorder(const model::Nest& nest, const model::CutJob& job, const cost::RouteProblem& rp,
                                   const std::vector<solve::NodeId>& route, const ShopRules& r, const StopToken& stop,
                                   nlohmann::json& report, double& penalty);

// Step 4 (entry refinement): with tip-up, the price of an entry's rapids that pass over parts
// already cut free at that point of the sequence (tip_up_weight each, freed as the program's
// detour pass frees them), so that sliding entries to shorten rapids does not bring back the
// rapids the order avoided (400 circles: 42 such rapids after sequencing, about 125 after the
// refinement without it, each then a detour); empty without tip-up.
EntryPenalty tip_up_entry_penalty(const model::Nest& nest, const std::vector<model::EntryCandidate>& seq, const ShopRules& r);

// Step 4 (after entry refinement): with part rigidity, each outer contour's entry is put back on
// the corner candidate nearest the material still uncut after it. Returns the number of outer
// contours entered at a corner.
int place_rigid_entries(const model::Nest& nest, const model::CutJob& job, std::vector<model::EntryCandidate>& seq,
                        const ShopRules& r);

// Does each cut after a micro-joint gap start with a lead-in (ShopRules::tab_lead_in, `auto`
// resolved for this post dialect)?
bool lead_in_after_tabs(const ShopRules& r, const nc::PostDialect& dialect);

// What the toolpath step needs besides the nest: lead-ins after micro-joint gaps are planned as
// entries, by the job's planner and entry options; the post dialect decides `auto`.
struct ToolpathContext {
  const model::EntryPlanner& planner;
  const model::EntryOptions& entries;
  const nc::PostDialect& dialect;
  // Micro-joints: a gap holds the part only where no other contour of the planner's nest comes
  // this close: beyond that distance skeleton is left between the two kerfs [mm].
  double tab_clearance_mm = 0.0;
  // Micro-joints: how far a gap's ends keep from the path's corners where they can (the kerf under
  // controller compensation: a short move after a gap is one the controller cannot offset) [mm].
  double tab_corner_clearance_mm = 0.0;
};

// ToolpathContext::tab_clearance_mm for a kerf mode: the planner's contours are the drawn ones
// under controller compensation (each kerf lies outside its part: 2 kerfs), the cut paths with
// cam offsets or none (each kerf centred on its path: 1 kerf); plus a micrometre.
double tab_clearance(nc::KerfMode mode, double kerf_mm);

// Step 5 (toolpath): detours around freed parts, then tabs. Returns the report of both. The
// detour searches stop when `stop` requests it (deadline or cancel): the rapids not yet routed
// stay straight and are counted in tip_up_program.unavoidable_left_at_time_limit. Where
// lead_in_after_tabs(), each cut after a gap is entered by a straight lead-in along the contour's
// normal (the job's lead-in length), where one is admissible: a tangential lead-in would start
// beside the gap and cut the tab off the skeleton.
nlohmann::json apply_to_toolpath(nc::Toolpath& path, const model::Nest& nest, const ShopRules& r, const StopToken& stop,
                                 const ToolpathContext& context);

// The micro-joints' warnings from the toolpath step's report (apply_to_toolpath()'s "tabs"): cuts
// after a tab resumed on the part's edge although lead-ins were asked for (tabs.resumed_on_path,
// naming up to five; `entry_on_edge`: the compensation's entry move starts there too), tabs a
// neighbour's cut leaves holding nothing (tabs.on_a_neighbours_cut) and parts with no edge on
// the skeleton (tabs.part_without_skeleton_edge). None without tabs.
Diagnostics tab_warnings(const nlohmann::json& rules, const nc::Toolpath& path, bool entry_on_edge);

// The report's "rules" object: the active rules with their settings, and what they did (the
// search's and the final route's effects, the toolpath passes, corner entries).
nlohmann::json report(const ShopRules& r, const nlohmann::json& order, const nlohmann::json& toolpath, int corner_entries);

}  // namespace cutroute::pipeline::rules
