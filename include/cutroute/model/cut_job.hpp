// CutJob: the cutting problem of one nest before optimisation: entry candidates with leads, precedence.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <cutroute/core/diagnostic.hpp>
#include <cutroute/geometry/contour.hpp>
#include <cutroute/model/nest.hpp>

namespace cutroute::model {

enum class LeadKind { none, line, arc, line_arc };
const char* to_string(LeadKind k);

// Lead-in / lead-out geometry. Lengths are per thickness in the machine profile; these are
// the values used for one job.
struct LeadSpec {
  LeadKind in_kind = LeadKind::line_arc;
  double in_length_mm = 3.0;       // straight part of the lead-in [mm]
  double in_arc_radius_mm = 1.5;   // radius of the tangent arc (arc, line_arc) [mm]
  LeadKind out_kind = LeadKind::line;
  double out_length_mm = 1.0;      // lead-out length (line) or radius (arc) [mm]
  double overcut_mm = 0.0;         // cut past the entry point along the contour before leaving [mm]
};

struct EntryOptions {
  LeadSpec lead;
  double entry_step_mm = 0.0;      // spacing of candidates along edges; 0 = adaptive (length / max)
  int max_candidates = 12;         // per contour (corners first, then points along edges)
  double kerf_mm = 0.2;            // [mm]
  double clearance_mm = -1.0;      // pierce / lead-in distance to other contours; < 0: kerf + 1 mm
  bool outer_clockwise = true;     // kerf-side convention (dialect): outer contours clockwise
  bool hole_clockwise = false;     // holes counter-clockwise
  bool free_direction = false;     // offer both directions (when the kerf side allows it)
  double corner_angle_deg = 15.0;  // a vertex whose tangent turns more than this is a corner
  double small_hole_mm = 0.0;      // holes narrower than this are pierced at their centre; 0 = auto (3 × lead)
  // Controller compensation (half the kerf): the controller refuses an entry move no longer than
  // this and a compensated arc no wider, so a lead shortened for want of room never goes that
  // short (the next fallback is taken instead). 0: no limit.
  double min_lead_mm = 0.0;
  // --kerf-mode cam: the drawn nest, when entries are planned on its kerf offset. Pierces, leads
  // and bridges keep clearance − kerf/2 from its contours too: where a toolpath cannot follow the
  // drawing (an acute inside corner, a slot narrower than the kerf) the drawn edge lies beyond
  // the toolpath's, and a lead planned against toolpaths alone can come within a kerf of it
  // (two holes of d2g_DRAAK touch at a point). Must outlive the planners built with it.
  const Nest* drawn = nullptr;
};

// How a candidate's lead-in had to be compromised to be admissible.
enum class Fallback { none, short_lead, on_contour, centre_pierce };
const char* to_string(Fallback f);

// What one piece of a basic segment cuts. A basic segment (source paper §2) is the geometry one
// cutting segment cuts between its lead-in and its lead-out: one whole contour (standard), several
// whole contours joined by bridges (chain cutting), open stretches of contours such as an edge
// shared by two parts (common-line cutting), or one piece of a contour cut in several (ECP).
enum class PieceKind {
  contour,      // a stretch of nest contour `contour` (the whole loop plus overcut when whole)
  bridge,       // a straight cut through scrap from the end of one piece to the start of the next
  common_edge,  // a stretch of contour `contour` that is also the boundary of a neighbouring part
  // One stretch of contour `contour` cut in several basic segments (multi-segment cutting, ECP:
  // model/multi_segment.hpp); the other segments cut the rest. Compensated like `contour`.
  contour_part,
};
const char* to_string(PieceKind k);

struct SegmentPiece {
  PieceKind kind = PieceKind::contour;
  ContourId contour;          // the nest contour cut by this piece; invalid for bridges
  geometry::Contour path;     // open, in the direction of travel [mm]
  ContourId other;            // common_edge: the neighbouring contour that shares the stretch
};

// One way to cut one basic segment: where to pierce and enter, in which direction, with which
// leads, and the ordered pieces cut between lead-in and lead-out. The pieces are continuous: the
// lead-in ends where pieces.front() starts, each piece starts where the previous one ends, the
// lead-out starts where pieces.back() ends.
struct EntryCandidate {
  ContourId contour;                 // the contour entered (that of the first non-bridge piece)
  double s_mm = 0.0;                 // arc length of the entry point along the stored contour [mm]
  geometry::Vec2 point;              // entry point on the contour [mm]
  bool clockwise = true;             // cut direction of the entered contour
  geometry::Vec2 pierce;             // pierce point [mm]
  geometry::Contour lead_in;         // open, pierce -> point (may be empty: pierce on contour)
  geometry::Contour lead_out;        // open, from the end of the last piece into scrap
  // Standard (one whole contour): one contour piece, from point, in the cut direction, including
  // the overcut. Never empty.
  std::vector<SegmentPiece> pieces;
  Fallback fallback = Fallback::none;
  bool corner = false;               // entry at a corner
};

// The cut path of a one-piece candidate (its first piece's path): what standard entries cut.
const geometry::Contour& entry_path(const EntryCandidate& e);
// Length of everything the candidate cuts between lead-in and lead-out [mm].
double pieces_length(const EntryCandidate& e);
// A candidate of more than one piece (a chain or a common-line segment), or of one piece that is
// not a whole contour (a single common line): refinement leaves it alone.
inline bool is_multi_piece(const EntryCandidate& e) {
  return e.pieces.size() > 1 || (!e.pieces.empty() && e.pieces.front().kind != PieceKind::contour);
}

// Where cutting this entry ends and the head lifts: end of the lead-out, else of the last piece,
// else the pierce point [mm].
geometry::Vec2 tool_off_point(const EntryCandidate& e);

// One cluster of the routing problem: a basic segment and the alternative ways to cut it.
struct BasicSegment {
  // The nest contours this segment cuts completely (one for a standard segment, the chained
  // contours of a chain in cutting order of its first candidate; may be empty for a segment made
  // only of common edges). Contours cut only in part appear in the candidates' pieces.
  std::vector<ContourId> contours;
  std::vector<EntryCandidate> candidates;  // never empty
};

struct CutJob {
  std::vector<BasicSegment> segments;                    // standard job: one per cut contour (sheet excluded)
  std::vector<std::pair<std::int32_t, std::int32_t>> precedence;  // (a, b): segments[a] before segments[b]
  Diagnostics diagnostics;                               // fallbacks, contours without admissible entry
};

// Every nest contour a segment cuts, completely or in part (its `contours` and the contours of
// its first candidate's non-bridge pieces), sorted, without repeats.
std::vector<ContourId> touched_contours(const BasicSegment& segment);

// Precedence between basic segments from the containment tree, added to `pairs`: a before b when
// a contour touched by a lies directly inside (parent) a contour touched by b, unless b touches
// the inner contour too (a line that a part inside a hole shares with the hole's edge). So all
// that lies inside a contour comes before every segment that cuts a piece of it, whichever of
// them ends up finishing it. The segments of parts drawn edge to edge with a contour
// (Nest::shared_edges, outer contours in the same container) count as touching it: their cuts cut
// pieces of its boundary too. Returns the pairs, sorted and without repeats, or nullopt when they
// form a cycle (no admissible order exists).
std::optional<std::vector<std::pair<std::int32_t, std::int32_t>>> segment_precedence(
    const Nest& nest, const std::vector<BasicSegment>& segments, std::vector<std::pair<std::int32_t, std::int32_t>> pairs = {});
// The same with finishes[k], the contours segment k may be the last to cut, in place of each
// segment's touched_contours() and the edge neighbours: a caller whose own pairs already put one
// segment after every other around a contour (common lines: a group's outline) names only that one.
std::optional<std::vector<std::pair<std::int32_t, std::int32_t>>> segment_precedence(
    const Nest& nest, const std::vector<std::vector<ContourId>>& finishes,
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs);

// Generates entry candidates and leads for every cut contour of the nest and the precedence
// pairs: every contour before the contour that directly contains it (holes before their outer
// contour, parts inside a hole before that hole, at any depth: transitively, everything inside a
// contour before it), and before the parts drawn edge to edge with that contour (their cuts cut
// pieces of its boundary and can free it first). A candidate is admissible when its pierce point lies in scrap (not inside
// any part's material), and its pierce point and lead-in keep `clearance` from every other
// contour and do not cross their own contour. When no candidate is admissible, fall back to a
// shorter lead, a centre pierce for small holes, or a pierce on the contour, and say so.
// One basic segment per contour (the standard technique).
CutJob make_cut_job(const Nest& nest, const EntryOptions& options);

// Builds and checks entries of one nest; holds the spatial index over its contours so that the
// continuous refinement after sequencing can ask for entries at any arc length.
class EntryPlanner {
 public:
  EntryPlanner(const Nest& nest, const EntryOptions& options);
  // A planner of the same nest with other options (leads, clearance): the per-contour geometry,
  // the costly part on large nests, is shared, not rebuilt.
  EntryPlanner(const EntryPlanner& same_nest, const EntryOptions& options);
  ~EntryPlanner();
  EntryPlanner(const EntryPlanner&) = delete;
  EntryPlanner& operator=(const EntryPlanner&) = delete;

