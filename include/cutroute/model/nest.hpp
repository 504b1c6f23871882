// Nest: closed contours of a sheet arranged in a containment tree: parts, holes, inner parts, sheet.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <cutroute/core/diagnostic.hpp>
#include <cutroute/core/ids.hpp>
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
  // is a rectangle enclosing every other contour, on a layer named like sheet/plate/border/blech
  // (case-insensitive substring), or an axis-aligned rectangle enclosing everything.
  std::optional<geometry::Vec2> sheet_size;
  double touch_tol_mm = 1e-6;   // boundaries closer than this count as touching [mm]
};

struct Nest {
  IdVector<ContourId, NestContour> contours;
  IdVector<PartId, Part> parts;
  std::optional<ContourId> sheet;  // the sheet border, when recognised or given
  int max_depth = 0;               // deepest contour depth (sheet not counted)
  Diagnostics diagnostics;         // crossing / overlapping contours, duplicates, ...
};

// Builds the containment tree with exact arcs: parent = smallest containing contour;
// contours that cross or overlap another produce an error diagnostic naming both.
// Cost: O(n log n) box queries through a StaticSpatialIndex plus one exact point-in-contour
// and one boundary-intersection test per candidate pair.
Nest build_nest(std::vector<SourceContour> contours, const NestOptions& options);

}  // namespace cutroute::model
