#include <cutroute/nc/micro_joints.hpp>

#include <algorithm>
#include <cmath>

#include <cutroute/core/tolerances.hpp>

namespace cutroute::nc {
namespace {

using geometry::Contour;
using geometry::Vec2;

// The part of an open path between arc lengths s0 < s1 (clamped to the path), arcs split exactly.
Contour sub_path(const Contour& c, double s0, double s1) {
  Contour out;
  double at = 0;
  const std::size_t n = geometry::segment_count(c);
  for (std::size_t i = 0; i < n && at < s1; ++i) {
    const geometry::Segment seg = geometry::segment(c, i);
    const double l = seg.length();
    if (l <= 0 || at + l <= s0) {
      at += l;
      continue;
    }
    const double u0 = std::max(0.0, (s0 - at) / l), u1 = std::min(1.0, (s1 - at) / l);
    const double bulge = seg.is_arc() ? std::tan(seg.sweep() * (u1 - u0) / 4) : 0.0;
    if (out.vertices.empty()) out.vertices.push_back({seg.point_at(u0), bulge});
    else out.vertices.back().bulge = bulge;
    out.vertices.push_back({seg.point_at(u1), 0.0});
    at += l;
  }
  return out;
}

}  // namespace

MicroJointStats add_micro_joints(Toolpath& path, const model::Nest& nest, const MicroJointOptions& o) {
  MicroJointStats st;
  if (o.tabs <= 0 || o.width_mm <= 0) return st;
  const double w = o.width_mm;
  const int n = o.tabs;
  auto outer_piece = [&](const CutPiece& p) {
    return p.role == PieceRole::contour && p.contour >= 0 &&
           nest.contours[model::ContourId(p.contour)].role == model::ContourRole::outer;
  };
  std::vector<CutSegment> out;
  out.reserve(path.segments.size());
  for (auto& whole : path.segments) {
    // A segment cuts one outer contour (standard) or several joined by bridges (chain): each one's
    // loop gets its gaps. What follows the last gap of a contour (its last stretch, the bridge, the
    // next contour, the lead-out) is one segment, whose next outer contour is split in turn.
    CutSegment seg = std::move(whole);
    const std::string label = seg.label;
    int tab_no = 0;  // gaps so far in this segment: the labels of the pieces after them
    for (std::size_t from = 0;;) {
      const auto it = std::find_if(seg.pieces.begin() + static_cast<std::ptrdiff_t>(from), seg.pieces.end(), outer_piece);
      if (it == seg.pieces.end()) break;
      const auto first = static_cast<std::size_t>(it - seg.pieces.begin());
      const double contour_len = geometry::length(nest.contours[model::ContourId(it->contour)].source.contour);
      const double piece_len = geometry::length(it->path);
      if (n * 2 * w > std::min(contour_len, piece_len)) {
        ++st.skipped;
        from = first + 1;
        continue;
      }
      ++st.contours;
      st.tabs += n;
      const CutPiece piece = *it;
      // Gap k centred at g_k = (k + 1/2) L / N. With lead-ins, a gap whose resumed cut has no room
      // for one is moved along the contour, by up to a quarter of the spacing less a gap width
      // either way, to the nearest place that has (notches, a neighbour close to that edge).
      std::vector<double> centre(static_cast<std::size_t>(n));
      std::vector<std::optional<Contour>> lead(static_cast<std::size_t>(n) + 1);
      const double spacing = contour_len / n, step = std::max(w, 1.0), reach = spacing / 4 - w;
      for (int k = 0; k < n; ++k) {
        const double g = (k + 0.5) * spacing;
        centre[static_cast<std::size_t>(k)] = g;
        if (!o.lead_in) continue;
        for (int t = 0; t <= 6; ++t) {
          const double shift = (t + 1) / 2 * step * (t % 2 ? 1 : -1);
          if (std::abs(shift) > reach && t > 0) break;
          const double resume = g + shift + w / 2;
          if (auto l = o.lead_in(piece.contour, sub_path(piece.path, resume, std::min(resume + step, piece_len)))) {
            centre[static_cast<std::size_t>(k)] = g + shift;
            lead[static_cast<std::size_t>(k) + 1] = std::move(l);
            break;
          }
        }
      }
      // Cut stretches between the gaps: [0, g0 - w/2], [g0 + w/2, g1 - w/2], ..., [g_{n-1} + w/2, piece end].
      std::vector<std::pair<double, double>> keep;
      double at = 0;
      for (const double g : centre) {
        keep.emplace_back(at, g - w / 2);
        at = g + w / 2;
      }
      keep.emplace_back(at, piece_len);
      const std::vector<CutPiece> after(seg.pieces.begin() + static_cast<std::ptrdiff_t>(first) + 1, seg.pieces.end());
      for (std::size_t j = 0; j < keep.size(); ++j) {
        CutSegment part;
        part.kerf = seg.kerf;
        part.feed_mm_min = seg.feed_mm_min;
        Contour stretch = sub_path(piece.path, keep[j].first, keep[j].second);
        if (j == 0) {
          part.pierce = seg.pierce;
          part.label = seg.label;
          part.rapid_via = seg.rapid_via;
          part.after_tab = seg.after_tab;
          part.pieces.assign(seg.pieces.begin(), seg.pieces.begin() + static_cast<std::ptrdiff_t>(first));
        } else if (auto& l = lead[j]) {
          l->vertices.back().p = stretch.vertices.front().p;  // the lead ends where the cut resumes, to the bit
          part.pierce = l->vertices.front().p;
          part.label = label + " after tab " + std::to_string(++tab_no);
          part.pieces.push_back({std::move(*l), PieceRole::lead_in, -1});
          ++st.lead_ins;
        } else {
          part.pierce = stretch.vertices.front().p;
          part.label = label + " after tab " + std::to_string(++tab_no);
          part.after_tab = true;
          st.on_path += o.lead_in != nullptr;
          // Under controller compensation the head crosses the gap on the offset path: along the
          // contour's corners, not across them (an arc in the gap is crossed on its chord, which
          // for a tab of a millimetre or two lies within a few hundredths of it).
          if (seg.kerf != KerfSide::none) {
            const Contour gap = sub_path(piece.path, keep[j - 1].second, keep[j].first);
            for (std::size_t v = 1; v + 1 < gap.vertices.size(); ++v) part.rapid_via.push_back(gap.vertices[v].p);
          }
        }
        part.pieces.push_back({std::move(stretch), PieceRole::contour, piece.contour});
        if (j + 1 < keep.size()) {
          out.push_back(std::move(part));
          continue;
        }
        part.pieces.insert(part.pieces.end(), after.begin(), after.end());
        from = part.pieces.size() - after.size();
        seg = std::move(part);
      }
    }
    out.push_back(std::move(seg));
  }
  path.segments = std::move(out);
  return st;
}

}  // namespace cutroute::nc
