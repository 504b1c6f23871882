#include <cutroute/model/kerf_offset.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/tolerances.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/offset.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>

#include "path_ops.hpp"

namespace cutroute::model {
namespace {

using geometry::Contour;
using geometry::Vec2;

constexpr std::size_t kListedOverlaps = 100;

// When the offset of a contour that cannot vanish comes back empty (spline outlines fitted into
// arcs of ~0.002 mm radius), its arcs whose chord is under a third of this times the kerf are
// straightened and the offset tried again; then its segments under this times the kerf are left
// out. The toolpath then deviates from kerf/2 by about that much at most, and a warning gives the
// measured deviation. (Here, not in core/tolerances.hpp: only this fallback uses it.)
constexpr double kTinyArcRel = 0.2;  // [1]

// A toolpath closer than kerf/2 to the drawing by more than this is worth a warning (and the
// retry above): the resolution of a program in mm [mm].
constexpr double kGougeWarnMm = 1e-3;

std::string name(const Nest& nest, ContourId id) {
  const auto& c = nest.contours[id];
  std::string s = std::string(c.role == ContourRole::hole ? "hole" : "contour") + " " + std::to_string(id.value() + 1);
  if (c.part.valid()) s += " (part " + std::to_string(c.part.value() + 1) + ")";
  return s;
}

std::string point(Vec2 p, const DrawingUnit& unit) { return format_position(p.x, p.y, unit); }

Diagnostic diagnostic(Severity sev, const char* code, std::string message, const NestContour& c) {
  Diagnostic d;
  d.severity = sev;
  d.code = code;
  d.message = std::move(message);
  d.line = c.source.line;
  d.handle = c.source.handle;
  d.layer = c.source.layer;
  return d;
}

// Signed offset distance for geometry::offset_contour (> 0 = left of travel) that moves the
// contour to its scrap side: outward for outer contours, into the hole for holes.
double scrap_side_distance(const NestContour& c, double half_kerf) {
  const bool ccw = geometry::orientation(c.source.contour) == geometry::Orientation::ccw;
  const bool inward = c.role == ContourRole::hole;
  return (inward == ccw ? 1.0 : -1.0) * half_kerf;
}

// Independent of the offset algorithm: an outward offset never vanishes, and an inward one only
// when every point of the region lies within `half` of the boundary, so area <= perimeter * half.
bool offset_cannot_vanish(const NestContour& c, double half) {
  if (c.role != ContourRole::hole) return true;
  return c.area_mm2 > 1.01 * geometry::length(c.source.contour) * half;
}

// The contour without its tiny details: arcs with a chord under chord_mm straightened (step 0)
// or, from step 1 on, such segments (lines too) dropped, the neighbour taking over their end.
Contour without_tiny_segments(const Contour& c, double chord_mm, int step) {
  Contour out;
  out.closed = c.closed;
  for (std::size_t i = 0; i < c.vertices.size(); ++i) {
    const auto s = geometry::segment(c, i);
    const bool tiny = geometry::distance(s.a, s.b) < chord_mm;
    if (tiny && step > 0) continue;
    out.vertices.push_back(c.vertices[i]);
    if (tiny && s.is_arc()) out.vertices.back().bulge = 0;
  }
  return out;
}

// How far apart two contours are at most, sampled both ways at five points per segment [mm].
double deviation(const Contour& a, const Contour& b) {
  double worst = 0;
  for (const auto* pair : {&a, &b}) {
    const Contour& from = *pair;
    const geometry::SegmentSet to = geometry::make_segment_set(pair == &a ? b : a);
    for (std::size_t i = 0; i < geometry::segment_count(from); ++i) {
      const auto s = geometry::segment(from, i);
      for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        const Vec2 q = s.point_at(t);
        double best = std::numeric_limits<double>::infinity();
        // Only the worst counts: measure against the segments within the current worst + a margin.
        to.index.visit(geometry::Box{q.x, q.y, q.x, q.y}.inflated(worst + 1.0), [&](std::uint32_t k) {
          best = std::min(best, geometry::closest_point(to.segments[k], q).distance);
          return true;
        });
        if (std::isfinite(best)) worst = std::max(worst, best);
      }
    }
  }
  return worst;
}

// How much closer than `half` the offset comes to the drawn contour, at its deepest: sampled at
// five points per segment, so it catches pieces the offset's own pruning let through.
struct Gouge {
  double depth = 0;  // [mm]
  Vec2 where;
};
Gouge deepest_gouge(const geometry::OffsetResult& r, const geometry::SegmentSet& drawn, double half) {
  Gouge g;
  for (const auto& loop : r.contours) {
    for (std::size_t i = 0; i < geometry::segment_count(loop); ++i) {
      const auto s = geometry::segment(loop, i);
      for (double t : {0.0, 0.25, 0.5, 0.75}) {
        const Vec2 q = s.point_at(t);
        drawn.index.visit(geometry::Box{q.x, q.y, q.x, q.y}.inflated(half), [&](std::uint32_t k) {
          const double depth = half - geometry::closest_point(drawn.segments[k], q).distance;
          if (depth > g.depth) g = {depth, q};
          return true;
        });
      }
    }
  }
  return g;
}

// A drawn point the toolpath misses: farther than kerf/2 + kerf from it. Inside corners are
// always missed a little ((1/sin(θ/2) - 1) · kerf/2: 0.4 · kerf/2 at 90°); a slot or cavity
// narrower than the kerf is missed by its depth. Sampled at vertices and segment midpoints.
std::optional<Vec2> missed_point(const Contour& drawn, const geometry::SegmentSet& path, double half_kerf) {
  const double reach = 3 * half_kerf;
  const auto n = geometry::segment_count(drawn);
  for (std::size_t i = 0; i < n; ++i) {
    const auto s = geometry::segment(drawn, i);
    for (Vec2 q : {s.a, s.point_at(0.5)}) {
      bool near = false;
      path.index.visit(geometry::Box{q.x, q.y, q.x, q.y}.inflated(reach), [&](std::uint32_t k) {
        near = geometry::closest_point(path.segments[k], q).distance <= reach;
        return !near;
      });
      if (!near) return q;
    }
  }
  return std::nullopt;
}

// The contour's offset by d. When it lost a contour that cannot vanish, or cuts into the
// drawing, the offset is tried again without the outline's tiny details (its known weak spot:
// fitted splines) and the better result kept; warnings say by how much the cut deviates.
geometry::OffsetResult offset_with_retries(const NestContour& c, const std::string& label, double d, double kerf_mm,
                                           const DrawingUnit& unit, Diagnostics& diagnostics, double* simplified_by = nullptr) {
  const double half = kerf_mm / 2;
  geometry::OffsetResult r = geometry::offset_contour(c.source.contour, d);
  const geometry::SegmentSet drawn_set = geometry::make_segment_set(c.source.contour);
  Gouge gouge = deepest_gouge(r, drawn_set, half);
  for (int step = 0; step < 2; ++step) {
    const bool lost = r.contours.empty() && offset_cannot_vanish(c, half);
    if (!lost && gouge.depth <= kGougeWarnMm) break;
    const double chord = (step == 0 ? kTinyArcRel / 3 : kTinyArcRel) * kerf_mm;
    const Contour plain = without_tiny_segments(c.source.contour, chord, step);
    if (plain.vertices.size() < 2 || plain == c.source.contour) continue;
    geometry::OffsetResult again = geometry::offset_contour(plain, d);
    if (again.contours.size() != 1) continue;
    const Gouge g = deepest_gouge(again, drawn_set, half);
    if (!lost && g.depth >= gouge.depth) continue;
    r = std::move(again);
    gouge = g;
    if (simplified_by) *simplified_by = deviation(plain, c.source.contour);
    diagnostics.push_back(diagnostic(Severity::warning, "kerf.simplified",
                                     label + ": details shorter than " + format_fixed(chord, 3) + " mm " +
                                         (step == 0 ? "straightened" : "left out") +
                                         " for the kerf offset; the toolpath deviates by up to " +
                                         format_fixed(deviation(plain, c.source.contour), 4) + " mm from kerf/2 there",
                                     c));
  }
  if (r.contours.size() == 1 && gouge.depth > kGougeWarnMm) {
    diagnostics.push_back(diagnostic(Severity::warning, "kerf.gouge",
                                     "the toolpath of " + label + " comes " + format_fixed(gouge.depth, 4) +
                                         " mm closer than kerf/2 to the drawing near " + point(gouge.where, unit) +
                                         " (kerf offset inaccuracy at outline details far below the kerf)",
                                     c));
  }
  return r;
}

}  // namespace

