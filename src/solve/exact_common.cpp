#include "exact_common.hpp"

#include <algorithm>

#include <cutroute/solve/lower_bound.hpp>

namespace cutroute::solve::detail {

DpLayout dp_layout(const Problem& p, ClusterId start) {
  DpLayout L;
  L.start = start;
  L.bit_of.assign(static_cast<std::size_t>(p.cluster_count()), -1);
  for (int c = 0; c < p.cluster_count(); ++c) {
    if (ClusterId(c) == start) continue;
    L.bit_of[static_cast<std::size_t>(c)] = L.mp++;
    L.cluster.push_back(ClusterId(c));
    L.first.push_back(L.np);
    L.size.push_back(p.cluster_size(ClusterId(c)));
    for (NodeId v : p.nodes_of(ClusterId(c))) {
      L.node.push_back(v);
      L.bit_of_local.push_back(L.mp - 1);
      ++L.np;
    }
  }
  return L;
}

std::vector<Cost> dp_local_steps(const Problem& p, const DpLayout& L) {
  const auto unp = static_cast<std::size_t>(L.np);
  std::vector<Cost> w(unp * unp);
  for (std::size_t i = 0; i < unp; ++i)
    for (std::size_t j = 0; j < unp; ++j) {
      const Cost c = L.bit_of_local[i] == L.bit_of_local[j] ? kForbiddenCost : p.step(L.node[i], L.node[j]);
      w[i * unp + j] = c >= kForbiddenCost ? kDpInf : c;
    }
  return w;
}

std::vector<Cost> dp_min_in(const Problem& p, const DpLayout& L) {
  std::vector<Cost> min_in(static_cast<std::size_t>(L.mp), kDpInf);
  for (std::size_t b = 0; b < min_in.size(); ++b)
    for (int j = L.first[b]; j < L.first[b] + L.size[b]; ++j)
      for (int u = 0; u < p.node_count(); ++u)
        if (p.cluster_of(NodeId(u)) != L.cluster[b]) min_in[b] = std::min(min_in[b], p.step(NodeId(u), L.node[static_cast<std::size_t>(j)]));
  return min_in;
}

Cost dp_sum(const std::vector<Cost>& min_in) {
  Cost sum = 0;
  for (Cost c : min_in) sum = std::min(kDpInf, sum + c);
  return sum;
}

Cost dp_closing_lb(const Problem& p, const DpLayout& L, NodeId s) {
  if (!p.closed() || L.mp == 0) return 0;
  Cost best = kDpInf;
  for (NodeId v : L.node) best = std::min(best, p.arc_cost(v, s));
  return best >= kForbiddenCost ? kDpInf : best;
}

Cost dp_take_incumbent(const Problem& p, const Solution* incumbent, Solution& out) {
  out.stats.solver = "exact";
  if (!incumbent || incumbent->route.empty() || uses_forbidden_arc(p, incumbent->route)) return kDpInf;
  out.route = incumbent->route;
  out.cost = incumbent->cost;
  out.status = SolveStatus::feasible;
  return incumbent->cost;
}

DpPotentials dp_potentials(const Problem& p, const DpLayout& L, const StopToken& stop) {
  DpPotentials d;
  const auto pot = assignment_potentials(p, stop);
  if (!pot) return d;
  d.ok = true;
  d.row.resize(static_cast<std::size_t>(L.mp));
  d.rc.resize(static_cast<std::size_t>(L.mp));
  for (std::size_t b = 0; b < d.row.size(); ++b) {
    const auto c = L.cluster[b].index();
    d.row[b] = pot->row[c];
    d.rc[b] = pot->row[c] + pot->col[c];
    d.all += d.rc[b];
  }
  d.all += pot->col[L.start.index()];
  d.min_inner_start = kDpInf;
  for (NodeId s : p.nodes_of(L.start)) d.min_inner_start = std::min(d.min_inner_start, p.inner_cost(s));
  return d;
}

void dp_progress(const ProgressFn& progress, double done, std::size_t start_nodes, Cost ub) {
  if (!progress) return;
  ProgressEvent e{"exact", std::min(1.0, done / static_cast<double>(std::max<std::size_t>(1, start_nodes))), std::nullopt};
  if (ub < kDpInf) e.best = static_cast<double>(ub);
  progress(e);
}

Solution dp_single_cluster(const Problem& p, ClusterId start, Solution& out) {
  const auto nodes = p.nodes_of(start);
  NodeId arg = nodes[0];
  for (NodeId s : nodes)
    if (p.inner_cost(s) < p.inner_cost(arg)) arg = s;
  out.route = {arg};
  out.cost = p.inner_cost(arg);
  out.status = SolveStatus::optimal;
  out.lower_bound = out.cost;
  return out;
}

Cost dp_keep_route(Solution& out, std::vector<NodeId>& rev, NodeId s, Cost cost) {
  rev.push_back(s);
  out.route.assign(rev.rbegin(), rev.rend());
  out.cost = cost;
  out.status = SolveStatus::feasible;
  return cost;
}

Solution dp_proven(Solution& out) {
  if (out.route.empty()) {
    out.status = SolveStatus::infeasible;
  } else {
    out.status = SolveStatus::optimal;
    out.lower_bound = out.cost;
  }
  return out;
}

}  // namespace cutroute::solve::detail
