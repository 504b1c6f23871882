// plan_common_entries(): entry candidates of the common-line segments (loops via EntryPlanner, trails here).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <cutroute/geometry/arc.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>
#include <cutroute/model/common_lines.hpp>

#include "common_detail.hpp"
#include "path_ops.hpp"

namespace cutroute::model {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

namespace {

// The nest whose contours are the closed segments of the plan (in plan order), plus the sheet:
// to EntryPlanner a group of parts joined by common lines is one part bounded by its loops.
Nest derived_nest(const Nest& nest, const CommonLinePlan& plan, std::vector<std::size_t>& segment_of) {
  std::vector<SourceContour> sources;
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    const auto& s = plan.segments[i];
    if (s.kind == CommonSegmentKind::trail) continue;
    SourceContour src = nest.contours[s.contours.front()].source;
    src.contour = s.path;
    sources.push_back(std::move(src));
    segment_of.push_back(i);
  }
  NestOptions o;
  o.detect_sheet = false;
  o.position_unit = nest.unit;
  Nest d = build_nest(std::move(sources), o);
  if (nest.sheet) {
    d.sheet = d.contours.next_id();
    d.contours.push_back(nest.contours[*nest.sheet]);
    d.sheet_box = nest.sheet_box;
  }
  return d;
}

// The candidate's pieces: the segment's pieces from arc length s of its path, one way, for
// `length` mm; its contour, arc length and direction those of the contour it enters.
void set_pieces(EntryCandidate& c, const Nest& nest, const CommonSegment& seg, double s_mm, bool forward,
                double length_mm) {
  const auto pieces = pieces_along(seg, s_mm, forward, length_mm);
  c.pieces.clear();
  for (const auto& p : pieces) {
    SegmentPiece sp;
    sp.kind = p.connector() ? PieceKind::bridge : (p.stretch >= 0 ? PieceKind::common_edge : PieceKind::contour);
    sp.contour = p.contour;
    sp.other = p.other;
    sp.path = p.path;
    c.pieces.push_back(std::move(sp));
  }
  const EnteredContour entered = entered_contour(nest, pieces);
  c.contour = entered.contour;
  c.s_mm = entered.s_mm;
  c.clockwise = entered.clockwise;
}

// Lead checks of trail ends against the original nest: every contour, the sheet border included.
class TrailLeads {
 public:
  TrailLeads(const Nest& nest, const EntryOptions& o) : nest_(nest), opt_(o) {
    clearance_ = o.clearance_mm >= 0 ? o.clearance_mm : o.kerf_mm + 1.0;
    std::vector<geometry::Box> boxes;
    for (const auto& c : nest.contours) {
      sets_.push_back(geometry::make_segment_set(c.source.contour));
      boxes.push_back(c.box);
    }
    index_ = geometry::StaticSpatialIndex(boxes);
  }

  // Candidates entering the trail at its start (forward) or end, best lead first; empty when no
  // lead fits.
  std::vector<EntryCandidate> enter(const CommonSegment& t, bool forward, bool lead_out_at_far_end) const {
    const Contour path = forward ? t.path : geometry::reversed(t.path);
    const Vec2 e = path.vertices.front().p;
    const Vec2 dir = geometry::segment(path, 0).tangent_at(0);
    const double full = opt_.lead.in_kind == LeadKind::none ? 0.0 : opt_.lead.in_length_mm + opt_.lead.in_arc_radius_mm;
    std::vector<EntryCandidate> out;
    for (double scale : {1.0, 0.5, 0.25}) {
      for (double turn : {0.0, kEighth, -kEighth}) {
        EntryCandidate c;
        c.point = e;
        set_pieces(c, nest_, t, forward ? 0.0 : geometry::length(t.path), forward, geometry::length(t.path));
        const Vec2 back = geometry::rotated(-dir, turn);
        c.pierce = e + back * (full * scale);
        if (full > 0) c.lead_in.vertices = {Vertex{c.pierce, 0}, Vertex{e, 0}};
        if (full > 0 && !(pierce_ok(c.pierce, t.contours, 0.5 * full * scale) && path_ok(c.lead_in, t.contours, true)))
          continue;
        if (scale < 1.0) c.fallback = Fallback::short_lead;
        if (lead_out_at_far_end) c.lead_out = lead_out(path, t.contours);
        out.push_back(std::move(c));
        if (full == 0) return out;
      }
      if (!out.empty()) return out;
    }
    return out;
  }

