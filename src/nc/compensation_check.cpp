#include <cutroute/nc/compensation_check.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include <cutroute/geometry/arc.hpp>
#include <cutroute/nc/gcode_writer.hpp>

namespace cutroute::nc {
namespace {

using geometry::Vec2;

constexpr double kDropMm = 1e-4;
constexpr double kRoundingMm = 1e-3;  // the writer's coordinate resolution (generic dialect)
// LinuxCNC's interpreter (interp_cutter.cc, TOLERANCE_CONCAVE_CORNER): a joint turning toward the
// tool by less than this is not a concave corner; the tool is taken on without a crossing [rad].
constexpr double kConcaveCornerRad = 0.05;
// How much more an arc may sweep once its offset ends at a concave corner's crossing before
// LinuxCNC refuses it ("Arc move in concave corner cannot be reached by the tool without
// gouging", move_endpoint_and_flush): 0.0254 in a G21 program, 0.001 in a G20 one, compared with
// the sweeps in radians [rad].
constexpr double kArcGrowthMmRad = 0.0254;
constexpr double kArcGrowthInchRad = 0.001;

struct Move {
  Vec2 a, b;
  double bulge = 0;  // 0: a line (arcs the writer turns into chords included)
  double length = 0;
  double radius = 0;
  Vec2 centre;       // arcs
  double sweep = 0;  // arcs: signed [rad]
  Vec2 t0, t1;  // unit tangents at the start and the end
};

// The program's coordinate grid: the writer rounds every end point to it, which turns a run of
// micrometre moves of a noisy drawing into a zig-zag whose inside corners the controller cannot
// reach (5 blocks of d2g_DRAAK that LinuxCNC refused went unflagged when the check read the
// unrounded path). The writer's own grid, to the last bit (ProgramGrid): an end point one bit off
// made the check read an arc about the other centre (a block of d2g_fraesen_test_02_2004 in
// inches that LinuxCNC refused went unflagged).
using Grid = ProgramGrid;

void append_line(Vec2 a, Vec2 b, std::vector<Move>& out, const Grid& grid) {
  Move m;
  m.a = grid(a);
  m.b = grid(b);
  m.length = geometry::distance(m.a, m.b);
  if (m.length <= kDropMm) return;  // rounds to nothing: the writer drops it
  m.t0 = m.t1 = (m.b - m.a) / m.length;
  out.push_back(m);
}

// An arc from a (on the grid) to b as the writer emits it (gcode_writer.cpp): a line when nearly
// straight or a chord under two grid steps, chords beyond kMaxArcRadiusMm or below kMinArcRadiusMm
// (a cusp of a spline fit: its chords zig-zag on the grid, and LinuxCNC refused such a corner that
// a single chord hid), two halves in the R format beyond 150 degrees, else one arc about the centre
// the writer writes (written_arc()), its radius taken at its end as the controller takes it.
void append_arc(Vec2 a, Vec2 to, double bulge, std::vector<Move>& out, const Grid& grid, const PostDialect& d) {
  const Vec2 b = grid(to);
  if (a == b) return;
  const ArcPlan plan = plan_arc(geometry::distance(a, b), bulge, grid.res_mm);
  const double sweep = 4 * std::atan(bulge);
  auto chords = [&](int k) {
    Vec2 at = a;
    for (int j = 1; j < k; ++j) {
      const Vec2 p = geometry::arc_point_at_sweep(a, b, bulge, sweep * j / k);
      append_line(at, p, out, grid);
      at = grid(p);
    }
    append_line(at, b, out, grid);
  };
  if (plan.form == ArcPlan::Form::line) return append_line(a, b, out, grid);
  if (plan.form == ArcPlan::Form::chords) return chords(plan.chords);
  if (d.arc_format == ArcFormat::r && std::abs(sweep) > 150.0 * std::numbers::pi / 180.0) {
    const Vec2 c = geometry::Segment{a, b, bulge}.center();
    const double a0 = std::atan2(a.y - c.y, a.x - c.x), r = geometry::distance(c, a);
    const Vec2 mid{c.x + r * std::cos(a0 + sweep / 2), c.y + r * std::sin(a0 + sweep / 2)};
    append_arc(a, mid, std::tan(sweep / 8), out, grid, d);
    return append_arc(grid(mid), b, std::tan(sweep / 8), out, grid, d);
  }
  const WrittenArc w = written_arc(a, b, bulge, d);
  if (w.chords > 0) return chords(w.chords);
  Move m;
  m.a = a;
  m.b = b;
  m.bulge = bulge;
  m.centre = w.centre;
  m.radius = geometry::distance(w.centre, b);
  double turn = std::atan2(b.y - m.centre.y, b.x - m.centre.x) - std::atan2(a.y - m.centre.y, a.x - m.centre.x);
  const double two_pi = 2 * std::numbers::pi;
  if (bulge > 0) {
    while (turn <= 0) turn += two_pi;
  } else {
    while (turn >= 0) turn -= two_pi;
  }
  m.sweep = turn;
  m.length = std::abs(turn) * m.radius;
  const double dir = bulge > 0 ? 1.0 : -1.0;
  m.t0 = geometry::perp(a - m.centre) * (dir / geometry::distance(a, m.centre));
  m.t1 = geometry::perp(b - m.centre) * (dir / m.radius);
  out.push_back(m);
}

// Appends the moves of a segment's pieces as the writer emits them: end points on the grid, moves
// that round to nothing dropped, arcs as append_arc().
void append_moves(const CutSegment& seg, std::vector<Move>& out, const Grid& grid, const PostDialect& d) {
  for (const auto& piece : seg.pieces) {
    const std::size_t n = geometry::segment_count(piece.path);
    for (std::size_t i = 0; i < n; ++i) {
      const geometry::Segment s = geometry::segment(piece.path, i);
      if (s.is_arc()) {
        append_arc(grid(s.a), s.b, s.bulge, out, grid, d);
      } else {
        append_line(s.a, s.b, out, grid);
      }
    }
  }
}

// How far along move m (0 at its start, its length at its end) the point x of its offset lies:
// the projection on a line, the arc length to x's angle on an arc.
double offset_param(const Move& m, Vec2 x) {
  if (m.bulge == 0) return geometry::dot(x - m.a, m.t0);
  const double a0 = std::atan2(m.a.y - m.centre.y, m.a.x - m.centre.x), ax = std::atan2(x.y - m.centre.y, x.x - m.centre.x);
  double turn = m.sweep > 0 ? ax - a0 : a0 - ax;  // in the arc's direction
  turn = std::remainder(turn - std::abs(m.sweep) / 2, 2 * std::numbers::pi) + std::abs(m.sweep) / 2;
  return turn * m.radius;
}

// An inside corner where an arc meets a move: the offsets (a line and a circle, or two circles)
// must cross, and where they cross the tool stops, which must lie on both moves. On lines that is
// r tan(θ/2) of each (the need[] below); where an arc meets the corner the offsets may not cross
// at all (a straight lead from the centre of a hole little wider than the tool), or cross beyond
// a short arc's end. LinuxCNC refuses both ("... in concave corner cannot be reached by the tool
// without gouging").
// Returns the crossing, or nullopt where there is none the tool can stop at.
std::optional<Vec2> arc_corner_crossing(const Move& in, const Move& out, double side, double r) {
  constexpr double kTangentMm = 1e-6;
  struct Offset {
    bool circle = false;
    Vec2 p, d;        // line: a point and the unit direction
    Vec2 c;           // circle: centre
    double rho = 0;   // circle: radius
  };
  auto offset = [&](const Move& m) {
    Offset o;
    if (m.bulge == 0) {
      o.p = m.a + geometry::perp(m.t0) * (side * r);
      o.d = m.t0;
    } else {
      o.circle = true;
      o.c = m.centre;
      o.rho = m.bulge * side > 0 ? m.radius - r : m.radius + r;  // the tool inside the arc, or outside
    }
    return o;
  };
  Offset f = offset(in);
  const Offset g = offset(out);
  // LinuxCNC places a line before an arc by the arc's radius at its end, as if the arc began on
  // that circle: where the written centre is a grid step nearer one end, the line's offset sits
  // that much nearer the centre, and at a shallow corner the crossing moves along it by many times
  // that (a 0.001-in line of d2g_DRAAK between two such corners).
  if (!f.circle && g.circle)
    f.p = out.centre + (in.b - out.centre) * (out.radius / geometry::distance(in.b, out.centre)) + geometry::perp(in.t0) * (side * r);
  std::vector<Vec2> xs;
  auto line_circle = [&](const Offset& l, const Offset& c) {
    const Vec2 w = l.p - c.c;
    const double b = geometry::dot(w, l.d), disc = b * b - (geometry::dot(w, w) - c.rho * c.rho);
    if (disc < -kTangentMm * c.rho) return;  // a line tangent to the circle, to rounding, still touches it
    const double root = std::sqrt(std::max(0.0, disc));
    for (double u : {-b - root, -b + root}) xs.push_back(l.p + l.d * u);
  };
  if (!f.circle) line_circle(f, g);
  else if (!g.circle) line_circle(g, f);
  else {
    const Vec2 dc = g.c - f.c;
    const double dist = geometry::norm(dc);
    if (dist > 1e-12) {
      const double along = (dist * dist + f.rho * f.rho - g.rho * g.rho) / (2 * dist), h2 = f.rho * f.rho - along * along;
      if (h2 >= -kTangentMm * f.rho) {  // circles tangent to rounding (a tangent arc lead) touch
        const Vec2 mid = f.c + dc * (along / dist), up = geometry::perp(dc) * (std::sqrt(std::max(0.0, h2)) / dist);
        // Between two arcs LinuxCNC takes the crossing on the side its rule names (interp_convert.cc,
        // arc to arc: counter-clockwise of the line of centres when the tool runs inside the first arc
        // and the second turns counter-clockwise, or outside and clockwise), not the nearer one. Where
        // the path turns straight back along the arc it came (d2g_DRAAK) that crossing lies behind
        // the first arc's start, and LinuxCNC refused the arc.
        const bool inside_in = in.bulge * side > 0;
        xs.push_back(inside_in == (out.bulge > 0) ? mid + up : mid - up);
      }
    }
  }
  if (xs.empty()) return std::nullopt;
  // The crossing at the corner: the one nearest to it.
  const Vec2 corner = in.b;
  const Vec2 x = *std::min_element(xs.begin(), xs.end(), [&](Vec2 p, Vec2 q) {
    return geometry::distance(p, corner) < geometry::distance(q, corner);
  });
  constexpr double kTol = 1e-6;
  if (offset_param(in, x) >= -kTol && offset_param(out, x) <= out.length + kTol) return x;
  return std::nullopt;
}

// One G41/G42 .. G40 block: the segments it holds (a contour and the pieces after its tabs when the
// compensation stays on over them), with the rapids over the gaps between them.
bool at_risk(const std::vector<Move>& ms, double side, double r, double arc_growth_rad) {
  if (ms.empty()) return false;
  // The entry move: the controller moves from the uncompensated point onto the offset path. Both
  // limits with a micrometre to spare: the written coordinates are rounded to it (an arc of radius
  // r to the last bit of its double was refused).
  const double at_most = r + kRoundingMm;
  if (ms.front().length <= at_most || (ms.front().bulge != 0 && ms.front().radius <= at_most)) return true;
  for (const Move& m : ms)
    if (m.bulge * side > 0 && m.radius <= at_most) return true;  // curving toward the tool: inside the arc
  // Where along each line its offset begins and ends: each inside corner takes r tan(theta / 2) of
  // both lines at it, or up to the crossing with an arc's offset. The controller moves the line's
  // end back to the corner it meets and refuses the line once that end lies behind its start; a
  // line of one grid step between two arcs at a cusp loses its length from both ends.
  std::vector<double> from(ms.size(), 0.0), to(ms.size());
  for (std::size_t i = 0; i < ms.size(); ++i) to[i] = ms[i].length;
  // How far the offset of each arc reaches back before its start [rad]: to the crossing at a
  // concave corner, to the offset end of the move before at a nearly straight joint (there the
  // controller takes the tool on from where that move left it), none at a convex corner (it goes
  // round it from the arc's own offset start).
  std::vector<double> reach_back(ms.size(), 0.0);
  // How far the offset of each arc reaches on past its end to the crossing at a concave corner
  // [rad]; elsewhere it ends where its own offset does, on the radius through its end.
  std::vector<double> reach_on(ms.size(), 0.0);
  // Whether the controller checks an arc's sweep as it ends: it does where it moves the arc's end,
  // at a concave corner, at a convex one before a line (it flushes the arc to its offset end
  // there) and at the G40, but not where an arc follows at a convex or nearly straight joint.
  std::vector<bool> end_checked(ms.size(), false);
  end_checked.back() = true;
  for (std::size_t i = 0; i + 1 < ms.size(); ++i) {
    const double theta = std::atan2(geometry::cross(ms[i].t1, ms[i + 1].t0), geometry::dot(ms[i].t1, ms[i + 1].t0));
    // Within kConcaveCornerRad of turning straight back, which way the path turned is a matter of
    // rounding, and LinuxCNC does not ask it (interp_convert.cc): before an arc the corner is
    // concave where the tool runs outside that arc; before a line, where it ran outside the arc
    // before (the "h" shape), else convex. d2g_DRAAK retraces a bridge between two holes arc by
    // arc; its turn back read as convex here, and LinuxCNC refused the arc after it.
    const bool turns_back = std::abs(theta) > std::numbers::pi - kConcaveCornerRad;
    const bool concave = turns_back ? (ms[i + 1].bulge != 0 ? ms[i + 1].bulge * side < 0 : ms[i].bulge * side < 0)
                              : theta * side > kConcaveCornerRad;  // as LinuxCNC tells a corner's side
    end_checked[i] = concave || (ms[i + 1].bulge == 0 && (turns_back || theta * side < -kConcaveCornerRad));
    if (ms[i + 1].bulge != 0 && std::abs(theta) <= kConcaveCornerRad) {
      const Vec2 left_at = ms[i].b + geometry::perp(ms[i].t1) * (side * r);
      reach_back[i + 1] = -offset_param(ms[i + 1], left_at) / ms[i + 1].radius;
    }
    if (turns_back ? !concave : theta * side <= 1e-9) continue;  // straight on, or turning away from the tool
    if (ms[i].bulge != 0 || ms[i + 1].bulge != 0) {
      // A turn toward the tool under kConcaveCornerRad is no corner to LinuxCNC: it needs no crossing
      // (a tangent lead arc whose written radius misses the contour's offset by a micrometre).
      if (!concave) continue;
      const auto x = arc_corner_crossing(ms[i], ms[i + 1], side, r);
      if (!x) return true;
      if (ms[i + 1].bulge != 0) reach_back[i + 1] = -offset_param(ms[i + 1], *x) / ms[i + 1].radius;
      else from[i + 1] = offset_param(ms[i + 1], *x);
      // The move before the corner now ends at the crossing.
      if (ms[i].bulge != 0) reach_on[i] = (offset_param(ms[i], *x) - ms[i].length) / ms[i].radius;
      else to[i] = offset_param(ms[i], *x);
      continue;
    }
    const double back = r * std::tan(std::min(std::abs(theta), std::numbers::pi - 1e-3) / 2);
    to[i] -= back;
    from[i + 1] = back;
  }
  for (std::size_t i = 1; i < ms.size(); ++i)
    if (ms[i].bulge == 0 && to[i] < from[i] - 1e-9) return true;
  // An arc may not sweep more than written where its end is checked, at a concave corner or not:
  // an arc taken on at a nearly straight joint from a move whose offset ends short of the arc's
  // own (its written centre off the drawn one by a grid step) sweeps more to its own offset end.
  // Nor may its ends pass each other: the controller then reads the sweep the long way round.
  for (std::size_t i = 0; i < ms.size(); ++i) {
    const double grown = reach_back[i] + reach_on[i];
    if (ms[i].bulge != 0 && end_checked[i] && (grown > arc_growth_rad || std::abs(ms[i].sweep) + grown <= 0)) return true;
  }
  return false;
}

}  // namespace

CompensationHazards compensation_hazards(const Toolpath& path, double tool_radius_mm, bool held_over_tabs,
                                         const PostDialect& written_with) {
  CompensationHazards h;
  if (!(tool_radius_mm > 0)) return h;
  const Grid grid(written_with);
  const double arc_growth_rad = written_with.units == "in" ? kArcGrowthInchRad : kArcGrowthMmRad;
  std::vector<Move> block;
  const CutSegment* first = nullptr;
  std::size_t first_k = 0;
  auto close = [&] {
    if (!first) return;
    ++h.compensated;
    if (at_risk(block, first->kerf == KerfSide::left ? 1.0 : -1.0, tool_radius_mm, arc_growth_rad)) h.at.push_back(first_k);
    block.clear();
    first = nullptr;
  };
  for (std::size_t k = 0; k < path.segments.size(); ++k) {
    const CutSegment& seg = path.segments[k];
    const bool continues = first && compensation_held(path.segments[k - 1], seg, held_over_tabs);
    if (!continues) close();
    if (seg.kerf == KerfSide::none) continue;
    if (continues) {  // the rapid over the gap, compensated too
      Vec2 at = tool_off_point(path.segments[k - 1]);
      for (const Vec2 via : seg.rapid_via) append_line(at, via, block, grid), at = via;
      append_line(at, seg.pierce, block, grid);
    } else {
      first = &seg;
      first_k = k;
    }
    append_moves(seg, block, grid, written_with);
  }
  close();
  return h;
}

}  // namespace cutroute::nc
