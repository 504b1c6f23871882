// cutroute speed: V_on*(n) of Table 1 for a material, thickness and number of frames.
#include <charconv>
#include <iostream>

#include <nlohmann/json.hpp>

#include <cutroute/core/units.hpp>
#include <cutroute/cost/speed_table.hpp>

#include "commands.hpp"

namespace cutroute::cli {

namespace {

std::string fixed(double v, int digits) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, digits);
  return std::string(buf, r.ptr);
}

struct SpeedOptions {
  std::string material;
  double thickness_mm = 0.0;
  long frames = 0;
  bool json = false;
  bool interpolate = false;
  std::string table;
};

int run_speed(const SpeedOptions& o) {
  const std::string path = o.table.empty() ? cost::default_speed_table_path() : o.table;
  auto table = cost::load_speed_table(path);
  if (!table) return fail(table.error());
  auto q = cost::find_speed(*table, o.material, o.thickness_mm, o.interpolate);
  if (!q) return fail(q.error());
  const auto s = q->at(static_cast<double>(o.frames));
  const double n0 = q->interpolated ? (1.0 - q->weight) * q->lower.n0 + q->weight * q->upper.n0 : q->lower.n0;
  if (o.json) {
    nlohmann::json j;
    j["material"] = q->material;
    j["thickness_mm"] = o.thickness_mm;
    j["frames"] = o.frames;
    j["n0"] = n0;
    j["v_on_m_s"] = s.v_m_s;
    j["v_on_mm_min"] = units::m_per_s_to_mm_per_min(s.v_m_s);
    j["v_set_m_s"] = q->v_set_m_s();
    j["regime"] = cost::to_string(s.regime);
    j["measured"] = q->measured;
    j["interpolated"] = q->interpolated;
    j["warnings"] = q->warnings;
    std::cout << json_text(j) << '\n';
  } else {
    std::cout << q->material << ' ' << fixed(o.thickness_mm, 2) << " mm, n = " << o.frames
              << " frames (n0 = " << fixed(n0, 0) << "): " << cost::to_string(s.regime) << " regime\n"
              << "V_on*(n)  " << fixed(s.v_m_s, 5) << " m/s  "
              << fixed(units::m_per_s_to_mm_per_min(s.v_m_s), 1) << " mm/min\n"
              << "set speed " << fixed(q->v_set_m_s(), 5) << " m/s  "
              << fixed(units::m_per_s_to_mm_per_min(q->v_set_m_s()), 1) << " mm/min\n"
              << "Table 1 row: " << (q->measured ? "measured" : "extrapolated by the authors (not measured)")
              << (q->interpolated ? ", interpolated between rows" : "") << '\n';
    for (const auto& w : q->warnings) std::cout << "warning: " << w << '\n';
  }
  return kOk;
}

}  // namespace

void add_speed(CLI::App& root, Commands& out) {
  auto opt = std::make_shared<SpeedOptions>();
  auto* app = root.add_subcommand("speed", "Real cutting speed V_on*(n) from Table 1 (ByStar 3015)");
  app->add_option("--material", opt->material, "Material or alias (AMg3M, 5754, St10kp, ...)")->required();
  app->add_option("--thickness", opt->thickness_mm, "Sheet thickness [mm]")
      ->required()
      ->check(CLI::PositiveNumber);
  app->add_option("--frames", opt->frames, "Frames (blocks) of the NC program, n")
      ->required()
      ->check(CLI::NonNegativeNumber);
  app->add_flag("--interpolate", opt->interpolate, "Blend the two neighbouring thicknesses linearly");
  app->add_option("--table", opt->table, "Speed table JSON (default: data/materials/bystar3015.json)");
  app->add_flag("--json", opt->json, "Print JSON");
  out.push_back({app, [opt] { return run_speed(*opt); }});
}

}  // namespace cutroute::cli