  // The admissible candidates of one cut contour (with fallbacks; never empty).
  std::vector<EntryCandidate> candidates(ContourId contour, Diagnostics& diagnostics) const;
  // The entry at arc length s (of the stored contour) with the normal leads, when admissible.
  std::optional<EntryCandidate> entry_at(ContourId contour, double s_mm, bool clockwise) const;
  // Only where that entry would pierce and end (no admissibility check, no cut path): cheap, for
  // searches that check the winner with entry_at() afterwards.
  struct Sketch {
    geometry::Vec2 pierce;     // [mm]
    geometry::Vec2 tool_off;   // end of the lead-out, else the entry point [mm]
    double lead_mm = 0.0;      // lead-in + lead-out length [mm]
  };
  Sketch sketch_at(ContourId contour, double s_mm, bool clockwise) const;
  double clearance_mm() const;
  // For chains and other multi-piece segments: the whole loop of a contour cut from arc length s
  // (of the stored contour) in a direction, plus the overcut when `overcut`.
  geometry::Contour whole_loop(ContourId contour, double s_mm, bool clockwise, bool overcut) const;
  // The lead-out after a whole loop entered at s (normal shape, else straight along the normal,
  // else along the corner bisector; empty when none is admissible).
  geometry::Contour lead_out_at(ContourId contour, double s_mm, bool clockwise) const;
  // Is the open path, which starts on contour `from` and ends on contour `to`, a cut through
  // scrap: it touches `from` and `to` only at its ends, keeps the clearance from every other
  // contour and its middle lies in scrap?
  bool bridge_clear(const geometry::Contour& path, ContourId from, ContourId to) const;
  // Does the open path come within `distance` of a contour outside `own` (not `own`, its holes or
  // what lies in them, nor the sheet's border)? Micro-joints: a tab on `own` whose neighbour's cut
  // runs that close holds nothing.
  bool near_other(ContourId own, const geometry::Contour& path, double distance) const;
  // The stored contour's closest point to p: its arc length [mm] and distance [mm].
  std::pair<double, double> closest(ContourId contour, geometry::Vec2 p) const;
  geometry::Vec2 point_at(ContourId contour, double s_mm) const;  // on the stored contour
  // s moved onto the vertex within kerf/2 of it, if any (stored contour): a cut that starts a hair
  // from a vertex begins with a move too short for a controller's compensation to turn in.
  double at_vertex_if_near(ContourId contour, double s_mm) const;
  double contour_length(ContourId contour) const;  // of the stored contour [mm]

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// make_cut_job() with a planner already built for this nest (reused by the caller afterwards),
// the contours' candidates found on `threads` threads (the same job whatever their number).
CutJob make_cut_job(const Nest& nest, const EntryPlanner& planner, int threads = 1);

}  // namespace cutroute::model
