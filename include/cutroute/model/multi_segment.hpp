// Multi-segment cutting (ECP): long contours cut in several pieces, each from its own pierce.
#pragma once

#include <optional>
#include <vector>

#include <cutroute/core/result.hpp>
#include <cutroute/model/cut_job.hpp>

namespace cutroute::model {

struct MultiSegmentOptions {
  // A contour is split only when the split points chosen on it lie at least this far apart [mm].
  // Splitting adds a pierce and a lead pair; it pays back only when the route would otherwise
  // cross the contour's span once more by rapid. 300 mm: at the default profile's effective rapid
  // speed (1 m/s) a 300 mm rapid costs as much as the 0.3 s pierce of 1 mm AMg3M.
  double min_span_mm = 300.0;
  // Pieces per split contour (2..8). More pieces: more places to enter and leave, more pierces.
  int max_pieces = 2;
};

// Where a contour is split: arc lengths of the stored contour, ascending, at least two.
struct SplitPlan {
  ContourId contour;
  std::vector<double> s_mm;   // split points [mm]
  double span_mm = 0.0;       // smallest distance between two split points [mm]
};

// The split points of one contour from its admissible standard entry points (a finite set: the
// planner's corners and points along edges): for two pieces the two points farthest apart, for
// more the farthest-point sequence started from them. nullopt when the contour has fewer than two
// admissible entry points or the points chosen lie closer than min_span_mm.
std::optional<SplitPlan> plan_split(const Nest& nest, ContourId contour, const std::vector<EntryCandidate>& standard,
                                    const MultiSegmentOptions& options);

// The pieces of a split contour, one basic segment each, in the contour's stored order. `planner`:
// built with free_direction (its corner entries are then offered in both directions). Piece i
// covers the stretch [s_i, s_i+1] (the last one wraps to s_0) and is offered from either end: from
// s_i in the stored direction and from s_i+1 against it (the kerf side follows the direction).
// Each candidate enters with the planner's lead-in at its start point (a corner lead where the
// standard candidates have one), cuts its stretch plus the overcut past its end point (into the
// neighbouring stretch: the junction is cut twice over the overcut length, so no sliver stays)
// and leaves with the lead-out there. Segments list no `contours` (none is cut completely); their
// candidates hold one PieceKind::contour_part piece. Empty when some piece has no admissible entry
// at either end.
std::vector<BasicSegment> split_segments(const Nest& nest, const EntryPlanner& planner, const SplitPlan& plan,
                                         const EntryOptions& entries);

// The multi-segment technique's cut job: the standard job in which every cut contour (outer or
// hole, the sheet excluded) whose plan_split() succeeds is replaced by its pieces. Precedence:
// segment_precedence(): everything inside a contour before any piece of it. `standard`: the
// standard job of the same nest and entry options when the caller has it. An error when no
// contour is split ("multi-segment cutting not available: ...").
Result<CutJob> make_multi_job(const Nest& nest, const EntryOptions& entries, const MultiSegmentOptions& options,
                              const CutJob* standard = nullptr);

}  // namespace cutroute::model