  // Pierced on the trail's end itself (a junction with a line cut before, or no room for a lead).
  EntryCandidate on_line(const CommonSegment& t, bool forward, bool lead_out_at_far_end) const {
    EntryCandidate c;
    const Contour path = forward ? t.path : geometry::reversed(t.path);
    set_pieces(c, nest_, t, forward ? 0.0 : geometry::length(t.path), forward, geometry::length(t.path));
    c.point = c.pierce = path.vertices.front().p;
    c.fallback = Fallback::on_contour;
    if (lead_out_at_far_end) c.lead_out = lead_out(path, t.contours);
    return c;
  }

 private:
  static constexpr double kEighth = std::numbers::pi / 4;

  bool own(std::size_t i, const std::vector<ContourId>& contours) const {
    return std::binary_search(contours.begin(), contours.end(), ContourId(static_cast<std::int32_t>(i)));
  }

  // In scrap: inside the sheet (when there is one), inside an even number of part contours,
  // on no boundary.
  bool in_scrap(Vec2 p) const {
    index_.query(geometry::Box{p.x, p.y, p.x, p.y}, scratch_);
    int inside = 0;
    bool in_sheet = !nest_.sheet;
    for (const auto i : scratch_) {
      const auto loc = geometry::locate(sets_[i], p, tol::kSamePointMm);
      if (nest_.contours[ContourId(static_cast<std::int32_t>(i))].role == ContourRole::sheet) {
        in_sheet = loc == geometry::Location::inside;
        continue;
      }
      if (loc == geometry::Location::on_boundary) return false;
      inside += loc == geometry::Location::inside;
    }
    return in_sheet && inside % 2 == 0;
  }

  bool pierce_ok(Vec2 p, const std::vector<ContourId>& contours, double own_min) const {
    if (!in_scrap(p)) return false;
    index_.query(geometry::Box{p.x, p.y, p.x, p.y}.inflated(clearance_), scratch_);
    for (const auto i : scratch_) {
      const double need = own(i, contours) ? std::min(clearance_, own_min) : clearance_;
      bool hit = false;
      sets_[i].index.visit(geometry::Box{p.x, p.y, p.x, p.y}.inflated(need), [&](std::uint32_t k) {
        hit = geometry::closest_point(sets_[i].segments[k], p).distance < need;
        return !hit;
      });
      if (hit) return false;
    }
    return true;
  }

  // Distance from p to the nearest of the contours the trail cuts, looked for up to `reach` [mm].
  double own_distance(Vec2 p, const std::vector<ContourId>& contours, double reach) const {
    double best = reach;
    index_.query(geometry::Box{p.x, p.y, p.x, p.y}.inflated(reach), scratch_);
    for (const auto i : scratch_) {
      if (!own(i, contours)) continue;
      sets_[i].index.visit(geometry::Box{p.x, p.y, p.x, p.y}.inflated(reach), [&](std::uint32_t k) {
        best = std::min(best, geometry::closest_point(sets_[i].segments[k], p).distance);
        return true;
      });
    }
    return best;
  }

