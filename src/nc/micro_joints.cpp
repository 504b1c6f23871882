#include <cutroute/nc/micro_joints.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

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

// Arc lengths along an open path where its direction turns by more than 15 degrees.
std::vector<double> corners_along(const Contour& c) {
  std::vector<double> out;
  const double cos_max = std::cos(15.0 * std::numbers::pi / 180.0);
  double at = 0;
  std::optional<Vec2> before;  // direction at the end of the last segment of non-zero length
  for (std::size_t i = 0; i < geometry::segment_count(c); ++i) {
    const geometry::Segment seg = geometry::segment(c, i);
    const double l = seg.length();
    if (l <= 0) continue;
    if (before && geometry::dot(*before, seg.tangent_at(0)) < cos_max) out.push_back(at);
    before = seg.tangent_at(1);
    at += l;
  }
  return out;
}

// The gaps planned on one contour piece: their centres along it, ascending, and the lead-in of
// the cut resumed after each (lead[k + 1] after gap k; nullopt: pierced on the path). For an
// outer contour's own piece also its length and (once asked for) its corners.
struct PieceGaps {
  std::vector<double> centre;
  std::vector<std::optional<Contour>> lead;
  double length = 0;  // [mm]
  std::optional<std::vector<double>> corners;
};

struct PieceRef {
  std::size_t segment, piece;
};

}  // namespace

