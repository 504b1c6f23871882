// cutroute estimate: cutting time (eq. 1 and eq. 10) and cost (eq. 3) of a G-code program.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <iostream>
#include <numbers>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include <cutroute/core/units.hpp>
#include <cutroute/cost/estimate.hpp>
#include <cutroute/cost/machine_profile.hpp>
#include <cutroute/cost/motion_model.hpp>
#include <cutroute/cost/speed_table.hpp>
#include <cutroute/io/estimate_json.hpp>
#include <cutroute/io/inspect_report.hpp>
#include <cutroute/nc/dialect.hpp>
#include <cutroute/nc/gcode_reader.hpp>
#include <cutroute/nc/post_dialect.hpp>

#include "input_options.hpp"

#include "commands.hpp"

namespace cutroute::cli {

namespace {

std::string fixed(double v, int digits) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, digits);
  return std::string(buf, r.ptr);
}

struct EstimateOptions {
  std::string program;
  std::string material;
  double thickness_mm = 0.0;
  std::string machine;
  std::string dialect;
  bool interpolate = false;
  bool json = false;
  std::string start;  // "X,Y": where the head stands when the program starts (default the origin)
};

// The reader dialect: --dialect when given, else the machine profile's.
Result<nc::Dialect> dialect_of(const cost::MachineProfile& p, const std::string& override_name) {
  if (!override_name.empty()) return nc::reader_dialect_named(override_name, "unknown --dialect");
  return cost::profile_reader_dialect(p);
}

// The cutting moves as the motion model sees them: a move starts from rest after a pierce or
// after anything that is not a cut; the turn is the angle between consecutive tangents.
std::vector<cost::MotionMove> cutting_moves(const std::vector<nc::Move>& moves, double v_set_mm_s) {
  std::vector<cost::MotionMove> out;
  out.reserve(moves.size());
  const nc::Move* prev = nullptr;
  for (const auto& m : moves) {
    if (!m.beam_on) {
      prev = nullptr;
      continue;
    }
    cost::MotionMove c;
    c.length_mm = m.length_mm;
    c.feed_mm_s = m.feed_mm_min > 0.0 ? m.feed_mm_min / 60.0 : v_set_mm_s;
    c.radius_mm = m.radius_mm;
    c.from_rest = m.pierce || prev == nullptr;
    if (prev) {
      double d = std::remainder(m.start_dir_rad - prev->end_dir_rad, 2.0 * std::numbers::pi);
      c.turn_rad = std::abs(d);
    }
    out.push_back(c);
    prev = &m;
  }
  return out;
}

