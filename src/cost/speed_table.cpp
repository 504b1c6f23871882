#include <cutroute/cost/speed_table.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <cutroute/core/tolerances.hpp>
#include <cutroute/core/version.hpp>

#include "cost/json_fields.hpp"

namespace cutroute::cost {

namespace {

using detail::json;

std::string lower(std::string s) {
  for (auto& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

std::string mm(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", t);
  return buf;
}

Result<SpeedRow> parse_row(const json& r, const std::string& path, const std::string& material) {
  if (!r.is_object()) return make_error("field " + path + " must be an object");
  SpeedRow row;
  row.material = material;
  const auto n0 = detail::positive(r, "n0", path);
  if (!n0) return n0.error();
  if (*n0 != std::floor(*n0))
    return make_error("field " + detail::field(path, "n0") + " must be a whole number");
  row.n0 = static_cast<int>(*n0);
  const auto cubic = r.find("cubic");
  if (cubic == r.end() || !cubic->is_array() || cubic->size() != 4)
    return make_error("field " + detail::field(path, "cubic") + " must be an array [a, b, c, d]");
  for (std::size_t i = 0; i < 4; ++i) {
    if (!(*cubic)[i].is_number())
      return make_error("field " + detail::item(detail::field(path, "cubic"), i) + " must be a number");
    row.cubic[i] = (*cubic)[i].get<double>();
  }
  const auto v_set = detail::positive(r, "v_set_m_s", path);
  if (!v_set) return v_set.error();
  row.v_set_m_s = *v_set;
  const auto power = r.find("power");
  if (power == r.end() || !power->is_object())
    return make_error("field " + detail::field(path, "power") + " must be an object {k, e}");
  const auto k = detail::positive(*power, "k", detail::field(path, "power"));
  if (!k) return k.error();
  const auto e = detail::number(*power, "e", detail::field(path, "power"));
  if (!e) return e.error();
  row.power_k = *k;
  row.power_e = *e;
  const auto measured = detail::boolean(r, "measured", path);
  if (!measured) return measured.error();
  row.measured = *measured;
  return row;
}

}  // namespace

const char* to_string(Regime r) {
  switch (r) {
    case Regime::cubic:
      return "cubic";
    case Regime::set:
      return "set";
    case Regime::power:
      return "power";
  }
  return "set";
}

SpeedAtFrames v_on_star(const SpeedRow& row, double n) {
  const double n0 = static_cast<double>(row.n0);
  if (n < n0) {
    const auto& c = row.cubic;
    return {((c[0] * n + c[1]) * n + c[2]) * n + c[3], Regime::cubic};
  }
  if (n == n0) return {row.v_set_m_s, Regime::set};
  return {row.power_k * std::pow(n, row.power_e), Regime::power};
}

Result<std::string> SpeedTable::resolve_material(const std::string& name) const {
  const std::string key = lower(name);
  for (const auto& m : materials) {
    if (lower(m.name) == key) return m.name;
    for (const auto& a : m.aliases)
      if (lower(a) == key) return m.name;
  }
  std::string list;
  for (const auto& m : materials) {
    list += (list.empty() ? "" : "; ") + m.name;
    if (!m.aliases.empty()) {
      list += " (also";
      for (const auto& a : m.aliases) list += " " + a;
      list += ")";
    }
  }
  return make_error("unknown material '" + name + "'; the table has: " + list);
}

std::vector<double> SpeedTable::thicknesses(const std::string& material) const {
  std::vector<double> t;
  for (const auto& r : rows)
    if (r.material == material) t.push_back(r.thickness_mm);
  return t;
}

std::string default_speed_table_path() { return std::string(data_dir()) + "/materials/bystar3015.json"; }

Result<SpeedTable> load_speed_table(const std::string& path) {
  auto parsed = detail::parse_json_file(path);
  if (!parsed) return parsed.error();
  const json& j = *parsed;
  SpeedTable t;
  auto src = detail::string(j, "source", "", false);
  auto machine = detail::string(j, "machine", "", false);
  if (!src) return detail::in_file(src.error(), path);
  if (!machine) return detail::in_file(machine.error(), path);
  t.source = *src;
  t.machine = *machine;
  const auto mats = j.find("materials");
  if (mats == j.end() || !mats->is_array() || mats->empty())
    return make_error("field materials must be a non-empty array", path);
  for (std::size_t i = 0; i < mats->size(); ++i) {
    const json& m = (*mats)[i];
    const std::string mp = detail::item("materials", i);
    if (!m.is_object()) return make_error("field " + mp + " must be an object", path);
    MaterialEntry e;
    auto name = detail::string(m, "name", mp);
    if (!name) return detail::in_file(name.error(), path);
    e.name = *name;
    auto desc = detail::string(m, "description", mp, false);
    if (!desc) return detail::in_file(desc.error(), path);
    e.description = *desc;
    if (const auto al = m.find("aliases"); al != m.end()) {
      if (!al->is_array()) return make_error("field " + mp + ".aliases must be an array of strings", path);
      for (std::size_t k = 0; k < al->size(); ++k) {
        if (!(*al)[k].is_string())
          return make_error("field " + detail::item(mp + ".aliases", k) + " must be a string", path);
        e.aliases.push_back((*al)[k].get<std::string>());
      }
    }
    for (const auto& other : t.materials) {
      auto names = other.aliases;
      names.push_back(other.name);
      for (const auto& n : names) {
        if (lower(n) == lower(e.name) ||
            std::any_of(e.aliases.begin(), e.aliases.end(),
                        [&](const std::string& a) { return lower(a) == lower(n); }))
          return make_error("field " + mp + ": name or alias '" + n + "' is already used by " + other.name,
                            path);
      }
    }
    const auto rows = m.find("rows");
    if (rows == m.end() || !rows->is_array() || rows->empty())
      return make_error("field " + mp + ".rows must be a non-empty array", path);
    for (std::size_t r = 0; r < rows->size(); ++r) {
      const std::string rp = detail::item(mp + ".rows", r);
      auto row = parse_row((*rows)[r], rp, e.name);
      if (!row) return detail::in_file(row.error(), path);
      const auto th = (*rows)[r].find("thickness_mm");
      if (th == (*rows)[r].end() || !th->is_array() || th->empty())
        return make_error("field " + rp + ".thickness_mm must be a non-empty array of thicknesses [mm]",
                          path);
      for (std::size_t k = 0; k < th->size(); ++k) {
        if (!(*th)[k].is_number() || !((*th)[k].get<double>() > 0.0))
          return make_error("field " + detail::item(rp + ".thickness_mm", k) + " must be a number > 0", path);
        SpeedRow copy = *row;
        copy.thickness_mm = (*th)[k].get<double>();
        for (const auto& existing : t.rows) {
          if (existing.material == copy.material &&
              std::abs(existing.thickness_mm - copy.thickness_mm) <= tol::kThicknessMm)
            return make_error("field " + rp + ": thickness " + mm(copy.thickness_mm) + " mm of " +
                                  copy.material + " appears twice",
                              path);
        }
        t.rows.push_back(copy);
      }
    }
    t.materials.push_back(std::move(e));
  }
  std::stable_sort(t.rows.begin(), t.rows.end(), [](const SpeedRow& a, const SpeedRow& b) {
    return a.material != b.material ? a.material < b.material : a.thickness_mm < b.thickness_mm;
  });
  return t;
}

double SpeedQuery::v_set_m_s() const { return (1.0 - weight) * lower.v_set_m_s + weight * upper.v_set_m_s; }

SpeedAtFrames SpeedQuery::at(double n) const {
  const auto a = v_on_star(lower, n);
  if (!interpolated) return a;
  const auto b = v_on_star(upper, n);
  return {(1.0 - weight) * a.v_m_s + weight * b.v_m_s, weight < 0.5 ? a.regime : b.regime};
}

Result<SpeedQuery> find_speed(const SpeedTable& table, const std::string& material, double thickness_mm,
                              bool interpolate) {
  auto canonical = table.resolve_material(material);
  if (!canonical) return canonical.error();
  SpeedQuery q;
  q.material = *canonical;
  q.thickness_mm = thickness_mm;
  const SpeedRow* below = nullptr;
  const SpeedRow* above = nullptr;
  for (const auto& r : table.rows) {
    if (r.material != q.material) continue;
    if (std::abs(r.thickness_mm - thickness_mm) <= tol::kThicknessMm) {
      q.lower = q.upper = r;
      q.measured = r.measured;
      if (!r.measured)
        q.warnings.push_back(q.material + " " + mm(r.thickness_mm) +
                             " mm is the authors' extrapolation in Table 1, not a measurement");
      return q;
    }
    if (r.thickness_mm < thickness_mm) below = &r;
    if (r.thickness_mm > thickness_mm && !above) above = &r;
  }
  std::string list;
  for (double t : table.thicknesses(q.material)) list += (list.empty() ? "" : ", ") + mm(t);
  if (!interpolate || !below || !above) {
    std::string msg =
        "no row for " + q.material + " " + mm(thickness_mm) + " mm; the table has " + list + " mm";
    if (below && above)
      msg += " (--interpolate blends the two neighbouring rows)";
    else if (interpolate)
      msg += " (outside the table: not extrapolated)";
    return make_error(msg);
  }
  q.lower = *below;
  q.upper = *above;
  q.weight = (thickness_mm - below->thickness_mm) / (above->thickness_mm - below->thickness_mm);
  q.interpolated = true;
  q.measured = below->measured && above->measured;
  q.warnings.push_back("interpolated linearly between " + q.material + " " + mm(below->thickness_mm) +
                       " mm and " + mm(above->thickness_mm) + " mm: not a row of Table 1");
  if (!q.measured)
    q.warnings.push_back("a neighbouring row is the authors' extrapolation, not a measurement");
  return q;
}

}  // namespace cutroute::cost
