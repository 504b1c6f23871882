#include "instance_distance.hpp"

#include <cmath>

namespace cutroute::io::detail {

std::optional<Metric> parse_metric(std::string_view n) {
  if (n == "EUC_2D") return Metric::euc_2d;
  if (n == "CEIL_2D") return Metric::ceil_2d;
  if (n == "ATT") return Metric::att;
  if (n == "GEO") return Metric::geo;
  if (n == "GEOM") return Metric::geom;
  if (n == "MAN_2D") return Metric::man_2d;
  if (n == "MAX_2D") return Metric::max_2d;
  return std::nullopt;
}

namespace {

// TSPLIB GEO: coordinates are DDD.MM (degrees and minutes); PI and the radius are TSPLIB's own.
double geo_radians(double v) {
  constexpr double kPi = 3.141592;
  const double deg = std::trunc(v);
  const double min = v - deg;
  return kPi * (deg + 5.0 * min / 3.0) / 180.0;
}

}  // namespace

std::int64_t tsplib_distance(Metric m, const Coord& a, const Coord& b) {
  const double dx = a.x - b.x, dy = a.y - b.y;
  switch (m) {
    case Metric::euc_2d: return static_cast<std::int64_t>(std::sqrt(dx * dx + dy * dy) + 0.5);
    case Metric::ceil_2d: return static_cast<std::int64_t>(std::ceil(std::sqrt(dx * dx + dy * dy)));
    case Metric::man_2d: return static_cast<std::int64_t>(std::fabs(dx) + std::fabs(dy) + 0.5);
    case Metric::max_2d:
      return std::max(static_cast<std::int64_t>(std::fabs(dx) + 0.5), static_cast<std::int64_t>(std::fabs(dy) + 0.5));
    case Metric::att: {
      const double r = std::sqrt((dx * dx + dy * dy) / 10.0);
      const auto t = static_cast<std::int64_t>(r + 0.5);
      return static_cast<double>(t) < r ? t + 1 : t;
    }
    case Metric::geo: {
      constexpr double kRrr = 6378.388;
      const double lat_a = geo_radians(a.x), lon_a = geo_radians(a.y);
      const double lat_b = geo_radians(b.x), lon_b = geo_radians(b.y);
      const double q1 = std::cos(lon_a - lon_b), q2 = std::cos(lat_a - lat_b), q3 = std::cos(lat_a + lat_b);
      return static_cast<std::int64_t>(kRrr * std::acos(0.5 * ((1.0 + q1) * q2 - (1.0 - q1) * q3)) + 1.0);
    }
    case Metric::geom: {
      constexpr double kPi = 3.14159265358979323846264;
      const double lat_a = kPi / 180.0 * a.x, lat_b = kPi / 180.0 * b.x;
      const double lon_a = kPi / 180.0 * a.y, lon_b = kPi / 180.0 * b.y;
      const double q1 = std::cos(lat_b) * std::sin(lon_a - lon_b);
      const double q3 = std::sin((lon_a - lon_b) / 2.0), q4 = std::cos((lon_a - lon_b) / 2.0);
      const double q2 = std::sin(lat_a + lat_b) * q3 * q3 - std::sin(lat_a - lat_b) * q4 * q4;
      const double q5 = std::cos(lat_a - lat_b) * q4 * q4 - std::cos(lat_a + lat_b) * q3 * q3;
      return static_cast<std::int64_t>(6378388.0 * std::atan2(std::sqrt(q1 * q1 + q2 * q2), q5) + 1.0);
    }
  }
  return 0;
}

}  // namespace cutroute::io::detail
