#include "support/nest_facts.hpp"

namespace cutroute::test {

bool in_material(const model::Nest& nest, geometry::Vec2 p) {
  int inside = 0;
  for (const auto& c : nest.contours) {
    if (c.role == model::ContourRole::sheet) continue;
    inside += geometry::locate(c.source.contour, p, 1e-9) == geometry::Location::inside;
  }
  return inside % 2 == 1;
}

}  // namespace cutroute::test
