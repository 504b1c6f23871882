// Kerf offset of contours and open paths: steps 0-2 and the top level (offset.hpp).
#include <cutroute/geometry/offset.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>

#include <cutroute/core/tolerances.hpp>

#include "geometry/offset_math.hpp"
#include "geometry/offset_prune.hpp"

namespace cutroute::geometry {

namespace {

using offset_detail::Piece;

// Below this sine of the turn angle, two opposite tangents are a 180° reversal [1].
constexpr double kReversalSine = 1e-12;

// A raw offset piece; a collapsed arc keeps its source (the centre is used by joins).
struct RawPiece {
  Piece piece;
  bool collapsed = false;
};

// Step 0: the source as pieces, zero-length segments dropped and the path kept continuous.
// nullopt when a coordinate or bulge is not a number.
std::optional<std::vector<Piece>> source_pieces(const Contour& c, bool closed) {
  const auto& vs = c.vertices;
  for (const Vertex& v : vs)
    if (!is_finite(v.p) || std::isnan(v.bulge)) return std::nullopt;
  const std::size_t n = vs.size();
  const std::size_t segments = n == 0 ? 0 : (closed ? n : n - 1);
  std::vector<Piece> pieces;
  std::vector<double> bulges;
  for (std::size_t i = 0; i < segments; ++i) {
    const Vec2 a = pieces.empty() ? vs[i].p : pieces.back().b;
    const Piece p = offset_detail::make_piece(a, vs[(i + 1) % n].p, vs[i].bulge);
    if (offset_detail::length(p) <= tol::kSamePointMm) continue;
    pieces.push_back(p);
    bulges.push_back(vs[i].bulge);
  }
  if (closed && !pieces.empty() && pieces.back().b != pieces.front().a)
    pieces.back() = offset_detail::make_piece(pieces.back().a, pieces.front().a, bulges.back());
  return pieces;
}

// Step 1: a line moves along its left normal; an arc keeps its centre and changes radius.
// An arc whose radius would fall to <= 0 collapses. On a closed contour its raw offset is then
// the mirrored arc (radius d - r, on the far side of the centre, a point when that is ~0): the
// true parallel curve, whose ends are |d| from the arc's end vertices so that the ordinary joins
// apply, and which lies wholly inside the band of width |d| so that step 3 drops it. On an open
// path (no step 3) a collapsed arc is simply left out.
RawPiece raw_offset(const Piece& s, double d, bool closed) {
  if (!s.is_arc()) {
    const Vec2 shift = perp(normalized(s.b - s.a)) * d;
    return {offset_detail::make_line(s.a + shift, s.b + shift)};
  }
  // Left of a counter-clockwise arc is its centre side.
  const double r = s.r - (s.sweep > 0 ? d : -d);
  const Vec2 ua = normalized(s.a - s.c);
  const Vec2 ub = normalized(s.b - s.c);
  if (r > tol::kOffsetCollapseRadiusMm) return {offset_detail::make_arc(s.c, r, s.c + ua * r, s.c + ub * r, s.sweep)};
  if (!closed) return {s, true};
  if (-r <= tol::kOffsetCollapseRadiusMm) return {offset_detail::make_line(s.c, s.c)};
  return {offset_detail::make_arc(s.c, -r, s.c + ua * r, s.c + ub * r, s.sweep)};
}

// Trims prev's end and next's start at their crossing nearest `near`; false if they do not meet.
bool trim_at_crossing(Piece& prev, Piece& next, Vec2 near) {
  const auto hits = offset_detail::intersect(prev, next, tol::kOffsetIntersectMm);
  if (hits.count == 0) return false;
  Vec2 x = hits.points[0];
  for (std::size_t h = 1; h < hits.count; ++h)
    if (distance(hits.points[h], near) < distance(x, near)) x = hits.points[h];
  const double tp = std::clamp(offset_detail::param_of(prev, x), 0.0, 1.0);
  const double tn = std::clamp(offset_detail::param_of(next, x), 0.0, 1.0);
  prev = offset_detail::sub_piece(prev, 0.0, tp, prev.a, x);
  next = offset_detail::sub_piece(next, tn, 1.0, x, next.b);
  return true;
}

// Do the full line or circle of p and of q meet (ignoring where the pieces end)?
bool supports_meet(const Piece& p, const Piece& q) {
  const double tol = tol::kOffsetIntersectMm;
  if (!p.is_arc() && !q.is_arc()) return true;  // parallel offsets of a concave corner do not occur
  if (!p.is_arc() || !q.is_arc()) {
    const Piece& line = p.is_arc() ? q : p;
    const Piece& arc = p.is_arc() ? p : q;
    const Vec2 u = normalized(line.b - line.a);
    return std::abs(cross(u, arc.c - line.a)) <= arc.r + tol;
  }
  const double dc = distance(p.c, q.c);
  return dc <= p.r + q.r + tol && dc >= std::abs(p.r - q.r) - tol;
}

// Straight connections through the given points; on closed contours these points lie inside
// the band of width |d| around the source, so step 3 removes whatever loop they close.
void connect_through(Vec2 from, const std::vector<Vec2>& through, Vec2 to, std::vector<Piece>& out) {
  Vec2 cur = from;
  for (Vec2 p : through) {
    out.push_back(offset_detail::make_line(cur, p));
    cur = p;
  }
  out.push_back(offset_detail::make_line(cur, to));
}

// Step 2: connects prev's end to next's start. `before` and `after` are their source pieces,
// which meet at a source vertex (the turn is judged on them: a raw piece may have been trimmed
// to nothing or mirrored). `collapsed_centres` are the centres of arcs left out between them
// (open paths only).
void join(Piece& prev, Piece& next, const Piece& before, const Piece& after,
          const std::vector<Vec2>& collapsed_centres, double d, bool closed, std::vector<Piece>& out) {
  if (!collapsed_centres.empty()) {
    Vec2 near{};
    for (Vec2 c : collapsed_centres) near += c;
    near = near / static_cast<double>(collapsed_centres.size());
    if (trim_at_crossing(prev, next, near)) return;
    connect_through(prev.b, closed ? collapsed_centres : std::vector<Vec2>{}, next.a, out);
    return;
  }
  if (distance(prev.b, next.a) <= tol::kOffsetJoinMm) {
    next.a = prev.b;
    return;
  }
  const Vec2 vertex = before.b;
  const Vec2 t1 = offset_detail::end_tangent(before);
  const Vec2 t2 = offset_detail::start_tangent(after);
  const double turn = cross(t1, t2);
  const bool reversal = std::abs(turn) <= kReversalSine && dot(t1, t2) < 0;
  const auto join_arc = [&] {
    const Vec2 u = prev.b - vertex;
    const Vec2 w = next.a - vertex;
    const double angle = std::atan2(std::abs(cross(u, w)), dot(u, w));  // [0, π]
    out.push_back(offset_detail::make_arc(vertex, std::abs(d), prev.b, next.a, d > 0 ? -angle : angle));
  };
  if (reversal || turn * d < 0) {
    // Gap: the path turns away from the offset side; both ends are |d| from the vertex.
    join_arc();
    return;
  }
  if (trim_at_crossing(prev, next, vertex)) return;
  // Concave, yet the two never meet: arcs curving away from each other (a cusp), where the
  // offset boundary passes around V like at a convex corner. (Pieces whose lines or circles do
  // meet, just beyond their ends, are the classic short-segment case handled through V.)
  if (closed && !supports_meet(prev, next)) {
    join_arc();
    return;
  }
  connect_through(prev.b, closed ? std::vector<Vec2>{vertex} : std::vector<Vec2>{}, next.a, out);
}

// Steps 1 and 2: the joined raw offset as a chain of pieces (closed: last end = first start).
std::vector<Piece> joined_raw_offset(const std::vector<Piece>& source, double d, bool closed) {
  std::vector<RawPiece> raw;
  raw.reserve(source.size());
  for (const Piece& s : source) raw.push_back(raw_offset(s, d, closed));
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < raw.size(); ++i)
    if (!raw[i].collapsed) kept.push_back(i);
  // A closed path needs two pieces to enclose anything (one arc cannot cross itself).
  if (kept.empty() || (closed && kept.size() < 2)) return {};

