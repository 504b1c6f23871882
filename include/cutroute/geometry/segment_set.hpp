// SegmentSet: one contour's segments with their boxes and an index, for many queries against it.
#pragma once

#include <cstddef>
#include <vector>

#include <cutroute/geometry/contour.hpp>
#include <cutroute/geometry/spatial_index.hpp>

namespace cutroute::geometry {

// Built once per contour (O(n log n)); then point location and boundary tests against it cost
// O(log n + segments near the query) instead of O(n). build_nest() keeps one per contour.
struct SegmentSet {
  std::vector<Segment> segments;
  std::vector<Box> boxes;        // exact box of each segment [mm]
  Box box;                       // of the whole contour [mm]
  bool closed = false;
  StaticSpatialIndex index;      // over `boxes`
};

SegmentSet make_segment_set(const Contour& c);

// The same answers as winding_number() / locate() / count_close_segment_pairs() on the contour.
int winding_number(const SegmentSet& s, Vec2 p);
Location locate(const SegmentSet& s, Vec2 p, double on_tol_mm);
std::size_t count_close_segment_pairs(const SegmentSet& a, const SegmentSet& b, double tol_mm, std::size_t limit);

}  // namespace cutroute::geometry
