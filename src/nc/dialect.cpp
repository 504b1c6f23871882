#include <cutroute/nc/dialect.hpp>

#include <algorithm>

namespace cutroute::nc {

bool Dialect::switches_on(int m) const {
  return std::find(beam_on.begin(), beam_on.end(), m) != beam_on.end();
}
bool Dialect::switches_off(int m) const {
  return std::find(beam_off.begin(), beam_off.end(), m) != beam_off.end();
}
bool Dialect::is_inert(int m) const { return std::find(inert.begin(), inert.end(), m) != inert.end(); }

bool fixed_meaning_m(int m) { return m == 0 || m == 1 || m == 2 || m == 30 || m == 6; }

std::vector<std::string> builtin_dialect_names() { return {"rs274", "rs274-m7m9", "fanuc-ms"}; }

Result<Dialect> builtin_dialect(const std::string& name) {
  if (name == "rs274") return Dialect{name, {3, 4}, {5}, DwellUnit::seconds};
  if (name == "rs274-m7m9") return Dialect{name, {7, 8}, {9}, DwellUnit::seconds};
  if (name == "fanuc-ms") return Dialect{name, {3, 4}, {5}, DwellUnit::milliseconds};
  std::string list;
  for (const auto& n : builtin_dialect_names()) list += (list.empty() ? "" : ", ") + n;
  return make_error("unknown G-code dialect '" + name + "' (built in: " + list + ")");
}

Result<Dialect> make_dialect(std::string name, std::vector<int> on, std::vector<int> off, DwellUnit unit,
                             const std::string& field) {
  if (on.empty()) return make_error(field + ".beam_on: at least one M code is needed");
  for (int m : on) {
    if (m < 0 || fixed_meaning_m(m))
      return make_error(field + ".beam_on: M" + std::to_string(m) + " cannot switch the beam");
    if (std::find(off.begin(), off.end(), m) != off.end())
      return make_error(field + ": M" + std::to_string(m) + " is in both beam_on and beam_off");
  }
  for (int m : off)
    if (m < 0 || fixed_meaning_m(m))
      return make_error(field + ".beam_off: M" + std::to_string(m) + " cannot switch the beam");
  return Dialect{std::move(name), std::move(on), std::move(off), unit};
}

}  // namespace cutroute::nc
