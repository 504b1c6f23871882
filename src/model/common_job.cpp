// make_common_job(): common-line cutting as a cut job of basic segments (loops, trails, untouched contours).
#include <cutroute/model/common_lines.hpp>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::model {

Result<CutJob> make_common_job(const Nest& nest, const EntryOptions& entries, const CommonLineOptions& options,
                               const CutJob* standard) {
  CommonLineOptions o = options;
  o.kerf_mm = entries.kerf_mm;
  CommonLinePlan plan = plan_common_lines(nest, o);
  if (plan.stretches.empty()) return make_error("common-line cutting not available: no two parts share an edge");
  CutJob job;
  job.diagnostics = std::move(plan.diagnostics);
  auto candidates = plan_common_entries(nest, plan, entries, job.diagnostics, standard);
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    BasicSegment b;
    // Only an untouched contour is cut completely by one segment; loops and trails cut parts of
    // contours (their candidates' pieces say which).
    if (plan.segments[i].kind == CommonSegmentKind::contour) b.contours = plan.segments[i].contours;
    b.candidates = std::move(candidates[i]);
    job.segments.push_back(std::move(b));
  }
  // What lies inside a part (its holes, parts in them) must be cut before the last segment that
  // cuts a piece of the part's boundary. A group's outline (a counter-clockwise loop) comes after
  // every line and scrap loop of the group when the plan says so for each segment around a part:
  // then the outline is the part's last cut, and all that lies inside waits for it alone. A part
  // inside the group (a grid's middle row) touches no outline and is cut free by whichever of its
  // lines comes last: everything inside it comes before all of them (a 6 x 6 grid with a hole in
  // each part cut 1-4 holes of freed parts before).
  std::vector<std::vector<ContourId>> finishes(plan.segments.size());
  for (std::size_t k = 0; k < plan.segments.size(); ++k) finishes[k] = plan.segments[k].contours;
  std::vector<std::pair<std::int32_t, std::int32_t>> sorted_pairs = plan.precedence;
  std::sort(sorted_pairs.begin(), sorted_pairs.end());
  std::vector<std::vector<std::int32_t>> around(nest.contours.size());
  for (std::size_t k = 0; k < plan.segments.size(); ++k)
    for (const ContourId c : plan.segments[k].contours) around[c.index()].push_back(static_cast<std::int32_t>(k));
  for (std::size_t k = 0; k < plan.segments.size(); ++k) {
    const CommonSegment& outline = plan.segments[k];
    if (outline.kind != CommonSegmentKind::loop || geometry::signed_area(outline.path) <= 0) continue;
    const auto last_cut = static_cast<std::int32_t>(k);
    for (const ContourId c : outline.contours) {
      const auto& segs = around[c.index()];
      const bool last = std::all_of(segs.begin(), segs.end(), [&](std::int32_t j) {
        return j == last_cut || std::binary_search(sorted_pairs.begin(), sorted_pairs.end(), std::pair{j, last_cut});
      });
      if (!last) continue;
      for (const std::int32_t j : segs)
        if (j != last_cut) std::erase(finishes[static_cast<std::size_t>(j)], c);
    }
  }
  auto precedence = segment_precedence(nest, finishes, std::move(plan.precedence));
  if (!precedence) return make_error("common-line cutting not available: no order cuts every hole and inner part before the lines around it");
  job.precedence = std::move(precedence).value();
  return job;
}

}  // namespace cutroute::model
