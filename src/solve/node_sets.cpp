#include "node_sets.hpp"

#include <algorithm>
#include <thread>

#include <cutroute/solve/heuristic.hpp>

#include "assignment.hpp"

namespace cutroute::solve::detail {

// Why: on the stacker-crane instances (GTSPLIB rbg) the assignment bound of a node set equals the best
// tour through it (89rbg443: 632 / 632 and 637 / 637 on the optimum's and on a stuck run's nodes), so
// the hard part is the node set, and a route search that keeps the order while it re-picks nodes
// (cluster optimisation) and the nodes while it reorders stalls in sets 3-7 clusters from the best.
// Scoring a node change by the re-solved assignment (O(m^2), a new node ordered anywhere) reaches a
// set of bound 632 from any start in 3-100 ms there.

// Not on symmetric matrices, where the bound is weak (it pairs nodes into 2-cycles), nor yet on
// cutting routes (inner costs), which were not measured. From 8 clusters (smaller ones go to the
// exact solver) to 400 (the search's matrix is m x m, each solve O(m^2)).
bool node_sets_apply(const Problem& p) {
  return p.has_matrix() && !p.has_inner_costs() && !p.has_precedence() && p.closed() && !p.symmetric() &&
         p.node_count() > p.cluster_count() && p.cluster_count() >= 8 && p.cluster_count() <= 400;
}

namespace {

// The assignment on `set` (one node per cluster, by cluster), solved from scratch.
void load(const Problem& p, const std::vector<NodeId>& set, Assignment& a) {
  const int m = p.cluster_count();
  a.reset(m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      a.at(i, j) = i == j ? Assignment::kBig
                          : p.arc_cost(set[static_cast<std::size_t>(i)], set[static_cast<std::size_t>(j)]);
  a.solve();
}

// The row and column a cluster gets when its node in `set` becomes v; its own entry is not used.
// Read straight from a matrix when there is one (through arc_cost() they were a third of the
// search's time). Forbidden arcs stay kForbiddenCost, below Assignment::kBig.
void row_and_column(const Problem& p, const std::vector<NodeId>& set, NodeId v, Cost* row, Cost* col) {
  const std::size_t n = static_cast<std::size_t>(p.node_count());
  if (const Cost* mat = p.matrix_data()) {
    const Cost* out = mat + v.index() * n;
    const Cost* in = mat + v.index();
    for (std::size_t j = 0; j < set.size(); ++j) {
      const std::size_t w = set[j].index();
      row[j] = out[w];
      col[j] = in[w * n];
    }
    return;
  }
  for (std::size_t j = 0; j < set.size(); ++j) row[j] = p.arc_cost(v, set[j]), col[j] = p.arc_cost(set[j], v);
}

class Search {
 public:
  Search(const Problem& p, const std::vector<NodeId>& route) : p_(&p), m_(p.cluster_count()) {
    set_.resize(static_cast<std::size_t>(m_));
    for (NodeId v : route) set_[p.cluster_of(v).index()] = v;
    load(p, set_, ap_);
    row_.resize(static_cast<std::size_t>(m_));
    col_.resize(static_cast<std::size_t>(m_));
  }

  Cost value() const { return ap_.value(); }
  const std::vector<NodeId>& nodes() const { return set_; }

  // First-improvement descent over single node changes, in full passes over the clusters. A change
  // whose bound (O(m)) cannot beat the current value is not solved (about 90 % of them on
  // 89rbg443), and a solve stops once it cannot beat it. Don't-look flags (re-examine only clusters
  // whose match changed, then one full pass) made each descent 3 times cheaper but the search much
  // weaker: 89rbg443 reached bound 632 in 5 of 20 searches against 20 of 20.
  void descend(const StopToken& stop) {
    while (pass() && !stop.stop_requested()) {
    }
  }

  void kick(Rng& rng) {
    const int k = 2 + static_cast<int>(rng.below(3));
    for (int r = 0; r < k; ++r) {
      const int c = static_cast<int>(rng.below(static_cast<std::uint64_t>(m_)));
      const auto nodes = p_->nodes_of(ClusterId(c));
      const NodeId v = nodes[rng.below(nodes.size())];
      if (v == set_[idx(c)]) continue;
      fill(v);
      ap_.replace(c, row_.data(), col_.data());
      set_[idx(c)] = v;
    }
  }

 private:
  static std::size_t idx(int c) { return static_cast<std::size_t>(c); }
  // One pass over all clusters; true when a change was kept.
  bool pass() {
    bool improved = false;
    for (int c = 0; c < m_; ++c)
      for (NodeId v : p_->nodes_of(ClusterId(c))) {
        if (v == set_[idx(c)]) continue;
        fill(v);
        if (ap_.bound_with(c, row_.data(), col_.data()) >= ap_.value()) continue;
        const Cost before = ap_.value();
        ap_.save(c, saved_);
        if (ap_.replace(c, row_.data(), col_.data(), before) && ap_.value() < before) {
          set_[idx(c)] = v;
          improved = true;
        } else {
          ap_.restore(c, saved_);
        }
      }
    return improved;
  }

  void fill(NodeId v) { row_and_column(*p_, set_, v, row_.data(), col_.data()); }

  const Problem* p_;
  int m_;
  std::vector<NodeId> set_;
  Assignment ap_;
  Assignment::Saved saved_;
  std::vector<Cost> row_, col_;
};

}  // namespace

NodeSet search_node_sets(const Problem& p, const std::vector<NodeId>& route, Rng& rng, int patience,
                         const StopToken& stop) {
  Search cur(p, route);
  cur.descend(stop);
  Search best = cur;
  for (int idle = 0; idle < patience && !stop.stop_requested(); ++idle) {
    cur.kick(rng);
    cur.descend(stop);
    if (cur.value() < best.value()) idle = -1;
    // Equal sets are taken too: the bound has wide plateaus (costs 0-24 on rbg).
    if (cur.value() <= best.value())
      best = cur;
    else
      cur = best;
  }
  return {best.nodes(), best.value()};
}

Problem restrict_to_nodes(const Problem& p, const std::vector<NodeId>& nodes) {
  const int m = p.cluster_count();
  ProblemBuilder b(m);
  std::vector<Cost> mat(static_cast<std::size_t>(m) * static_cast<std::size_t>(m), 0);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      if (i != j)
        mat[static_cast<std::size_t>(i) * static_cast<std::size_t>(m) + static_cast<std::size_t>(j)] =
            p.arc_cost(nodes[static_cast<std::size_t>(i)], nodes[static_cast<std::size_t>(j)]);
  b.set_cost_matrix(std::move(mat));
  for (int c = 0; c < m; ++c) {
    b.add_cluster({NodeId(c)});
    const Cost inner = p.inner_cost(nodes[static_cast<std::size_t>(c)]);
    if (inner != 0) b.set_inner_cost(NodeId(c), inner);
  }
  b.set_start_cluster(p.start_cluster());
  b.set_kind(p.kind());
  b.set_name(p.name());
  return std::move(b.build().value());
}

std::vector<NodeId> node_set_start(const Problem& p, int threads, Rng& rng, const StopToken& stop) {
  // Search patience: on 89rbg443 searches reached bound 632 in 13 of 20 with 100 rounds, 20 of 20
  // with 200 (0.1 s each); every one of 25 runs ended at 632 with 300.
  constexpr int kPatience = 300;
  const auto count = static_cast<std::size_t>(std::max(1, threads));
  std::vector<Rng> rngs;
  for (std::size_t t = 0; t < count; ++t) rngs.push_back(rng.split());
  std::vector<NodeSet> sets(count);
  auto run = [&](std::size_t t) {
    const std::vector<NodeId> route = construct_route(p, rngs[t]);
    sets[t] = search_node_sets(p, route, rngs[t], kPatience, stop);
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < count; ++t) pool.emplace_back(run, t);
  run(0);
  for (auto& th : pool) th.join();
  if (stop.stop_requested()) return {};
  const auto best = std::min_element(sets.begin(), sets.end(),
                                     [](const NodeSet& a, const NodeSet& b) { return a.bound < b.bound; });
  const Problem sub = restrict_to_nodes(p, best->nodes);
  SolveParams sp;
  sp.threads = static_cast<int>(count);
  sp.seed = rng.next();
  sp.time_limit_s = 0;
  sp.target_cost = best->bound;
  // Stagnation by rounds only: the default minimum work kept a 10-node restricted problem (10ry48p,
  // bound far below any tour) busy for 0.3 s. 18 rounds: 89rbg443's restricted problem reached 632
  // in 30 of 30 seeds with 30 rounds (6 rounds: 27 of 30); with 18, seeds 1-70 of 65rbg323,
  // 81rbg403 and 89rbg443 all end at their best known, as with 30, and where the bound is not tight
  // (81rbg403: 1 166 against 1 170; 65rbg323: 470 against 471) the wasted rounds go: their runs
  // take 13-18 % less CPU.
  sp.min_stagnation_work = 0;
  sp.stagnation_rounds = 18;
  const Solution r = solve_heuristic(sub, sp, stop, {});
  std::vector<NodeId> route;
  for (NodeId v : r.route) route.push_back(best->nodes[v.index()]);
  return route;
}

}  // namespace cutroute::solve::detail

namespace cutroute::solve {

NodeSetResult node_set_search(const Problem& p, const std::vector<NodeId>& route, std::uint64_t seed,
                              int patience) {
  Rng rng(seed);
  const detail::NodeSet s = detail::search_node_sets(p, route, rng, patience, StopToken());
  return {s.nodes, s.bound};
}

Cost assignment_bound(const Problem& p, const std::vector<NodeId>& nodes) {
  detail::Assignment a;
  detail::load(p, nodes, a);
  return a.value();
}

std::vector<std::pair<Cost, Cost>> assignment_bounds_after(
    const Problem& p, std::vector<NodeId> nodes, const std::vector<std::pair<ClusterId, NodeId>>& changes) {
  detail::Assignment a;
  detail::load(p, nodes, a);
  std::vector<Cost> row(nodes.size()), col(nodes.size());
  std::vector<std::pair<Cost, Cost>> out;
  for (auto [c, v] : changes) {
    nodes[c.index()] = v;
    detail::row_and_column(p, nodes, v, row.data(), col.data());
    const Cost skip = a.bound_with(c.value(), row.data(), col.data());
    a.replace(c.value(), row.data(), col.data());
    out.emplace_back(skip, a.value());
  }
  return out;
}

}  // namespace cutroute::solve
