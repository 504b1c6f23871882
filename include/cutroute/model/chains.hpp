// Chain cutting: runs of neighbouring outer contours joined by bridges, cut with one pierce.
#pragma once

#include <vector>

#include <cutroute/model/cut_job.hpp>

namespace cutroute::model {

struct ChainOptions {
  // Outer contours of different parts whose boundaries come closer than this may be chained [mm].
  // 20 mm: a bridge that long costs about as much cutting time as the pierce and lead pair it
  // saves on thin sheet (1 mm aluminium: 0.3 s pierce at ~75 mm/s); longer bridges rarely pay.
  double max_gap_mm = 20.0;
  int max_contours = 3;      // longest run of contours in one chain
  int max_candidates = 12;   // per chain (bridge positions x orders)
};

// One candidate chain: outer contours in a run, each within max_gap of the next.
struct ChainLink {
  ContourId a, b;
  double gap_mm = 0.0;       // smallest distance between the two boundaries [mm] (sampled)
};

// Pairs of outer contours (of different parts) whose boundaries come closer than max_gap, with
// their gap, sorted by gap (then by contour ids). `threads`: how many may share the work (the
// result is the same).
std::vector<ChainLink> chain_links(const Nest& nest, const ChainOptions& options, int threads = 1);

// The chain technique's cut job: the standard job in which runs of neighbouring outer contours
// become one basic segment each. Runs are formed greedily from the closest pairs (each contour in
// at most one run, at most max_contours per run, no run closing on itself). A chain is cut with
// one pierce: lead-in into the first contour at p, that contour completely (back to p), a
// straight bridge from p to the closest point q of the next contour, that contour completely
// from q, ..., lead-out from the last. A bridge must stay in scrap, touch its two contours only
// at its ends, keep the clearance from every other contour and be no longer than max_gap.
// Candidates: entries of the first contour near the second (the planner's corners and points
// where the contours are closest), in both orders of the run. A run that gets no admissible
// candidate is shortened (then dropped); a chain that would make the precedence cyclic is
// dropped. Standard segments for all contours left. `standard`: the standard job of the same nest
// and entry options when the caller has it already (saves building it again); `planner`: a
// planner of this nest with these entry options, likewise. `threads`: how many may share the work
// (the job is the same).
CutJob make_chain_job(const Nest& nest, const EntryOptions& entries, const ChainOptions& options,
                      const CutJob* standard = nullptr, const EntryPlanner* planner = nullptr, int threads = 1);

}  // namespace cutroute::model
