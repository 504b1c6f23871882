#include <cutroute/cost/machine_profile.hpp>

#include <filesystem>

#include <cutroute/core/version.hpp>
#include <cutroute/nc/post_dialect.hpp>

#include "cost/json_fields.hpp"

namespace cutroute::cost {

namespace {

// What a cutting machine can have; beyond these a profile value is a typo or a unit slip (a pierce
// of 1e308 s made the estimate NaN, a rapid speed of 1e-300 m/s a total of 4e300 s).
constexpr double kMaxSpeedMS = 100.0;    // working and rapid speeds [m/s]
constexpr double kMinRapidMS = 1.0e-3;   // rapid speed [m/s]: 1 mm/s
constexpr double kMaxTimeS = 3600.0;     // pierce, head lift and lower [s]
constexpr double kMaxWorkAreaMm = 1e5;   // axis travel: the largest gantry tables are tens of metres [mm]
constexpr double kMaxKerfMm = 20.0;      // as --kerf
constexpr double kMaxLeadMm = 1000.0;    // lead-in, lead-out [mm]
constexpr double kMaxRate = 1.0e9;       // cost rates [unit per m, per pierce]

using detail::json;

// A misspelt optional field would otherwise be ignored without a word.
Diagnostic unknown_keys(const json& obj, std::initializer_list<const char*> known, const std::string& path) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const char* k : known) ok = ok || it.key() == k;
    if (!ok) return make_error("unknown field " + detail::field(path, it.key()));
  }
  return {};
}

Result<std::vector<int>> m_codes(const json& obj, const std::string& key, const std::string& path) {
  std::vector<int> out;
  const auto it = obj.find(key);
  if (it == obj.end() || it->is_null()) return out;
  if (!it->is_array())
    return make_error("field " + detail::field(path, key) + " must be an array like [\"M3\", \"M4\"]");
  for (std::size_t i = 0; i < it->size(); ++i) {
    const json& v = (*it)[i];
    const std::string f = detail::item(detail::field(path, key), i);
    if (!v.is_string()) return make_error("field " + f + " must be a string like \"M3\"");
    const std::string s = v.get<std::string>();
    if (s.size() < 2 || (s[0] != 'M' && s[0] != 'm') || s.size() > 6)
      return make_error("field " + f + " must be an M code like \"M3\", not \"" + s + "\"");
    int m = 0;
    for (std::size_t k = 1; k < s.size(); ++k) {
      if (s[k] < '0' || s[k] > '9')
        return make_error("field " + f + " must be an M code like \"M3\", not \"" + s + "\"");
      m = m * 10 + (s[k] - '0');
    }
    out.push_back(m);
  }
  return out;
}

Result<DialectSpec> parse_dialect(const json& j) {
  DialectSpec d;
  const auto it = j.find("dialect");
  if (it == j.end() || it->is_null()) {
    d.name = "rs274";
    return d;
  }
  if (it->is_string()) {
    d.name = it->get<std::string>();
    return d;
  }
  if (!it->is_object()) return make_error("field dialect must be a name or an object");
  auto name = detail::string(*it, "name", "dialect");
  if (!name) return name.error();
  d.name = *name;
  auto on = m_codes(*it, "beam_on", "dialect");
  if (!on) return on.error();
  auto off = m_codes(*it, "beam_off", "dialect");
  if (!off) return off.error();
  d.beam_on = *on;
  d.beam_off = *off;
  if (d.beam_on.empty() != d.beam_off.empty())
    return make_error("fields dialect.beam_on and dialect.beam_off must be given together");
  auto unit = detail::string(*it, "dwell_p_unit", "dialect", false);
  if (!unit) return unit.error();
  if (!unit->empty() && *unit != "s" && *unit != "ms")
    return make_error("field dialect.dwell_p_unit must be \"s\" or \"ms\"");
  d.dwell_p_unit = *unit;
  return d;
}

