// Private: the TSPLIB distance functions (EUC_2D, CEIL_2D, ATT, GEO, GEOM, MAN_2D, MAX_2D).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace cutroute::io::detail {

enum class Metric { euc_2d, ceil_2d, att, geo, geom, man_2d, max_2d };
std::optional<Metric> parse_metric(std::string_view name);

struct Coord {
  double x = 0, y = 0;
};

// As TSPLIB 95 (Reinelt) defines them; GEOM as LKH-2 defines it (exact spherical distance in metres,
// decimal degrees). Integer results, as the benchmark values assume.
std::int64_t tsplib_distance(Metric m, const Coord& a, const Coord& b);

}  // namespace cutroute::io::detail
