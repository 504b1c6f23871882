// make_common_job(): common-line cutting as a cut job of basic segments (loops, trails, untouched contours).
#include <cutroute/model/common_lines.hpp>

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
  job.precedence = std::move(plan.precedence);
  return job;
}

}  // namespace cutroute::model