  // The lead keeps `clearance` from every contour the trail does not cut, and its kerf off the
  // material of the ones it cuts except where it joins the trail (at_end: its last point, else its
  // first), which the trail's own kerf reaches anyway: on parts drawn kerf apart the join lies half
  // a kerf from them and the whole lead must stay that far (a lead turned by 45° into the gap took
  // 0.22 mm off a corner at kerf 1.5); on parts drawn touching it lies on them and the last half
  // kerf of the lead may come as close. Without a kerf: touching them only at the join.
  bool path_ok(const Contour& lead, const std::vector<ContourId>& contours, bool at_end) const {
    const double len = geometry::length(lead);
    const double half = 0.5 * opt_.kerf_mm;
    const double need = std::max(tol::kSamePointMm, half - tol::kCommonLineMm);
    const double at_join = own_distance(at_end ? lead.vertices.back().p : lead.vertices.front().p, contours, need);
    double trim = 0;  // the stretch next to the join that may come nearer
    if (at_join < need) trim = half - at_join > tol::kSamePointMm ? half - at_join : std::min(0.05 * len, 0.1);
    const bool check_own = len - trim > tol::kSamePointMm;
    const Contour away = check_own ? detail::sub_path(lead, at_end ? 0.0 : trim, len - trim) : lead;
    const auto lead_set = geometry::make_path_set(lead), away_set = geometry::make_path_set(away);
    index_.query(geometry::bounding_box(lead).inflated(clearance_), scratch_);
    const std::vector<std::uint32_t> near = scratch_;
    for (const auto i : near) {
      const bool mine = own(i, contours);
      if (mine && !check_own) continue;
      if (geometry::count_close_segment_pairs(mine ? away_set : lead_set, sets_[i], mine ? need : clearance_, 1) > 0)
        return false;
    }
    return true;
  }

  // A straight lead-out continuing the trail past its far end (else turned by ±45°) into scrap.
  Contour lead_out(const Contour& path, const std::vector<ContourId>& contours) const {
    const double len = opt_.lead.out_kind == LeadKind::none ? 0.0 : opt_.lead.out_length_mm;
    if (!(len > 0)) return {};
    const Vec2 f = path.vertices.back().p;
    const Vec2 dir = geometry::segment(path, geometry::segment_count(path) - 1).tangent_at(1);
    for (double turn : {0.0, kEighth, -kEighth}) {
      Contour lead;
      lead.vertices = {Vertex{f, 0}, Vertex{f + geometry::rotated(dir, turn) * len, 0}};
      if (in_scrap(lead.vertices.back().p) && path_ok(lead, contours, false)) return lead;
    }
    return {};
  }

  const Nest& nest_;
  EntryOptions opt_;
  double clearance_ = 0;
  std::vector<geometry::SegmentSet> sets_;
  geometry::StaticSpatialIndex index_;
  mutable std::vector<std::uint32_t> scratch_;
};

// Per plan segment: may this untouched contour keep its standard candidates? Its box widened by
// the longest lead and the clearance must meet no loop or trail (see plan_common_entries()).
std::vector<char> reusable_standard(const Nest& nest, const CommonLinePlan& plan, const EntryOptions& options,
                                    double clearance, const CutJob* standard) {
  std::vector<char> ok(plan.segments.size(), 0);
  if (!standard) return ok;
  std::vector<geometry::Box> joined;
  for (const auto& s : plan.segments)
    if (s.kind != CommonSegmentKind::contour) joined.push_back(geometry::bounding_box(s.path));
  const geometry::StaticSpatialIndex index(joined);
  const auto& L = options.lead;
  const double reach = L.in_length_mm + 2 * L.in_arc_radius_mm + L.out_length_mm + L.overcut_mm + clearance + 1.0;
  std::vector<std::uint32_t> hits;
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    const auto& s = plan.segments[i];
    if (s.kind != CommonSegmentKind::contour) continue;
    index.query(nest.contours[s.contours.front()].box.inflated(reach), hits);
    ok[i] = hits.empty() ? 1 : 0;
  }
  return ok;
}