MicroJointStats add_micro_joints(Toolpath& path, const model::Nest& nest, const MicroJointOptions& o) {
  MicroJointStats st;
  if (o.tabs <= 0 || o.width_mm <= 0) return st;
  const double w = o.width_mm;
  const int n = o.tabs;
  const auto outer = [&](std::int32_t c) {
    return c >= 0 && nest.contours[model::ContourId(c)].role == model::ContourRole::outer;
  };
  // Each outer contour's own pieces (not a common line) in cutting order, and the contours a
  // common line runs along.
  std::vector<std::vector<PieceRef>> own(nest.contours.size());
  std::vector<char> shares(nest.contours.size(), 0);
  std::vector<std::vector<PieceGaps>> gaps(path.segments.size());
  for (std::size_t s = 0; s < path.segments.size(); ++s) {
    const auto& pieces = path.segments[s].pieces;
    gaps[s].resize(pieces.size());
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const CutPiece& p = pieces[i];
      if (p.role != PieceRole::contour || p.contour < 0) continue;
      if (p.shared_with >= 0) {
        shares[static_cast<std::size_t>(p.contour)] = shares[static_cast<std::size_t>(p.shared_with)] = 1;
      } else if (outer(p.contour)) {
        own[static_cast<std::size_t>(p.contour)].push_back({s, i});
        gaps[s][i].length = geometry::length(p.path);
      }
    }
  }
  const double step = std::max(w, 1.0);
  // Gap centred at g on the piece `spacing` apart from the contour's next, or moved within
  // [lo, hi], by steps of `step` (further on first), to the nearest place that holds (up to
  // spacing / 2 - w either way: a neighbour's cut along that edge) and, with lead-ins, whose
  // resumed cut has room for one (up to spacing / 4 - w and 6 steps: notches, a neighbour close
  // to that edge). Where nothing holds the gap stays at g and is counted.
  const auto place = [&](PieceRef ref, double g, double spacing, double lo, double hi) {
    const CutPiece& piece = path.segments[ref.segment].pieces[ref.piece];
    PieceGaps& pg = gaps[ref.segment][ref.piece];
    pg.centre.push_back(g);
    pg.lead.resize(pg.centre.size() + 1);
    if (!o.lead_in && !o.holds && o.corner_clearance_mm <= 0) return;
    const double lead_reach = spacing / 4 - w, hold_reach = o.holds ? spacing / 2 - w : lead_reach;
    // Both ends of the gap at least corner_clearance_mm from a corner (or on it).
    if (o.corner_clearance_mm > 0 && !pg.corners) pg.corners = corners_along(piece.path);
    const auto clear = [&](double x) {
      if (!pg.corners) return true;
      for (const double c : *pg.corners)
        for (const double end : {x - w / 2, x + w / 2})
          if (std::abs(end - c) > 1e-6 && std::abs(end - c) < o.corner_clearance_mm) return false;
      return true;
    };
    std::optional<double> held;       // the nearest place that holds and is clear of corners
    std::optional<double> held_only;  // the nearest place that holds, for want of one clear of corners
    for (int t = 0;; ++t) {
      const double shift = (t + 1) / 2 * step * (t % 2 ? 1 : -1);
      const bool lead_search = o.lead_in && t <= 6 && (std::abs(shift) <= lead_reach || t == 0);
      if (t > 0 && std::abs(shift) > hold_reach && !lead_search) break;
      if (held && !lead_search) break;
      const double x = g + shift;
      if (x < lo || x > hi) continue;
      if (o.holds && !o.holds(piece.contour, sub_path(piece.path, x - w / 2, x + w / 2))) continue;
      if (!clear(x)) {
        if (!held_only) held_only = x;
        continue;
      }
      if (!held) held = x;
      if (!lead_search) break;
      const double resume = x + w / 2;
      if (auto l = o.lead_in(piece.contour, sub_path(piece.path, resume, std::min(resume + step, pg.length)))) {
        pg.centre.back() = x;
        pg.lead.back() = std::move(l);
        return;
      }
    }
    if (held) pg.centre.back() = *held;
    else if (held_only) pg.centre.back() = *held_only;
    else ++st.unheld;
  };
  constexpr double kAnywhere = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < own.size(); ++c) {
    const auto& pieces = own[c];
    if (pieces.empty()) {
      // A part whose whole outline is shared with its neighbours has no edge on the skeleton.
      if (shares[c] && outer(static_cast<std::int32_t>(c))) {
        ++st.skipped;
        st.enclosed.push_back(static_cast<std::int32_t>(c));
      }
      continue;
    }
    if (pieces.size() == 1 && !shares[c]) {
      // The whole loop in one piece (standard, chain, a part without common lines): gap k centred
      // at (k + 1/2) L / N from where the piece enters the contour, so none sits at the entry
      // (lead-in or bridge) or at the end where the part drops last.
      const CutPiece& piece = path.segments[pieces[0].segment].pieces[pieces[0].piece];
      const double contour_len = geometry::length(nest.contours[model::ContourId(piece.contour)].source.contour);
      if (n * 2 * w > std::min(contour_len, gaps[pieces[0].segment][pieces[0].piece].length)) {
        ++st.skipped;
        continue;
      }
      const double spacing = contour_len / n;
      for (int k = 0; k < n; ++k) place(pieces[0], (k + 0.5) * spacing, spacing, -kAnywhere, kAnywhere);
    } else {
      // Common lines: the part is held only by its own edges, the stretches of the group's outline
      // between junctions; multi-segment cutting: by its pieces, which meet end to end at the split
      // points. The gaps are spread over them, at least max(w, 1 mm) from a junction (where a
      // neighbour's cut or the next piece meets the edge), at (k + 1/2) U / N along the usable length U.
      const double margin = step + w / 2;
      const auto usable_of = [&](PieceRef r) { return std::max(0.0, gaps[r.segment][r.piece].length - 2 * margin); };
      double usable = 0;
      for (const PieceRef r : pieces) usable += usable_of(r);
      if (usable < n * 2 * w) {
        ++st.skipped;
        continue;
      }
      const double spacing = usable / n;
      std::size_t at = 0;
      double before = 0;  // usable length of the pieces before pieces[at]
      for (int k = 0; k < n; ++k) {
        const double u = (k + 0.5) * spacing;
        for (;;) {
          const double here = usable_of(pieces[at]);
          if (u < before + here || at + 1 == pieces.size()) {
            place(pieces[at], margin + (u - before), spacing, margin, gaps[pieces[at].segment][pieces[at].piece].length - margin);
            break;
          }
          before += here;
          ++at;
        }
      }
    }
    ++st.contours;
    st.tabs += n;
  }

  std::vector<CutSegment> out;
  out.reserve(path.segments.size());
  for (std::size_t s = 0; s < path.segments.size(); ++s) {
    CutSegment& whole = path.segments[s];
    if (std::all_of(gaps[s].begin(), gaps[s].end(), [](const PieceGaps& g) { return g.centre.empty(); })) {
      out.push_back(std::move(whole));
      continue;
    }
    // What follows a gap (the rest of the piece, the pieces after it, the lead-out) is a new
    // segment, split in turn at the next piece with gaps.
    std::vector<CutPiece> pieces = std::move(whole.pieces);
    CutSegment cur = std::move(whole);  // the first keeps the segment's pierce, rapid and label
    cur.pieces.clear();
    const KerfSide kerf = cur.kerf;
    const double feed = cur.feed_mm_min;
    const std::string label = cur.label;
    int tab_no = 0;  // gaps so far in this segment: the labels of the pieces after them
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      PieceGaps& pg = gaps[s][i];
      if (pg.centre.empty()) {
        cur.pieces.push_back(std::move(pieces[i]));
        continue;
      }
      const CutPiece& piece = pieces[i];
      // Cut stretches between the gaps: [0, g0 - w/2], [g0 + w/2, g1 - w/2], ..., [g_{n-1} + w/2, piece end].
      std::vector<std::pair<double, double>> keep;
      double at = 0;
      for (const double g : pg.centre) {
        keep.emplace_back(at, g - w / 2);
        at = g + w / 2;
      }
      keep.emplace_back(at, pg.length);
      for (std::size_t j = 0; j < keep.size(); ++j) {
        Contour stretch = sub_path(piece.path, keep[j].first, keep[j].second);
        if (j > 0) {
          out.push_back(std::move(cur));
          cur = CutSegment{};
          cur.kerf = kerf;
          cur.feed_mm_min = feed;
          cur.label = label + " after tab " + std::to_string(++tab_no);
          if (auto& l = pg.lead[j]) {
            l->vertices.back().p = stretch.vertices.front().p;  // the lead ends where the cut resumes, to the bit
            cur.pierce = l->vertices.front().p;
            cur.pieces.push_back({std::move(*l), PieceRole::lead_in, -1, -1});
            ++st.lead_ins;
          } else {
            cur.pierce = stretch.vertices.front().p;
            cur.after_tab = true;
            st.on_path += o.lead_in != nullptr;
            // Under controller compensation the head crosses the gap on the offset path: along the
            // contour's corners, not across them (an arc in the gap is crossed on its chord, which
            // for a tab of a millimetre or two lies within a few hundredths of it).
            if (kerf != KerfSide::none) {
              const Contour gap = sub_path(piece.path, keep[j - 1].second, keep[j].first);
              for (std::size_t v = 1; v + 1 < gap.vertices.size(); ++v) cur.rapid_via.push_back(gap.vertices[v].p);
            }
          }
        }
        cur.pieces.push_back({std::move(stretch), PieceRole::contour, piece.contour, -1});
      }
    }
    out.push_back(std::move(cur));
  }
  path.segments = std::move(out);
  return st;
}

}  // namespace cutroute::nc
