#include <cutroute/model/kerf_neighbours.hpp>

#include <algorithm>
#include <vector>

#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>

namespace cutroute::model {
namespace {
// A loss below a program's resolution is none: nests spaced by exactly the kerf (written to
// 0.001 mm) are not closer than it [mm].
constexpr double kResolutionMm = 1e-3;
}  // namespace

KerfNeighbours closer_than_kerf(const Nest& nest, double kerf_mm, double touch_tol_mm) {
  KerfNeighbours out;
  if (!(kerf_mm - kResolutionMm > touch_tol_mm)) return out;
  std::vector<geometry::Box> boxes;
  std::vector<std::size_t> of;
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    const NestContour& c = nest.contours[ContourId(static_cast<std::int32_t>(i))];
    if (c.role == ContourRole::sheet || !c.part.valid()) continue;
    boxes.push_back(c.box.inflated(kerf_mm / 2));
    of.push_back(i);
  }
  const geometry::StaticSpatialIndex index(boxes);
  std::vector<std::optional<geometry::SegmentSet>> sets(of.size());
  auto set_of = [&](std::size_t k) -> const geometry::SegmentSet& {
    if (!sets[k]) sets[k] = geometry::make_segment_set(nest.contours[ContourId(static_cast<std::int32_t>(of[k]))].source.contour);
    return *sets[k];
  };
  std::vector<std::uint32_t> hits;
  for (std::size_t a = 0; a < of.size(); ++a) {
    index.query(boxes[a], hits);
    std::sort(hits.begin(), hits.end());
    const ContourId ca(static_cast<std::int32_t>(of[a]));
    for (const auto b : hits) {
      if (b <= a) continue;
      const ContourId cb(static_cast<std::int32_t>(of[b]));
      if (nest.contours[ca].part == nest.contours[cb].part) continue;
      if (geometry::count_close_segment_pairs(set_of(a), set_of(b), kerf_mm - kResolutionMm, 1) == 0) continue;
      if (geometry::boundary_contact(set_of(a), set_of(b), touch_tol_mm).any()) continue;
      if (out.pairs++ == 0) {
        out.first_a = ca;
        out.first_b = cb;
        // A vertex of a's boundary within the kerf of b's, else a's first vertex.
        const geometry::Contour& ga = nest.contours[ca].source.contour;
        out.near = ga.vertices.front().p;
        for (const auto& v : ga.vertices)
          if (geometry::locate(set_of(b), v.p, kerf_mm) == geometry::Location::on_boundary) {
            out.near = v.p;
            break;
          }
      }
    }
  }
  return out;
}

}  // namespace cutroute::model
