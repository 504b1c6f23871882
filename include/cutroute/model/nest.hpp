// Nest: closed contours of a sheet arranged in a containment tree: parts, holes, inner parts, sheet.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <cutroute/core/diagnostic.hpp>
#include <cutroute/core/drawing_unit.hpp>
#include <cutroute/core/ids.hpp>
#include <cutroute/core/tolerances.hpp>
#include <cutroute/geometry/contour.hpp>

namespace cutroute::model {

using ContourId = Id<struct ContourTag>;
using PartId = Id<struct PartTag>;

enum class ContourRole {
  outer,  // outer boundary of a part (even depth)
  hole,   // inner boundary of a part (odd depth)
  sheet,  // the sheet border: not a part, never cut
};
const char* to_string(ContourRole r);

// A closed contour as it enters the nest, with where it came from.
struct SourceContour {
  geometry::Contour contour;            // closed
  std::string layer;
  std::vector<std::int32_t> sources;    // caller's entity ids (e.g. DXF entity indices)
  std::string handle;                   // first source entity's handle, for messages
  std::optional<long> line;             // first source entity's line, for messages
};

struct NestContour {
  SourceContour source;
  ContourRole role = ContourRole::outer;
  int depth = 0;             // 0 = not inside any other contour (the sheet border not counted)
  ContourId parent;          // the smallest contour containing this one; invalid at depth 0
  PartId part;               // the part this contour bounds; invalid for the sheet
  double area_mm2 = 0.0;     // absolute area [mm²]
  geometry::Box box;         // [mm]
};

struct Part {
  ContourId outer;
  std::vector<ContourId> holes;
  ContourId inside_hole;     // the hole of another part this part lies in; invalid if none
  PartId parent_part;        // the part owning inside_hole; invalid if none
};

struct NestOptions {
  // Sheet border: given size (W, H) [mm] from --sheet, else detected: the largest contour that
  // is a rectangle (in any orientation) enclosing every other contour, on a layer named like
  // sheet/plate/border/blech (case-insensitive substring), or enclosing parts with holes.
  std::optional<geometry::Vec2> sheet_size;
  double touch_tol_mm = 1e-6;   // boundaries closer than this count as touching [mm]
  bool detect_sheet = true;     // false: never look for a border (sheet_size still applies)
  // Boundaries that cross by no more than this are reported as touching (a warning), not as
  // overlapping parts (an error) [mm]. The DXF loader sets its curve-conversion tolerance here:
  // a SPLINE touching a neighbour may cross it by that much once turned into arcs.
  double crossing_tol_mm = 0.0;
  // A contour that meets itself is an error ("nest.crossing") unless the loop it closes is shorter
  // than this [mm]: snapping ends (--snap) and converting curves leave zig-zags of a few of their
  // tolerances (d2g_DRAAK: 53 loops of at most 0.015 mm). The DXF loader sets 4 × max(snap, curve tolerance).
  double self_loop_tol_mm = 4 * tol::kSnapMm;
  // The unit the places in messages are given in: the drawing's (the DXF loader sets it), so that
  // an inch drawing's crossing is named where its drawing has it.
  DrawingUnit position_unit;
};

struct Nest {
  IdVector<ContourId, NestContour> contours;   // the input contours in input order, minus the
                                               // dropped ones (duplicates, invalid; see below)
  IdVector<PartId, Part> parts;                // in order of their outer contour
  std::optional<ContourId> sheet;  // the sheet border, when recognised or given
  int max_depth = 0;               // deepest contour depth (sheet not counted)
  Diagnostics diagnostics;         // crossing / overlapping contours, duplicates, ...
  // The sheet's extent [mm]: the border's box when there is a border contour; with
  // options.sheet_size and no matching border, the rectangle (0, 0)–(W, H).
  std::optional<geometry::Box> sheet_box;
  // Pairs of contours whose boundaries share a stretch (parts drawn edge to edge; warning
  // "nest.common_edge"), lower index first, in index order. Cutting either cuts a piece of both.
  std::vector<std::pair<ContourId, ContourId>> shared_edges;
  std::size_t dropped_duplicates = 0;  // exact repeats of an earlier contour (error diagnostic each)
  std::size_t dropped_invalid = 0;     // open, empty, zero-length or non-finite input (error diagnostic each)
  DrawingUnit unit;  // the drawing's unit, in which messages name places (NestOptions::position_unit)
};

// Builds the containment tree with exact arcs: parent = smallest containing contour;
// contours that cross or overlap another produce an error diagnostic naming both.
// Cost: O(n log n) box queries through a StaticSpatialIndex plus one exact point-in-contour
// and one boundary-intersection test per candidate pair.
//
// Steps (nest.cpp has one function per step):
//  1. prepare: area, box; drop (with an error diagnostic) contours that are not closed, have no
//     length or non-finite coordinates, and exact duplicates (the same vertex cycle, bit-exact,
//     from any start vertex and in either direction; the first in input order stays). A
//     contour enclosing no area (a slot traced there and back, a symmetric figure 8) stays,
//     with a warning: it is cut but holds nothing.
//  2. find the sheet candidate: the largest contour that is a rectangle whose box encloses every
//     other contour's box (overhang up to tol::kSheetOverhangMm allowed) and that either matches
//     options.sheet_size (its sides) or lies on a layer named like sheet/plate/border/blech or is
//     detected by geometry alone; in any orientation (a nest drawn rotated).
//  3. containment tree over the other contours: for every pair of overlapping boxes, one
//     exact boundary test within touch_tol_mm and, when one box holds the other, one exact
//     point-in-contour test of a vertex of the smaller. parent = the smallest container.
//     Where the boundaries meet, both are sampled (vertices, segment quarter points) against the
//     other region, and every diagnostic names both contours and a common point ("near (x, y)"):
//       crossing (samples on both sides), or all samples on the other boundary: error
//       "cross or overlap" (crossing: "by at least D mm", D from the samples), and neither
//       becomes the other's parent;
//       touching with a common stretch (shared edge): error "share a boundary stretch";
//       touching in points only (tangent, corner on edge): warning "touch".
//     Touching contours still nest when the smaller one's samples lie inside the bigger.
//     Only the first 1000 such pairs are listed; one more diagnostic counts the rest.
//  4. a candidate found by geometry alone (no size, no layer) is accepted only when it holds
//     at least 2 top-level contours and some contour inside it has a contour inside it in turn
//     (a part with a hole): a rectangular plate with holes, or a rectangular part with one
//     cut-out holding a nested part, thus stays a part. Rejected: rebuild with it. (A plate
//     with several cut-outs each holding a nested part is still taken for a sheet: give the
//     border a layer name or set detect_sheet = false.)
//  5. depth (sheet not counted), role by parity (even = outer, odd = hole), parts: each outer
//     with its holes; an outer at depth >= 2 lies in a hole: inside_hole, parent_part.
// The sheet border itself has role sheet, depth 0, no parent and no part; it takes no part in
// the boundary tests. A contour whose box comes within touch_tol_mm of the border (or sticks
// out of it) gets a warning instead.
Nest build_nest(std::vector<SourceContour> contours, const NestOptions& options);

}  // namespace cutroute::model
