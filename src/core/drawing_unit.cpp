#include <cutroute/core/drawing_unit.hpp>

#include <algorithm>
#include <cmath>

#include <cutroute/core/number_format.hpp>

namespace cutroute {

std::string format_position(double x_mm, double y_mm, const DrawingUnit& unit) {
  const bool mm = unit.mm_per_unit == 1.0;
  // 3 decimals in mm (1 µm); in other units as many as keep that step: 1 in = 25.4 mm -> 4, 1 ft -> 5.
  const int decimals = mm ? 3 : static_cast<int>(std::clamp(std::lround(3 + std::log10(unit.mm_per_unit)), 0L, 9L));
  const double k = mm ? 1.0 : 1.0 / unit.mm_per_unit;
  std::string s = "(";  // appended piece by piece: GCC 12 warns (-Wrestrict) on "(" + std::string
  s += format_fixed(x_mm * k, decimals);
  s += ", ";
  s += format_fixed(y_mm * k, decimals);
  s += ")";
  if (!mm) {
    s += ' ';
    s += unit.name;
  }
  return s;
}

}  // namespace cutroute
