#include <cutroute/io/nest_loader.hpp>

#include <algorithm>
#include <cmath>

#include <map>

#include <cutroute/core/drawing_unit.hpp>
#include <cutroute/core/number_format.hpp>
#include <cutroute/geometry/chain.hpp>
#include <cutroute/geometry/spatial_index.hpp>

namespace cutroute::io {

namespace {

// A chained contour is named after its first entity (layer, handle, line) in messages.
void take_origin(const std::vector<DxfEntity>& ents, const std::vector<std::int32_t>& sources, std::string& layer,
                 std::string& handle, std::optional<long>& line) {
  if (sources.empty()) return;
  const auto& first = ents[static_cast<std::size_t>(sources.front())];
  layer = first.layer;
  handle = first.handle;
  line = first.line;
}

// Each open path's first point located among the nest's contours: inside a part's material (its
// outer contour, none of its holes) it may be a hole drawn with a gap, and the part is then cut
// without it. Boxes first (a packed R-tree), exact point-in-contour on the few candidates.
void place_open_paths(const model::Nest& nest, std::vector<OpenPath>& open) {
  if (open.empty() || nest.contours.empty()) return;
  std::vector<geometry::Box> boxes;
  boxes.reserve(nest.contours.size());
  for (const auto& c : nest.contours) boxes.push_back(c.box);
  const geometry::StaticSpatialIndex index(boxes);
  std::vector<std::uint32_t> near;
  for (OpenPath& p : open) {
    if (p.path.vertices.empty()) continue;
    const geometry::Vec2 at = p.path.vertices.front().p;
    index.query(geometry::Box{at.x, at.y, at.x, at.y}, near);
    // The smallest contour holding the point decides: an outer one means part material.
    std::optional<model::ContourId> holder;
    for (const std::uint32_t k : near) {
      const model::ContourId id(static_cast<std::int32_t>(k));
      const auto& c = nest.contours[id];
      if (c.role == model::ContourRole::sheet) continue;
      if (geometry::locate(c.source.contour, at, 0.0) != geometry::Location::inside) continue;
      if (!holder || c.area_mm2 < nest.contours[*holder].area_mm2) holder = id;
    }
    if (holder && nest.contours[*holder].role == model::ContourRole::outer) p.inside_part = nest.contours[*holder].part;
  }
}

}  // namespace

double gap_to_close(double gap_mm) {
  // The figure as printed (3 decimals) must join the ends when typed back: ends 0.3 mm apart in the
  // drawing may lie 0.30000000000000004 apart, which --close-gaps 0.3 does not reach.
  double g = std::ceil(gap_mm * 1000) / 1000;
  while (g < gap_mm) g += 0.001;
  return std::min(g, geometry::kGapHintMm);
}

LoadedNest assemble_nest(DxfDrawing drawing, const NestLoadOptions& options) {
  LoadedNest out;
  out.file = drawing.file;
  out.units_in_file = drawing.units_in_file;
  out.units_source = drawing.units_source;
  out.mm_per_unit = drawing.mm_per_unit;
  out.unit = DrawingUnit{drawing.mm_per_unit, drawing.unit_name};
  out.entity_counts = drawing.entity_counts;
  out.layers = drawing.layers;
  out.skipped = drawing.skipped;
  out.diagnostics = std::move(drawing.diagnostics);

  // One chaining group per layer, numbered in order of first appearance (deterministic).
  std::map<std::string, std::int32_t> layer_group;
  std::vector<geometry::ChainPiece> pieces;
  pieces.reserve(drawing.entities.size());
  for (std::size_t i = 0; i < drawing.entities.size(); ++i) {
    auto& e = drawing.entities[i];
    auto [it, inserted] = layer_group.try_emplace(e.layer, static_cast<std::int32_t>(layer_group.size()));
    pieces.push_back({std::move(e.path), static_cast<std::int32_t>(i), it->second});
  }
  geometry::ChainResult chained = geometry::chain_contours(pieces, options.snap_mm, options.close_gaps_mm);
  out.dropped_zero_length = chained.dropped_zero_length;
  out.dropped_duplicates = chained.dropped_duplicates;

  const auto& ents = drawing.entities;
  std::vector<model::SourceContour> closed;
  closed.reserve(chained.closed.size());
  for (auto& c : chained.closed) {
    model::SourceContour sc;
    sc.contour = std::move(c.contour);
    sc.sources = std::move(c.sources);
    take_origin(ents, sc.sources, sc.layer, sc.handle, sc.line);
    closed.push_back(std::move(sc));
  }
  for (const geometry::ClosedGap& g : chained.gaps_closed) {
    const auto& a = ents[static_cast<std::size_t>(g.source_a)];
    const auto& b = ents[static_cast<std::size_t>(g.source_b)];
    auto name = [](const DxfEntity& e) {
      if (!e.handle.empty()) return "entity " + e.handle;
      return e.line ? "the entity at line " + std::to_string(*e.line) : std::string("an entity");
    };
    const std::string between = g.source_a == g.source_b ? "the ends of " + name(a) : name(a) + " and " + name(b);
    Diagnostic d = make_warning("gap of " + format_fixed(g.width_mm, 3) + " mm between " + between + " closed at " +
                                    format_position(g.at.x, g.at.y, out.unit),
                                out.file, a.line);
    d.handle = a.handle;
    d.layer = a.layer;
    d.code = "chain.gap_closed";
    out.gaps_closed.emplace_back(g.at, d.message);
    out.diagnostics.push_back(std::move(d));
  }
  for (auto& c : chained.open) {
    OpenPath p;
    p.path = std::move(c.contour);
    p.nearest_end_mm = c.nearest_end_mm;
    p.entities = c.sources.size();
    take_origin(ents, c.sources, p.layer, p.handle, p.line);
    out.open_paths.push_back(std::move(p));
  }

  model::NestOptions nest_options = options.nest;
  nest_options.position_unit = out.unit;
  nest_options.crossing_tol_mm = std::max(nest_options.crossing_tol_mm, options.dxf.curve_tol_mm);
  nest_options.self_loop_tol_mm = std::max(nest_options.self_loop_tol_mm, 4 * std::max(options.snap_mm, options.dxf.curve_tol_mm));
  out.nest = model::build_nest(std::move(closed), nest_options);
  place_open_paths(out.nest, out.open_paths);
  // The open paths' warnings (they need the nest: which part holds them) and the chaining's counts
  // go before the nest's diagnostics.
  for (const OpenPath& p : out.open_paths) {
    if (p.path.vertices.empty()) continue;
    const auto a = p.path.vertices.front().p;
    const auto b = p.path.vertices.back().p;
    std::string message = "open contour from " + std::to_string(p.entities) + " entities, ends at " + format_position(a.x, a.y, out.unit) +
                          " and " + format_position(b.x, b.y, out.unit) + "; kept as an open path, not cut";
    if (p.inside_part)
      message += "; it lies in the material of part " + std::to_string(p.inside_part->value() + 1) +
                 ": if it is a hole drawn with a gap, that part is cut without it";
    if (p.nearest_end_mm > options.close_gaps_mm)
      message += "; an end lies " + format_fixed(p.nearest_end_mm, 3) + " mm from another free end (--close-gaps " +
                 format_fixed(gap_to_close(p.nearest_end_mm), 3) + " would join them)";
    Diagnostic d = make_warning(std::move(message), out.file, p.line);
    d.handle = p.handle;
    d.layer = p.layer;
    d.code = "chain.open";
    out.diagnostics.push_back(std::move(d));
  }
  if (chained.dropped_zero_length > 0) {
    out.diagnostics.push_back(make_warning(
        std::to_string(chained.dropped_zero_length) + " zero-length entities dropped", out.file));
    out.diagnostics.back().code = "chain.zero_length";
  }
  if (chained.dropped_duplicates > 0) {
    out.diagnostics.push_back(make_warning(
        std::to_string(chained.dropped_duplicates) + " duplicated entities dropped", out.file));
    out.diagnostics.back().code = "chain.duplicate";
  }
  for (auto& d : out.nest.diagnostics) {
    if (d.file.empty()) d.file = out.file;
    out.diagnostics.push_back(d);
  }
  return out;
}

Result<LoadedNest> load_nest(const std::string& path, const NestLoadOptions& options) {
  auto drawing = read_dxf(path, options.dxf);
  if (!drawing) return drawing.error();
  return assemble_nest(std::move(drawing).value(), options);
}

}  // namespace cutroute::io
