#include <cutroute/io/batch_summary.hpp>

#include <algorithm>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/text.hpp>
#include <cutroute/io/route_picture.hpp>

namespace cutroute::io {
namespace {

std::string field(const std::string& raw) {
  const std::string s = to_utf8(raw);  // file names and messages may not be UTF-8; the table is
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string row(const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) line += ',';
    line += field(cells[i]);
  }
  line += '\n';
  return line;
}

std::string number(const nlohmann::json& r, const char* key, int decimals) {
  return r.contains(key) && r[key].is_number() ? format_fixed(r[key].get<double>(), decimals) : "";
}

// The report's warnings by code, in order of first appearance: "chain.open:2 kerf.trimmed:1".
std::string warning_codes(const nlohmann::json& r) {
  std::vector<std::pair<std::string, int>> codes;
  if (r.contains("diagnostics") && r["diagnostics"].is_array())
    for (const auto& d : r["diagnostics"]) {
      if (d.value("severity", std::string()) != "warning") continue;
      std::string code = d.value("code", std::string());
      if (code.empty()) code = "warning";
      auto it = std::find_if(codes.begin(), codes.end(), [&](const auto& c) { return c.first == code; });
      if (it == codes.end()) codes.emplace_back(code, 1);
      else ++it->second;
    }
  std::string out;
  for (const auto& [code, n] : codes) out += (out.empty() ? "" : " ") + code + ":" + std::to_string(n);
  return out;
}

}  // namespace

std::string batch_summary_csv(const std::vector<BatchEntry>& entries) {
  std::string csv = row({"nest", "status", "technique", "material", "thickness_mm", "pierces", "cut_length_mm", "rapid_length_mm",
                         "frames", "t_cut_s", "t_cut_const_speed_s", "cost", "cost_unit", "route", "program", "error", "warnings"});
  double pierces = 0, cut = 0, rapid = 0, frames = 0, t_cut = 0, t_const = 0, cost = 0;
  std::string unit;
  bool one_unit = true;
  int ok = 0;
  for (const auto& e : entries) {
    const nlohmann::json& r = e.report;
    if (!r.is_object()) {
      csv += row({e.nest, e.not_started ? "not started" : "error", "", "", "", "", "", "", "", "", "", "", "", "", e.program, e.error, ""});
      continue;
    }
    ++ok;
    pierces += r.value("pierces", 0.0);
    cut += r.value("cut_length_mm", 0.0);
    rapid += r.value("rapid_length_mm", 0.0);
    frames += r.value("frames", 0.0);
    t_cut += r.value("t_cut_s", 0.0);
    t_const += r.value("t_cut_const_speed_s", 0.0);
    cost += r.value("cost", 0.0);
    const std::string u = r.value("cost_unit", std::string());
    one_unit = one_unit && (ok == 1 || u == unit);
    unit = u;
    std::string route = route_quality(r);
    if (const auto cut_at = route.find(" to its lower bound"); cut_at != std::string::npos) route.resize(cut_at);
    csv += row({e.nest, "ok", r.value("chosen", std::string()), r.value("material", std::string()), number(r, "thickness_mm", 3),
                number(r, "pierces", 0), number(r, "cut_length_mm", 1), number(r, "rapid_length_mm", 1), number(r, "frames", 0),
                number(r, "t_cut_s", 2), number(r, "t_cut_const_speed_s", 2), number(r, "cost", 2), u, route, e.program, "",
                warning_codes(r)});
  }
  csv += row({"total", std::to_string(ok) + " of " + std::to_string(entries.size()) + " cut", "", "", "", format_fixed(pierces, 0),
              format_fixed(cut, 1), format_fixed(rapid, 1), format_fixed(frames, 0), format_fixed(t_cut, 2), format_fixed(t_const, 2),
              ok > 0 && one_unit ? format_fixed(cost, 2) : "", ok > 0 && one_unit ? unit : "", "", "", "", ""});
  return csv;
}

}  // namespace cutroute::io
