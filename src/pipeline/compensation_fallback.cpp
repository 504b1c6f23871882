#include "compensation_fallback.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <cutroute/geometry/contour.hpp>
#include <cutroute/model/kerf_offset.hpp>
#include <cutroute/nc/compensation_check.hpp>
#include <cutroute/nc/gcode_writer.hpp>

namespace cutroute::pipeline {

namespace {

// An open path (a lead or a bridge: one to three lines and tangent arcs) moved sideways by
// `left_mm` (> 0 left of travel, < 0 right), as a controller's compensation moves it: each line
// parallel, each arc concentric with the same sweep. Written here because geometry/offset.hpp
// (Clipper) offsets whole regions and flattens arcs; these paths need the exact per-segment
// offset. Where two offset segments do not meet (a corner between them), a straight move joins
// them. nullopt when an arc would shrink to nothing.
std::optional<geometry::Contour> sideways(const geometry::Contour& path, double left_mm) {
  geometry::Contour out;
  for (std::size_t i = 0; i < geometry::segment_count(path); ++i) {
    const geometry::Segment seg = geometry::segment(path, i);
    geometry::Vec2 a, b;
    if (!seg.is_arc()) {
      const geometry::Vec2 n = geometry::perp(seg.tangent_at(0.0)) * left_mm;
      a = seg.a + n;
      b = seg.b + n;
    } else {
      // Left of travel is the centre's side on a counter-clockwise arc.
      const geometry::Vec2 c = seg.center();
      const double r = seg.radius(), r2 = r - (seg.bulge > 0 ? left_mm : -left_mm);
      if (!(r2 > 1e-6)) return std::nullopt;
      a = c + (seg.a - c) * (r2 / r);
      b = c + (seg.b - c) * (r2 / r);
    }
    if (out.vertices.empty()) out.vertices.push_back({a, 0.0});
    else if (geometry::distance(out.vertices.back().p, a) > 1e-9) out.vertices.push_back({a, 0.0});
    out.vertices.back().bulge = seg.bulge;
    out.vertices.push_back({b, 0.0});
  }
  return out;
}

// Does the beam, its centre on `path`, keep its kerf out of contour `id`'s material: every sample
// on the scrap side and at least kerf/2 (less `tol_mm`) from the drawn contour?
bool clear_of(const model::Nest& nest, model::ContourId id, const geometry::Contour& path, double half_kerf, double tol_mm) {
  const model::NestContour& c = nest.contours[id];
  for (std::size_t i = 0; i < geometry::segment_count(path); ++i) {
    const geometry::Segment seg = geometry::segment(path, i);
    for (int k = 0; k <= 20; ++k) {
      const geometry::Vec2 q = seg.point_at(k / 20.0);
      if (geometry::distance(c.source.contour, q) < half_kerf - tol_mm) return false;
      const bool inside = geometry::locate(c.source.contour, q, 0.0) == geometry::Location::inside;
      if (inside != (c.role == model::ContourRole::hole)) return false;
    }
  }
  return true;
}

}  // namespace

OffsetCuts offset_refused_blocks(nc::Toolpath& path, const model::Nest& nest, double kerf_mm, bool held_over_tabs,
                                 const nc::PostDialect& written_with, bool pieces) {
  OffsetCuts rewritten;
  if (!(kerf_mm > 0)) return rewritten;
  const nc::CompensationHazards h = nc::compensation_hazards(path, kerf_mm / 2, held_over_tabs, written_with);
  for (const std::size_t k : h.at) {
    nc::CutSegment& seg = path.segments[k];
    if (seg.after_tab || (k + 1 < path.segments.size() && path.segments[k + 1].after_tab)) continue;
    // Every contour piece must cut one contour, whole or a piece of it (a chain's parts, joined by
    // bridges, are rewritten together: one segment is one compensated block), and no two may
    // follow each other without a lead or bridge between them to take up the move of their ends.
    std::vector<std::pair<std::size_t, geometry::Contour>> offsets;
    double deviation = 0.0;
    bool whole = true;
    for (std::size_t i = 0; i < seg.pieces.size() && whole; ++i) {
      const nc::CutPiece& piece = seg.pieces[i];
      if (piece.role != nc::PieceRole::contour) continue;
      whole = piece.contour >= 0 && piece.shared_with < 0 && piece.path.vertices.size() >= 2 &&
              (i == 0 || seg.pieces[i - 1].role != nc::PieceRole::contour);
      if (!whole) break;
      const model::ContourId id(piece.contour);
      const geometry::Contour& drawn = nest.contours[id].source.contour;
      const double drawn_mm = geometry::length(drawn), piece_mm = geometry::length(piece.path);
      const geometry::Vec2 from = piece.path.vertices.front().p;
      double simplified_by = 0.0;
      std::optional<geometry::Contour> offset;
      if (piece_mm >= drawn_mm - 1e-6 * std::max(1.0, drawn_mm)) {
        // The whole contour: the piece, closed, has the contour's orientation or the reverse (an
        // overcut retraces a few millimetres of the loop, which keeps the sign).
        geometry::Contour loop = piece.path;
        loop.closed = true;
        const bool clockwise = geometry::orientation(loop) == geometry::Orientation::cw;
        offset = model::kerf_offset_cut(nest, id, kerf_mm, from, clockwise, piece_mm - drawn_mm, &simplified_by);
      } else if (pieces) {
        // A piece of it (multi-segment cutting): its direction from how it runs along the drawing.
        const double total = drawn_mm, s0 = geometry::closest_point(drawn, from).length_along;
        const double ahead = std::fmod(geometry::closest_point(drawn, geometry::point_at_length(piece.path, 0.5 * piece_mm)).length_along -
                                           s0 + total,
                                       total);
        const bool along_drawing = ahead < 0.5 * total;
        const bool clockwise = (geometry::orientation(drawn) == geometry::Orientation::cw) == along_drawing;
        offset = model::kerf_offset_piece(nest, id, kerf_mm, from, piece.path.vertices.back().p, clockwise, &simplified_by);
      }
      whole = offset && offset->vertices.size() >= 2;
      deviation = std::max(deviation, simplified_by);
      if (whole) offsets.emplace_back(i, std::move(*offset));
    }
    if (!whole || offsets.empty()) continue;
    // Leads and bridges take the path the controller's compensation would have given them: moved
    // sideways by kerf/2 to the compensation's side (the scrap side where they meet a contour). At
    // a detail finer than the kerf the lead's end may not meet the contour tangentially (that is
    // what the controller refuses), and the path moved sideways would cut into the part: the lead
    // is then moved whole, by the move of its end onto the offset loop. Each is joined to the loops
    // by a straight move where the two do not meet exactly, and must keep its kerf out of the
    // contours at its ends; where neither way does, the cut stays compensated (and warned of).
    const double half = kerf_mm / 2, tol = std::max(1e-3, nc::ProgramGrid(written_with).res_mm);
    const double left = seg.kerf == nc::KerfSide::left ? half : -half;
    std::vector<geometry::Contour> moved(seg.pieces.size());
    std::vector<geometry::Contour> loops(seg.pieces.size());
    for (auto& [i, offset] : offsets) loops[i] = std::move(offset);
    auto joined = [&](std::size_t i, geometry::Contour p) {
      if (i > 0 && !loops[i - 1].vertices.empty()) {
        const geometry::Vec2 from = loops[i - 1].vertices.back().p;
        if (geometry::distance(from, p.vertices.front().p) > 1e-9) p.vertices.insert(p.vertices.begin(), {from, 0.0});
      }
      if (i + 1 < seg.pieces.size() && !loops[i + 1].vertices.empty()) {
        const geometry::Vec2 to = loops[i + 1].vertices.front().p;
        if (geometry::distance(p.vertices.back().p, to) > 1e-9) p.vertices.push_back({to, 0.0});
      }
      return p;
    };
    auto clear = [&](std::size_t i, const geometry::Contour& p) {
      for (const std::size_t j : {i - 1, i + 1})
        if (j < seg.pieces.size() && seg.pieces[j].role == nc::PieceRole::contour &&
            !clear_of(nest, model::ContourId(seg.pieces[j].contour), p, half, tol))
          return false;
      return true;
    };
    bool ok = true;
    for (std::size_t i = 0; i < seg.pieces.size() && ok; ++i) {
      const nc::CutPiece& piece = seg.pieces[i];
      if (piece.role == nc::PieceRole::contour || piece.path.vertices.size() < 2) continue;
      if (auto side = sideways(piece.path, left)) {
        geometry::Contour p = joined(i, std::move(*side));
        if (clear(i, p)) {
          moved[i] = std::move(p);
          continue;
        }
      }
      // Moved whole: by the lead-in's end onto its loop's start, the lead-out's start onto its loop's end.
      const bool in = i + 1 < seg.pieces.size() && !loops[i + 1].vertices.empty();
      const bool out_of = i > 0 && !loops[i - 1].vertices.empty();
      if (in && out_of) {  // a bridge: straight from one loop's end to the next loop's start
        geometry::Contour p;
        p.vertices = {{loops[i - 1].vertices.back().p, 0.0}, {loops[i + 1].vertices.front().p, 0.0}};
        ok = clear(i, p);
        if (ok) moved[i] = std::move(p);
        continue;
      }
      if (!in && !out_of) {  // a lead with no loop beside it
        ok = false;
        break;
      }
      const geometry::Vec2 by = in ? loops[i + 1].vertices.front().p - piece.path.vertices.back().p
                                   : loops[i - 1].vertices.back().p - piece.path.vertices.front().p;
      geometry::Contour p = piece.path;
      for (auto& v : p.vertices) v.p = v.p + by;
      p = joined(i, std::move(p));
      ok = clear(i, p);
      if (ok) moved[i] = std::move(p);
    }
    if (!ok) continue;
    for (std::size_t i = 0; i < seg.pieces.size(); ++i) {
      if (!loops[i].vertices.empty()) seg.pieces[i].path = std::move(loops[i]);
      else if (!moved[i].vertices.empty()) seg.pieces[i].path = std::move(moved[i]);
    }
    seg.pierce = seg.pieces.front().path.vertices.front().p;
    seg.kerf = nc::KerfSide::none;
    rewritten.labels.push_back(seg.label);
    rewritten.deviation_mm = std::max(rewritten.deviation_mm, deviation);
  }
  return rewritten;
}

}  // namespace cutroute::pipeline
