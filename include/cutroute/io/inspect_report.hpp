// inspect_report(): the JSON summary of a loaded nest printed by `cutroute inspect`.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include <cutroute/io/nest_loader.hpp>

namespace cutroute::io {

// Fields: file, units_in_file, units_source, mm_per_unit, entities {TYPE: count} (skipped types
// included), skipped {TYPE: count}, contours_closed (the sheet border included when there is one),
// contours_open, parts, holes, max_depth, sheet (null or {bbox_mm}), cut_length_mm (closed
// contours of parts: outers and holes, sheet excluded) [mm], open_length_mm [mm],
// total_length_mm (every curve, sheet and open paths included) [mm], bbox_mm [xmin, ymin, xmax,
// ymax] of all geometry, dropped {zero_length, duplicates}, diagnostics [{severity, message,
// line?, handle?, layer?}].
nlohmann::json inspect_report(const LoadedNest& nest);

// A short human-readable summary of the same report.
std::string inspect_text(const nlohmann::json& report);

nlohmann::json to_json(const Diagnostic& d);

}  // namespace cutroute::io
