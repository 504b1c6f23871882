#include <cutroute/io/inspect_report.hpp>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/text.hpp>

namespace cutroute::io {

nlohmann::json to_json(const Diagnostic& d) {
  nlohmann::json j;
  j["severity"] = to_string(d.severity);
  j["message"] = d.message;
  if (d.line) j["line"] = *d.line;
  if (!d.handle.empty()) j["handle"] = d.handle;
  if (!d.layer.empty()) j["layer"] = d.layer;
  if (!d.code.empty()) j["code"] = d.code;
  return j;
}

nlohmann::json inspect_report(const LoadedNest& loaded) {
  const model::Nest& nest = loaded.nest;
  double cut = 0, total = 0, open = 0;
  std::size_t holes = 0;
  geometry::Box bbox;
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    const auto& c = nest.contours[model::ContourId(static_cast<std::int32_t>(i))];
    const double len = geometry::length(c.source.contour);
    total += len;
    if (c.role != model::ContourRole::sheet) cut += len;
    if (c.role == model::ContourRole::hole) ++holes;
    bbox.add(c.box);
  }
  for (const auto& p : loaded.open_paths) {
    const double len = geometry::length(p.path);
    open += len;
    total += len;
    bbox.add(geometry::bounding_box(p.path));
  }

  nlohmann::json j;
  j["file"] = to_utf8(loaded.file);  // a file name in a legacy encoding: JSON needs UTF-8
  j["units_in_file"] = loaded.units_in_file;
  j["units_source"] = loaded.units_source;
  j["mm_per_unit"] = loaded.mm_per_unit;
  j["entities"] = loaded.entity_counts;
  j["layers"] = loaded.layers;  // entities per layer, before --layers / --ignore-layers
  j["skipped"] = loaded.skipped;
  j["contours_closed"] = nest.contours.size();
  j["contours_open"] = loaded.open_paths.size();
  j["gaps_closed"] = loaded.gaps_closed.size();
  j["parts"] = nest.parts.size();
  j["holes"] = holes;
  j["max_depth"] = nest.max_depth;
  if (nest.sheet) {
    const auto& b = nest.contours[*nest.sheet].box;
    j["sheet"] = {{"bbox_mm", {b.xmin, b.ymin, b.xmax, b.ymax}}};
  } else {
    j["sheet"] = nullptr;
  }
  j["cut_length_mm"] = cut;
  j["open_length_mm"] = open;
  j["total_length_mm"] = total;
  j["bbox_mm"] = bbox.empty() ? nlohmann::json::array() : nlohmann::json{bbox.xmin, bbox.ymin, bbox.xmax, bbox.ymax};
  // Repeated entities (a LINE twice) and whole outlines drawn twice (warned "duplicates contour").
  j["dropped"] = {{"zero_length", loaded.dropped_zero_length},
                  {"duplicates", loaded.dropped_duplicates},
                  {"duplicate_contours", loaded.nest.dropped_duplicates}};
  auto diags = nlohmann::json::array();
  for (const auto& d : loaded.diagnostics) diags.push_back(to_json(d));
  j["diagnostics"] = std::move(diags);
  return j;
}

std::string inspect_text(const nlohmann::json& r) {
  std::string s;
  s += r["file"].get<std::string>() + "\n";
  s += "  units: " + r["units_in_file"].get<std::string>() + " (from " + r["units_source"].get<std::string>() + ")\n";
  s += "  entities:";
  for (const auto& [type, n] : r["entities"].items()) s += " " + type + " " + std::to_string(n.get<std::size_t>());
  s += "\n";
  if (r.contains("layers") && !r["layers"].empty()) {
    s += "  layers (entities):";
    for (const auto& [layer, n] : r["layers"].items()) s += " " + (layer.empty() ? std::string("(no name)") : layer) + " " + std::to_string(n.get<std::size_t>());
    s += "\n";
  }
  const std::size_t gaps = r.value("gaps_closed", std::size_t{0});
  s += "  contours: " + std::to_string(r["contours_closed"].get<std::size_t>()) + " closed" +
       (gaps > 0 ? " (" + std::to_string(gaps) + " gap(s) in the drawing closed)" : std::string()) + ", " +
       std::to_string(r["contours_open"].get<std::size_t>()) + " open\n";
  s += "  parts: " + std::to_string(r["parts"].get<std::size_t>()) + ", holes: " +
       std::to_string(r["holes"].get<std::size_t>()) + ", max depth: " + std::to_string(r["max_depth"].get<int>()) +
       (r["sheet"].is_null() ? "" : ", sheet border recognised") + "\n";
  s += "  cut length: " + format_fixed(r["cut_length_mm"].get<double>(), 3) + " mm\n";
  if (!r["bbox_mm"].empty()) {
    s += "  extent: " + format_fixed(r["bbox_mm"][2].get<double>() - r["bbox_mm"][0].get<double>(), 3) + " x " +
         format_fixed(r["bbox_mm"][3].get<double>() - r["bbox_mm"][1].get<double>(), 3) + " mm\n";
  }
  std::size_t warnings = 0, errors = 0;
  for (const auto& d : r["diagnostics"]) {
    if (d["severity"] == "error") ++errors;
    if (d["severity"] == "warning") ++warnings;
  }
  s += "  diagnostics: " + std::to_string(errors) + " errors, " + std::to_string(warnings) + " warnings\n";
  return s;
}

}  // namespace cutroute::io