// Per nest contour: its basic segment in the standard job (one per contour there), else -1.
std::vector<int> standard_segment_of(const Nest& nest, const CutJob* standard) {
  std::vector<int> of(nest.contours.size(), -1);
  if (!standard) return of;
  for (std::size_t k = 0; k < standard->segments.size(); ++k) {
    const auto& seg = standard->segments[k];
    if (seg.contours.size() == 1 && seg.contours.front().index() < of.size()) of[seg.contours.front().index()] = static_cast<int>(k);
  }
  return of;
}

}  // namespace

std::vector<std::vector<EntryCandidate>> plan_common_entries(const Nest& nest, const CommonLinePlan& plan,
                                                             const EntryOptions& options, Diagnostics& diagnostics,
                                                             const CutJob* standard) {
  std::vector<std::vector<EntryCandidate>> out(plan.segments.size());
  std::vector<std::size_t> segment_of;
  const Nest derived = derived_nest(nest, plan, segment_of);
  const EntryPlanner planner(derived, options);
  const std::vector<char> reuse = reusable_standard(nest, plan, options, planner.clearance_mm(), standard);
  const std::vector<int> standard_of = standard_segment_of(nest, standard);
  for (std::size_t d = 0; d < segment_of.size() && d < derived.contours.size(); ++d) {
    const std::size_t i = segment_of[d];
    auto& cands = out[i];
    if (reuse[i]) {
      const int k = standard_of[plan.segments[i].contours.front().index()];
      if (k >= 0 && !standard->segments[static_cast<std::size_t>(k)].candidates.empty()) {
        cands = standard->segments[static_cast<std::size_t>(k)].candidates;
        continue;
      }
    }
    cands = planner.candidates(ContourId(static_cast<std::int32_t>(d)), diagnostics);
    const auto& seg = plan.segments[i];
    const bool stored_cw = geometry::orientation(seg.path) == geometry::Orientation::cw;
    for (auto& c : cands) {
      if (seg.kind == CommonSegmentKind::contour) {
        c.contour = c.pieces.front().contour = seg.contours.front();
        continue;
      }
      // A loop: the planner's whole cut (with the overcut) as the pieces of the loop it passes.
      const double s0 = geometry::closest_point(seg.path, c.point).length_along;
      set_pieces(c, nest, seg, s0, c.clockwise == stored_cw, pieces_length(c));
    }
  }
  const TrailLeads leads(nest, options);
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    const auto& t = plan.segments[i];
    if (t.kind != CommonSegmentKind::trail) continue;
    auto& cands = out[i];
    // Leads from every end that may be entered; a pierce on the line only when none fits.
    for (const bool forward : {true, false}) {
      if (!(forward ? t.enter_at_start : t.enter_at_end) || t.pierce_on_line) continue;
      for (auto& c : leads.enter(t, forward, forward ? t.end_on_loop : t.start_on_loop)) cands.push_back(std::move(c));
    }
    if (!cands.empty()) continue;
    const bool forward = t.enter_at_start;
    cands.push_back(leads.on_line(t, forward, forward ? t.end_on_loop : t.start_on_loop));
    if (!t.pierce_on_line) {
      Diagnostic dg = make_warning("common line from " + detail::point_text(cands.front().point, nest.unit) +
                                   ": no room for a lead-in; pierced on the line");
      dg.code = "common.pierce_on_line";
      diagnostics.push_back(std::move(dg));
    }
  }
  for (std::size_t i = 0; i < out.size(); ++i)
    if (out[i].empty()) {
      // Only when the derived nest dropped a loop (it never should): pierce on the path itself.
      EntryCandidate c;
      set_pieces(c, nest, plan.segments[i], 0.0, true, geometry::length(plan.segments[i].path));
      c.point = c.pierce = plan.segments[i].path.vertices.front().p;
      c.fallback = Fallback::on_contour;
      out[i].push_back(std::move(c));
    }
  return out;
}

}  // namespace cutroute::model