Result<CuttingParams> parse_cutting(const json& c, const std::string& path) {
  if (!c.is_object()) return make_error("field " + path + " must be an object");
  if (auto d = unknown_keys(c,
                            {"material", "thickness_mm", "v_set_m_s", "pierce_time_s", "kerf_mm",
                             "lead_in_mm", "lead_out_mm", "note"},
                            path);
      !d.message.empty())
    return d;
  CuttingParams p;
  auto material = detail::string(c, "material", path);
  if (!material) return material.error();
  p.material = *material;
  auto th = detail::positive(c, "thickness_mm", path);
  if (!th) return th.error();
  p.thickness_mm = *th;
  if (c.contains("v_set_m_s") && !c["v_set_m_s"].is_null()) {
    auto v = detail::positive(c, "v_set_m_s", path, true, 0.0, kMaxSpeedMS);
    if (!v) return v.error();
    p.v_set_m_s = *v;
  }
  auto pt = detail::non_negative(c, "pierce_time_s", path, true, 0.0, kMaxTimeS);
  if (!pt) return pt.error();
  p.pierce_time_s = *pt;
  auto kerf = detail::non_negative(c, "kerf_mm", path, true, 0.0, kMaxKerfMm);
  if (!kerf) return kerf.error();
  p.kerf_mm = *kerf;
  auto li = detail::non_negative(c, "lead_in_mm", path, true, 0.0, kMaxLeadMm);
  if (!li) return li.error();
  p.lead_in_mm = *li;
  auto lo = detail::non_negative(c, "lead_out_mm", path, true, 0.0, kMaxLeadMm);
  if (!lo) return lo.error();
  p.lead_out_mm = *lo;
  return p;
}

