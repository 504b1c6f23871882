// Kerf offset: a contour moved sideways by a distance, with its arcs kept as exact arcs.
#pragma once

// Why hand-written: Clipper (polyclipping) and Boost.Geometry offset polygons only; the arcs
// of a DXF contour would have to be flattened into chords and the G-code would lose its G2/G3.
// This follows the classic raw-offset / join / trim / prune approach for bulge polylines
// (as in CavalierContours, whose README describes it), written from scratch.
//
// Conventions: bulge = tan(sweep / 4) of the arc from a vertex to the next, > 0 counter-
// clockwise (contour.hpp). `distance` > 0 offsets to the LEFT of the direction of travel,
// < 0 to the right. Left is inward for a counter-clockwise closed contour and outward for a
// clockwise one.
//
// Algorithm (offset_contour; offset_open_path runs steps 0-2):
//  0. Clean the input: drop zero-length segments, clamp |bulge| to 1e9, reject non-finite
//     coordinates (empty result). |d| <= tol::kOffsetJoinMm returns the cleaned source.
//  1. Raw offset of every segment: a line moves along its left normal by d; an arc keeps its
//     centre and gets radius r - d (counter-clockwise arc) or r + d (clockwise arc). An arc
//     whose radius would fall to <= tol::kOffsetCollapseRadiusMm collapses and is dropped: on
//     a closed contour it is first replaced by its mirrored parallel curve (radius |r - d| on
//     the far side of the centre, or the centre itself), which the joins treat like any raw
//     piece and which step 3 then removes, since it lies wholly within |d| of the source; on
//     an open path it is left out at once.
//  2. Join consecutive raw segments at each source vertex V:
//     - ends closer than tol::kOffsetJoinMm (tangent-continuous source): connect as they are;
//     - gap (the vertex is convex on the offset side): a join arc of radius |d| centred on V,
//       its bulge from the exact turn angle;
//     - overlap (concave side): intersect the two raw segments (line-line, line-arc, arc-arc)
//       and trim both at the intersection nearest V. Without an intersection (a short
//       segment), closed contours go through V itself (a spike that step 3 removes) and open
//       paths get a straight connection. If the two raw pieces' full circles (or line and
//       circle) do not meet at all, they curve away from each other (a cusp): a join arc as
//       for a gap. Convex/concave is judged on the source tangents.
//       On open paths, the neighbours of a left-out collapsed arc are intersected likewise,
//       else connected by a straight line.
//  3. Closed contours only: the joined path crosses itself where the source has features
//     narrower than 2|d| (thin slots, small holes). Split it at every self-intersection into
//     slices; keep a slice only if it does not cross the source and its sampled distance to
//     the source is >= |d| - tol::kOffsetGougeMm; stitch the kept slices end to start into
//     closed loops; keep the loops with the source's orientation and an area above
//     tol::kOffsetMinLoopAreaMm2.
//
// Complexity: steps 0-2 are O(n); step 3 finds crossings by sorting boxes on x (O(n log n + k)
// for k box overlaps) and checks each slice against the source in O(n), O(n²) in the worst case.

#include <vector>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::geometry {

struct OffsetResult {
  // Closed offset loops with the source's orientation; the first vertex of each loop is where
  // its first kept piece starts. Usually one loop; none when the contour collapsed; several
  // when a thin neck of the source splits the offset region. Loops of the opposite orientation
  // are dropped: e.g. around a cavity whose mouth is narrower than 2|d|, which an outward
  // offset seals (the tool could not enter it anyway).
  std::vector<Contour> contours;
  // No loop survived (e.g. a hole smaller than the kerf, or a degenerate/zero-area source).
  bool collapsed = false;
  // Step 3 discarded some part of the joined raw offset (a slice, or a loop of the wrong
  // orientation); may be set together with `collapsed`.
  bool self_intersection_removed = false;
};

// Offsets a closed contour by `distance` mm to its left (negative: right) with lines and exact
// arcs. An open contour is passed to offset_open_path and returned as the only element.
OffsetResult offset_contour(const Contour& c, double distance);

// Offsets an open path (lead-ins, lead-outs) by `distance` mm to its left (negative: right):
// per-segment raw offset and joins (steps 0-2), no loop removal. The result is open; its end
// points are the offsets of the source's end points (unless an arc at an end collapsed, which
// is left out). Empty for fewer than two distinct points or non-finite input. `c.closed` is
// ignored.
Contour offset_open_path(const Contour& c, double distance);

}  // namespace cutroute::geometry
