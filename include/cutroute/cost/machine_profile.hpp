// MachineProfile: one cutting machine's speeds, pierce times, costs, lead lengths and G-code
// dialect, read from JSON (every field and unit in docs/MACHINE-PROFILE.md).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <cutroute/core/result.hpp>
#include <cutroute/nc/dialect.hpp>

namespace cutroute::cost {

// Technology for one material and thickness.
struct CuttingParams {
  std::string material;             // as written in the profile (name or alias of the speed table)
  double thickness_mm = 0.0;        // [mm]
  std::optional<double> v_set_m_s;  // programmed cutting speed [m/s]; empty = the table's set speed
  double pierce_time_s = 0.0;       // t_pt, time of one pierce [s]
  double kerf_mm = 0.0;             // kerf width [mm]
  double lead_in_mm = 0.0;          // default lead-in length [mm]
  double lead_out_mm = 0.0;         // default lead-out length [mm]
};

// Eq. 3 coefficients. Without them the cost is eq. 3 in its time form (C_on = 1/V_on*,
// C_off = 1/V_off, C_pt = t_pt), i.e. seconds.
struct Costs {
  std::string unit;          // currency or other unit name, e.g. "EUR"
  double c_on_per_m = 0.0;   // C_on [unit per m cut]
  double c_off_per_m = 0.0;  // C_off [unit per m of rapid travel]
  double c_pt = 0.0;         // C_pt [unit per pierce]
};

// The motion model's limits (cost/motion_model.hpp); not used by eq. 1/3/10. The motion
// estimate is made only when accel_m_s2 is given.
struct MotionLimits {
  std::optional<double> accel_m_s2;             // path acceleration limit [m/s^2]
  std::optional<double> jerk_m_s3;              // jerk limit [m/s^3] (read, not used yet)
  std::optional<double> block_time_s;           // minimum time the controller spends on one block [s]
  std::optional<double> junction_deviation_mm;  // corner rounding allowance [mm]
};

struct DialectSpec {
  std::string name;          // built-in name, or the custom dialect's name
  std::vector<int> beam_on;  // empty = the built-in dialect's codes
  std::vector<int> beam_off;
  std::string dwell_p_unit;  // "s" or "ms"; empty = the built-in dialect's
};

struct MachineProfile {
  std::string file;  // where it was read from
  std::string name;
  std::string speed_table;         // absolute path of the Table 1 data file
  double rapid_speed_m_s = 0.0;    // V_off [m/s]
  double head_lift_lower_s = 0.0;  // per pierce: lift after the cut + lower before the pierce [s]
  // The travel of the X and Y axes: a program whose moves span more cannot run on the machine (a
  // drawing read in the wrong unit, a sheet bigger than the table) [mm]; absent: not checked.
  std::optional<std::array<double, 2>> work_area_mm;
  DialectSpec dialect;
  std::optional<Costs> costs;
  MotionLimits motion;
  std::optional<std::string> default_material;
  std::optional<double> default_thickness_mm;  // [mm]
  std::vector<CuttingParams> cutting;
};

// Reads and validates a profile; errors name the file and the field ("cutting[2].pierce_time_s
// must be >= 0"). A relative speed_table path is relative to the profile's folder.
Result<MachineProfile> load_machine_profile(const std::string& path);
// <data_dir>/machines/bystar3015.json
std::string default_machine_profile_path();

// The dialect the machine reads its programs in, from the profile's `dialect` (a reader dialect
// name, a post-processor dialect's name or JSON file, read from the profile's folder first, or
// explicit codes); errors name the profile and the field.
Result<nc::Dialect> profile_reader_dialect(const MachineProfile& p);

}  // namespace cutroute::cost
