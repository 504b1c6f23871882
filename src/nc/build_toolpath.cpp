#include <cutroute/nc/build_toolpath.hpp>

#include <algorithm>

namespace cutroute::nc {

namespace {

// "part 3 outer", "part 3 hole 2": how a contour is named in comments, reports and pictures;
// hole_number is its 1-based place among its part's holes (0: none).
std::string label_of(const model::Nest& nest, model::ContourId id, int hole_number) {
  const auto& c = nest.contours[id];
  if (!c.part.valid()) return "contour " + std::to_string(id.value() + 1);
  const std::string part = "part " + std::to_string(c.part.value() + 1);
  if (c.role == model::ContourRole::outer) return part + " outer";
  return hole_number > 0 ? part + " hole " + std::to_string(hole_number) : part + " hole";
}

}  // namespace

Toolpath build_toolpath(const model::Nest& nest, const std::vector<const model::EntryCandidate*>& sequence,
                        const ToolpathOptions& options) {
  Toolpath tp;
  tp.start = options.start;
  tp.end = options.end;
  tp.pierce_time_s = options.pierce_time_s;
  tp.segments.reserve(sequence.size());
  // Contours cut in several pieces (multi-segment cutting): how many, to number them in the labels.
  std::vector<int> part_count(nest.contours.size(), 0), part_done(nest.contours.size(), 0);
  const auto is_part = [](const model::EntryCandidate& e) {
    return e.contour.valid() && !e.pieces.empty() && e.pieces.front().kind == model::PieceKind::contour_part;
  };
  for (const auto* e : sequence)
    if (is_part(*e)) ++part_count[e->contour.index()];
  // Each hole's number among its part's holes, once: looked up per label, a perforated plate of
  // 40 000 holes took 0.6 s (O(holes) per label).
  std::vector<int> hole_number(nest.contours.size(), 0);
  for (const auto& part : nest.parts)
    for (std::size_t k = 0; k < part.holes.size(); ++k) hole_number[part.holes[k].index()] = static_cast<int>(k) + 1;
  const auto label = [&](model::ContourId id) { return label_of(nest, id, hole_number[id.index()]); };
  for (const auto* e : sequence) {
    CutSegment s;
    s.pierce = e->pierce;
    s.feed_mm_min = options.feed_mm_min;
    s.label = label(e->contour);
    if (is_part(*e))
      s.label += ", piece " + std::to_string(++part_done[e->contour.index()]) + " of " + std::to_string(part_count[e->contour.index()]);
    for (const auto& piece : e->pieces) {
      if (piece.kind == model::PieceKind::bridge || piece.contour == e->contour) continue;
      const std::string more = label(piece.contour);
      if (s.label.find(more) == std::string::npos) s.label += " + " + more;
    }
    // A common line (common_edge pieces, bridges across kerf gaps) is a centre line: cut without
    // compensation, the kerf takes half from each part (or exactly the gap they were drawn apart).
    const bool centre_line = std::none_of(e->pieces.begin(), e->pieces.end(),
                                          [](const model::SegmentPiece& p) {
                                            return p.kind == model::PieceKind::contour || p.kind == model::PieceKind::contour_part;
                                          });
    if (options.kerf == KerfMode::controller && !centre_line) {
      const auto role = nest.contours[e->contour].role;
      const bool scrap_left = role == model::ContourRole::outer ? e->clockwise : !e->clockwise;
      s.kerf = scrap_left ? KerfSide::left : KerfSide::right;
    }
    if (e->lead_in.vertices.size() >= 2) s.pieces.push_back({e->lead_in, PieceRole::lead_in, -1});
    for (const auto& piece : e->pieces) {
      const bool bridge = piece.kind == model::PieceKind::bridge;
      const bool shared = piece.kind == model::PieceKind::common_edge && piece.other.valid();
      s.pieces.push_back({piece.path, bridge ? PieceRole::bridge : PieceRole::contour, bridge ? -1 : piece.contour.value(),
                          shared ? piece.other.value() : -1});
    }
    if (e->lead_out.vertices.size() >= 2) s.pieces.push_back({e->lead_out, PieceRole::lead_out, -1});
    tp.segments.push_back(std::move(s));
  }
  return tp;
}

}  // namespace cutroute::nc