int run_estimate(const EstimateOptions& o) {
  // A thickness alone is looked up for the profile's default material, as optimize does.
  if (!o.material.empty() && o.thickness_mm <= 0.0) {
    std::cerr << "cutroute: error: --material needs --thickness\n";
    return kUsageError;
  }
  geometry::Vec2 start{0, 0};
  if (!o.start.empty()) {
    auto p = parse_point(o.start, "--start");
    if (!p) {
      std::cerr << "cutroute: error: " << p.error().message << '\n';
      return kUsageError;
    }
    start = *p;
  }
  auto profile =
      cost::load_machine_profile(o.machine.empty() ? cost::default_machine_profile_path() : o.machine);
  if (!profile) return fail(profile.error());
  auto table = cost::load_speed_table(profile->speed_table);
  if (!table) return fail(table.error());
  std::string material = o.material;
  double thickness = o.thickness_mm;
  if (material.empty()) {
    if (!profile->default_material || !profile->default_thickness_mm) {
      return fail(
          make_error("no material given: use --material M --thickness T (the profile has no default_job)",
                     profile->file));
    }
    material = *profile->default_material;
    if (thickness <= 0.0) thickness = *profile->default_thickness_mm;
  }
  auto conditions = cost::make_conditions(*profile, *table, material, thickness, o.interpolate);
  if (!conditions) return fail(conditions.error());
  auto dialect = dialect_of(*profile, o.dialect);
  if (!dialect) return fail(dialect.error());
  nc::ReadOptions ro;
  ro.dialect = *dialect;
  ro.start_mm = start;
  std::vector<nc::Move> moves;
  const auto& lim = profile->motion;
  if (lim.accel_m_s2) ro.moves = &moves;
  auto stats = nc::read_gcode_file(o.program, ro);
  if (!stats) return fail(stats.error());
  // Unknown M codes that a shipped post dialect writes (plasma-thc's torch-height outputs): the
  // program was likely written with it.
  if (!stats->unknown_m_codes.empty() && o.dialect.empty())
    for (const auto& name : nc::post_dialect_names()) {
      auto post = nc::find_post_dialect(name);
      if (!post) continue;
      auto reads = nc::reader_dialect(*post);
      if (!reads) continue;
      const bool all = std::all_of(stats->unknown_m_codes.begin(), stats->unknown_m_codes.end(),
                                   [&](int m) { return reads->is_inert(m) || reads->switches_on(m) || reads->switches_off(m); });
      if (!all) continue;
      stats->warnings.push_back(make_warning("its unknown M codes are what the post dialect '" + name + "' writes: --dialect " +
                                                 name + " reads the program as written by it",
                                             o.program));
      stats->warnings.back().code = "gcode.post_dialect";
      break;
    }
  for (const auto& w : stats->warnings) std::cerr << "cutroute: " << format(w) << '\n';
  if (stats->suppressed_warnings > 0)
    std::cerr << "cutroute: " << o.program << ": " << stats->suppressed_warnings
              << " more warning(s) not shown\n";
  const auto e = cost::estimate_time(cost::program_totals(*stats), *conditions);
  const bool measured = conditions->speed.measured;
  std::optional<cost::MotionTime> motion;
  if (lim.accel_m_s2) {
    const cost::MotionParams mp{*lim.accel_m_s2 * units::kMmPerM, lim.junction_deviation_mm.value_or(0.0),
                                lim.block_time_s.value_or(0.0)};
    auto t = cost::time_moves(cutting_moves(moves, units::m_per_s_to_mm_per_s(e.v_on_set_m_s)), mp);
    if (!t) return fail(make_error("field motion: " + t.error().message, profile->file));
    motion = *t;
  }

  if (o.json) {
    nlohmann::json j;
    j["program"] = o.program;
    j["machine"] = profile->name;
    j["material"] = conditions->material;
    j["thickness_mm"] = thickness;
    j["dialect"] = dialect->name;
    j["pierces"] = stats->pierces;
    j["cut_length_mm"] = stats->cut_length_mm;
    j["rapid_length_mm"] = stats->rapid_length_mm;
    j["feed_off_length_mm"] = stats->feed_off_length_mm;
    j["frames"] = stats->frames;
    j["v_on_set_m_s"] = e.v_on_set_m_s;
    j["v_on_m_s"] = e.v_on_m_s;
    // The names of optimize's report, so one reader takes both.
    j["v_on_regime"] = cost::to_string(e.regime);
    j["measured_speed_row"] = measured;
    j["t_cut_const_speed_s"] = e.t_cut_const_speed_s;
    j["t_cut_s"] = e.t_cut_s;
    j["cost"] = e.cost;
    j["cost_unit"] = e.cost_unit;
    j["breakdown"] = io::breakdown_json(e);
    j["dwells"] = stats->dwells;
    j["cut_time_at_programmed_feed_s"] = stats->cut_time_at_feed_s;
    if (motion) {
      j["motion"] = {{"cutting_s", motion->time_s},
                     {"mean_cut_speed_m_s", motion->mean_speed_mm_s / units::kMmPerM},
                     {"block_limited_moves", motion->block_limited}};
    }
    // `warnings` as text, as before; `diagnostics` as optimize's report has them, each with its
    // code, so that one reader takes both and a policy can act on a kind without parsing text.
    j["warnings"] = nlohmann::json::array();
    j["diagnostics"] = nlohmann::json::array();
    for (const auto& w : conditions->warnings) {
      j["warnings"].push_back(w);
      Diagnostic d = make_warning(w);
      d.code = "material.conditions";  // optimize's code for the same interpolated or extrapolated rows
      j["diagnostics"].push_back(io::to_json(d));
    }
    for (const auto& w : stats->warnings) {
      j["warnings"].push_back(format(w));
      j["diagnostics"].push_back(io::to_json(w));
    }
    if (stats->suppressed_warnings > 0) {
      Diagnostic d = make_warning(std::to_string(stats->suppressed_warnings) + " more warning(s) not shown", o.program);
      d.code = "gcode.warnings_capped";
      j["warnings"].push_back(format(d));
      j["diagnostics"].push_back(io::to_json(d));
    }
    std::cout << json_text(j) << '\n';
    return kOk;
  }
  std::cout << o.program << ": " << conditions->material << ' ' << fixed(thickness, 2) << " mm on "
            << profile->name << "\n"
            << "  frames n            " << stats->frames << "\n"
            << "  pierces N_pt        " << stats->pierces << "\n"
            << "  cut length L_on     " << fixed(stats->cut_length_mm, 3) << " mm\n"
            << "  rapid length L_off  " << fixed(stats->rapid_length_mm, 3) << " mm\n";
  if (stats->feed_off_length_mm > 0.0)
    std::cout << "  feed moves, beam off " << fixed(stats->feed_off_length_mm, 3) << " mm\n";
  std::cout << "  V_on set            " << fixed(e.v_on_set_m_s, 5) << " m/s ("
            << fixed(units::m_per_s_to_mm_per_min(e.v_on_set_m_s), 1) << " mm/min)\n"
            << "  V_on*(n)            " << fixed(e.v_on_m_s, 5) << " m/s ("
            << fixed(units::m_per_s_to_mm_per_min(e.v_on_m_s), 1) << " mm/min), " << cost::to_string(e.regime)
            << " regime" << (measured ? "" : ", extrapolated row") << "\n"
            << "  T_cut, eq. 1 (set speed)   " << fixed(e.t_cut_const_speed_s, 2) << " s\n"
            << "  T_cut, eq. 10 (V_on*(n))   " << fixed(e.t_cut_s, 2) << " s\n"
            << "    cutting " << fixed(e.cutting_s, 2) << " s, rapid " << fixed(e.rapid_s, 2) << " s, pierce "
            << fixed(e.pierce_s, 2) << " s\n"
            << "  outside eq. 10: dwell " << fixed(e.dwell_s, 2) << " s (pierce dwells replace "
            << fixed(e.pierce_replaced_s, 2) << " s of t_pt), beam-off feed " << fixed(e.feed_off_s, 2)
            << " s, head " << fixed(e.head_s, 2) << " s\n"
            << "  total               " << fixed(e.total_s, 2) << " s\n";
  if (motion) {
    std::cout << "  motion model: cutting " << fixed(motion->time_s, 2) << " s, mean cut speed "
              << fixed(motion->mean_speed_mm_s / units::kMmPerM, 5) << " m/s, " << motion->block_limited
              << " block-time-limited moves\n";
  }
  std::cout << "  cost, eq. 3         " << fixed(e.cost, 2) << ' ' << e.cost_unit << "\n";
  for (const auto& w : conditions->warnings) std::cout << "warning: " << w << '\n';
  return kOk;
}

}  // namespace

