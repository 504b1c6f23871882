#include <cutroute/nc/compensation_check.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <cutroute/geometry/arc.hpp>
#include <cutroute/nc/gcode_writer.hpp>

namespace cutroute::nc {
namespace {

using geometry::Vec2;

constexpr double kDropMm = 1e-4;
constexpr double kRoundingMm = 1e-3;  // the writer's coordinate resolution (generic dialect)

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
// unrounded path).
struct Grid {
  double res_mm;
  Vec2 operator()(Vec2 p) const { return {std::round(p.x / res_mm) * res_mm, std::round(p.y / res_mm) * res_mm}; }
};

void append_line(Vec2 a, Vec2 b, std::vector<Move>& out, const Grid& grid) {
  Move m;
  m.a = grid(a);
  m.b = grid(b);
  m.length = geometry::distance(m.a, m.b);
  if (m.length <= kDropMm) return;  // rounds to nothing: the writer drops it
  m.t0 = m.t1 = (m.b - m.a) / m.length;
  out.push_back(m);
}

// Appends the moves of a segment's pieces as the writer emits them (gcode_writer.cpp): end points
// on the grid, moves that round to nothing dropped, arcs nearly straight or with a chord under two
// grid steps written as lines, arcs beyond kMaxArcRadiusMm or below kMinArcRadiusMm as chords (a
// cusp of a spline fit: its chords zig-zag on the grid, and LinuxCNC refused such a corner that a
// single chord hid), the others as arcs through the rounded end points.
void append_moves(const CutSegment& seg, std::vector<Move>& out, const Grid& grid) {
  for (const auto& piece : seg.pieces) {
    const std::size_t n = geometry::segment_count(piece.path);
    for (std::size_t i = 0; i < n; ++i) {
      const geometry::Segment s = geometry::segment(piece.path, i);
      const Vec2 a = grid(s.a), b = grid(s.b);
      const ArcPlan plan = s.is_arc() ? plan_arc(geometry::distance(a, b), s.bulge, grid.res_mm) : ArcPlan{};
      if (plan.form == ArcPlan::Form::line) {
        append_line(a, b, out, grid);
        continue;
      }
      if (plan.form == ArcPlan::Form::chords) {
        const double sweep = 4 * std::atan(s.bulge);
        Vec2 at = a;
        for (int j = 1; j < plan.chords; ++j) {
          const Vec2 p = geometry::arc_point_at_sweep(a, b, s.bulge, sweep * j / plan.chords);
          append_line(at, p, out, grid);
          at = grid(p);
        }
        append_line(at, b, out, grid);
        continue;
      }
      const geometry::Segment w{a, b, s.bulge};
      Move m;
      m.a = a;
      m.b = b;
      m.bulge = s.bulge;
      m.length = w.length();
      m.radius = w.radius();
      m.centre = w.center();
      m.sweep = w.sweep();
      m.t0 = w.tangent_at(0);
      m.t1 = w.tangent_at(1);
      out.push_back(m);
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
bool arc_corner_reachable(const Move& in, const Move& out, double side, double r) {
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
  const Offset f = offset(in), g = offset(out);
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
        xs.push_back(mid + up);
        xs.push_back(mid - up);
      }
    }
  }
  if (xs.empty()) return false;
  // The crossing at the corner: the one nearest to it.
  const Vec2 corner = in.b;
  const Vec2 x = *std::min_element(xs.begin(), xs.end(), [&](Vec2 p, Vec2 q) {
    return geometry::distance(p, corner) < geometry::distance(q, corner);
  });
  constexpr double kTol = 1e-6;
  return offset_param(in, x) >= -kTol && offset_param(out, x) <= out.length + kTol;
}

// One G41/G42 .. G40 block: the segments it holds (a contour and the pieces after its tabs when the
// compensation stays on over them), with the rapids over the gaps between them.
bool at_risk(const std::vector<Move>& ms, double side, double r) {
  if (ms.empty()) return false;
  // The entry move: the controller moves from the uncompensated point onto the offset path. Both
  // limits with a micrometre to spare: the written coordinates are rounded to it (an arc of radius
  // r to the last bit of its double was refused).
  const double at_most = r + kRoundingMm;
  if (ms.front().length <= at_most || (ms.front().bulge != 0 && ms.front().radius <= at_most)) return true;
  for (const Move& m : ms)
    if (m.bulge * side > 0 && m.radius <= at_most) return true;  // curving toward the tool: inside the arc
  // Each inside corner needs r tan(theta / 2) of both moves at it for the offsets to intersect.
  std::vector<double> need(ms.size(), 0.0);
  for (std::size_t i = 0; i + 1 < ms.size(); ++i) {
    const double theta = std::atan2(geometry::cross(ms[i].t1, ms[i + 1].t0), geometry::dot(ms[i].t1, ms[i + 1].t0));
    if (theta * side <= 1e-9) continue;  // straight on, or turning away from the tool
    if (ms[i].bulge != 0 || ms[i + 1].bulge != 0) {
      if (!arc_corner_reachable(ms[i], ms[i + 1], side, r)) return true;
      continue;
    }
    const double back = r * std::tan(std::min(std::abs(theta), std::numbers::pi - 1e-3) / 2);
    need[i] += back;
    need[i + 1] += back;
  }
  for (std::size_t i = 1; i < ms.size(); ++i)
    if (need[i] > ms[i].length + 1e-9) return true;
  return false;
}

}  // namespace

CompensationHazards compensation_hazards(const Toolpath& path, double tool_radius_mm, bool held_over_tabs, double resolution_mm) {
  CompensationHazards h;
  if (!(tool_radius_mm > 0)) return h;
  const Grid grid{resolution_mm > 0 ? resolution_mm : kRoundingMm};
  std::vector<Move> block;
  const CutSegment* first = nullptr;
  std::size_t first_k = 0;
  auto close = [&] {
    if (!first) return;
    ++h.compensated;
    if (at_risk(block, first->kerf == KerfSide::left ? 1.0 : -1.0, tool_radius_mm)) h.at.push_back(first_k);
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
    append_moves(seg, block, grid);
  }
  close();
  return h;
}

}  // namespace cutroute::nc
