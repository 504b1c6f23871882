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
};

// How a candidate's lead-in had to be compromised to be admissible.
enum class Fallback { none, short_lead, on_contour, centre_pierce };
const char* to_string(Fallback f);

// One way to enter one contour: where, in which direction, with which leads.
struct EntryCandidate {
  ContourId contour;
  double s_mm = 0.0;                 // arc length of the entry point along the stored contour [mm]
  geometry::Vec2 point;              // entry point on the contour [mm]
  bool clockwise = true;             // cut direction
  geometry::Vec2 pierce;             // pierce point [mm]
  geometry::Contour lead_in;         // open, pierce -> point (may be empty: pierce on contour)
  geometry::Contour lead_out;        // open, from the contour's end point (after overcut) into scrap
  geometry::Contour path;            // the contour itself: open, from point, in the cut direction,
                                     // including the overcut
  Fallback fallback = Fallback::none;
  bool corner = false;               // entry at a corner
};

// Where cutting this entry ends and the head lifts: end of the lead-out, else of the cut path,
// else the pierce point [mm].
geometry::Vec2 tool_off_point(const EntryCandidate& e);

struct ContourEntries {
  ContourId contour;
  std::vector<EntryCandidate> candidates;  // never empty for a cut contour
};

struct CutJob {
  std::vector<ContourEntries> contours;                  // one per cut contour (sheet excluded)
  std::vector<std::pair<std::int32_t, std::int32_t>> precedence;  // (a, b): contours[a] before contours[b]
  Diagnostics diagnostics;                               // fallbacks, contours without admissible entry
};

// Generates entry candidates and leads for every cut contour of the nest and the precedence
// pairs: every contour before the contour that directly contains it (holes before their outer
// contour, parts inside a hole before that hole, at any depth: transitively, everything inside a
// contour before it). A candidate is admissible when its pierce point lies in scrap (not inside
// any part's material), and its pierce point and lead-in keep `clearance` from every other
// contour and do not cross their own contour. When no candidate is admissible, fall back to a
// shorter lead, a centre pierce for small holes, or a pierce on the contour, and say so.
CutJob make_cut_job(const Nest& nest, const EntryOptions& options);

// Builds and checks entries of one nest; holds the spatial index over its contours so that the
// continuous refinement after sequencing can ask for entries at any arc length.
class EntryPlanner {
 public:
  EntryPlanner(const Nest& nest, const EntryOptions& options);
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
  double contour_length(ContourId contour) const;  // of the stored contour [mm]

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cutroute::model
