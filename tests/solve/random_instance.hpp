// Random small solver instances for the tests, and an exhaustive reference solver written
// independently of solve/ (enumerates cluster orders, exact node choice per order).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/solve/problem.hpp>

namespace cutroute::test {

struct RandomSpec {
  int clusters = 5;
  int max_nodes = 3;   // nodes per cluster drawn in [1, max_nodes]
  bool symmetric = true;
  bool closed = true;
  int precedence_pairs = 0;
  int forbidden_arcs = 0;
  bool inner_costs = false;
  // Adds an independent draw in [0, asym_noise) to every arc of a symmetric spec: a nearly
  // symmetric asymmetric matrix (like SOP prob.100 or kro124p).
  int asym_noise = 0;
  // Node ids dealt to clusters in random order instead of consecutively (like GTSPLIB, whose
  // clusters are scattered over the node numbering).
  bool scatter_nodes = false;
};

inline solve::Problem random_problem(const RandomSpec& s, Rng& rng) {
  using namespace solve;
  std::vector<std::vector<NodeId>> clusters;
  int n = 0;
  for (int c = 0; c < s.clusters; ++c) {
    const int k = 1 + static_cast<int>(rng.below(static_cast<std::uint64_t>(s.max_nodes)));
    clusters.emplace_back();
    for (int j = 0; j < k; ++j) clusters.back().push_back(NodeId(n++));
  }
  if (s.scatter_nodes) {
    std::vector<int> perm(static_cast<std::size_t>(n));
    for (int v = 0; v < n; ++v) perm[static_cast<std::size_t>(v)] = v;
    rng.shuffle(perm.begin(), perm.end());
    for (auto& c : clusters)
      for (NodeId& v : c) v = NodeId(perm[v.index()]);
  }
  const auto un = static_cast<std::size_t>(n);
  std::vector<Cost> m(un * un, 0);
  if (s.symmetric) {
    std::vector<double> x(un), y(un);
    for (std::size_t i = 0; i < un; ++i) x[i] = static_cast<double>(rng.below(1000)), y[i] = static_cast<double>(rng.below(1000));
    for (std::size_t i = 0; i < un; ++i)
      for (std::size_t j = 0; j < un; ++j)
        m[i * un + j] = static_cast<Cost>(std::hypot(x[i] - x[j], y[i] - y[j]) + 0.5) +
                        (s.asym_noise > 0 && i != j ? static_cast<Cost>(rng.below(static_cast<std::uint64_t>(s.asym_noise))) : 0);
  } else {
    for (auto& v : m) v = static_cast<Cost>(rng.below(1000));
  }
  ProblemBuilder b(n);
  for (auto& c : clusters) b.add_cluster(c);
  b.set_cost_matrix(std::move(m));
  b.set_kind(s.closed ? RouteKind::closed_tour : RouteKind::open_path);
  const int start = static_cast<int>(rng.below(static_cast<std::uint64_t>(s.clusters)));
  b.set_start_cluster(ClusterId(start));
  if (s.inner_costs)
    for (int v = 0; v < n; ++v) b.set_inner_cost(NodeId(v), static_cast<Cost>(rng.below(300)));
  // Precedence from a random hidden order: always acyclic, never before the start cluster.
  std::vector<int> order;
  for (int c = 0; c < s.clusters; ++c)
    if (c != start) order.push_back(c);
  rng.shuffle(order.begin(), order.end());
  for (int k = 0; k < s.precedence_pairs && order.size() >= 2; ++k) {
    auto i = rng.below(order.size() - 1);
    auto j = i + 1 + rng.below(order.size() - 1 - i);
    b.add_precedence(ClusterId(order[i]), ClusterId(order[j]));
  }
  for (int k = 0; k < s.forbidden_arcs; ++k)
    b.forbid_arc(NodeId(static_cast<int>(rng.below(un))), NodeId(static_cast<int>(rng.below(un))));
  return std::move(b.build()).value();
}

// The k-th spec of the mixed 300-instance sets (exact_vs_brute_test, lower_bound_test): 2-8
// clusters of 1-5 nodes, symmetric or not, closed or open, with or without precedence, inner costs
// and forbidden arcs, each kind on its own period of k.
inline RandomSpec mixed_spec(int k, Rng& rng) {
  RandomSpec spec;
  spec.clusters = 2 + static_cast<int>(rng.below(7));  // 2..8
  spec.max_nodes = 1 + static_cast<int>(rng.below(5));  // 1..5
  spec.symmetric = k % 2 == 0;
  spec.closed = k % 3 != 0;
  spec.precedence_pairs = (k / 2) % 2 == 0 ? 0 : 1 + static_cast<int>(rng.below(6));
  spec.inner_costs = k % 5 == 0;
  spec.forbidden_arcs = k % 7 == 0 ? 3 : 0;
  return spec;
}

// Exhaustive optimum: every permutation of the non-start clusters that keeps precedence, with the
// best node choice for that order by a shortest path over (layer, node). Returns max() if infeasible.
inline solve::Cost brute_force(const solve::Problem& p) {
  using namespace solve;
  constexpr Cost kInf = std::numeric_limits<Cost>::max();
  std::vector<int> rest;
  for (int c = 0; c < p.cluster_count(); ++c)
    if (ClusterId(c) != p.start_cluster()) rest.push_back(c);
  Cost best = kInf;
  auto arc = [&](NodeId a, NodeId b) -> Cost { return p.forbidden(a, b) ? kInf : p.arc_cost(a, b); };
  auto add = [](Cost a, Cost b) { return a == kInf || b == kInf ? kInf : a + b; };
  do {
    bool ok = true;
    for (auto [a, b] : p.precedence()) {
      const auto pa = std::find(rest.begin(), rest.end(), a.value()) - rest.begin();
      const auto pb = std::find(rest.begin(), rest.end(), b.value()) - rest.begin();
      if (a == p.start_cluster()) continue;
      if (pa > pb) ok = false;
    }
    if (!ok) continue;
    for (NodeId s : p.nodes_of(p.start_cluster())) {
      std::vector<std::pair<NodeId, Cost>> layer{{s, p.inner_cost(s)}};
      for (int c : rest) {
        std::vector<std::pair<NodeId, Cost>> next;
        for (NodeId v : p.nodes_of(ClusterId(c))) {
          Cost bv = kInf;
          for (auto [u, cu] : layer) bv = std::min(bv, add(add(cu, arc(u, v)), p.inner_cost(v)));
          next.emplace_back(v, bv);
        }
        layer.swap(next);
      }
      for (auto [u, cu] : layer) {
        Cost total = cu;
        if (p.closed() && !rest.empty()) total = add(total, arc(u, s));
        best = std::min(best, total);
      }
    }
  } while (std::next_permutation(rest.begin(), rest.end()));
  return best;
}

}  // namespace cutroute::test
