// Micro-joints (tabs): a post-pass that leaves N uncut gaps of width w on every outer contour of a toolpath.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <cutroute/model/nest.hpp>
#include <cutroute/nc/toolpath.hpp>

namespace cutroute::nc {

// A lead-in for a cut resumed after a gap: the open path from a pierce in scrap to the start of
// `resumed` (the stretch of nest contour `contour` cut next, in its direction of travel), or
// nullopt where none is admissible. The pipeline makes it with the job's own leads.
using ResumeLeadIn = std::function<std::optional<geometry::Contour>(std::int32_t contour, const geometry::Contour& resumed)>;

// Does a gap over this stretch of contour `contour` (open, in the direction of travel) hold the part
// to the skeleton? False where a neighbour's cut runs so close that nothing is left beyond the tab.
using TabHolds = std::function<bool(std::int32_t contour, const geometry::Contour& gap)>;

struct MicroJointOptions {
  int tabs = 0;              // tabs per outer contour; 0: off
  double width_mm = 1.0;     // length of each uncut gap, measured along the programmed path [mm]
  // Empty: each cut after a gap is pierced on the path. Else it starts with this lead-in where
  // one is admissible (and on the path where none is).
  ResumeLeadIn lead_in;
  TabHolds holds;            // empty: a gap holds anywhere
  // A gap's ends keep at least this from a corner of the path (a turn above 15 degrees) where
  // a place within reach allows: a cut resumed just before a corner begins with a move too short
  // for a controller's compensation (LinuxCNC refuses it) [mm]; 0: anywhere.
  double corner_clearance_mm = 0.0;
};

struct MicroJointStats {
  int contours = 0;          // outer contours that got tabs
  int tabs = 0;              // gaps left in total
  int skipped = 0;           // outer contours too short for their tabs (left whole), enclosed ones included
  // Common lines: outer contours whose whole outline is shared with neighbours (no edge on the
  // skeleton for a tab: nothing holds the part once its lines are cut), in nest order.
  std::vector<std::int32_t> enclosed;
  int lead_ins = 0;          // cuts after a gap entered by a lead-in
  int on_path = 0;           // cuts after a gap pierced on the path although a lead-in was asked for
  int unheld = 0;            // gaps left where `holds` says no (no place that holds within reach)
};

// Every contour piece of an outer contour (of length L, the overcut past it excluded) gets its
// tabs centred at (k + 1/2) L / N from the point where that piece enters it, k = 0..N-1 (a gap
// where `holds` says no moves by steps of max(w, 1 mm), further on first, up to L / 2N - w either
// way, to the nearest place that holds; with `lead_in`, a gap whose resumed cut gets none moves
// likewise up to L / 4N - w, to the nearest place that holds and whose resumed cut gets one), so none
// sits at the entry where the lead-in (or a chain's bridge) joins or at the end where the part
// drops last. Each piece is a whole loop: a segment of the standard technique cuts one, a chain
// several joined by bridges (each loop gets its gaps). A part cut in several pieces (its stretches
// of a common-line group's outline, `CutPiece::shared_with` < 0, or the pieces of multi-segment
// cutting) is held by those: its N gaps are spread over them at (k + 1/2) U / N along their usable
// length U, at least max(w, 1 mm) from each piece's ends (junctions with a neighbour's cut or with
// its other pieces, the loop's entry), never on a common line;
// a part whose usable length is under 2·N·w is left whole and counted. The segment is split there:
// the beam goes off before each gap, the head moves over the gap, and the next piece is a new
// segment with the same feed and kerf side: pierced on the contour (no lead-in) and marked
// `after_tab` (with controller compensation its rapid follows the gap's corners), or, with
// `lead_in`, entered from scrap like any cut (a pierce off the part: no pierce mark on its edge,
// and a compensation entry move where the controller cannot hold the offset over the gap). The
// first lead-in stays on the first piece, the lead-out (and the overcut) on the last. A contour
// whose gaps would not leave at least one gap width of cut between them (N · 2w > L) is left
// whole and counted.
MicroJointStats add_micro_joints(Toolpath& path, const model::Nest& nest, const MicroJointOptions& options);

}  // namespace cutroute::nc
