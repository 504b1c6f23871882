#include <cutroute/pipeline/shop_rules.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <unordered_map>

#include <cutroute/core/tolerances.hpp>
#include <cutroute/core/units.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/nc/micro_joints.hpp>
#include <cutroute/nc/rapid_detours.hpp>
#include <cutroute/solve/history_search.hpp>
#include <cutroute/solve/solution.hpp>

#include "shop_rules_steps.hpp"

namespace cutroute::pipeline {

const char* to_string(ClampSide s) {
  switch (s) {
    case ClampSide::left: return "left";
    case ClampSide::right: return "right";
    case ClampSide::bottom: return "bottom";
    case ClampSide::top: return "top";
  }
  return "left";
}

std::optional<ClampSide> parse_clamp_side(const std::string& s) {
  for (ClampSide c : {ClampSide::left, ClampSide::right, ClampSide::bottom, ClampSide::top})
    if (s == to_string(c)) return c;
  return std::nullopt;
}

const char* to_string(TabLeadIn t) {
  switch (t) {
    case TabLeadIn::automatic: return "auto";
    case TabLeadIn::on: return "on";
    case TabLeadIn::off: return "off";
  }
  return "auto";
}

std::optional<TabLeadIn> parse_tab_lead_in(const std::string& s) {
  for (TabLeadIn t : {TabLeadIn::automatic, TabLeadIn::on, TabLeadIn::off})
    if (s == to_string(t)) return t;
  return std::nullopt;
}

std::vector<std::string> check(const ShopRules& r) {
  std::vector<std::string> e;
  auto finite_nonneg = [&](double v, const char* name) {
    if (!std::isfinite(v) || v < 0) e.push_back(std::string(name) + " must be a finite number >= 0");
  };
  finite_nonneg(r.heat_distance_mm, "--heat-distance");
  finite_nonneg(r.heat_weight, "--heat-weight");
  finite_nonneg(r.tip_up_weight, "--tip-up-weight");
  finite_nonneg(r.tip_up_margin_mm, "--tip-up-margin");
  finite_nonneg(r.sheet_weight_per_mm, "--sheet-weight");
  finite_nonneg(r.sheet_band_mm, "--sheet-band");
  if (r.heat_memory < 1 || r.heat_memory > 16) e.push_back("--heat-memory must be in 1..16");
  if (r.tabs < 0 || r.tabs > 64) e.push_back("--tabs must be in 0..64");
  if (r.tabs > 0 && (!std::isfinite(r.tab_width_mm) || r.tab_width_mm <= 0)) e.push_back("--tab-width must be > 0");
  if (r.search_evaluations < 0) e.push_back("the rules' search budget must be >= 0");
  return e;
}

namespace rules {
namespace {

using geometry::Vec2;
using solve::Cost;
using solve::NodeId;

double box_gap(const geometry::Box& a, const geometry::Box& b) {
  const double dx = std::max({0.0, a.xmin - b.xmax, b.xmin - a.xmax});
  const double dy = std::max({0.0, a.ymin - b.ymax, b.ymin - a.ymax});
  return std::hypot(dx, dy);
}

// Are two contours closer than d anywhere? Exact with arcs (segment to segment distances).
bool closer_than(const geometry::Contour& a, const geometry::Contour& b, const geometry::Box& bb, double d) {
  const std::size_t na = geometry::segment_count(a), nb = geometry::segment_count(b);
  for (std::size_t i = 0; i < na; ++i) {
    const geometry::Segment s = geometry::segment(a, i);
    if (box_gap(s.bounding_box(), bb) >= d) continue;
    for (std::size_t j = 0; j < nb; ++j) {
      const geometry::Segment t = geometry::segment(b, j);
      if (box_gap(s.bounding_box(), t.bounding_box()) >= d) continue;
      if (geometry::distance(s, t) < d) return true;
    }
  }
  return false;
}

// Where a cut contour stands along the sweep: larger = farther from the clamped side [mm].
double sweep_key(const model::Nest& nest, model::ContourId id, ClampSide side) {
  const auto& c = nest.contours[id];
  const Vec2 centre = c.part.valid() ? nest.contours[nest.parts[c.part].outer].box.center() : c.box.center();
  switch (side) {
    case ClampSide::left: return centre.x;
    case ClampSide::right: return -centre.x;
    case ClampSide::bottom: return centre.y;
    case ClampSide::top: return -centre.y;
  }
  return centre.x;
}

struct Effects {
  int heat_pairs = 0;          // consecutive contours closer than D
  int heat_near = 0;           // close pairs within the memory window (all distances)
  double heat_penalty = 0;     // [objective unit]
  int tip_up_rapids = 0;       // straight rapids over freed parts
  double tip_up_penalty = 0;
  double behind_mm = 0;        // sum over steps behind the sweep front beyond the band [mm]
  int behind_steps = 0;
  double sheet_penalty = 0;
  double penalty() const { return heat_penalty + tip_up_penalty + sheet_penalty; }  // [objective unit]
};

// The SequenceCost of the pipeline: the problem's own price of the route (a prefix without the
// closing arc) plus the rules' penalties. Not thread-safe (caches); history_search is one thread.
class RuleCost {
 public:
  RuleCost(const model::Nest& nest, const model::CutJob& job, const cost::RouteProblem& rp, const ShopRules& r)
      : nest_(nest), rp_(rp), r_(r), obstacles_(nest, r.tip_up_margin_mm) {
    const std::size_t m = job.segments.size();
    touched_.resize(m);
    parts_.resize(m);
    key_.assign(m, {0.0, 0.0});
    for (std::size_t j = 0; j < m; ++j) {
      // A standard segment cuts one contour; a chain several whole ones; a common-line or
      // multi-segment piece parts of several. The rules see every contour a segment cuts.
      touched_[j] = model::touched_contours(job.segments[j]);
      std::pair<double, double> span{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
      for (const model::ContourId id : touched_[j]) {
        const auto& c = nest.contours[id];
        // A part counts as cut free once a segment has cut (any of) its outer contour, as the
        // program's detour pass (nc/rapid_detours.hpp) counts it.
        if (c.role == model::ContourRole::outer && c.part.valid()) parts_[j].push_back(c.part.value());
        if (r.sheet_clamp) {
          const double k = sweep_key(nest, id, *r.sheet_clamp);
          span = {std::min(span.first, k), std::max(span.second, k)};
        }
      }
      if (r.sheet_clamp && !touched_[j].empty()) key_[j] = span;
    }
    near_.resize(m);
    freed_stamp_.assign(nest.parts.size(), 0);
    freed_pos_.assign(nest.parts.size(), 0);
  }

  // Are segments a and b closer than the heat distance (any contour of one to any of the other)?
  // Decided when first asked and kept: a search asks about the pairs next to each other in the
  // routes it prices, a few per contour, while all pairs within the distance were 365 000 on
  // 10 000 circles 12 mm apart (0.5 s to measure, a tenth of --time-limit 5).
  bool near(int a, int b) const {
    if (a > b) std::swap(a, b);
    auto& known = near_[static_cast<std::size_t>(a)];
    const auto it = std::lower_bound(known.begin(), known.end(), std::pair<int, bool>{b, false},
                                     [](const auto& x, const auto& y) { return x.first < y.first; });
    if (it != known.end() && it->first == b) return it->second;
    const double d = r_.heat_distance_mm;
    auto pair_close = [&](model::ContourId ia, model::ContourId ib) {
      const auto &ca = nest_.contours[ia], &cb = nest_.contours[ib];
      return ia == ib || (box_gap(ca.box, cb.box) < d && closer_than(ca.source.contour, cb.source.contour, cb.box, d));
    };
    const auto& tb = touched_[static_cast<std::size_t>(b)];
    const bool close = std::any_of(touched_[static_cast<std::size_t>(a)].begin(), touched_[static_cast<std::size_t>(a)].end(),
                                   [&](model::ContourId ia) {
                                     return std::any_of(tb.begin(), tb.end(), [&](model::ContourId ib) { return pair_close(ia, ib); });
                                   });
    known.insert(it, {b, close});
    return close;
  }

  // Where segment j stands along the sweep: the least and the largest key of the contours it cuts.
  std::pair<double, double> sweep_span(std::size_t j) const { return key_[j]; }

  Cost operator()(std::span<const NodeId> route) const { return price(route, nullptr); }

  Cost price(std::span<const NodeId> route, Effects* fx) const {
    const auto& p = rp_.problem;
    if (route.empty()) return 0;
    Cost c = p.inner_cost(route[0]);
    for (std::size_t i = 1; i < route.size(); ++i) c += p.arc_cost(route[i - 1], route[i]) + p.inner_cost(route[i]);
    const bool complete = static_cast<int>(route.size()) == p.cluster_count();
    if (complete && p.closed() && route.size() > 1) c += p.arc_cost(route.back(), route.front());
    return c + units::seconds_to_ticks(penalty(route, complete, fx));
  }

 private:
  int contour_at(NodeId v) const { return rp_.nodes[v.index()].segment; }

  // Parts the straight rapid from a's tool-off point to b's pierce point passes over, cached by
  // node pair: the parts' lists one after another in pool_ (count, then the parts), found through
  // a hash of the pairs the search asked for. It was a dense table over the route's nodes: 3 010
  // contours took 250 MB (41 MB without tip-up), and 10 000 would have taken 2.4 GB. The span
  // lives until the next call.
  std::span<const int> crossed(NodeId a, NodeId b) const {
    const std::uint64_t key = static_cast<std::uint64_t>(a.index()) << 32 | static_cast<std::uint64_t>(b.index());
    const auto [it, fresh] = slot_.try_emplace(key, static_cast<std::uint32_t>(pool_.size()));
    if (fresh) {
      const auto parts = obstacles_.crossed(rp_.tool_off[a.index()], rp_.pierce[b.index()]);
      pool_.push_back(static_cast<int>(parts.size()));
      pool_.insert(pool_.end(), parts.begin(), parts.end());
    }
    const int* at = pool_.data() + it->second;
    return {at + 1, static_cast<std::size_t>(at[0])};
  }
  bool over_freed(NodeId a, NodeId b, std::size_t before) const {
    for (int part : crossed(a, b))
      if (freed_stamp_[static_cast<std::size_t>(part)] == stamp_ && freed_pos_[static_cast<std::size_t>(part)] < before) return true;
    return false;
  }

  double penalty(std::span<const NodeId> route, bool complete, Effects* fx) const {
    double pen = 0;
    const bool tip = r_.avoid_tip_up && r_.tabs <= 0;
    ++stamp_;
    double front = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i < route.size(); ++i) {
      const int j = contour_at(route[i]);
      if (r_.heat_distance_mm > 0) {
        double w = r_.heat_weight;
        for (std::size_t k = 1; k <= static_cast<std::size_t>(r_.heat_memory) && k < i; ++k, w /= 2) {
          if (!near(j, contour_at(route[i - k]))) continue;
          pen += w;
          if (fx) {
            fx->heat_penalty += w;
            ++fx->heat_near;
            fx->heat_pairs += k == 1;
          }
        }
      }
      if (r_.sheet_clamp) {
        // The contour of the segment nearest the clamp is the one that may lie behind the front.
        const auto [lo, hi] = key_[static_cast<std::size_t>(j)];
        const double behind = front - lo - r_.sheet_band_mm;
        if (behind > 0) {
          pen += r_.sheet_weight_per_mm * behind;
          if (fx) {
            fx->behind_mm += behind;
            ++fx->behind_steps;
            fx->sheet_penalty += r_.sheet_weight_per_mm * behind;
          }
        }
        front = std::max(front, hi);
      }
      if (tip) {
        if (over_freed(route[i - 1], route[i], i)) {
          pen += r_.tip_up_weight;
          if (fx) {
            ++fx->tip_up_rapids;
            fx->tip_up_penalty += r_.tip_up_weight;
          }
        }
        for (const int part : parts_[static_cast<std::size_t>(j)]) {
          if (freed_stamp_[static_cast<std::size_t>(part)] == stamp_) continue;  // freed earlier
          freed_stamp_[static_cast<std::size_t>(part)] = stamp_;
          freed_pos_[static_cast<std::size_t>(part)] = i;
        }
      }
    }
    if (tip && complete && rp_.problem.closed() && route.size() > 1 && over_freed(route.back(), route.front(), route.size())) {
      pen += r_.tip_up_weight;
      if (fx) {
        ++fx->tip_up_rapids;
        fx->tip_up_penalty += r_.tip_up_weight;
      }
    }
    return pen;
  }

