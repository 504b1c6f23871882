#include "input_options.hpp"

#include <charconv>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>

#include <cutroute/core/number_format.hpp>

namespace cutroute::cli {

CLI::Validator finite_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double v = 0;
        try {
          std::size_t used = 0;
          v = std::stod(text, &used);
          if (used != text.size()) return "not a number: " + text;
        } catch (const std::exception&) {
          return "not a number: " + text;
        }
        if (!std::isfinite(v) || v < lo || v > hi)
          return "Value " + text + " not in range " + format_fixed(lo, 3) + " to " + format_fixed(hi, 3);
        return {};
      },
      "FLOAT in [" + format_fixed(lo, 3) + " - " + format_fixed(hi, 3) + "]");
}

void add_input_options(CLI::App* app, InputOptions& o) {
  app->add_option("--snap", o.snap_mm, "End-point snapping distance when chaining entities [mm]")
      ->check(finite_range(0.0, 10.0))
      ->capture_default_str();
  app->add_option("--close-gaps", o.close_gaps_mm,
                  "Chain ends still apart after --snap are joined, with a warning, when closer than this [mm] (0: off)")
      ->check(finite_range(0.0, 1.0))
      ->capture_default_str();
  app->add_option("--units", o.units, "Drawing units, overriding the file's header")
      ->check(CLI::IsMember({"mm", "cm", "m", "in", "ft"}));
  app->add_option("--layers", o.layers, "Read only these layers (comma-separated)")->delimiter(',');
  app->add_option("--ignore-layers", o.ignore_layers, "Ignore these layers (comma-separated)")->delimiter(',');
  app->add_option("--sheet", o.sheet, "Sheet size W,H [mm]; the sheet's border is then not a part");
}

Result<io::NestLoadOptions> to_load_options(const InputOptions& o) {
  io::NestLoadOptions lo;
  lo.snap_mm = o.snap_mm;
  lo.close_gaps_mm = o.close_gaps_mm;
  if (!o.units.empty()) lo.dxf.units = o.units;
  lo.dxf.layers = o.layers;
  lo.dxf.ignore_layers = o.ignore_layers;
  if (!o.sheet.empty()) {
    const auto comma = o.sheet.find(',');
    double w = 0, h = 0;
    bool ok = comma != std::string::npos;
    if (ok) {
      const char* s = o.sheet.data();
      const auto r1 = std::from_chars(s, s + comma, w);
      const auto r2 = std::from_chars(s + comma + 1, s + o.sheet.size(), h);
      ok = r1.ec == std::errc{} && r1.ptr == s + comma && r2.ec == std::errc{} && r2.ptr == s + o.sheet.size() &&
           std::isfinite(w) && std::isfinite(h) && w > 0 && h > 0 && w <= units::kMaxCoordinateMm &&
           h <= units::kMaxCoordinateMm;
    }
    if (!ok)
      return make_error("--sheet wants W,H in mm, two positive numbers of at most " + format_fixed(units::kMaxCoordinateMm, 0) +
                        " (got '" + o.sheet + "')");
    lo.nest.sheet_size = geometry::Vec2{w, h};
  }
  return lo;
}

Result<geometry::Vec2> parse_point(const std::string& s, const char* what) {
  const auto comma = s.find(',');
  try {
    if (comma == std::string::npos) throw std::invalid_argument("no comma");
    std::size_t i1 = 0, i2 = 0;
    const double x = std::stod(s.substr(0, comma), &i1);
    const double y = std::stod(s.substr(comma + 1), &i2);
    if (i1 != comma || i2 != s.size() - comma - 1 || !std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("bad");
    // A start 1e308 mm away made rapids of infinite length ("G0 Xinf" in the program).
    if (std::abs(x) > units::kMaxCoordinateMm || std::abs(y) > units::kMaxCoordinateMm)
      return make_error(std::string(what) + " is more than 1e6 mm from the origin (got '" + s + "')");
    return geometry::Vec2{x, y};
  } catch (const std::exception&) {
    return make_error(std::string(what) + " wants X,Y in mm (got '" + s + "')");
  }
}

}  // namespace cutroute::cli
