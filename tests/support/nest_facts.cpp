#include "support/nest_facts.hpp"

#include <algorithm>

namespace cutroute::test {

bool in_material(const model::Nest& nest, geometry::Vec2 p) {
  int inside = 0;
  for (const auto& c : nest.contours) {
    if (c.role == model::ContourRole::sheet) continue;
    inside += geometry::locate(c.source.contour, p, 1e-9) == geometry::Location::inside;
  }
  return inside % 2 == 1;
}

std::vector<geometry::Vec2> boundary_samples(const geometry::Contour& c, double step) {
  std::vector<geometry::Vec2> out;
  for (std::size_t i = 0; i < geometry::segment_count(c); ++i) {
    const auto s = geometry::segment(c, i);
    const int k = std::max(2, static_cast<int>(s.length() / step));
    for (int j = 0; j < k; ++j) out.push_back(s.point_at(static_cast<double>(j) / k));
  }
  return out;
}

}  // namespace cutroute::test
