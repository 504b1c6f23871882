// Facts about a nest recomputed from its contours alone, for tests that judge cut jobs and chains.
#pragma once

#include <vector>

#include <cutroute/model/nest.hpp>

namespace cutroute::test {

// Is p inside material: inside an odd number of the nest's part contours (exact winding number
// per contour, no spatial index: slow and simple on purpose).
bool in_material(const model::Nest& nest, geometry::Vec2 p);

// Points about every `step` mm along a contour, from its vertices (lines interpolated, arcs by
// angle; at least two per segment): where "is every boundary point cut?" is asked.
std::vector<geometry::Vec2> boundary_samples(const geometry::Contour& c, double step);

}  // namespace cutroute::test
