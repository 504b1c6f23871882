// load_nest(): DXF file -> curves -> chained contours -> nest (parts, holes, sheet), with diagnostics.
#pragma once

#include <optional>
#include <utility>
#include <string>
#include <vector>

#include <cutroute/core/diagnostic.hpp>
#include <cutroute/core/result.hpp>
#include <cutroute/io/dxf.hpp>
#include <cutroute/model/nest.hpp>

namespace cutroute::io {

// An open chain kept as an open path: engraving / marking strokes, or a drawing gap.
// Never cut by default.
struct OpenPath {
  geometry::Contour path;
  std::string layer;
  std::string handle;          // first entity of the chain
  std::optional<long> line;
  double nearest_end_mm = -1;  // its end nearest another free end (or its own other end), if within 1 mm
  std::size_t entities = 0;    // how many entities it was chained from
  std::optional<model::PartId> inside_part;  // the part whose material holds its first point
};

struct NestLoadOptions {
  DxfOptions dxf;
  double snap_mm = tol::kSnapMm;   // end-point snapping when chaining [mm]
  double close_gaps_mm = tol::kCloseGapMm;  // ends still apart joined within this, with a warning [mm]
  model::NestOptions nest;
};

struct LoadedNest {
  std::string file;
  std::string units_in_file;
  std::string units_source;
  double mm_per_unit = 1.0;
  DrawingUnit unit;  // the drawing's unit: places in messages are given in it
  std::map<std::string, std::size_t> entity_counts;  // every modelspace entity type (skipped included)
  std::map<std::string, std::size_t> skipped;
  std::map<std::string, std::size_t> layers;         // entities per layer, filters not applied
  std::size_t dropped_zero_length = 0;
  std::size_t dropped_duplicates = 0;
  // Joints made across a gap (--close-gaps), each warned "chain.gap_closed": where, and that warning's
  // message, for the pictures' marks.
  std::vector<std::pair<geometry::Vec2, std::string>> gaps_closed;
  model::Nest nest;
  std::vector<OpenPath> open_paths;
  Diagnostics diagnostics;   // reader, chaining and nest diagnostics, in that order
};

// The pipeline of the foundation: io::read_dxf -> geometry::chain_contours (per layer: a cut
// contour never joins an engraving stroke on another layer) -> model::build_nest.
// Fails only when the file cannot be read; crossing contours are error diagnostics in the
// result (the caller decides whether they stop the job).
Result<LoadedNest> load_nest(const std::string& path, const NestLoadOptions& options);
LoadedNest assemble_nest(DxfDrawing drawing, const NestLoadOptions& options);

// The smallest --close-gaps of three decimals that joins ends gap_mm apart (at most 1 mm).
double gap_to_close(double gap_mm);

}  // namespace cutroute::io
