// Facts about a nest recomputed from its contours alone, for tests that judge cut jobs and chains.
#pragma once

#include <cutroute/model/nest.hpp>

namespace cutroute::test {

// Is p inside material: inside an odd number of the nest's part contours (exact winding number
// per contour, no spatial index: slow and simple on purpose).
bool in_material(const model::Nest& nest, geometry::Vec2 p);

}  // namespace cutroute::test
