// Exact point-in-contour with arcs: winding number of the chord polygon plus one term per arc.
//
// A closed contour with arcs is its chord polygon plus, for each arc, the closed loop "arc, then
// chord back". That loop bounds the circular segment between arc and chord and turns the same
// way as the arc, so
//     winding(p) = winding_of_chord_polygon(p) + Σ_arcs sign(sweep) · [p inside that segment].
// "Inside the segment" is "inside the arc's circle" and "on the arc's side of the chord"; both
// are sign tests of well-conditioned expressions (arc.hpp), so no flattening and no
// trigonometry is involved. Points exactly on a chord line are resolved by the same symbolic
// perturbation (p moved by +ε in x, then +δ in y) in both terms, so they agree exactly, e.g. at
// the centre of a circle made of two half arcs, whose chord polygon is degenerate.
#include <cutroute/geometry/contour.hpp>

#include <cutroute/geometry/arc.hpp>
#include <cutroute/geometry/intersect.hpp>

#include "geometry/arc_detail.hpp"
#include "geometry/winding_detail.hpp"

namespace cutroute::geometry {

namespace {

// Sign of cross(b - a, p' - a) for p' = p + (ε, δ), 0 < δ << ε << 1: the same expression the
// chord-polygon crossing test uses, so both terms see the same side.
int perturbed_side(Vec2 a, Vec2 b, Vec2 p) {
  const Vec2 c = b - a;
  const double s = cross(c, p - a);
  if (s > 0) return 1;
  if (s < 0) return -1;
  // d/dε cross(c, (ε, 0)) = -c.y; d/dδ cross(c, (0, δ)) = c.x
  if (c.y != 0) return c.y > 0 ? -1 : 1;
  if (c.x != 0) return c.x > 0 ? 1 : -1;
  return 0;
}

}  // namespace

namespace detail {

int winding_contribution(Vec2 a, Vec2 b, double bulge, Vec2 p) {
  int w = 0;
  // Chord: half-open crossing rule in y (≡ p.y + δ) and "strictly left / right" in x;
  // a point exactly on the chord counts as right of it (≡ p.x + ε).
  if (a.y <= p.y) {
    if (b.y > p.y && perturbed_side(a, b, p) > 0) ++w;
  } else if (b.y <= p.y && perturbed_side(a, b, p) < 0) {
    --w;
  }
  const Segment s{a, b, bulge};
  if (!s.is_arc()) return w;
  const double beta = sanitize_bulge(bulge);
  // Arc side: a counter-clockwise arc bulges to the right of its chord.
  const int side = perturbed_side(a, b, p);
  const bool arc_side = beta > 0 ? side < 0 : side > 0;
  if (arc_side && arc_disk_side(a, b, beta, p) < 0) w += beta > 0 ? 1 : -1;
  return w;
}

}  // namespace detail

int winding_number(const Contour& c, Vec2 p) {
  if (!c.closed) return 0;
  const std::size_t n = c.vertices.size();
  int w = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vertex& va = c.vertices[i];
    w += detail::winding_contribution(va.p, c.vertices[(i + 1) % n].p, va.bulge, p);
  }
  return w;
}

Location locate(const Contour& c, Vec2 p, double on_tol_mm) {
  if (!(on_tol_mm >= 0.0)) on_tol_mm = 0.0;
  // On-boundary first: cheap box rejection per segment before the exact distance.
  const std::size_t n = segment_count(c);
  for (std::size_t i = 0; i < n; ++i) {
    const Segment s = segment(c, i);
    if (!detail::coarse_box(s).inflated(on_tol_mm).contains(p)) continue;
    if (closest_point(s, p).distance <= on_tol_mm) {
      return Location::on_boundary;
    }
  }
  return winding_number(c, p) != 0 ? Location::inside : Location::outside;
}

}  // namespace cutroute::geometry