Result<MachineProfile> parse_profile(const json& j, const std::string& path) {
  if (auto d = unknown_keys(j,
                            {"format", "name", "notes", "sources", "speed_table", "rapid_speed_m_s",
                             "head_lift_lower_s", "work_area_mm", "dialect", "costs", "motion", "default_job", "cutting"},
                            "");
      !d.message.empty())
    return d;
  MachineProfile p;
  p.file = path;
  auto name = detail::string(j, "name", "");
  if (!name) return name.error();
  p.name = *name;
  auto table = detail::string(j, "speed_table", "");
  if (!table) return table.error();
  std::filesystem::path tp(*table);
  if (tp.is_relative()) tp = std::filesystem::path(path).parent_path() / tp;
  p.speed_table = tp.lexically_normal().string();
  auto voff = detail::in_range(detail::positive(j, "rapid_speed_m_s", ""), "rapid_speed_m_s", kMinRapidMS, kMaxSpeedMS);
  if (!voff) return voff.error();
  p.rapid_speed_m_s = *voff;
  auto head = detail::non_negative(j, "head_lift_lower_s", "", false, 0.0, kMaxTimeS);
  if (!head) return head.error();
  p.head_lift_lower_s = *head;
  if (const auto w = j.find("work_area_mm"); w != j.end() && !w->is_null()) {
    if (!w->is_array() || w->size() != 2 || !(*w)[0].is_number() || !(*w)[1].is_number())
      return make_error("field work_area_mm must be two numbers [X, Y] (mm)");
    const double x = (*w)[0].get<double>(), y = (*w)[1].get<double>();
    if (!(x > 0 && y > 0 && x <= kMaxWorkAreaMm && y <= kMaxWorkAreaMm))
      return make_error("field work_area_mm must hold two lengths in (0, 100000] mm");
    p.work_area_mm = std::array<double, 2>{x, y};
  }
  auto dialect = parse_dialect(j);
  if (!dialect) return dialect.error();
  p.dialect = *dialect;
  if (const auto c = j.find("costs"); c != j.end() && !c->is_null()) {
    if (!c->is_object()) return make_error("field costs must be an object");
    Costs k;
    auto unit = detail::string(*c, "unit", "costs");
    if (!unit) return unit.error();
    k.unit = *unit;
    auto on = detail::non_negative(*c, "c_on_per_m", "costs", true, 0.0, kMaxRate);
    if (!on) return on.error();
    auto off = detail::non_negative(*c, "c_off_per_m", "costs", true, 0.0, kMaxRate);
    if (!off) return off.error();
    auto pt = detail::non_negative(*c, "c_pt", "costs", true, 0.0, kMaxRate);
    if (!pt) return pt.error();
    k.c_on_per_m = *on;
    k.c_off_per_m = *off;
    k.c_pt = *pt;
    p.costs = k;
  }
  if (const auto m = j.find("motion"); m != j.end() && !m->is_null()) {
    if (!m->is_object()) return make_error("field motion must be an object");
    if (auto d =
            unknown_keys(*m, {"accel_m_s2", "jerk_m_s3", "block_time_s", "junction_deviation_mm"}, "motion");
        !d.message.empty())
      return d;
    for (const std::string key : {"accel_m_s2", "jerk_m_s3", "block_time_s", "junction_deviation_mm"}) {
      if (!m->contains(key) || (*m)[key].is_null()) continue;
      const bool may_be_zero = key == "block_time_s" || key == "junction_deviation_mm";
      auto v = may_be_zero ? detail::non_negative(*m, key, "motion") : detail::positive(*m, key, "motion");
      if (!v) return v.error();
      if (key == "accel_m_s2")
        p.motion.accel_m_s2 = *v;
      else if (key == "jerk_m_s3")
        p.motion.jerk_m_s3 = *v;
      else if (key == "block_time_s")
        p.motion.block_time_s = *v;
      else
        p.motion.junction_deviation_mm = *v;
    }
  }
  if (const auto d = j.find("default_job"); d != j.end() && !d->is_null()) {
    if (!d->is_object()) return make_error("field default_job must be an object");
    auto mat = detail::string(*d, "material", "default_job");
    if (!mat) return mat.error();
    auto th = detail::positive(*d, "thickness_mm", "default_job");
    if (!th) return th.error();
    p.default_material = *mat;
    p.default_thickness_mm = *th;
  }
  const auto cut = j.find("cutting");
  if (cut == j.end() || !cut->is_array() || cut->empty())
    return make_error("field cutting must be a non-empty array of technology rows");
  for (std::size_t i = 0; i < cut->size(); ++i) {
    auto c = parse_cutting((*cut)[i], detail::item("cutting", i));
    if (!c) return c.error();
    p.cutting.push_back(*c);
  }
  return p;
}

}  // namespace

std::string default_machine_profile_path() { return std::string(data_dir()) + "/machines/bystar3015.json"; }

Result<MachineProfile> load_machine_profile(const std::string& path) {
  auto parsed = detail::parse_json_file(path);
  if (!parsed) {
    // The built-in profile missing: the data folder is not where this binary looked.
    Diagnostic e = parsed.error();
    if (path == default_machine_profile_path())
      e.message += " (the built-in machine profile, in the data folder " + std::string(data_dir()) +
                   ": set CUTROUTE_DATA_DIR to the project's data/ folder, keep data/ beside the executable, or give --machine)";
    return e;
  }
  auto p = parse_profile(*parsed, path);
  if (!p) return detail::in_file(p.error(), path);
  return p;
}

Result<nc::Dialect> profile_reader_dialect(const MachineProfile& p) {
  const auto& d = p.dialect;
  const auto unit = d.dwell_p_unit == "ms" ? nc::DwellUnit::milliseconds : nc::DwellUnit::seconds;
  if (d.beam_on.empty()) {
    auto b = nc::reader_dialect_named(d.name, "field dialect: unknown dialect", p.file,
                                      std::filesystem::path(p.file).parent_path().string());
    if (b && !d.dwell_p_unit.empty()) b->dwell_p_unit = unit;
    return b;
  }
  auto m = nc::make_dialect(d.name, d.beam_on, d.beam_off, unit, "dialect");
  if (!m) return make_error("field " + m.error().message, p.file);
  return m;
}

}  // namespace cutroute::cost
