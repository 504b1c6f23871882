// Common-line cutting: edges shared by adjacent parts, the cut graph with each shared stretch once, and its basic segments.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <cutroute/core/diagnostic.hpp>
#include <cutroute/core/result.hpp>
#include <cutroute/core/tolerances.hpp>
#include <cutroute/geometry/contour.hpp>
#include <cutroute/model/cut_job.hpp>
#include <cutroute/model/nest.hpp>

namespace cutroute::model {

struct CommonLineOptions {
  // Parts drawn this far apart share one cut on the centre line between them (the cut's width
  // removes exactly the gap); parts drawn touching (gap 0) share one cut on the common edge [mm].
  // make_common_job() sets it from the job's kerf.
  double kerf_mm = 0.2;
  // Two edges run together when their distance equals 0 or kerf_mm within this at both ends of
  // the stretch (parallel lines, or arcs on concentric circles) [mm].
  double tol_mm = tol::kCommonLineMm;
  // Shorter shared stretches are ignored (the two edges are cut as usual): saving less than this
  // does not pay for the extra pierce of a trail [mm].
  double min_length_mm = 1.0;
};

// One stretch where the boundaries of two contours run together, cut once.
struct CommonStretch {
  geometry::Segment centre;   // the cut: on the centre line between the two edges, from a to b [mm]
  ContourId first, second;    // the two contours (first < second)
  double gap_mm = 0.0;        // drawn distance between the two edges: ~0 or ~kerf [mm]
  // Arc lengths along each stored contour where the stretch begins (beside centre.a) and ends
  // (beside centre.b). first_s0 < first_s1; the second contour usually runs the other way
  // (second_s0 > second_s1). Each interval lies within one segment of its contour [mm].
  double first_s0 = 0.0, first_s1 = 0.0, second_s0 = 0.0, second_s1 = 0.0;
  double length() const { return centre.length(); }
};

// Finds the shared stretches of a nest: pairs of segments of different contours (the sheet
// excluded) that are parallel lines or arcs on one circle (concentric with radii kerf apart),
// at distance 0 or kerf_mm (within tol_mm, at both ends of their overlap), with the two parts'
// material on opposite sides and an overlap of at least min_length_mm. Only the overlapping part
// of two edges is common (partial overlap). A stretch overlapping one already found on either
// contour is dropped (a valid nest has none). Order: by first contour, its segment, then second.
// Cost: one box query per contour and per segment pair whose boxes come within kerf + tol.
std::vector<CommonStretch> find_common_stretches(const Nest& nest, const CommonLineOptions& options);

enum class CommonSegmentKind {
  contour,  // a nest contour that shares nothing: cut whole as before
  loop,     // a closed boundary of a group of parts joined by common lines (outer, or a scrap
            // island enclosed by the group)
  trail,    // an open run of common stretches, joined straight through at junctions
};
const char* to_string(CommonSegmentKind k);

// One piece of a segment's path and what it cuts.
struct CommonPiece {
  ContourId contour;        // boundary piece: its contour; common stretch: the stretch's first
                            // contour; invalid for a connector across a kerf gap
  int stretch = -1;         // common stretch: index into CommonLinePlan::stretches; else -1
  geometry::Contour path;   // open, in the segment's direction [mm]
  ContourId other;          // common stretch: its second contour; else invalid
  bool connector() const { return !contour.valid(); }
};

// One basic segment of the common-line decomposition (PAPERS.md §2): geometry without leads.
struct CommonSegment {
  CommonSegmentKind kind = CommonSegmentKind::contour;
  // contour: the nest contour as stored. loop: closed, the group's material on its left (an outer
  // boundary runs counter-clockwise, a boundary around enclosed scrap clockwise). trail: open.
  // Where two parts are drawn kerf apart the path crosses the gap by a short connector.
  geometry::Contour path;
  std::vector<CommonPiece> pieces;   // `path` piece by piece (kind contour: one piece)
  std::vector<ContourId> contours;  // nest contours whose boundary it cuts (all or in part), ascending
  int group = -1;                   // the group of parts joined by common lines; -1 for kind contour
  double shared_mm = 0.0;           // trail: length of the common stretches it cuts once for two parts [mm]
  // Trail only: may the cut start at this end? An end on a loop of the group is entered from the
  // scrap outside; a trail with no end on a loop is entered at a junction on a trail cut before
  // it (pierce on the cut line: `pierce_on_line`).
  bool enter_at_start = false, enter_at_end = false;
  bool start_on_loop = false, end_on_loop = false;  // trail only: the end lies on a loop of its group
  bool pierce_on_line = false;
};

struct CommonLinePlan {
  std::vector<CommonStretch> stretches;
  // Every cut contour of the nest is cut by exactly one contour segment or, in part, by loops and
  // trails of its group; every boundary stretch by exactly one segment.
  std::vector<CommonSegment> segments;
  // (a, b): segments[a] before segments[b]. Every segment before the smallest loop or contour
  // enclosing it (holes and inner parts first; the trails of a group before its outer loop,
  // since after that loop the parts are free and may move); a trail entered at a junction after
  // the trail through that junction.
  std::vector<std::pair<std::int32_t, std::int32_t>> precedence;
  double shared_length_mm = 0.0;    // sum of the stretch lengths: cut length saved [mm]
  int groups = 0;                   // groups of parts joined by common lines
  Diagnostics diagnostics;
};

// The common-line decomposition of a nest. Steps (common_graph.cpp):
//  1. find_common_stretches(); group the contours they join (union-find).
//  2. cut graph: nodes are the stretch ends, merged when closer than kerf + tol (a junction of
//     parts drawn kerf apart: where their centre lines cross); edges are the stretches (once each)
//     and the pieces of contour boundary between them ("own" edges, one part on one side only).
//  3. trails: at each node, pair the common edges that continue each other most straightly
//     (straight through at a 4-way junction), and follow the pairs.
//  4. loops: the own edges, oriented with their material on the left, traced face by face (at a
//     node the tightest left turn): the outer boundary of each group and any scrap it encloses;
//     not a short one the trails' kerf already cuts (a T's mouth on parts drawn kerf apart).
//  5. entry ends of trails and precedence (see CommonLinePlan::precedence).
// Contours of a nest without stretches come out as one contour segment each, in nest order.
CommonLinePlan plan_common_lines(const Nest& nest, const CommonLineOptions& options);

// The cut job of common-line cutting (one basic segment per loop, trail and untouched contour,
// the plan's precedence, candidates from plan_common_entries()). The common lines are found with
// the job's kerf (entries.kerf_mm). Error ("not available") when no two parts share a stretch.
// `standard`: the standard job of the same nest and entry options, when the caller has it: its
// candidates are reused for untouched contours far from every common line (see plan_common_entries).
Result<CutJob> make_common_job(const Nest& nest, const EntryOptions& entries, const CommonLineOptions& options,
                               const CutJob* standard = nullptr);

// The pieces a cut of the segment passes, starting at arc length s_mm of its path, along the path
// (forward) or against it, for length_mm (on a closed segment it may wrap past s: the overcut).
// Each piece is cut exactly where it lies on the way; empty pieces are left out.
std::vector<CommonPiece> pieces_along(const CommonSegment& segment, double s_mm, bool forward, double length_mm);

// The nest contour a cut over these pieces enters first (its first piece that is not a
// connector; a common stretch counts as its first contour), the arc length of the entry point on
// it, and whether the cut runs along it clockwise. What kerf side and labels are taken from.
struct EnteredContour {
  ContourId contour;
  double s_mm = 0.0;        // [mm] along the stored contour
  bool clockwise = true;
};
EnteredContour entered_contour(const Nest& nest, const std::vector<CommonPiece>& pieces);

// Entry candidates for every segment of a plan, aligned with plan.segments (never empty).
// Contours and loops: model::EntryPlanner on a derived nest whose contours are the closed
// segments (so the scrap, clearance and fallback rules are the same as for plain contours).
// Trails: at each end that may be entered, a straight lead-in continuing the trail backwards
// (else turned by ±45°, else shortened) whose pierce lies in scrap at `clearance` from every
// contour and which keeps half a kerf from the contours it cuts (but where it meets the trail)
// and `clearance` from the others; a lead-out continuing the trail past an
// end on a loop. The candidates' pieces: contour pieces (own boundary), common_edge pieces (a
// shared stretch, named after its first contour) and bridges (connectors across a kerf gap);
// contour, s_mm and clockwise: those of the nest contour the cut enters (entered_contour()).
// With `standard` (the standard job of this nest and options), an untouched contour whose box,
// widened by its leads and the clearance, meets no loop or trail keeps its standard candidates:
// every check behind them (scrap, clearance, crossing) looks only inside that box, where the
// derived nest is the nest itself.
std::vector<std::vector<EntryCandidate>> plan_common_entries(const Nest& nest, const CommonLinePlan& plan,
                                                             const EntryOptions& options, Diagnostics& diagnostics,
                                                             const CutJob* standard = nullptr);

}  // namespace cutroute::model
