// Kerf offset of a whole nest (--kerf-mode cam): the path the torch centre follows per contour.
#pragma once

#include <optional>

#include <cutroute/core/diagnostic.hpp>
#include <cutroute/model/nest.hpp>

namespace cutroute::model {

// The nest with every cut contour replaced by its kerf offset (geometry/offset.hpp, arcs kept
// exact): outer contours moved outward and holes inward, by kerf / 2, so that the kerf lies in
// scrap and the part keeps its drawn size. Everything else (ids, roles, depth, parents, parts,
// sheet) is the drawn nest's, so a ContourId names the same contour in both; box and area are
// those of the offset. Planning entries on this nest puts pierces, leads and clearances on the
// geometry the torch actually follows.
struct KerfNest {
  Nest nest;
  // Per contour, with its line, handle and layer, and a stable code:
  //  error   "kerf.collapsed"  a hole too small for the kerf: no offset loop is left;
  //  error   "kerf.failed"     the offset algorithm lost a contour that cannot vanish (an outer
  //                            contour, or a hole with area > perimeter * kerf/2), even without
  //                            its tiny details (see kerf.simplified);
  //  error   "kerf.split"      a hole with a neck narrower than the kerf: its toolpath falls
  //                            apart into several loops;
  //  error   "kerf.overlap"    the toolpaths of two contours cross or touch: the parts are closer
  //                            than the kerf (or drawn touching), so cutting one cuts into the other;
  //  warning "kerf.simplified" the offset needed the contour's tiny arcs straightened or tiny
  //                            segments left out (chords under 0.2 kerf); gives the deviation;
  //  warning "kerf.gouge"     the toolpath comes closer than kerf/2 to the drawing by more than
  //                            1 µm somewhere (offset inaccuracy at details far below the kerf);
  //  warning "kerf.trimmed"    a feature narrower than the kerf (a slot, an inside corner
  //                            cavity) cannot be followed; the toolpath passes it by.
  // A contour that collapsed or split keeps its drawn geometry in `nest` (so the nest stays whole
  // for messages); the caller must not cut it while those errors stand.
  Diagnostics diagnostics;
};

// Offsets every contour but the sheet border by kerf_mm / 2 to its scrap side. kerf_mm <= 0
// returns the nest unchanged. Overlaps: at most 100 pairs are listed, one more diagnostic counts
// the rest. Cost: one offset per contour, then one boundary test per pair of overlapping boxes.
KerfNest offset_for_kerf(const Nest& nest, double kerf_mm);

// The path the torch centre follows to cut one contour on its kerf offset, as offset_for_kerf()
// offsets it: from the offset's point nearest `near`, clockwise or not, one loop plus `extra_mm`
// (an overcut). nullopt when the offset is not one loop (collapsed, split or failed).
// `simplified_by`: set to how far the drawing was simplified for the offset (kerf.simplified: the
// path deviates by up to that much from kerf/2 there), 0 when it was not.
std::optional<geometry::Contour> kerf_offset_cut(const Nest& nest, ContourId id, double kerf_mm, geometry::Vec2 near,
                                                 bool clockwise, double extra_mm, double* simplified_by = nullptr);
// A piece of that path: from the offset's point nearest `from` to the one nearest `to`, clockwise
// or not (multi-segment cutting's pieces of a contour).
std::optional<geometry::Contour> kerf_offset_piece(const Nest& nest, ContourId id, double kerf_mm, geometry::Vec2 from,
                                                   geometry::Vec2 to, bool clockwise, double* simplified_by = nullptr);

}  // namespace cutroute::model
