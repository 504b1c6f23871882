// SegmentSet: indexed segments of one contour; winding, location and boundary tests through the index.
#include <cutroute/geometry/segment_set.hpp>

#include <algorithm>
#include <limits>

#include <cutroute/geometry/intersect.hpp>

#include "geometry/winding_detail.hpp"

namespace cutroute::geometry {

SegmentSet make_path_set(const Contour& c) {
  SegmentSet s;
  s.closed = c.closed;
  const std::size_t n = segment_count(c);
  s.segments.reserve(n);
  s.boxes.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.segments.push_back(segment(c, i));
    s.boxes.push_back(s.segments.back().bounding_box());
    s.box.add(s.boxes.back());
  }
  return s;
}

SegmentSet make_segment_set(const Contour& c) {
  SegmentSet s = make_path_set(c);
  s.index = StaticSpatialIndex(s.boxes);
  return s;
}

int winding_number(const SegmentSet& s, Vec2 p) {
  if (!s.closed) return 0;
  // Only segments reaching the ray from p towards +x can contribute: a chord crossing it, or an
  // arc whose circular segment holds p (and so whose box holds p).
  const Box ray{p.x, p.y, std::numeric_limits<double>::infinity(), p.y};
  int w = 0;
  s.index.visit(ray, [&](std::uint32_t i) {
    const Segment& seg = s.segments[i];
    w += detail::winding_contribution(seg.a, seg.b, seg.bulge, p);
    return true;
  });
  return w;
}

Location locate(const SegmentSet& s, Vec2 p, double on_tol_mm) {
  if (!(on_tol_mm >= 0.0)) on_tol_mm = 0.0;
  bool on = false;
  s.index.visit(Box{p.x, p.y, p.x, p.y}.inflated(on_tol_mm), [&](std::uint32_t i) {
    on = closest_point(s.segments[i], p).distance <= on_tol_mm;
    return !on;
  });
  if (on) return Location::on_boundary;
  return winding_number(s, p) != 0 ? Location::inside : Location::outside;
}

std::size_t count_close_segment_pairs(const SegmentSet& a, const SegmentSet& b, double tol_mm, std::size_t limit) {
  if (limit == 0) return 0;
  if (!(tol_mm >= 0.0)) tol_mm = 0.0;
  if (!a.box.inflated(tol_mm).intersects(b.box)) return 0;
  // Walk the smaller set, query the larger one's index; a set without an index (make_path_set) is
  // walked. The count is the same either way: a pair is close when either box, inflated by tol_mm,
  // meets the other.
  const bool a_indexed = a.index.size() == a.segments.size(), b_indexed = b.index.size() == b.segments.size();
  std::size_t found = 0;
  if (!a_indexed && !b_indexed) {
    for (std::size_t i = 0; i < a.segments.size() && found < limit; ++i) {
      const Box near = a.boxes[i].inflated(tol_mm);
      for (std::size_t j = 0; j < b.segments.size() && found < limit; ++j)
        if (near.intersects(b.boxes[j]) &&
            intersect(a.segments[i], b.segments[j], tol_mm).kind != SegmentIntersection::Kind::none)
          ++found;
    }
    return found;
  }
  const bool a_small = !a_indexed || (b_indexed && a.segments.size() <= b.segments.size());
  const SegmentSet& small = a_small ? a : b;
  const SegmentSet& large = a_small ? b : a;
  const Box large_box = large.box.inflated(tol_mm);
  for (std::size_t i = 0; i < small.segments.size(); ++i) {
    if (!small.boxes[i].intersects(large_box)) continue;
    large.index.visit(small.boxes[i].inflated(tol_mm), [&](std::uint32_t j) {
      const Segment& sa = a_small ? small.segments[i] : large.segments[j];
      const Segment& sb = a_small ? large.segments[j] : small.segments[i];
      if (intersect(sa, sb, tol_mm).kind != SegmentIntersection::Kind::none) ++found;
      return found < limit;
    });
    if (found >= limit) break;
  }
  return found;
}

BoundaryContact boundary_contact(const SegmentSet& a, const SegmentSet& b, double tol_mm) {
  BoundaryContact contact;
  if (!(tol_mm >= 0.0)) tol_mm = 0.0;
  if (!a.box.inflated(tol_mm).intersects(b.box)) return contact;
  const bool a_small = a.segments.size() <= b.segments.size();
  const SegmentSet& small = a_small ? a : b;
  const SegmentSet& large = a_small ? b : a;
  const Box large_box = large.box.inflated(tol_mm);
  for (std::size_t i = 0; i < small.segments.size(); ++i) {
    if (!small.boxes[i].intersects(large_box)) continue;
    large.index.visit(small.boxes[i].inflated(tol_mm), [&](std::uint32_t j) {
      const SegmentIntersection x = intersect(small.segments[i], large.segments[j], tol_mm);
      if (x.kind != SegmentIntersection::Kind::none && !contact.any()) contact.first = x.points[0];
      if (x.kind == SegmentIntersection::Kind::points) ++contact.points;
      if (x.kind == SegmentIntersection::Kind::overlap) ++contact.overlaps;
      return true;
    });
  }
  return contact;
}

std::optional<Vec2> self_contact(const SegmentSet& s, double min_loop_mm) {
  const std::size_t n = s.segments.size();
  std::vector<double> along(n + 1, 0.0);  // length of segments [0, k)
  for (std::size_t k = 0; k < n; ++k) along[k + 1] = along[k] + s.segments[k].length();
  std::optional<Vec2> found;
  for (std::size_t i = 0; i < n && !found; ++i) {
    s.index.visit(s.boxes[i], [&](std::uint32_t j32) {
      const std::size_t j = j32;
      if (j <= i + 1 || (s.closed && i == 0 && j + 1 == n)) return true;  // itself, or neighbours
      const SegmentIntersection x = intersect(s.segments[i], s.segments[j], 0.0);
      if (x.kind == SegmentIntersection::Kind::none) return true;
      // The shorter of the two loops the contact closes: forward from i to j, or (closed) from j
      // round the end back to i; each with the stretches of i and j past the contact, bounded by
      // the straight distance to their ends (an upper bound is enough to keep real loops).
      const Vec2 p = x.points[0];
      const double inner = geometry::distance(p, s.segments[i].b) + along[j] - along[i + 1] + geometry::distance(s.segments[j].a, p);
      double loop = inner;
      if (s.closed) {
        const double outer = geometry::distance(p, s.segments[j].b) + along[n] - along[j + 1] + along[i] +
                             geometry::distance(s.segments[i].a, p);
        loop = std::min(loop, outer);
      }
      if (loop < min_loop_mm) return true;
      found = p;
      return false;
    });
  }
  return found;
}

BoundarySides boundary_sides(const SegmentSet& a, const SegmentSet& b, double tol_mm) {
  BoundarySides sides;
  for (const Segment& s : a.segments) {
    // Quarter points too: an inscribed circle touches its square exactly at its vertices and
    // half-way points.
    for (const Vec2 p : {s.a, s.point_at(0.25), s.point_at(0.5), s.point_at(0.75)}) {
      const Location where = locate(b, p, tol_mm);
      if (where == Location::outside) ++sides.outside;
      if (where != Location::inside) continue;
      // Depth costs O(|b|) per sample, so only the first 64 inside samples are measured.
      if (++sides.inside <= 64) {
        double d = std::numeric_limits<double>::infinity();
        for (const Segment& t : b.segments) d = std::min(d, closest_point(t, p).distance);
        sides.depth = std::max(sides.depth, d);
      }
    }
  }
  return sides;
}

}  // namespace cutroute::geometry
