#include <cutroute/model/cut_job.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/parallel.hpp>
#include <cutroute/core/tolerances.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>

#include "path_ops.hpp"

namespace cutroute::model {

using geometry::Box;
using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

const char* to_string(LeadKind k) {
  switch (k) {
    case LeadKind::none: return "none";
    case LeadKind::line: return "line";
    case LeadKind::arc: return "arc";
    case LeadKind::line_arc: return "line_arc";
  }
  return "none";
}

const char* to_string(PieceKind k) {
  switch (k) {
    case PieceKind::contour: return "contour";
    case PieceKind::bridge: return "bridge";
    case PieceKind::common_edge: return "common_edge";
    case PieceKind::contour_part: return "contour_part";
  }
  return "contour";
}

const geometry::Contour& entry_path(const EntryCandidate& e) {
  static const geometry::Contour kEmpty;
  return e.pieces.empty() ? kEmpty : e.pieces.front().path;
}

double pieces_length(const EntryCandidate& e) {
  double sum = 0;
  for (const auto& p : e.pieces) sum += geometry::length(p.path);
  return sum;
}

geometry::Vec2 tool_off_point(const EntryCandidate& e) {
  if (!e.lead_out.vertices.empty()) return e.lead_out.vertices.back().p;
  for (auto it = e.pieces.rbegin(); it != e.pieces.rend(); ++it)
    if (!it->path.vertices.empty()) return it->path.vertices.back().p;
  return e.pierce;
}

std::vector<ContourId> touched_contours(const BasicSegment& segment) {
  std::vector<ContourId> out = segment.contours;
  if (!segment.candidates.empty())
    for (const auto& p : segment.candidates.front().pieces) {
      if (p.contour.valid()) out.push_back(p.contour);
      if (p.other.valid()) out.push_back(p.other);  // a common edge cuts both contours' boundaries
    }
  std::sort(out.begin(), out.end(), [](ContourId a, ContourId b) { return a.value() < b.value(); });
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

// Parts drawn edge to edge (Nest::shared_edges, both outer contours in the same container): each
// part's neighbours, whose cuts also cut pieces of its boundary and may free it before its own.
std::vector<std::vector<ContourId>> edge_neighbours(const Nest& nest) {
  std::vector<std::vector<ContourId>> out(nest.contours.size());
  for (const auto& [a, b] : nest.shared_edges) {
    const auto &ca = nest.contours[a], &cb = nest.contours[b];
    if (ca.role != ContourRole::outer || cb.role != ContourRole::outer || ca.parent != cb.parent) continue;
    out[a.index()].push_back(b);
    out[b.index()].push_back(a);
  }
  return out;
}

std::optional<std::vector<std::pair<std::int32_t, std::int32_t>>> containment_order(
    const Nest& nest, const std::vector<std::vector<ContourId>>& finishes,
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs, const std::vector<std::vector<ContourId>>* neighbours) {
  const std::size_t m = finishes.size();
  // Which segments touch each contour (a contour cut in part by two segments has two).
  std::vector<std::vector<std::int32_t>> by_contour(nest.contours.size());
  for (std::size_t k = 0; k < m; ++k)
    for (auto c : finishes[k]) by_contour[c.index()].push_back(static_cast<std::int32_t>(k));
  std::vector<std::int32_t> outer_cuts;
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    const auto& c = nest.contours[ContourId(static_cast<std::int32_t>(i))];
    if (!c.parent.valid()) continue;
    const auto& inner = by_contour[i];
    outer_cuts = by_contour[c.parent.index()];
    if (neighbours)
      for (const ContourId q : (*neighbours)[c.parent.index()])
        outer_cuts.insert(outer_cuts.end(), by_contour[q.index()].begin(), by_contour[q.index()].end());
    for (auto b : outer_cuts) {
      // A segment that cuts both (a line shared by a part and the edge of the hole it sits in)
      // finishes either of them; it waits for nothing inside.
      if (std::find(inner.begin(), inner.end(), b) != inner.end()) continue;
      for (auto a : inner) pairs.emplace_back(a, b);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  // Kahn's algorithm: every segment is ordered exactly when the pairs have no cycle.
  std::vector<int> indegree(m, 0);
  std::vector<std::vector<std::int32_t>> next(m);
  for (auto [a, b] : pairs) {
    next[static_cast<std::size_t>(a)].push_back(b);
    ++indegree[static_cast<std::size_t>(b)];
  }
  std::vector<std::int32_t> ready;
  for (std::size_t k = 0; k < m; ++k)
    if (indegree[k] == 0) ready.push_back(static_cast<std::int32_t>(k));
  std::size_t done = 0;
  while (!ready.empty()) {
    const auto k = ready.back();
    ready.pop_back();
    ++done;
    for (auto b : next[static_cast<std::size_t>(k)])
      if (--indegree[static_cast<std::size_t>(b)] == 0) ready.push_back(b);
  }
  if (done != m) return std::nullopt;
  return pairs;
}

}  // namespace

std::optional<std::vector<std::pair<std::int32_t, std::int32_t>>> segment_precedence(
    const Nest& nest, const std::vector<BasicSegment>& segments, std::vector<std::pair<std::int32_t, std::int32_t>> pairs) {
  std::vector<std::vector<ContourId>> touched(segments.size());
  for (std::size_t k = 0; k < segments.size(); ++k) touched[k] = touched_contours(segments[k]);
  const auto neighbours = edge_neighbours(nest);
  return containment_order(nest, touched, std::move(pairs), &neighbours);
}

std::optional<std::vector<std::pair<std::int32_t, std::int32_t>>> segment_precedence(
    const Nest& nest, const std::vector<std::vector<ContourId>>& finishes,
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs) {
  return containment_order(nest, finishes, std::move(pairs), nullptr);
}

const char* to_string(Fallback f) {
  switch (f) {
    case Fallback::none: return "none";
    case Fallback::short_lead: return "short_lead";
    case Fallback::on_contour: return "on_contour";
    case Fallback::centre_pierce: return "centre_pierce";
  }
  return "none";
}

namespace {

const double kQuarterBulge = std::tan(std::numbers::pi / 8);  // bulge of a 90° arc

// Scrap lies left of the direction of travel for clockwise outer contours and counter-clockwise
// holes (the default kerf convention: G41 keeps the beam in scrap).
bool scrap_on_left(ContourRole role, bool clockwise) {
  return role == ContourRole::outer ? clockwise : !clockwise;
}

struct Site {
  double s = 0;
  bool corner = false;
  double turn = 0;  // |turn angle| at a corner [rad]
};

// |Turn angle| of a closed contour's tangent at vertex i [rad]: 0 where it runs straight on.
double turn_at_vertex(const Contour& c, std::size_t i) {
  const std::size_t n = geometry::segment_count(c);
  const Vec2 a = geometry::segment(c, (i + n - 1) % n).tangent_at(1), b = geometry::segment(c, i).tangent_at(0);
  return std::abs(std::atan2(geometry::cross(a, b), geometry::dot(a, b)));
}

}  // namespace

// Per contour, computed once and shared by planners of the same nest with other leads:
// orientation, length, the contour reversed, its segments indexed (queries against outlines of
// thousands of arcs cost O(log n), not O(n)) and measured (points at an arc length in O(log n)).
struct PlannerGeometry {
  geometry::StaticSpatialIndex index;  // over every contour's box, sheet included
  std::vector<char> stored_cw;
  std::vector<double> length;
  std::vector<Contour> reversed;
  std::vector<geometry::SegmentSet> sets;
  std::vector<detail::Measured> measured_stored, measured_reversed;

  explicit PlannerGeometry(const Nest& n) {
    std::vector<Box> boxes;
    boxes.reserve(n.contours.size());
    for (const auto& c : n.contours) {
      boxes.push_back(c.box);
      stored_cw.push_back(geometry::orientation(c.source.contour) == geometry::Orientation::cw);
      length.push_back(geometry::length(c.source.contour));
      reversed.push_back(geometry::reversed(c.source.contour));
      sets.push_back(geometry::make_segment_set(c.source.contour));
      measured_stored.push_back(detail::measure(c.source.contour));
      measured_reversed.push_back(detail::measure(reversed.back()));
    }
    index = geometry::StaticSpatialIndex(boxes);
  }
  // The drawn contours (EntryOptions::drawn), by the same ids; empty without one.
  PlannerGeometry(const Nest& n, const Nest* drawn) : PlannerGeometry(n) {
    if (!drawn) return;
    std::vector<Box> boxes;
    for (const auto& c : drawn->contours) {
      boxes.push_back(c.box);
      drawn_sets.push_back(geometry::make_segment_set(c.source.contour));
    }
    drawn_index = geometry::StaticSpatialIndex(boxes);
  }
  geometry::StaticSpatialIndex drawn_index;
  std::vector<geometry::SegmentSet> drawn_sets;
};

struct EntryPlanner::Impl {
  const Nest& nest;
  EntryOptions opt;
  double clearance;
  std::shared_ptr<const PlannerGeometry> geo;
  const geometry::StaticSpatialIndex& index;
  const std::vector<char>& stored_cw;
  const std::vector<double>& length;
  const std::vector<Contour>& reversed;
  const std::vector<geometry::SegmentSet>& sets;
  const std::vector<detail::Measured>& measured_stored;
  const std::vector<detail::Measured>& measured_reversed;
  double drawn_clearance;  // from the drawn contours (EntryOptions::drawn)
  // Spatial-index query results: one buffer per thread, as make_cut_job asks for the candidates of
  // several contours at once.
  static std::vector<std::uint32_t>& scratch() {
    thread_local std::vector<std::uint32_t> v;
    return v;
  }
  static std::vector<std::uint32_t>& drawn_scratch() {
    thread_local std::vector<std::uint32_t> v;
    return v;
  }

  Impl(const Nest& n, const EntryOptions& o, std::shared_ptr<const PlannerGeometry> g)
      : nest(n), opt(o), clearance(o.clearance_mm >= 0 ? o.clearance_mm : o.kerf_mm + 1.0), geo(std::move(g)),
        index(geo->index), stored_cw(geo->stored_cw), length(geo->length), reversed(geo->reversed), sets(geo->sets),
        measured_stored(geo->measured_stored), measured_reversed(geo->measured_reversed),
        drawn_clearance(std::max(0.0, clearance - 0.5 * o.kerf_mm)) {}

  // Does the open path (or point) keep drawn_clearance from every drawn contour but `own_a` and
  // `own_b`? Always true without drawn contours.
  bool drawn_clear(const geometry::SegmentSet& path, std::int64_t own_a, std::int64_t own_b = -1) const {
    if (geo->drawn_sets.empty()) return true;
    geo->drawn_index.query(path.box.inflated(drawn_clearance), drawn_scratch());
    for (auto i : drawn_scratch()) {
      if (i == own_a || i == own_b) continue;
      if (geometry::count_close_segment_pairs(path, geo->drawn_sets[i], drawn_clearance, 1) > 0) return false;
    }
    return true;
  }
  bool drawn_clear(Vec2 p, std::int64_t own) const {
    if (geo->drawn_sets.empty()) return true;
    geo->drawn_index.query(Box{p.x, p.y, p.x, p.y}.inflated(drawn_clearance), drawn_scratch());
    for (auto i : drawn_scratch())
      if (i != own && closer_than(geo->drawn_sets[i], p, drawn_clearance)) return false;
    return true;
  }

  const NestContour& nc(ContourId id) const { return nest.contours[id]; }

  // The contour as cut: oriented in the cut direction.
  const Contour& oriented(ContourId id, bool clockwise) const {
    return (stored_cw[id.index()] != 0) == clockwise ? nc(id).source.contour : reversed[id.index()];
  }
  const detail::Measured& measured(ContourId id, bool clockwise) const {
    return (stored_cw[id.index()] != 0) == clockwise ? measured_stored[id.index()] : measured_reversed[id.index()];
  }
  // Arc length along the oriented path of the point at arc length s of the stored contour.
  double to_path_s(ContourId id, double s, bool clockwise) const {
    const double total = length[id.index()];
    return (stored_cw[id.index()] != 0) == clockwise ? s : std::fmod(total - s + total, total);
  }

  // Is p in scrap: inside the sheet (when there is one) and inside an even number of part contours.
  bool in_scrap(Vec2 p) const {
    Box b;
    b.add(p);
    index.query(b, scratch());
    int inside = 0;
    for (auto i : scratch()) {
      const ContourId id(static_cast<std::int32_t>(i));
      const auto& c = nc(id);
      const auto loc = geometry::locate(sets[i], p, tol::kSamePointMm);
      if (c.role == ContourRole::sheet) {
        if (loc != geometry::Location::inside) return false;
        continue;
      }
      if (loc == geometry::Location::on_boundary) return false;
      if (loc == geometry::Location::inside) ++inside;
    }
    if (nest.sheet && scratch().empty()) return false;
    return inside % 2 == 0;
  }

  // Does the open path keep `clearance` from every contour but `own`, and not cross `own` except
  // at its last point (lead-in) or first point (lead-out)?
  bool path_clear(const Contour& path, ContourId own, bool touches_at_end) const {
    if (path.vertices.size() < 2) return true;
    const geometry::SegmentSet lead = geometry::make_path_set(path);
    const Box box = lead.box.inflated(clearance);
    index.query(box, scratch());
    for (auto i : scratch()) {
      if (i == own.index()) continue;
      if (geometry::count_close_segment_pairs(lead, sets[i], clearance, 1) > 0) return false;
    }
    if (!drawn_clear(lead, own.index())) return false;
    // Own contour: trim the touching end by a little, then no contact at all is allowed.
    const double len = geometry::length(path);
    const double trim = std::min(0.05 * len, 0.1);
    const Contour own_part = touches_at_end ? detail::sub_path(path, 0, len - trim) : detail::sub_path(path, trim, len - trim);
    return geometry::count_close_segment_pairs(geometry::make_path_set(own_part), sets[own.index()],
                                               tol::kSamePointMm, 1) == 0;
  }

  // A lead-out starts on its contour, so not crossing any boundary is not enough: it must also
  // end in scrap (a path that crosses no boundary stays in the region where it ends).
  bool lead_out_ok(const Contour& lead, ContourId own) const {
    if (lead.vertices.size() < 2) return true;
    return in_scrap(lead.vertices.back().p) && path_clear(lead, own, false);
  }

  // Is some segment of the set closer to p than d? Only segments whose box is near are measured.
  static bool closer_than(const geometry::SegmentSet& set, Vec2 p, double d) {
    bool hit = false;
    set.index.visit(Box{p.x, p.y, p.x, p.y}.inflated(d), [&](std::uint32_t k) {
      hit = geometry::closest_point(set.segments[k], p).distance < d;
      return !hit;
    });
    return hit;
  }

  bool pierce_ok(Vec2 p, ContourId own, double own_min) const {
    if (!in_scrap(p)) return false;
    const Box box = Box{p.x, p.y, p.x, p.y}.inflated(clearance);
    index.query(box, scratch());
    for (auto i : scratch()) {
      const double need = i == own.index() ? own_min : clearance;
      if (closer_than(sets[i], p, need)) return false;
    }
    return drawn_clear(p, own.index());
  }

  // Lead-in into p with unit tangent t (travel) and unit scrap normal n; `left` = n is the left normal.
  // `t_out`: the tangent the cut leaves p with (differs from t at a vertex).
  Contour lead_in(Vec2 p, Vec2 t, Vec2 t_out, Vec2 n, bool left, bool corner, double scale) const {
    const auto& L = opt.lead;
    const double len = L.in_length_mm * scale, r = L.in_arc_radius_mm * scale;
    Contour lead;
    const LeadKind kind = corner && L.in_kind != LeadKind::none ? LeadKind::line : L.in_kind;
    switch (kind) {
      case LeadKind::none:
        return lead;
      case LeadKind::line:
        lead.vertices = {Vertex{p + n * len, 0}, Vertex{p, 0}};
        // Under controller compensation the lead is the entry move: the controller moves the tool
        // from the pierce straight to the start of the first cut move offset by r, the kerf's
        // half, to the scrap side. Along the scrap normal that path keeps r off the part; a lead
        // that runs on along the first edge (an entry at a corner, snapped there from the edge
        // before it) passes the corner at L r / sqrt(L^2 + r^2), closer than r (by 53 um for a
        // 1.5-mm plasma kerf and a 2-mm lead; 0.05 um for a laser's 0.15 mm). Where it comes
        // closer than r by more than the output's micrometre, the lead gets a midpoint: the entry
        // move then ends half a lead out, and the rest is cut compensated.
        if (opt.min_lead_mm > 0) {
          const Vec2 to = p + (left ? geometry::perp(t_out) : -geometry::perp(t_out)) * opt.min_lead_mm;
          const Contour entry_move{{Vertex{p + n * len, 0}, Vertex{to, 0}}, false};
          if (opt.min_lead_mm - geometry::distance(entry_move, p) > 1e-3) lead.vertices.insert(lead.vertices.begin() + 1, Vertex{p + n * (len / 2), 0});
        }
        break;
      case LeadKind::arc: {
        const Vec2 c = p + n * r;
        lead.vertices = {Vertex{c - t * r, left ? kQuarterBulge : -kQuarterBulge}, Vertex{p, 0}};
        break;
      }
      case LeadKind::line_arc: {
        const Vec2 q = p + n * r - t * r;
        lead.vertices = {Vertex{q + n * len, 0}, Vertex{q, left ? kQuarterBulge : -kQuarterBulge}, Vertex{p, 0}};
        break;
      }
    }
    return lead;
  }

  // Does the lead start with a move longer than min_lead_mm, and is each of its arcs wider? By a
  // micrometre at least: the program's coordinates are rounded to it, and a lead-in arc of half a
  // 1.5-mm lead (0.75 mm, to the last bit of its double) was refused by LinuxCNC for r = 0.75.
  bool long_enough(const Contour& lead) const {
    if (opt.min_lead_mm <= 0 || geometry::segment_count(lead) == 0) return true;
    const double least = opt.min_lead_mm + 1e-3;
    if (!(geometry::segment(lead, 0).length() > least)) return false;
    for (std::size_t i = 0; i < geometry::segment_count(lead); ++i) {
      const geometry::Segment seg = geometry::segment(lead, i);
      if (seg.is_arc() && !(seg.radius() > least)) return false;
    }
    return true;
  }

  // `variant` 0: the normal shape; 1: straight along the scrap normal; 2: along `alt` (the
  // bisector at a corner). Tried in this order when the first one is not admissible.
  Contour lead_out(Vec2 p, Vec2 t, Vec2 n, bool left, double scale, int variant = 0, Vec2 alt = {}) const {
    const auto& L = opt.lead;
    const double len = L.out_length_mm * scale;
    Contour lead;
    if (len <= 0) return lead;
    if (variant > 0) {
      const Vec2 dir = variant == 1 ? n : alt;
      lead.vertices = {Vertex{p, 0}, Vertex{p + dir * len, 0}};
      return lead;
    }
    switch (L.out_kind) {
      case LeadKind::none:
        return lead;
      case LeadKind::line:
      case LeadKind::line_arc:
        // Diagonally forward into scrap: leaves the kerf without dwelling on the part edge.
        lead.vertices = {Vertex{p, 0}, Vertex{p + geometry::normalized(n + t) * len, 0}};
        break;
      case LeadKind::arc: {
        const Vec2 c = p + n * len;
        lead.vertices = {Vertex{p, left ? kQuarterBulge : -kQuarterBulge}, Vertex{c + t * len, 0}};
        break;
      }
    }
    return lead;
  }

  std::vector<Site> sites(const Contour& path) const {
    const std::size_t n = geometry::segment_count(path);
    const double total = geometry::length(path);
    std::vector<Site> corners;
    double acc = 0;
    const double min_turn = opt.corner_angle_deg * std::numbers::pi / 180.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double turn = turn_at_vertex(path, i);
      if (turn > min_turn) corners.push_back({acc, true, turn});
      acc += geometry::segment(path, i).length();
    }
    const auto max_c = static_cast<std::size_t>(std::max(1, opt.max_candidates));
    std::stable_sort(corners.begin(), corners.end(), [](const Site& x, const Site& y) { return x.turn > y.turn; });
    if (corners.size() > max_c / 2) corners.resize(max_c / 2);
    std::vector<Site> out = corners;
    const std::size_t fill = max_c - out.size();
    double step = opt.entry_step_mm > 0 ? opt.entry_step_mm : total / static_cast<double>(std::max<std::size_t>(fill, 1));
    const std::size_t count = std::min(fill, static_cast<std::size_t>(std::max(1.0, std::floor(total / step))));
    step = total / static_cast<double>(std::max<std::size_t>(count, 1));
    for (std::size_t k = 0; k < count; ++k) {
      const double s = (static_cast<double>(k) + 0.5) * step;
      bool near = false;
      for (const auto& c : corners) {
        double d = std::abs(c.s - s);
        d = std::min(d, total - d);
        near |= d < step / 2;
      }
      if (!near) out.push_back({s, false, 0});
    }
    std::sort(out.begin(), out.end(), [](const Site& x, const Site& y) { return x.s < y.s; });
    return out;
  }

  // The entry's point and leads at arc length s of the oriented path, unchecked and without the
  // cut path (cheap: a few points and tangents).
  EntryCandidate shape(ContourId id, const Contour& path, double s_path, bool clockwise, bool corner, double scale,
                       double total_len) const {
    const bool left = scrap_on_left(nc(id).role, clockwise);
    const auto at = detail::at_length(path, measured(id, clockwise), s_path);
    Vec2 n = left ? geometry::perp(at.tangent) : -geometry::perp(at.tangent);
    if (corner) {
      // At a corner, lead in along the bisector of the two scrap-side normals. Caution: at_length()
      // gives an exact vertex the tangent of the segment ending there, so `at` and `before` are
      // both the incoming edge's, and the lead runs along its normal (in line with the outgoing
      // edge at a right angle); only vertex 0 gets the bisector. lead_in() copes with that under
      // compensation (t_out); changing it would move every corner entry.
      const auto before = detail::at_length(path, measured(id, clockwise), s_path - 1e-6 * std::max(1.0, total_len));
      const Vec2 n0 = left ? geometry::perp(before.tangent) : -geometry::perp(before.tangent);
      const Vec2 sum = n + n0;
      if (geometry::norm(sum) > 1e-9) n = geometry::normalized(sum);
    }
    EntryCandidate e;
    e.contour = id;
    e.point = at.point;
    e.clockwise = clockwise;
    e.corner = corner;
    const Vec2 t_out = opt.min_lead_mm > 0 ? detail::at_length(path, measured(id, clockwise), s_path + 1e-6 * std::max(1.0, total_len)).tangent
                                            : at.tangent;
    e.lead_in = lead_in(at.point, at.tangent, t_out, n, left, corner, scale);
    e.pierce = e.lead_in.vertices.empty() ? at.point : e.lead_in.vertices.front().p;
    const auto end = opt.lead.overcut_mm > 0 ? detail::at_length(path, measured(id, clockwise), s_path + opt.lead.overcut_mm) : at;
    const Vec2 n_end = left ? geometry::perp(end.tangent) : -geometry::perp(end.tangent);
    e.lead_out = lead_out(end.point, end.tangent, n_end, left, scale);
    return e;
  }

  // The lead-out `normal` when admissible. The lead-out starts on the contour: at a sharp concave
  // corner the normal shape can point into the part. Then try straight along the normal, then
  // along the corner bisector, else none.
  Contour checked_lead_out(ContourId id, const Contour& path, double s_path, bool clockwise, double scale,
                           double total_len, Contour normal) const {
    if (lead_out_ok(normal, id)) return normal;
    const bool left = scrap_on_left(nc(id).role, clockwise);
    const double back = 1e-6 * std::max(1.0, total_len);
    const auto end = detail::at_length(path, measured(id, clockwise), s_path + opt.lead.overcut_mm);
    const auto before = detail::at_length(path, measured(id, clockwise), s_path + opt.lead.overcut_mm - back);
    const Vec2 n1 = left ? geometry::perp(end.tangent) : -geometry::perp(end.tangent);
    const Vec2 n0 = left ? geometry::perp(before.tangent) : -geometry::perp(before.tangent);
    const Vec2 bis = geometry::norm(n0 + n1) > 1e-9 ? geometry::normalized(n0 + n1) : n1;
    for (int variant : {1, 2}) {
      Contour alt = lead_out(end.point, end.tangent, n1, left, scale, variant, bis);
      if (lead_out_ok(alt, id)) return alt;
    }
    return Contour{};
  }

  // An entry a hair from a vertex leaves a move of a few micrometres between the lead and the
  // vertex (and again at the end of the cut): under controller compensation the offset path cannot
  // turn a corner within it, and LinuxCNC refused such programs ("concave corner cannot be reached
  // by the tool without gouging"; 7 blocks of bryanduxbury_jewelrybox, 5 of d2g_AFluegel_Rippen).
  // The arc length (stored contour) of the vertex within half a kerf of s, if any, and whether the
  // contour turns there as at a corner.
  std::optional<std::pair<double, bool>> vertex_near(ContourId id, double s) const {
    const auto& cum = measured_stored[id.index()].cum;
    if (cum.size() < 2) return std::nullopt;
    const auto it = std::lower_bound(cum.begin(), cum.end(), s);
    std::size_t best = cum.size();
    double best_d = 0.5 * opt.kerf_mm;
    for (auto k : {it - cum.begin() - 1, it - cum.begin()}) {
      if (k < 0 || static_cast<std::size_t>(k) >= cum.size()) continue;
      const double d = std::abs(cum[static_cast<std::size_t>(k)] - s);
      if (d > 0 && d <= best_d) best = static_cast<std::size_t>(k), best_d = d;
    }
    if (best == cum.size()) return std::nullopt;
    const std::size_t n = cum.size() - 1;  // segments; the last vertex is the first again
    const std::size_t v = best % n;
    return std::pair{cum[v], turn_at_vertex(nc(id).source.contour, v) > opt.corner_angle_deg * std::numbers::pi / 180.0};
  }

  // Builds the entry at arc length s of the oriented path; nullopt when not admissible.
  std::optional<EntryCandidate> build(ContourId id, const Contour& path, double s_path, bool clockwise, bool corner,
                                      double scale, double total_len) const {
    // An entry within half a kerf of a vertex is made at the vertex (a corner entry where the
    // contour turns there): the rapids change by less than a kerf.
    if (!corner)
      if (const auto v = vertex_near(id, to_path_s(id, s_path, clockwise))) {
        s_path = to_path_s(id, v->first, clockwise);
        corner = v->second;
      }
    EntryCandidate e = shape(id, path, s_path, clockwise, corner, scale, total_len);
    const double lead_len = geometry::length(e.lead_in);
    if (!pierce_ok(e.pierce, id, std::min(clearance, 0.5 * lead_len))) return std::nullopt;
    if (!path_clear(e.lead_in, id, true)) return std::nullopt;
    e.pieces = {SegmentPiece{PieceKind::contour, id, detail::sub_path(path, measured(id, clockwise), s_path, total_len + opt.lead.overcut_mm), {}}};
    e.lead_out = checked_lead_out(id, path, s_path, clockwise, scale, total_len, std::move(e.lead_out));
    // s along the stored contour: the oriented path runs backwards when it was reversed (the map
    // s -> total - s is its own inverse).
    e.s_mm = to_path_s(id, s_path, clockwise);
    return e;
  }

  std::optional<EntryCandidate> centre_pierce(ContourId id, const Contour& path, bool clockwise, double total) const {
    const Vec2 centre = nc(id).box.center();
    if (geometry::locate(sets[id.index()], centre, tol::kSamePointMm) != geometry::Location::inside) return std::nullopt;
    const auto cp = geometry::closest_point(path, centre);
    EntryCandidate e;
    e.contour = id;
    e.point = cp.point;
    e.clockwise = clockwise;
    e.pierce = centre;
    e.lead_in.vertices = {Vertex{centre, 0}, Vertex{cp.point, 0}};
    if (!in_scrap(centre) || !path_clear(e.lead_in, id, true)) return std::nullopt;
    e.pieces = {SegmentPiece{PieceKind::contour, id, detail::sub_path(path, measured(id, clockwise), cp.length_along, total + opt.lead.overcut_mm), {}}};
    e.fallback = Fallback::centre_pierce;
    (void)total;
    e.s_mm = to_path_s(id, cp.length_along, clockwise);
    return e;
  }
};

EntryPlanner::EntryPlanner(const Nest& nest, const EntryOptions& options)
    : impl_(std::make_unique<Impl>(nest, options, std::make_shared<const PlannerGeometry>(nest, options.drawn))) {}
EntryPlanner::EntryPlanner(const EntryPlanner& same_nest, const EntryOptions& options)
    : impl_(std::make_unique<Impl>(same_nest.impl_->nest, options, same_nest.impl_->geo)) {}
EntryPlanner::~EntryPlanner() = default;
double EntryPlanner::clearance_mm() const { return impl_->clearance; }
double EntryPlanner::contour_length(ContourId id) const { return impl_->length[id.index()]; }

std::optional<EntryCandidate> EntryPlanner::entry_at(ContourId id, double s_mm, bool clockwise) const {
  return impl_->build(id, impl_->oriented(id, clockwise), impl_->to_path_s(id, s_mm, clockwise), clockwise, false, 1.0,
                      impl_->length[id.index()]);
}

EntryPlanner::Sketch EntryPlanner::sketch_at(ContourId id, double s_mm, bool clockwise) const {
  const EntryCandidate e = impl_->shape(id, impl_->oriented(id, clockwise), impl_->to_path_s(id, s_mm, clockwise),
                                        clockwise, false, 1.0, impl_->length[id.index()]);
  Sketch k;
  k.pierce = e.pierce;
  k.tool_off = e.lead_out.vertices.empty() ? e.point : e.lead_out.vertices.back().p;
  k.lead_mm = geometry::length(e.lead_in) + geometry::length(e.lead_out);
  return k;
}

geometry::Contour EntryPlanner::whole_loop(ContourId id, double s_mm, bool clockwise, bool overcut) const {
  return detail::sub_path(impl_->oriented(id, clockwise), impl_->measured(id, clockwise), impl_->to_path_s(id, s_mm, clockwise),
                          impl_->length[id.index()] + (overcut ? impl_->opt.lead.overcut_mm : 0.0));
}

geometry::Contour EntryPlanner::lead_out_at(ContourId id, double s_mm, bool clockwise) const {
  const Contour& path = impl_->oriented(id, clockwise);
  const double s_path = impl_->to_path_s(id, s_mm, clockwise), total = impl_->length[id.index()];
  EntryCandidate e = impl_->shape(id, path, s_path, clockwise, false, 1.0, total);
  return impl_->checked_lead_out(id, path, s_path, clockwise, 1.0, total, std::move(e.lead_out));
}

bool EntryPlanner::bridge_clear(const geometry::Contour& path, ContourId from, ContourId to) const {
  const auto& I = *impl_;
  if (path.vertices.size() < 2) return false;
  const double len = geometry::length(path);
  if (!(len > 2 * tol::kSamePointMm)) return false;
  // Its two ends are on `from` and `to`; a little in from them, nothing may be touched at all.
  const double trim = std::min(0.05 * len, 0.1);
  const Contour inner = detail::sub_path(path, trim, len - 2 * trim);
  const geometry::SegmentSet set = geometry::make_path_set(inner);
  I.index.query(set.box.inflated(I.clearance), I.scratch());
  const std::vector<std::uint32_t> near = I.scratch();
  for (auto i : near) {
    const bool end_contour = i == from.index() || i == to.index();
    const double need = end_contour ? tol::kSamePointMm : I.clearance;
    if (geometry::count_close_segment_pairs(set, I.sets[i], need, 1) > 0) return false;
  }
  if (!I.drawn_clear(set, from.index(), to.index())) return false;
  return I.in_scrap(detail::at_length(path, 0.5 * len).point);
}

bool EntryPlanner::near_other(ContourId own, const geometry::Contour& path, double distance) const {
  const auto& I = *impl_;
  if (path.vertices.empty()) return false;
  const geometry::SegmentSet set = geometry::make_path_set(path);
  I.index.query(set.box.inflated(distance), I.scratch());
  // Contours inside `own` (its holes, parts in them) are on the other side of its cut.
  const auto inside_own = [&](ContourId c) {
    for (int guard = 0; c.valid() && guard < 64; ++guard, c = I.nest.contours[c].parent)
      if (c == own) return true;
    return false;
  };
  for (auto i : I.scratch()) {
    const ContourId c(static_cast<std::int32_t>(i));
    if (I.nest.contours[c].role == ContourRole::sheet || inside_own(c)) continue;
    if (geometry::count_close_segment_pairs(set, I.sets[i], distance, 1) > 0) return true;
  }
  return false;
}

std::pair<double, double> EntryPlanner::closest(ContourId id, geometry::Vec2 p) const {
  const auto cp = geometry::closest_point(impl_->nc(id).source.contour, p);
  return {cp.length_along, cp.distance};
}

double EntryPlanner::at_vertex_if_near(ContourId id, double s_mm) const {
  const auto v = impl_->vertex_near(id, s_mm);
  return v ? v->first : s_mm;
}

geometry::Vec2 EntryPlanner::point_at(ContourId id, double s_mm) const {
  return detail::at_length(impl_->nc(id).source.contour, impl_->measured_stored[id.index()], s_mm).point;
}

std::vector<EntryCandidate> EntryPlanner::candidates(ContourId id, Diagnostics& diagnostics) const {
  const auto& c = impl_->nc(id);
  const bool conv_cw = c.role == ContourRole::outer ? impl_->opt.outer_clockwise : impl_->opt.hole_clockwise;
  std::vector<bool> directions{conv_cw};
  if (impl_->opt.free_direction) directions.push_back(!conv_cw);

  std::vector<EntryCandidate> out;
  const auto diag = [&](const std::string& msg, const char* code) {
    Diagnostic d = make_warning(msg, std::string(), c.source.line);
    d.code = code;
    d.handle = c.source.handle;
    d.layer = c.source.layer;
    diagnostics.push_back(std::move(d));
  };
  for (double scale : {1.0, 0.5, 0.25}) {
    for (bool cw : directions) {
      const Contour& path = impl_->oriented(id, cw);
      const double total = impl_->length[id.index()];
      for (const auto& site : impl_->sites(path)) {
        if (auto e = impl_->build(id, path, site.s, cw, site.corner, scale, total)) {
          if (scale < 1.0 && !impl_->long_enough(e->lead_in)) continue;
          if (scale < 1.0) e->fallback = Fallback::short_lead;
          out.push_back(std::move(*e));
        }
      }
    }
    if (!out.empty()) {
      if (scale < 1.0)
        diag("contour " + std::to_string(id.value() + 1) + ": no room for the full lead-in; lead shortened to " +
             format_fixed(scale * 100, 0) + " %",
             "leads.shortened");
      return out;
    }
  }
  const Contour& path = impl_->oriented(id, conv_cw);
  const double total = impl_->length[id.index()];
  if (c.role == ContourRole::hole) {
    if (auto e = impl_->centre_pierce(id, path, conv_cw, total)) {
      diag("hole " + std::to_string(id.value() + 1) + ": too small for a lead-in; pierced at its centre", "leads.centre_pierce");
      out.push_back(std::move(*e));
      return out;
    }
  }
  // Last resort: pierce on the contour itself (marks the edge, but every contour gets cut).
  EntryCandidate e;
  e.contour = id;
  e.clockwise = conv_cw;
  const auto& m = impl_->measured(id, conv_cw);
  const auto at = detail::at_length(path, m, 0);
  e.point = at.point;
  e.pierce = at.point;
  e.pieces = {SegmentPiece{PieceKind::contour, id, detail::sub_path(path, m, 0, total + impl_->opt.lead.overcut_mm), {}}};
  e.fallback = Fallback::on_contour;
  e.s_mm = 0;
  diag("contour " + std::to_string(id.value() + 1) + ": no admissible lead-in; pierced on the contour", "leads.on_contour");
  out.push_back(std::move(e));
  return out;
}

CutJob make_cut_job(const Nest& nest, const EntryOptions& options) { return make_cut_job(nest, EntryPlanner(nest, options)); }

CutJob make_cut_job(const Nest& nest, const EntryPlanner& planner, int threads) {
  CutJob job;
  std::vector<std::int32_t> job_index(nest.contours.size(), -1);
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    const ContourId id(static_cast<std::int32_t>(i));
    if (nest.contours[id].role == ContourRole::sheet) continue;
    job_index[i] = static_cast<std::int32_t>(job.segments.size());
    job.segments.push_back({{id}, {}});
  }
  // Each contour's candidates depend on the nest alone (the lead clearance checks are most of a
  // large nest's job: 3.0 s of a plate of 40 000 holes), so the contours are dealt round-robin to
  // the threads and their diagnostics merged in contour order afterwards.
  const std::size_t count = job.segments.size();
  std::vector<Diagnostics> said(count);
  deal(count, threads, 64, [&](std::size_t k) {
    job.segments[k].candidates = planner.candidates(job.segments[k].contours.front(), said[k]);
  });
  for (auto& d : said) job.diagnostics.insert(job.diagnostics.end(), std::make_move_iterator(d.begin()), std::make_move_iterator(d.end()));
  const auto neighbours = edge_neighbours(nest);
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    const auto& c = nest.contours[ContourId(static_cast<std::int32_t>(i))];
    if (job_index[i] < 0 || !c.parent.valid()) continue;
    const auto parent = job_index[c.parent.index()];
    if (parent >= 0) job.precedence.emplace_back(job_index[i], parent);
    // Parts drawn edge to edge: each neighbour's cut cuts a piece of the parent's boundary, and
    // together they can free it before its own cut (the middle of a grid drawn touching had a
    // hole cut in a free part). What lies inside a part comes before its neighbours' cuts too.
    for (const ContourId q : neighbours[c.parent.index()])
      if (job_index[q.index()] >= 0) job.precedence.emplace_back(job_index[i], job_index[q.index()]);
  }
  return job;
}

}  // namespace cutroute::model
