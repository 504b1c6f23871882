// compensation_hazards(): the cutting segments of a toolpath whose path a controller's cutter compensation cannot follow.
#pragma once

#include <vector>

#include <cutroute/nc/post_dialect.hpp>
#include <cutroute/nc/toolpath.hpp>

namespace cutroute::nc {

struct CompensationHazards {
  int compensated = 0;          // compensated blocks (G41/G42 .. G40) in all
  std::vector<std::size_t> at;  // the blocks at risk: the index of each one's first segment in the toolpath
};

// Under G41/G42 the controller offsets each move by the tool radius r to the kerf side and joins
// the offset moves at their intersections. It cannot where the drawing has details finer than
// the kerf, and LinuxCNC then refuses the block. A block is at risk when, on its path as written
// (end points rounded to the program's grid, moves that round to nothing dropped, arcs below the
// writer's 0.02 mm radius taken as chords):
//   - its first move (the entry move) is no longer than r, or an arc of radius at most r;
//   - an arc curving toward the tool side (the inside of the arc) has a radius of at most r;
//   - a later move is shorter than the offset intersections at its ends need: at each inside
//     corner (turning toward the tool side by theta) between lines r tan(theta / 2) on both
//     moves; where an arc meets the corner, the offsets (a line and a circle of radius R -/+ r,
//     or two circles) must cross, and on both moves (a straight lead from the centre of a hole
//     little wider than the tool misses the offset circle). A line loses its length at both ends
//     together: the controller refuses it once the corner at its end lies behind the one at its
//     start (a grid-step line between two arc corners). Before an arc the controller places the
//     line by the arc's radius at its end, as if the arc began on that circle;
//   - an arc would sweep more than written (below) where the controller checks its end: at a
//     concave corner, at a convex one before a line and at the G40 (an arc taken on at a nearly
//     straight joint from the offset end of the move before sweeps more than its own offset).
// Measured against LinuxCNC's interpreter on the 27 corpus programs (scripts/check-compensation,
// the blocks compared by name): at kerf 0.15 mm the same blocks on every program but d2g_DRAAK,
// where it flags 680 and LinuxCNC refuses 575, 574 of them flagged (the other: a hairpin between
// two spline arcs of 16-19 m radius) and 106 accepted (spline arcs whose offsets LinuxCNC still
// joins); with a plasma kerf of 1.5 mm (St10kp 3 mm, plasma-thc) the same on 25, DRAAK 726 / 618,
// pongbox 48 / 47, every refused block flagged (figures before session 50; since then DRAAK at
// 0.15 mm flags 681, 107 of them blocks LinuxCNC accepts, and written to 0.001 in the corpus has 2
// refused blocks unflagged, both in DRAAK, against 41). Radii and the entry move's length are compared
// with a micrometre to spare (the program's resolution).
// `held_over_tabs`: beam_switches_under_compensation() of the dialect written with. Where the
// writer keeps compensation on over micro-joint gaps (compensation_held()), a contour and the
// pieces after its tabs are one block, with the rapids over the gaps, and only its first move is
// an entry.
// `written_with`: the dialect the program is written in. The path is rounded to its grid as the
// writer rounds it (to the last bit: the writer's choice between centres a grid step apart turns
// on it), and its arcs have the centres it writes (written_arc(); the controller takes an
// arc's radius at its end). Where the offset of an arc must reach a concave corner beyond the arc's
// ends, LinuxCNC lets the arc grow by at most 0.0254 of a radian in a G21 program but 0.001 in a
// G20 one (its interpreter compares the sweeps in radians against a length in the program's
// unit): near-tangent joints of arcs on the 0.001-in grid, which the same path in millimetres
// passes, are refused. A block whose arcs grow more is at risk.
CompensationHazards compensation_hazards(const Toolpath& path, double tool_radius_mm, bool held_over_tabs,
                                         const PostDialect& written_with = PostDialect{});

}  // namespace cutroute::nc
