// Units policy: which unit every layer uses, and the only conversion constants in the code base.
#pragma once

#include <cstdint>

namespace cutroute::units {

// Geometry is double millimetres everywhere inside the library. Drawing units are converted
// once, in the DXF reader; G-code units once, in the G-code reader and writer.
inline constexpr double kMmPerInch = 25.4;
inline constexpr double kMmPerFoot = 304.8;
inline constexpr double kMmPerCm = 10.0;
inline constexpr double kMmPerM = 1000.0;

// Coordinates beyond this magnitude are rejected as absurd at the input boundary: the largest
// cutting tables are ~30 m long, and 1e6 mm keeps double resolution below 1e-9 mm.
inline constexpr double kMaxCoordinateMm = 1.0e6;

// Time is seconds (double) everywhere except inside the solver.
// Speeds: Table 1 of the source paper is in m/s; G-code feeds are mm/min; convert only here.
inline constexpr double m_per_s_to_mm_per_min(double v_m_s) { return v_m_s * 60000.0; }
inline constexpr double mm_per_min_to_m_per_s(double v_mm_min) { return v_mm_min / 60000.0; }
inline constexpr double m_per_s_to_mm_per_s(double v_m_s) { return v_m_s * 1000.0; }

// Solver costs are int64 in one fixed time unit: microseconds. Resolution 1 µs (a 1 mm rapid
// at 1 m/s is 1000 ticks); range ±9.2e18 µs ≈ 292 000 years, so sums over any route cannot
// overflow when each arc is below kMaxArcCostTicks.
inline constexpr std::int64_t kTicksPerSecond = 1'000'000;
inline constexpr std::int64_t kMaxArcCostTicks = std::int64_t{1} << 52;

inline constexpr std::int64_t seconds_to_ticks(double s) {
  return static_cast<std::int64_t>(s * static_cast<double>(kTicksPerSecond) + (s >= 0 ? 0.5 : -0.5));
}
inline constexpr double ticks_to_seconds(std::int64_t t) {
  return static_cast<double>(t) / static_cast<double>(kTicksPerSecond);
}

}  // namespace cutroute::units