  const std::size_t n = raw.size();
  const std::size_t joins = closed ? kept.size() : kept.size() - 1;
  std::vector<std::vector<Piece>> connectors(kept.size());
  for (std::size_t k = 0; k < joins; ++k) {
    const std::size_t i = kept[k];
    const std::size_t j = kept[(k + 1) % kept.size()];
    std::vector<Vec2> centres;
    for (std::size_t m = (i + 1) % n; m != j; m = (m + 1) % n) centres.push_back(raw[m].piece.c);
    join(raw[i].piece, raw[j].piece, source[i], source[j], centres, d, closed, connectors[k]);
  }

  // Pieces trimmed to nothing are dropped; the neighbour takes over their end point.
  std::vector<Piece> path;
  auto append = [&path](const Piece& p) {
    if (offset_detail::length(p) > tol::kOffsetJoinMm) {
      path.push_back(p);
    } else if (!path.empty()) {
      path.back().b = p.b;
    }
  };
  for (std::size_t k = 0; k < kept.size(); ++k) {
    append(raw[kept[k]].piece);
    for (const Piece& p : connectors[k]) append(p);
  }
  if (closed && !path.empty()) path.back().b = path.front().a;
  return path;
}

double signed_area(const std::vector<Piece>& loop) {
  double area = 0.0;
  for (const Piece& p : loop) area += offset_detail::area_term(p);
  return area;
}

Contour to_contour(const std::vector<Piece>& pieces, bool closed) {
  Contour c;
  c.closed = closed;
  c.vertices.reserve(pieces.size() + 1);
  // Slivers left where crossings fall next to a vertex would be zero-length moves in G-code;
  // dropping one moves the next vertex by at most tol::kOffsetJoinMm.
  for (const Piece& p : pieces)
    if (!closed || offset_detail::length(p) > tol::kOffsetJoinMm) c.vertices.push_back({p.a, p.bulge()});
  if (!closed && !pieces.empty()) c.vertices.push_back({pieces.back().b, 0.0});
  return c;
}

}  // namespace

