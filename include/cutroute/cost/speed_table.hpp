// Table 1 of Tavaeva & Petunin: the real cutting speed V_on*(n) as a function of the number of
// frames n of the NC program, per material and thickness (PAPERS.md §1), and its lookup.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <cutroute/core/result.hpp>

namespace cutroute::cost {

// One row of Table 1 (a row printed for "3.5, 3.9 mm" becomes two rows).
struct SpeedRow {
  std::string material;           // canonical name, e.g. "AMg3M"
  double thickness_mm = 0.0;      // [mm]
  int n0 = 0;                     // threshold number of frames [frames]
  std::array<double, 4> cubic{};  // a, b, c, d of a n^3 + b n^2 + c n + d [m/s with n in frames]
  double v_set_m_s = 0.0;         // programmed ("set") speed, the value at n = n0 [m/s]
  double power_k = 0.0;           // k of k n^e [m/s]
  double power_e = 0.0;           // e of k n^e [dimensionless]
  bool measured = true;           // false: the authors' extrapolation, not a measurement
};

enum class Regime { cubic, set, power };
const char* to_string(Regime r);

// V_on*(n) for one row: the cubic for 0 < n < n0, the set speed at n = n0, the power law for
// n > n0. n = 0 (an empty program) uses the cubic's value at 0, d. [m/s]
struct SpeedAtFrames {
  double v_m_s = 0.0;
  Regime regime = Regime::set;
};
SpeedAtFrames v_on_star(const SpeedRow& row, double n);

struct MaterialEntry {
  std::string name;
  std::vector<std::string> aliases;
  std::string description;
};

struct SpeedTable {
  std::string source;  // citation from the data file
  std::string machine;
  std::vector<MaterialEntry> materials;
  std::vector<SpeedRow> rows;  // sorted by material, then thickness

  // Canonical material name for a name or alias (case-insensitive), or an error listing them.
  Result<std::string> resolve_material(const std::string& name) const;
  // Thicknesses there are for a canonical material, ascending [mm].
  std::vector<double> thicknesses(const std::string& material) const;
};

Result<SpeedTable> load_speed_table(const std::string& path);
// <data_dir>/materials/bystar3015.json
std::string default_speed_table_path();

// The speed model for one material and thickness: either one row of the table, or (with
// interpolate) two neighbouring rows of the same material blended linearly by thickness.
struct SpeedQuery {
  std::string material;       // canonical
  double thickness_mm = 0.0;  // as asked [mm]
  SpeedRow lower;             // the row used (or the thinner neighbour)
  SpeedRow upper;             // == lower unless interpolated
  double weight = 0.0;        // share of `upper` in [0, 1]
  bool interpolated = false;
  bool measured = true;  // every row used is a measurement
  std::vector<std::string> warnings;

  double v_set_m_s() const;          // [m/s]
  SpeedAtFrames at(double n) const;  // regime: of the nearer row when interpolated
};

// Errors: unknown material (lists the materials and aliases), unknown thickness (lists the
// thicknesses, and says --interpolate exists when the thickness lies between two rows).
Result<SpeedQuery> find_speed(const SpeedTable& table, const std::string& material, double thickness_mm,
                              bool interpolate);

}  // namespace cutroute::cost