KerfNest offset_for_kerf(const Nest& drawn, double kerf_mm) {
  KerfNest out;
  out.nest = drawn;
  if (!(kerf_mm > 0)) return out;
  const double half = kerf_mm / 2;
  const std::string kerf_text = format_fixed(kerf_mm, 3) + " mm";

  // 1. One offset per cut contour.
  std::vector<char> offset_ok(drawn.contours.size(), 0);
  std::vector<geometry::SegmentSet> sets(drawn.contours.size());
  for (std::size_t i = 0; i < drawn.contours.size(); ++i) {
    const ContourId id(static_cast<std::int32_t>(i));
    const NestContour& c = drawn.contours[id];
    if (c.role == ContourRole::sheet) continue;
    const double d = scrap_side_distance(c, half);
    const geometry::OffsetResult r = offset_with_retries(c, name(drawn, id), d, kerf_mm, drawn.unit, out.diagnostics);
    // A hole smaller than the kerf: the beam would burn it larger than drawn, so the part is out
    // of tolerance. A shop must decide that (redraw, drill, or accept a bigger hole), not the
    // program silently: it is an error, and no program is written while it stands.
    if (r.contours.empty()) {
      if (offset_cannot_vanish(c, half)) {
        out.diagnostics.push_back(diagnostic(Severity::error, "kerf.failed",
                                             "the kerf offset of " + name(drawn, id) +
                                                 " failed (outline details far below the kerf, e.g. from fitted "
                                                 "splines?); use --kerf-mode controller for this drawing",
                                             c));
      } else {
        out.diagnostics.push_back(diagnostic(Severity::error, "kerf.collapsed",
                                             name(drawn, id) + " is too small for the kerf (" + kerf_text +
                                                 "): no toolpath is left after offsetting by half the kerf",
                                             c));
      }
      continue;
    }
    // Several loops: the torch cannot pass the neck, so the drawn shape cannot be cut as one
    // contour; cutting the loops apart would leave the neck's scrap hanging. Same policy.
    if (r.contours.size() > 1) {
      out.diagnostics.push_back(diagnostic(Severity::error, "kerf.split",
                                           name(drawn, id) + " has a neck narrower than the kerf (" + kerf_text +
                                               "): its toolpath falls apart into " + std::to_string(r.contours.size()) +
                                               " loops",
                                           c));
      continue;
    }
    NestContour& o = out.nest.contours[id];
    o.source.contour = std::move(r.contours.front());
    o.box = geometry::bounding_box(o.source.contour);
    o.area_mm2 = std::abs(geometry::signed_area(o.source.contour));
    sets[i] = geometry::make_segment_set(o.source.contour);
    offset_ok[i] = 1;
    if (r.self_intersection_removed) {
      if (const auto q = missed_point(c.source.contour, sets[i], half)) {
        out.diagnostics.push_back(diagnostic(Severity::warning, "kerf.trimmed",
                                             name(drawn, id) + ": a feature narrower than the kerf (" + kerf_text +
                                                 ") near " + point(*q, drawn.unit) + " cannot be cut: the toolpath passes it by",
                                             c));
      }
    }
  }

  // 2. Toolpaths that cross or touch: the parts are closer than the kerf.
  std::vector<geometry::Box> boxes;
  std::vector<std::uint32_t> of;
  for (std::size_t i = 0; i < drawn.contours.size(); ++i) {
    if (!offset_ok[i]) continue;
    boxes.push_back(out.nest.contours[ContourId(static_cast<std::int32_t>(i))].box);
    of.push_back(static_cast<std::uint32_t>(i));
  }
  const geometry::StaticSpatialIndex index(boxes);
  std::vector<std::uint32_t> hits;
  std::size_t overlaps = 0;
  for (std::size_t a = 0; a < of.size(); ++a) {
    index.query(boxes[a].inflated(tol::kSamePointMm), hits);
    std::sort(hits.begin(), hits.end());
    for (auto b : hits) {
      if (b <= a) continue;
      const auto ia = of[a], ib = of[b];
      const auto contact = geometry::boundary_contact(sets[ia], sets[ib], tol::kSamePointMm);
      if (!contact.any()) continue;
      if (++overlaps > kListedOverlaps) continue;
      const ContourId ca(static_cast<std::int32_t>(ia)), cb(static_cast<std::int32_t>(ib));
      out.diagnostics.push_back(diagnostic(Severity::error, "kerf.overlap",
                                           "the toolpaths of " + name(drawn, ca) + " and " + name(drawn, cb) +
                                               " meet near " + point(contact.first, drawn.unit) +
                                               ": the contours are closer than the kerf (" + kerf_text +
                                               "), so cutting one cuts into the other",
                                           drawn.contours[ca]));
    }
  }
  // A part in a hole less than a kerf from its edge all round: the hole's toolpath shrinks and
  // the part's grows past it, so the two never meet, yet each cut takes from the other. Their
  // order is then inverted: the hole's path lies inside the part's.
  for (const Part& part : drawn.parts) {
    if (!part.inside_hole.valid()) continue;
    const auto ip = static_cast<std::size_t>(part.outer.value()), ih = static_cast<std::size_t>(part.inside_hole.value());
    if (!offset_ok[ip] || !offset_ok[ih]) continue;
    const Contour& hole_path = out.nest.contours[part.inside_hole].source.contour;
    if (hole_path.vertices.empty() || geometry::winding_number(sets[ip], hole_path.vertices.front().p) == 0) continue;
    if (geometry::boundary_contact(sets[ih], sets[ip], tol::kSamePointMm).any()) continue;  // listed above
    if (++overlaps > kListedOverlaps) continue;
    out.diagnostics.push_back(diagnostic(Severity::error, "kerf.overlap",
                                         "the toolpaths of " + name(drawn, part.inside_hole) + " and " +
                                             name(drawn, part.outer) + " pass each other: the part lies closer than the kerf (" +
                                             kerf_text + ") to the hole's edge all round, so cutting one cuts into the other",
                                         drawn.contours[part.outer]));
  }
  if (overlaps > kListedOverlaps) {
    Diagnostic d;
    d.severity = Severity::error;
    d.code = "kerf.overlap";
    d.message = std::to_string(overlaps - kListedOverlaps) + " more pairs of toolpaths meet (not listed)";
    out.diagnostics.push_back(std::move(d));
  }
  return out;
}

