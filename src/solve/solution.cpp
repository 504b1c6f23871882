#include <cutroute/solve/solution.hpp>

#include <string>

namespace cutroute::solve {

const char* to_string(SolveStatus s) {
  switch (s) {
    case SolveStatus::optimal: return "optimal";
    case SolveStatus::feasible: return "feasible";
    case SolveStatus::infeasible: return "infeasible";
    case SolveStatus::no_solution: return "no_solution";
  }
  return "?";
}

Cost route_cost(const Problem& p, std::span<const NodeId> route) {
  if (route.empty()) return 0;
  Cost total = p.inner_cost(route[0]);
  for (std::size_t i = 1; i < route.size(); ++i) total += p.arc_cost(route[i - 1], route[i]) + p.inner_cost(route[i]);
  if (p.closed() && route.size() > 1) total += p.arc_cost(route.back(), route.front());
  return total;
}

bool uses_forbidden_arc(const Problem& p, std::span<const NodeId> route) {
  for (std::size_t i = 0; i + 1 < route.size(); ++i)
    if (p.forbidden(route[i], route[i + 1])) return true;
  return p.closed() && route.size() > 1 && p.forbidden(route.back(), route.front());
}

std::vector<std::string> validate(const Problem& p, const Solution& s) {
  std::vector<std::string> errors;
  const int m = p.cluster_count();
  const auto& r = s.route;
  if (static_cast<int>(r.size()) != m)
    errors.push_back("route has " + std::to_string(r.size()) + " nodes, the problem has " + std::to_string(m) + " clusters");
  std::vector<int> pos(static_cast<std::size_t>(m), -1);
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (!r[i].valid() || r[i].value() >= p.node_count()) {
      errors.push_back("route position " + std::to_string(i) + " holds node " + std::to_string(r[i].value()) + " outside the problem");
      return errors;
    }
    const ClusterId c = p.cluster_of(r[i]);
    if (pos[c.index()] >= 0)
      errors.push_back("cluster " + std::to_string(c.value()) + " visited twice (positions " + std::to_string(pos[c.index()]) +
                       " and " + std::to_string(i) + ")");
    else pos[c.index()] = static_cast<int>(i);
  }
  for (int c = 0; c < m; ++c)
    if (pos[c] < 0) errors.push_back("cluster " + std::to_string(c) + " is not visited");
  if (!r.empty() && p.cluster_of(r[0]) != p.start_cluster())
    errors.push_back("route starts in cluster " + std::to_string(p.cluster_of(r[0]).value()) + ", not in the start cluster " +
                     std::to_string(p.start_cluster().value()));
  // Checking the closure, not only the given pairs, so a bug in the closure itself cannot hide a violation.
  for (auto [a, b] : p.precedence())
    if (pos[a.index()] >= 0 && pos[b.index()] >= 0 && pos[a.index()] > pos[b.index()])
      errors.push_back("precedence violated: cluster " + std::to_string(a.value()) + " must come before cluster " + std::to_string(b.value()));
  for (int b = 0; b < m; ++b)
    for (ClusterId a : p.all_before(ClusterId(b)))
      if (pos[a.index()] >= 0 && pos[b] >= 0 && pos[a.index()] > pos[b])
        errors.push_back("transitive precedence violated: cluster " + std::to_string(a.value()) + " before " + std::to_string(b));
  for (std::size_t i = 0; i + 1 < r.size(); ++i)
    if (p.forbidden(r[i], r[i + 1]))
      errors.push_back("forbidden arc " + std::to_string(r[i].value()) + " -> " + std::to_string(r[i + 1].value()));
  if (p.closed() && r.size() > 1 && p.forbidden(r.back(), r.front()))
    errors.push_back("forbidden closing arc " + std::to_string(r.back().value()) + " -> " + std::to_string(r.front().value()));
  const Cost recomputed = route_cost(p, r);
  if (recomputed != s.cost)
    errors.push_back("reported cost " + std::to_string(s.cost) + " differs from recomputed cost " + std::to_string(recomputed));
  if (s.lower_bound && *s.lower_bound > s.cost && !r.empty())
    errors.push_back("lower bound " + std::to_string(*s.lower_bound) + " exceeds the route cost " + std::to_string(s.cost));
  return errors;
}

}  // namespace cutroute::solve
