// estimate_time(): eq. 1, eq. 10 and eq. 3 of PAPERS.md §1 for one program's totals, with a
// breakdown into cutting, rapid, pierce, dwell and the other terms.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <cutroute/core/result.hpp>
#include <cutroute/cost/machine_profile.hpp>
#include <cutroute/cost/speed_table.hpp>
#include <cutroute/nc/gcode_reader.hpp>

namespace cutroute::cost {

// What a program contains, whoever measured it (the G-code reader, or a toolpath).
struct ProgramTotals {
  double cut_length_mm = 0.0;               // L_on [mm]
  double rapid_length_mm = 0.0;             // L_off (rapid moves) [mm]
  double feed_off_length_mm = 0.0;          // feed moves with the beam off [mm]
  double feed_off_time_s = 0.0;             // the part of those with a programmed feed, at that feed [s]
  double feed_off_length_no_feed_mm = 0.0;  // the part without a programmed feed [mm]
  double dwell_s = 0.0;                     // programmed dwells [s]
  std::size_t pierce_dwells = 0;            // pierces whose time is programmed as a dwell
  std::size_t pierces = 0;                  // N_pt
  std::size_t frames = 0;                   // n
};

// The machine and technology numbers eq. 1/3/10 need, for one material and thickness.
struct CuttingConditions {
  std::string material;
  double thickness_mm = 0.0;       // [mm]
  SpeedQuery speed;                // Table 1 row(s)
  double v_set_m_s = 0.0;          // programmed speed V_on [m/s]
  double pierce_time_s = 0.0;      // t_pt [s]
  double rapid_speed_m_s = 0.0;    // V_off [m/s]
  double head_lift_lower_s = 0.0;  // per pierce [s]
  // The profile's technology row (kerf, lead-in/out, pierce time) for this material and
  // thickness; with interpolation every number is the linear blend of the two neighbours.
  CuttingParams technology;
  std::optional<Costs> costs;
  std::vector<std::string> warnings;

  // V_on*(n): Table 1, scaled by v_set / (table set speed) when the profile programs another
  // speed than the table's (the frame effect is taken as relative) [m/s].
  SpeedAtFrames v_on_star(double n) const;
};

// Looks the material and thickness up in the profile's technology list and in the table.
// Errors: unknown material or thickness (listing what exists), missing technology row.
Result<CuttingConditions> make_conditions(const MachineProfile& profile, const SpeedTable& table,
                                          const std::string& material, double thickness_mm, bool interpolate);

struct TimeEstimate {
  double v_on_set_m_s = 0.0;  // V_on, programmed [m/s]
  double v_on_m_s = 0.0;      // V_on*(n) [m/s]
  Regime regime = Regime::set;
  double t_cut_const_speed_s = 0.0;  // eq. 1: L_on/V_on + L_off/V_off + N_pt t_pt [s]
  double t_cut_s = 0.0;              // eq. 10: L_on/V_on*(n) + L_off/V_off + N_pt t_pt [s]
  double cutting_s = 0.0;            // L_on / V_on*(n) [s]
  double rapid_s = 0.0;              // L_off / V_off [s]
  double pierce_s = 0.0;             // N_pt t_pt [s]
  // Terms outside eq. 10, added in total_s only:
  double dwell_s = 0.0;     // programmed G4 dwells [s]
  // A pierce whose dwell is programmed takes that dwell, not t_pt: total_s counts it once.
  double pierce_replaced_s = 0.0;  // pierce_dwells × t_pt, taken out of total_s [s]
  double feed_off_s = 0.0;  // feed moves with the beam off, at their F (else at V_on) [s]
  double head_s = 0.0;      // N_pt × head lift/lower [s]
  double total_s = 0.0;     // t_cut_s + dwell_s − pierce_replaced_s + feed_off_s + head_s [s]
  double cost = 0.0;        // eq. 3 with V_on*(n) in the time form [cost_unit]
  std::string cost_unit;    // "s" in the time form, else Costs::unit
};

TimeEstimate estimate_time(const ProgramTotals& program, const CuttingConditions& conditions);

// The totals of a program as the G-code reader measured them (what `estimate` prices).
ProgramTotals program_totals(const nc::ProgramStats& s);

}  // namespace cutroute::cost