OffsetResult offset_contour(const Contour& c, double distance) {
  OffsetResult result;
  if (!c.closed) {
    Contour open = offset_open_path(c, distance);
    if (!open.vertices.empty()) result.contours.push_back(std::move(open));
    result.collapsed = result.contours.empty();
    return result;
  }
  const auto source = source_pieces(c, true);
  const double source_area = source ? signed_area(*source) : 0.0;
  if (!source || !std::isfinite(distance) || std::abs(source_area) <= tol::kOffsetMinLoopAreaMm2) {
    result.collapsed = true;
    return result;
  }
  // Below the join resolution an offset cannot be told from the source (and the snapped joins
  // could touch it).
  if (std::abs(distance) <= tol::kOffsetJoinMm) {
    result.contours.push_back(to_contour(*source, true));
    return result;
  }

  const std::vector<Piece> path = joined_raw_offset(*source, distance, true);
  const auto pruned = offset_detail::prune_invalid_loops(path, *source, std::abs(distance));
  result.self_intersection_removed = pruned.removed;
  for (const auto& loop : pruned.loops) {
    const double area = signed_area(loop);
    if (std::abs(area) > tol::kOffsetMinLoopAreaMm2 && (area > 0) == (source_area > 0)) {
      result.contours.push_back(to_contour(loop, true));
    } else {
      result.self_intersection_removed = true;  // an inverted or vanishing loop
    }
  }
  result.collapsed = result.contours.empty();
  return result;
}

Contour offset_open_path(const Contour& c, double distance) {
  const auto source = source_pieces(c, false);
  if (!source || source->empty() || !std::isfinite(distance)) return Contour{};
  if (std::abs(distance) <= tol::kOffsetJoinMm) return to_contour(*source, false);
  return to_contour(joined_raw_offset(*source, distance, false), false);
}

}  // namespace cutroute::geometry
