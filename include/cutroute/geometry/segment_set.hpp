// SegmentSet: one contour's segments with their boxes and an index, for many queries against it.
#pragma once

#include <cstddef>
#include <optional>
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
// The segments and boxes of a short path without the index, for count_close_segment_pairs() alone
// (which walks such a set against the other's index): a lead is tested against its neighbours
// once, and building its index was a tenth of planning the entries of 72 000 contours. The other
// queries need make_segment_set().
SegmentSet make_path_set(const Contour& path);

// The same answers as winding_number() / locate() / count_close_segment_pairs() on the contour.
int winding_number(const SegmentSet& s, Vec2 p);
Location locate(const SegmentSet& s, Vec2 p, double on_tol_mm);
std::size_t count_close_segment_pairs(const SegmentSet& a, const SegmentSet& b, double tol_mm, std::size_t limit);

// How the boundaries of a and b meet (segment pairs within tol_mm, by SegmentIntersection kind):
// `points` pairs meeting in isolated points (crossing or touching), `overlaps` pairs sharing a
// stretch (common edge). Both 0: the boundaries are farther apart than tol_mm.
struct BoundaryContact {
  std::size_t points = 0;
  std::size_t overlaps = 0;
  Vec2 first;  // a common point (the first found; for messages), valid when any() [mm]
  bool any() const { return points + overlaps > 0; }
};
BoundaryContact boundary_contact(const SegmentSet& a, const SegmentSet& b, double tol_mm);

// Where the boundary of a lies relative to the region of b: a's vertices and the points at 1/4,
// 1/2 and 3/4 of each segment located in b; samples within tol_mm of b's boundary are not counted. Tells touching (all
// counted samples on one side) from crossing (samples on both sides).
struct BoundarySides {
  std::size_t inside = 0;
  std::size_t outside = 0;
  double depth = 0.0;  // largest distance from an inside sample to b's boundary: a lower
                       // bound of how far a reaches into b (at most 64 samples measured) [mm]
};
BoundarySides boundary_sides(const SegmentSet& a, const SegmentSet& b, double tol_mm);

// A point where the boundary meets itself: two segments that are not neighbours along it cross,
// touch or overlap (a figure eight, a spline that loops), the loop they close being at least
// min_loop_mm long (shorter ones are the zig-zags of snapped or converted ends). nullopt: a simple
// curve. Exact (no tolerance): neighbours share their end point, others must not meet at all.
std::optional<Vec2> self_contact(const SegmentSet& s, double min_loop_mm);

}  // namespace cutroute::geometry
