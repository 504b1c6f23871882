#include <cutroute/model/multi_segment.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/tolerances.hpp>

#include "path_ops.hpp"

namespace cutroute::model {

using geometry::Vec2;

namespace {

struct Spot {
  double s = 0;  // arc length along the stored contour [mm]
  Vec2 p;
};

// The distinct admissible entry points of a contour's standard candidates, by arc length.
std::vector<Spot> entry_spots(ContourId contour, const std::vector<EntryCandidate>& candidates) {
  std::vector<Spot> out;
  for (const auto& e : candidates)
    if (e.contour == contour && e.fallback == Fallback::none) out.push_back({e.s_mm, e.point});
  std::sort(out.begin(), out.end(), [](const Spot& a, const Spot& b) { return a.s < b.s; });
  out.erase(std::unique(out.begin(), out.end(),
                        [](const Spot& a, const Spot& b) { return geometry::distance(a.p, b.p) <= tol::kSamePointMm; }),
            out.end());
  return out;
}

// The candidate of `all` entering at arc length s in direction cw (a corner entry keeps its corner
// lead), else the planner's normal entry there; nullopt when neither is admissible.
std::optional<EntryCandidate> entry_for(const EntryPlanner& planner, const std::vector<EntryCandidate>& all, ContourId c,
                                        double s, bool cw) {
  const Vec2 p = planner.point_at(c, s);
  for (const auto& e : all)
    if (e.fallback == Fallback::none && e.clockwise == cw && geometry::distance(e.point, p) <= tol::kSamePointMm) return e;
  return planner.entry_at(c, s, cw);
}

}  // namespace

std::optional<SplitPlan> plan_split(const Nest& nest, ContourId contour, const std::vector<EntryCandidate>& standard,
                                    const MultiSegmentOptions& options) {
  if (nest.contours[contour].role == ContourRole::sheet) return std::nullopt;
  const std::vector<Spot> spots = entry_spots(contour, standard);
  if (spots.size() < 2) return std::nullopt;
  // The two points farthest apart (first pair in arc-length order on ties: deterministic).
  std::size_t a = 0, b = 1;
  for (std::size_t i = 0; i < spots.size(); ++i)
    for (std::size_t j = i + 1; j < spots.size(); ++j)
      if (geometry::distance(spots[i].p, spots[j].p) > geometry::distance(spots[a].p, spots[b].p)) {
        a = i;
        b = j;
      }
  std::vector<std::size_t> chosen{a, b};
  // Farthest-point sequence: each further point as far as possible from those already chosen.
  const auto want = std::min<std::size_t>(static_cast<std::size_t>(std::clamp(options.max_pieces, 2, 8)), spots.size());
  std::vector<double> near(spots.size());
  for (std::size_t i = 0; i < spots.size(); ++i)
    near[i] = std::min(geometry::distance(spots[i].p, spots[a].p), geometry::distance(spots[i].p, spots[b].p));
  while (chosen.size() < want) {
    std::size_t best = spots.size();
    for (std::size_t i = 0; i < spots.size(); ++i)
      if (std::find(chosen.begin(), chosen.end(), i) == chosen.end() && (best == spots.size() || near[i] > near[best])) best = i;
    chosen.push_back(best);
    for (std::size_t i = 0; i < spots.size(); ++i) near[i] = std::min(near[i], geometry::distance(spots[i].p, spots[best].p));
  }
  SplitPlan plan;
  plan.contour = contour;
  plan.span_mm = geometry::distance(spots[a].p, spots[b].p);
  for (std::size_t i = 0; i < chosen.size(); ++i)
    for (std::size_t j = i + 1; j < chosen.size(); ++j)
      plan.span_mm = std::min(plan.span_mm, geometry::distance(spots[chosen[i]].p, spots[chosen[j]].p));
  if (plan.span_mm < options.min_span_mm) return std::nullopt;
  for (auto i : chosen) plan.s_mm.push_back(spots[i].s);
  std::sort(plan.s_mm.begin(), plan.s_mm.end());
  return plan;
}

std::vector<BasicSegment> split_segments(const Nest& nest, const EntryPlanner& planner, const SplitPlan& plan,
                                         const EntryOptions& entries) {
  const ContourId c = plan.contour;
  const double total = planner.contour_length(c);
  const bool stored_cw = geometry::orientation(nest.contours[c].source.contour) == geometry::Orientation::cw;
  Diagnostics ignored;  // the standard job already reported this contour's fallbacks
  const std::vector<EntryCandidate> all = planner.candidates(c, ignored);
  const double overcut = std::max(0.0, entries.lead.overcut_mm);
  std::vector<BasicSegment> out;
  const std::size_t n = plan.s_mm.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double a = plan.s_mm[i], b = plan.s_mm[(i + 1) % n];
    const double len = i + 1 < n ? b - a : total - a + b;
    BasicSegment seg;
    // From a along the stored direction, or from b against it.
    for (const auto& [from, to, cw] : {std::tuple{a, b, stored_cw}, std::tuple{b, a, !stored_cw}}) {
      auto e = entry_for(planner, all, c, from, cw);
      if (!e) continue;
      e->pieces = {SegmentPiece{PieceKind::contour_part, c, detail::sub_path(planner.whole_loop(c, from, cw, true), 0, len + overcut), {}}};
      e->lead_out = planner.lead_out_at(c, to, cw);
      seg.candidates.push_back(std::move(*e));
    }
    if (seg.candidates.empty()) return {};
    out.push_back(std::move(seg));
  }
  return out;
}

Result<CutJob> make_multi_job(const Nest& nest, const EntryOptions& entries, const MultiSegmentOptions& options,
                              const CutJob* standard) {
  CutJob own;
  if (!standard) own = make_cut_job(nest, entries);
  const CutJob& base = standard ? *standard : own;
  EntryOptions both = entries;
  both.free_direction = true;
  const EntryPlanner planner(nest, both);
  CutJob job;
  job.diagnostics = base.diagnostics;
  std::size_t split = 0;
  for (const auto& seg : base.segments) {
    if (seg.contours.size() == 1) {
      if (auto plan = plan_split(nest, seg.contours.front(), seg.candidates, options)) {
        auto pieces = split_segments(nest, planner, *plan, entries);
        if (!pieces.empty()) {
          for (auto& p : pieces) job.segments.push_back(std::move(p));
          ++split;
          continue;
        }
      }
    }
    job.segments.push_back(seg);
  }
  if (split == 0)
    return make_error("multi-segment cutting not available: no contour has two admissible entry points " +
                      format_fixed(options.min_span_mm, 0) + " mm apart or more (--multi-min-span)");
  auto prec = segment_precedence(nest, job.segments);
  if (!prec) return make_error("multi-segment cutting: the pieces leave no admissible cutting order");
  job.precedence = std::move(*prec);
  return job;
}

}  // namespace cutroute::model
