// read_dxf(): reads a DXF drawing (via dxflib) into curves in millimetres with layers, handles and lines.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <cutroute/core/diagnostic.hpp>
#include <cutroute/core/result.hpp>
#include <cutroute/core/tolerances.hpp>
#include <cutroute/geometry/contour.hpp>

namespace cutroute::io {

// One drawn curve after INSERT expansion, extrusion handling and unit conversion.
// LINE/ARC become one-segment open contours; CIRCLE a closed 2-vertex contour; LWPOLYLINE and
// POLYLINE keep their bulges and closed flag; SPLINE and ELLIPSE are converted to arcs/lines
// within the curve tolerance.
struct DxfEntity {
  geometry::Contour path;     // [mm]
  std::string type;           // "LINE", "ARC", "CIRCLE", "LWPOLYLINE", "POLYLINE", "SPLINE", "ELLIPSE"
  std::string layer;          // after INSERT layer "0" inheritance
  std::string handle;         // hex handle of the entity (of the INSERT for block contents), may be empty
  std::optional<long> line;   // 1-based line of the entity's "0" group in the file (of the
                              // top-level INSERT for block contents, like `handle`)
  std::string block;          // innermost block the curve comes from; empty in modelspace
  std::optional<long> source_line;  // line of the curve's own "0" group (inside its BLOCK for
                                    // block contents; equal to `line` in modelspace)
};

struct DxfOptions {
  std::optional<std::string> units;       // override: "mm", "cm", "m", "in", "ft"
  std::vector<std::string> layers;        // keep only these layers (empty = all)
  std::vector<std::string> ignore_layers; // drop these layers
  double curve_tol_mm = tol::kArcChordMm; // SPLINE/ELLIPSE to arcs chord tolerance [mm], in
                                          // [1e-6, 100]; also used for arcs under non-uniform
                                          // INSERT scale (they become elliptic)
  std::size_t max_entities = 2'000'000;   // after INSERT expansion; beyond: input error
  int max_insert_depth = 32;              // INSERT nesting levels; beyond: input error
};

struct DxfDrawing {
  std::string file;
  std::string units_in_file;              // "mm", "cm", "m", "in", "ft", "unitless", ...
  std::string units_source;               // "$INSUNITS", "$MEASUREMENT", "default", "option"
  double mm_per_unit = 1.0;
  std::string unit_name = "mm";           // the unit its numbers are read in: the header's, or --units
  std::optional<int> insunits;            // raw $INSUNITS of the HEADER, when present
  std::optional<int> measurement;         // raw $MEASUREMENT of the HEADER, when present
  std::vector<DxfEntity> entities;        // curves only, in file order (block contents at
                                          // the place of their INSERT)
  std::map<std::string, std::size_t> entity_counts;  // every entity type seen in modelspace
                                                      // (after INSERT expansion), skipped ones included;
                                                      // each placed INSERT counts too; paper space
                                                      // and filtered layers do not
  std::map<std::string, std::size_t> skipped;        // types read but not turned into curves
  // Modelspace entities per layer after INSERT expansion (a block's layer-0 entities on the
  // INSERT's layer), before the layer filters: what --layers can name.
  std::map<std::string, std::size_t> layers;
  Diagnostics diagnostics;                // warnings (skipped, converted, odd values)
};

// Never crashes or hangs on bad content: malformed files give an error Diagnostic naming the
// file and line (exit code 2 in the CLI).
//
// Units: $INSUNITS when it names a length unit (in, ft, mm, cm, m, and mil, yd, um, dm), else
// $MEASUREMENT (0 = inch, 1 = mm), else mm with units_in_file "unitless"; options.units
// overrides the scale (units_source "option") and units_in_file still tells what the file said.
// Layer names are compared case-insensitively (as AutoCAD does) by the layer filters.
Result<DxfDrawing> read_dxf(const std::string& path, const DxfOptions& options);
Result<DxfDrawing> read_dxf_string(const std::string& content, const std::string& name, const DxfOptions& options);

}  // namespace cutroute::io
