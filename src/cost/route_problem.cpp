#include <cutroute/cost/route_problem.hpp>

#include <cmath>
#include <memory>

#include <cutroute/core/units.hpp>
#include <cutroute/nc/toolpath.hpp>

namespace cutroute::cost {

double RoutePrices::cut_price(double mm) const {
  return objective == Objective::time ? mm / v_on_mm_s : mm * c_on_per_mm;
}
double RoutePrices::rapid_price(double mm) const {
  return objective == Objective::time ? mm / v_off_mm_s + head_s : mm * c_off_per_mm;
}
double RoutePrices::pierce_price() const { return objective == Objective::time ? pierce_s : c_pt; }

namespace {

solve::Cost to_ticks(double v) {
  const double t = v * static_cast<double>(units::kTicksPerSecond);
  // Values are never negative here; + 0.5 and truncation rounds like llround, several times faster.
  return static_cast<solve::Cost>(std::min(t, static_cast<double>(solve::kMaxCost)) + 0.5);
}

}  // namespace

double inner_price(const model::EntryCandidate& e, const RoutePrices& prices) {
  const double cut_mm = geometry::length(e.lead_in) + model::pieces_length(e) + geometry::length(e.lead_out);
  return prices.cut_price(cut_mm) + prices.pierce_price();
}

Result<RouteProblem> build_route_problem(const model::CutJob& job, const RoutePrices& prices,
                                         const RouteProblemOptions& options) {
  if (prices.objective == Objective::time && (!(prices.v_on_mm_s > 0) || !(prices.v_off_mm_s > 0)))
    return make_error("cutting and rapid speeds must be positive");
  RouteProblem rp;
  rp.returns_to_start = options.return_to_start;
  rp.nodes.push_back({-1, -1});
  rp.pierce.push_back(options.start);
  rp.tool_off.push_back(options.start);
  std::vector<solve::Cost> inner{0};
  std::vector<std::vector<solve::NodeId>> clusters{{solve::NodeId(0)}};
  for (std::size_t c = 0; c < job.segments.size(); ++c) {
    std::vector<solve::NodeId> members;
    const auto& cands = job.segments[c].candidates;
    if (cands.empty()) return make_error("basic segment " + std::to_string(c + 1) + " has no entry candidate");
    for (std::size_t k = 0; k < cands.size(); ++k) {
      const auto& e = cands[k];
      members.emplace_back(static_cast<std::int32_t>(rp.nodes.size()));
      rp.nodes.push_back({static_cast<std::int32_t>(c), static_cast<std::int32_t>(k)});
      rp.pierce.push_back(e.pierce);
      rp.tool_off.push_back(model::tool_off_point(e));
      inner.push_back(to_ticks(inner_price(e, prices)));
    }
    clusters.push_back(std::move(members));
  }
  const int n = static_cast<int>(rp.nodes.size());
  solve::ProblemBuilder b(n);
  b.set_name("cut job");
  for (auto& members : clusters) b.add_cluster(std::move(members));
  for (int v = 0; v < n; ++v) b.set_inner_cost(solve::NodeId(v), inner[static_cast<std::size_t>(v)]);
  b.set_start_cluster(solve::ClusterId(0));
  b.set_kind(options.return_to_start ? solve::RouteKind::closed_tour : solve::RouteKind::open_path);
  for (auto [a, c] : job.precedence) b.add_precedence(solve::ClusterId(a + 1), solve::ClusterId(c + 1));

  // A rapid's price is affine in its length: a + b·mm (computed once, not per call: the solver
  // asks for millions of arcs on large nests).
  const double a = prices.rapid_price(0.0), slope = prices.rapid_price(1.0) - a;
  if (n <= options.matrix_max_nodes) {
    auto arc = [&](int from, int to) {
      const geometry::Vec2 d = rp.pierce[static_cast<std::size_t>(to)] - rp.tool_off[static_cast<std::size_t>(from)];
      return to_ticks(a + slope * std::sqrt(d.x * d.x + d.y * d.y));
    };
    std::vector<solve::Cost> m(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (i != j) m[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)] = arc(i, j);
    b.set_cost_matrix(std::move(m));
  } else {
    // Same prices as the matrix (to_ticks of a + slope·mm), from the points on demand.
    solve::PlanarCosts pc;
    pc.out.reserve(rp.tool_off.size());
    pc.in.reserve(rp.pierce.size());
    for (const auto& q : rp.tool_off) pc.out.push_back({q.x, q.y});
    for (const auto& q : rp.pierce) pc.in.push_back({q.x, q.y});
    pc.base = a;
    pc.per_unit = slope;
    pc.scale = static_cast<double>(units::kTicksPerSecond);
    b.set_planar_costs(std::move(pc));
  }
  auto problem = b.build();
  if (!problem) return problem.error();
  rp.problem = std::move(problem).value();
  return rp;
}

std::vector<const model::EntryCandidate*> route_entries(const model::CutJob& job, const RouteProblem& rp,
                                                         const std::vector<solve::NodeId>& route) {
  std::vector<const model::EntryCandidate*> out;
  out.reserve(route.size());
  for (auto v : route) {
    const auto& node = rp.nodes[v.index()];
    if (node.segment < 0) continue;
    out.push_back(&job.segments[static_cast<std::size_t>(node.segment)].candidates[static_cast<std::size_t>(node.candidate)]);
  }
  return out;
}

}  // namespace cutroute::cost