  const model::Nest& nest_;
  const cost::RouteProblem& rp_;
  const ShopRules& r_;
  nc::PartObstacles obstacles_;
  std::vector<std::vector<model::ContourId>> touched_;  // per segment: the contours it cuts
  std::vector<std::vector<int>> parts_;                 // per segment: the parts whose outer contour it cuts
  std::vector<std::pair<double, double>> key_;          // per segment: least and largest sweep key
  mutable std::vector<std::vector<std::pair<int, bool>>> near_;  // per segment a: (b > a, near?) sorted by b
  mutable std::unordered_map<std::uint64_t, std::uint32_t> slot_;  // node pair -> offset in pool_
  mutable std::vector<int> pool_;
  mutable std::vector<std::uint64_t> freed_stamp_;
  mutable std::vector<std::size_t> freed_pos_;
  mutable std::uint64_t stamp_ = 0;
};

nlohmann::json effects_json(const Effects& fx, const ShopRules& r) {
  nlohmann::json j;
  if (r.heat_distance_mm > 0)
    j["heat"] = {{"consecutive_closer_than_d", fx.heat_pairs}, {"close_pairs_in_memory", fx.heat_near}, {"penalty", fx.heat_penalty}};
  if (r.avoid_tip_up && r.tabs <= 0) j["tip_up"] = {{"straight_rapids_over_freed_parts", fx.tip_up_rapids}, {"penalty", fx.tip_up_penalty}};
  if (r.sheet_clamp)
    j["sheet"] = {{"steps_behind_front", fx.behind_steps}, {"behind_front_mm", fx.behind_mm}, {"penalty", fx.sheet_penalty}};
  return j;
}

// The centre of the material still uncut after each position of the sequence: the mean centre of
// the parts whose outer contour is cut later; the sheet's (else the nest's) centre when none is.
// One pass from the end (it was a scan per outer contour, O(m^2): about 0.5 s on 10 000 circles).
std::vector<Vec2> uncut_centres(const model::Nest& nest, const std::vector<model::EntryCandidate>& seq) {
  Vec2 fallback;
  if (nest.sheet) {
    fallback = nest.contours[*nest.sheet].box.center();
  } else {
    geometry::Box all;
    for (const auto& c : nest.contours) all.add(c.box);
    fallback = all.center();
  }
  std::vector<Vec2> out(seq.size(), fallback);
  Vec2 sum{0, 0};
  int n = 0;
  for (std::size_t i = seq.size(); i-- > 0;) {
    if (n > 0) out[i] = sum / n;
    const auto& c = nest.contours[seq[i].contour];
    if (c.role != model::ContourRole::outer) continue;
    sum = sum + c.box.center();
    ++n;
  }
  return out;
}

}  // namespace

TimeShares time_shares(const ShopRules& r) {
  TimeShares t;
  if (r.orders()) t.search = 0.2;
  if (r.avoid_tip_up && r.tabs <= 0) t.refine = t.detours = 0.1;
  return t;
}

void restrict_candidates(model::CutJob& job, const model::Nest& nest, const ShopRules& r) {
  if (!r.part_rigidity) return;
  for (auto& ce : job.segments) {
    if (ce.contours.size() != 1 || nest.contours[ce.contours.front()].role != model::ContourRole::outer) continue;
    const bool any_corner = std::any_of(ce.candidates.begin(), ce.candidates.end(), [](const auto& e) { return e.corner; });
    if (!any_corner) continue;
    std::erase_if(ce.candidates, [](const model::EntryCandidate& e) { return !e.corner; });
  }
}

std::vector<NodeId> reorder(const model::Nest& nest, const model::CutJob& job, const cost::RouteProblem& rp,
                            const std::vector<NodeId>& route, const ShopRules& r, const StopToken& stop,
                            nlohmann::json& report, double& penalty) {
  const RuleCost rc(nest, job, rp, r);
  const solve::SequenceCost cost = [&rc](std::span<const NodeId> x) { return rc(x); };
  std::vector<std::vector<NodeId>> starts{route};
  const auto m = static_cast<long long>(route.size());
  // Greedy costs O(m³) rule steps: only where that is below the search's own budget.
  if (m <= 300) starts.push_back(solve::greedy_route(rp.problem, cost, route));
  if (r.sheet_clamp) {
    std::vector<double> prio(static_cast<std::size_t>(rp.problem.cluster_count()), 0.0);
    for (const NodeId v : route) {
      const int j = rp.nodes[v.index()].segment;
      if (j >= 0) prio[rp.problem.cluster_of(v).index()] = rc.sweep_span(static_cast<std::size_t>(j)).first;
    }
    starts.push_back(solve::order_by_priority(rp.problem, route, prio));
  }
  solve::HistorySearchParams params;
  // Each evaluation prices the whole route: keep the total work near 4e7 rule steps (a few seconds).
  params.max_evaluations = std::min(r.search_evaluations, std::max<long long>(1000, 40000000LL / std::max<long long>(1, m)));
  const auto res = solve::history_search(rp.problem, cost, starts, params, stop);
  Effects before, after;
  rc.price(route, &before);
  if (res.route.empty()) {
    report["route"] = effects_json(before, r);
    penalty = before.penalty();
    return route;
  }
  rc.price(res.route, &after);
  penalty = after.penalty();
  report["route"] = effects_json(after, r);
  report["search"] = {{"starts", starts.size()},
                      {"evaluations", res.evaluations},
                      {"moves", res.improvements},
                      {"local_optimum", res.local_optimum},
                      {"solver_route_s", units::ticks_to_seconds(cost(route))},
                      {"best_start_s", units::ticks_to_seconds(res.initial_cost)},
                      {"final_s", units::ticks_to_seconds(res.cost)},
                      {"solver_route", effects_json(before, r)}};
  return res.route;
}

EntryPenalty tip_up_entry_penalty(const model::Nest& nest, const std::vector<model::EntryCandidate>& seq, const ShopRules& r) {
  if (!r.avoid_tip_up || r.tabs > 0) return {};
  auto obstacles = std::make_shared<const nc::PartObstacles>(nest, r.tip_up_margin_mm);
  constexpr std::size_t kNever = std::numeric_limits<std::size_t>::max();
  auto freed_at = std::make_shared<std::vector<std::size_t>>(nest.parts.size(), kNever);
  for (std::size_t k = 0; k < seq.size(); ++k)
    for (const auto& piece : seq[k].pieces) {
      if (!piece.contour.valid()) continue;
      const auto& c = nest.contours[piece.contour];
      if (c.role == model::ContourRole::outer && c.part.valid()) {
        auto& f = (*freed_at)[c.part.index()];
        f = std::min(f, k);
      }
    }
  const double w = r.tip_up_weight;
  return [obstacles, freed_at, w](std::size_t k, Vec2 prev, Vec2 pierce, Vec2 off, const std::optional<Vec2>& next) {
    const auto& at = *freed_at;
    double v = 0;
    if (obstacles->crosses_any(prev, pierce, [&](int part) { return at[static_cast<std::size_t>(part)] < k; })) v += w;
    if (next && obstacles->crosses_any(off, *next, [&](int part) { return at[static_cast<std::size_t>(part)] <= k; })) v += w;
    return v;
  };
}

int place_rigid_entries(const model::Nest& nest, const model::CutJob& job, std::vector<model::EntryCandidate>& seq,
                        const ShopRules& r) {
  if (!r.part_rigidity) return 0;
  int corners = 0;
  // The first one-contour segment of each contour (a search through the segments per outer
  // contour was O(m^2) too).
  std::vector<int> segment_of(nest.contours.size(), -1);
  for (std::size_t j = job.segments.size(); j-- > 0;)
    if (job.segments[j].contours.size() == 1) segment_of[job.segments[j].contours.front().index()] = static_cast<int>(j);
  const std::vector<Vec2> centres = uncut_centres(nest, seq);
  for (std::size_t i = 0; i < seq.size(); ++i) {
    if (nest.contours[seq[i].contour].role != model::ContourRole::outer) continue;
    const int j = segment_of[seq[i].contour.index()];
    if (j < 0) continue;
    const Vec2 target = centres[i];
    const model::EntryCandidate* best = nullptr;
    for (const auto& e : job.segments[static_cast<std::size_t>(j)].candidates) {
      if (!e.corner || e.clockwise != seq[i].clockwise) continue;
      if (!best || geometry::distance(e.point, target) < geometry::distance(best->point, target) - tol::kSamePointMm) best = &e;
    }
    if (!best) continue;
    seq[i] = *best;
    ++corners;
  }
  return corners;
}

bool lead_in_after_tabs(const ShopRules& r, const nc::PostDialect& dialect) {
  if (r.tabs <= 0 || r.tab_lead_in == TabLeadIn::off) return false;
  return r.tab_lead_in == TabLeadIn::on || !nc::beam_switches_under_compensation(dialect);
}

double tab_clearance(nc::KerfMode mode, double kerf_mm) {
  return (mode == nc::KerfMode::controller ? 2 * kerf_mm : kerf_mm) + 1e-3;
}

nlohmann::json apply_to_toolpath(nc::Toolpath& path, const model::Nest& nest, const ShopRules& r, const StopToken& stop,
                                 const ToolpathContext& context) {
  nlohmann::json j;
  if (r.avoid_tip_up && r.tabs <= 0) {
    const nc::DetourStats st = nc::route_rapids_around_freed_parts(path, nest, r.tip_up_margin_mm, stop);
    j["tip_up_program"] = {{"rapids_over_freed_parts", st.rapids_over_freed},
                           {"detours", st.detours},
                           {"unavoidable", st.unavoidable},
                           {"unavoidable_search_budget_spent", st.over_budget},
                           {"unavoidable_left_at_time_limit", st.left_at_time_limit},
                           {"detour_extra_mm", st.extra_mm}};
  }
  if (r.tabs > 0) {
    nc::MicroJointOptions mj{r.tabs, r.tab_width_mm, {}, {}, context.tab_corner_clearance_mm};
    // Parts drawn edge to edge (or closer than the kerfs): a gap on the shared edge is cut away by
    // the neighbour's cut, so gaps move off such edges.
    mj.holds = [&](std::int32_t contour, const geometry::Contour& gap) {
      return !context.planner.near_other(model::ContourId(contour), gap, context.tab_clearance_mm);
    };
    const bool lead_ins = lead_in_after_tabs(r, context.dialect);
    // Straight lead-ins of the job's length, else of half of it where that is still longer than
    // a compensation entry move must be (EntryOptions::min_lead_mm): tight scrap between notches
    // or parts.
    std::vector<std::unique_ptr<model::EntryPlanner>> planners;
    for (double scale : {1.0, 0.5}) {
      model::EntryOptions straight = context.entries;
      straight.lead.in_kind = model::LeadKind::line;
      straight.lead.in_length_mm *= scale;
      if (lead_ins && (scale == 1.0 || straight.lead.in_length_mm > context.entries.min_lead_mm + 1e-3))
        planners.push_back(std::make_unique<model::EntryPlanner>(context.planner, straight));
    }
    // A straight lead-in at the point where the cut resumes, in its direction of travel: the
    // planner checks it as any entry (pierce in scrap, clearance from every other contour).
    if (lead_ins)
      mj.lead_in = [&](std::int32_t contour, const geometry::Contour& resumed) -> std::optional<geometry::Contour> {
        const model::ContourId id(contour);
        const model::EntryPlanner& any = *planners.front();
        const Vec2 at = resumed.vertices.front().p;
        const double s = any.closest(id, at).first, len = any.contour_length(id);
        // Travelling along the stored contour's orientation or against it: a point a little
        // further along the resumed cut is the contour's point a little ahead of s or behind it.
        const double d = std::min(0.05, geometry::length(resumed) / 4);
        const Vec2 next = geometry::point_at_length(resumed, d);
        const bool along = geometry::distance(next, any.point_at(id, std::fmod(s + d, len))) <
                           geometry::distance(next, any.point_at(id, std::fmod(s - d + len, len)));
        const bool stored_cw = geometry::orientation(nest.contours[id].source.contour) == geometry::Orientation::cw;
        for (const auto& planner : planners)
          if (auto e = planner->entry_at(id, s, along == stored_cw); e && e->lead_in.vertices.size() >= 2) return std::move(e->lead_in);
        return std::nullopt;
      };
    const nc::MicroJointStats st = nc::add_micro_joints(path, nest, mj);
    j["tabs"] = {{"per_outer_contour", r.tabs}, {"width_mm", r.tab_width_mm}, {"contours", st.contours},
                 {"tabs", st.tabs}, {"contours_too_short", st.skipped}, {"lead_in_after_tab", lead_ins},
                 {"lead_ins", st.lead_ins}, {"resumed_on_path", lead_ins ? st.on_path : st.tabs},
                 {"on_a_neighbours_cut", st.unheld}};
    if (!st.enclosed.empty()) {
      auto parts = nlohmann::json::array();
      for (const std::int32_t c : st.enclosed) parts.push_back(nest.contours[model::ContourId(c)].part.value() + 1);
      j["tabs"]["parts_without_skeleton_edge"] = std::move(parts);
    }
  }
  return j;
}

Diagnostics tab_warnings(const nlohmann::json& rules, const nc::Toolpath& path, bool entry_on_edge) {
  Diagnostics out;
  if (!rules.is_object() || !rules.contains("tabs")) return out;
  const nlohmann::json& tabs = rules["tabs"];
  const std::string of_all = " of " + std::to_string(tabs["tabs"].get<int>());
  if (const int n = tabs["resumed_on_path"].get<int>(); tabs["lead_in_after_tab"].get<bool>() && n > 0) {
    constexpr int kNamed = 5;
    std::string where;
    int named = 0;
    for (const auto& seg : path.segments)
      if (seg.after_tab && named++ < kNamed) where += (where.empty() ? "" : ", ") + seg.label;
    Diagnostic w = make_warning("micro-joints: " + std::to_string(n) + of_all +
                                " cuts after a tab resume on the contour, with no room in the scrap for a lead-in (" + where +
                                (named > kNamed ? ", ..." : "") + "): the pierce marks the part's edge there" +
                                (entry_on_edge ? ", and the compensation's entry move starts on it" : ""));
    w.code = "tabs.resumed_on_path";
    out.push_back(std::move(w));
  }
  if (const int n = tabs["on_a_neighbours_cut"].get<int>(); n > 0) {
    Diagnostic w = make_warning("micro-joints: " + std::to_string(n) + of_all +
                                " tabs lie where a neighbouring part's cut runs within the kerf of them (parts drawn edge to "
                                "edge): they hold nothing; --technique common cuts shared edges once and puts tabs elsewhere");
    w.code = "tabs.on_a_neighbours_cut";
    out.push_back(std::move(w));
  }
  if (tabs.contains("parts_without_skeleton_edge")) {
    std::string parts;
    for (const auto& k : tabs["parts_without_skeleton_edge"]) parts += (parts.empty() ? "" : ", ") + std::to_string(k.get<int>());
    Diagnostic w = make_warning("micro-joints: part(s) " + parts +
                                " share their whole outline with neighbours: no edge on the skeleton for a tab, nothing "
                                "holds them once their common lines are cut");
    w.code = "tabs.part_without_skeleton_edge";
    out.push_back(std::move(w));
  }
  return out;
}

nlohmann::json report(const ShopRules& r, const nlohmann::json& order, const nlohmann::json& toolpath, int corner_entries) {
  nlohmann::json j;
  auto active = nlohmann::json::array();
  nlohmann::json settings;
  if (r.heat_distance_mm > 0) {
    active.push_back("heat");
    settings["heat"] = {{"distance_mm", r.heat_distance_mm}, {"weight", r.heat_weight}, {"memory", r.heat_memory}};
  }
  if (r.avoid_tip_up) {
    active.push_back("tip_up");
    settings["tip_up"] = {{"weight", r.tip_up_weight}, {"margin_mm", r.tip_up_margin_mm}, {"held_by_tabs", r.tabs > 0}};
  }
  if (r.part_rigidity) active.push_back("part_rigidity");
  if (r.sheet_clamp) {
    active.push_back("sheet_rigidity");
    settings["sheet_rigidity"] = {{"clamp", to_string(*r.sheet_clamp)}, {"weight_per_mm", r.sheet_weight_per_mm},
                                  {"band_mm", r.sheet_band_mm}};
  }
  if (r.tabs > 0) {
    active.push_back("tabs");
    settings["tabs"] = {{"count", r.tabs}, {"width_mm", r.tab_width_mm}, {"lead_in", to_string(r.tab_lead_in)}};
  }
  j["active"] = active;
  j["settings"] = settings;
  if (order.contains("search")) j["search"] = order["search"];
  if (order.contains("route")) j["route"] = order["route"];
  if (r.part_rigidity) j["part_rigidity"] = {{"outer_contours_entered_at_a_corner", corner_entries}};
  for (auto it = toolpath.begin(); it != toolpath.end(); ++it) j[it.key()] = it.value();
  return j;
}

}  // namespace rules
}  // namespace cutroute::pipeline