void add_estimate(CLI::App& root, Commands& out) {
  auto opt = std::make_shared<EstimateOptions>();
  auto* app =
      root.add_subcommand("estimate", "Cutting time (eq. 1, eq. 10) and cost (eq. 3) of a G-code program");
  app->add_option("program", opt->program, "G-code program (.nc, .ngc)")->required();
  app->add_option("--material", opt->material, "Material or alias (default: the profile's default_job)");
  app->add_option("--thickness", opt->thickness_mm, "Sheet thickness [mm]")->check(finite_range(1e-3, 1000));
  app->add_option("--machine", opt->machine, "Machine profile JSON (default: data/machines/bystar3015.json)");
  app->add_option("--dialect", opt->dialect,
                  "Dialect overriding the profile's: rs274, rs274-m7m9, fanuc-ms, or a post-processor "
                  "dialect (generic, plasma-thc, a dialect JSON file) to read a program written with it");
  app->add_flag("--interpolate", opt->interpolate, "Blend the two neighbouring thicknesses linearly");
  app->add_flag("--json", opt->json, "Print JSON");
  app->add_option("--start", opt->start,
                  "Where the head stands when the program starts, X,Y [mm] (default 0,0; optimize's --start: "
                  "its program begins with the rapid from there)");
  out.push_back({app, [opt] { return run_estimate(*opt); }});
}

}  // namespace cutroute::cli