namespace {

// Contour `id`'s kerf offset as one loop, clockwise or not; nullopt when it is not one loop.
std::optional<geometry::Contour> offset_loop(const Nest& nest, ContourId id, double kerf_mm, bool clockwise, double* simplified_by) {
  const NestContour& c = nest.contours[id];
  if (simplified_by) *simplified_by = 0.0;
  if (!(kerf_mm > 0) || c.role == ContourRole::sheet) return std::nullopt;
  Diagnostics said;  // the whole-nest offset reports them; here only the path is wanted
  geometry::OffsetResult r =
      offset_with_retries(c, name(nest, id), scrap_side_distance(c, kerf_mm / 2), kerf_mm, nest.unit, said, simplified_by);
  if (r.contours.size() != 1) return std::nullopt;
  geometry::Contour loop = std::move(r.contours.front());
  if ((geometry::orientation(loop) == geometry::Orientation::cw) != clockwise) loop = geometry::reversed(loop);
  return loop;
}

}  // namespace

std::optional<geometry::Contour> kerf_offset_cut(const Nest& nest, ContourId id, double kerf_mm, geometry::Vec2 near,
                                                 bool clockwise, double extra_mm, double* simplified_by) {
  auto loop = offset_loop(nest, id, kerf_mm, clockwise, simplified_by);
  if (!loop) return std::nullopt;
  const double s0 = geometry::closest_point(*loop, near).length_along;
  return detail::sub_path(*loop, s0, geometry::length(*loop) + std::max(0.0, extra_mm));
}

std::optional<geometry::Contour> kerf_offset_piece(const Nest& nest, ContourId id, double kerf_mm, geometry::Vec2 from,
                                                   geometry::Vec2 to, bool clockwise, double* simplified_by) {
  auto loop = offset_loop(nest, id, kerf_mm, clockwise, simplified_by);
  if (!loop) return std::nullopt;
  const double total = geometry::length(*loop);
  const double s0 = geometry::closest_point(*loop, from).length_along, s1 = geometry::closest_point(*loop, to).length_along;
  double along = std::fmod(s1 - s0, total);
  if (along <= 0) along += total;
  return detail::sub_path(*loop, s0, along);
}

}  // namespace cutroute::model
