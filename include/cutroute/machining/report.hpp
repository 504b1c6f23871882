// Outputs of `cutroute machining` built as values (the CLI writes them): the JSON report, a text
// summary, the CSV of valley and grid, and the SVG cost map (the seed's Figs. 1-2).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <cutroute/machining/optimize.hpp>

namespace cutroute::machining {

// Everything one run produced; fig5 and sweep are optional extras.
struct RunOutput {
  const Problem* problem = nullptr;
  const OptimizeResult* result = nullptr;
  std::optional<Fig5Result> fig5;        // cross-check on the same grid size
  std::vector<AccuracyCostPoint> sweep;  // cost of accuracy, when problem.K_TZ_sweep is given
};

// Unit of each constraint row's value and limit.
const char* constraint_unit(ConstraintId c);

// Field names carry their units (vc_m_min, f_mm_rev, ...); numbers at full precision.
nlohmann::json report_json(const RunOutput& out);
// A few readable lines for a terminal.
std::string report_text(const RunOutput& out);
// One table: section (valley | grid), vc, f, Vf, CT, T, feasible, binding/worst constraint.
std::string report_csv(const RunOutput& out);
// Cost map on log axes (vc, Vf): feasible region, valley vc*(f), near-optimal contours, optimum.
std::string report_svg(const RunOutput& out);

}  // namespace cutroute::machining
