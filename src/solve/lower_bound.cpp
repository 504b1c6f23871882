#include <cutroute/solve/lower_bound.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "assignment.hpp"
#include "planar_neighbours.hpp"
#include "planar_rows.hpp"

namespace cutroute::solve {

namespace {

constexpr int kMaxClusters = 1500;
constexpr int kMaxNodes = 12000;
constexpr Cost kNo = kForbiddenCost;  // a cluster arc no route can use
constexpr double kTwoCycleShare = 0.2;  // see route_lower_bound()

// Cheapest steps (arc + inner cost of the head) and cheapest arcs between clusters, m x m,
// kNo on the diagonal and where precedence rules an arc out (see the header).
struct ClusterGraph {
  int m = 0;
  std::vector<Cost> step, arc;
  Cost at(const std::vector<Cost>& v, int a, int b) const { return v[static_cast<std::size_t>(a) * static_cast<std::size_t>(m) + static_cast<std::size_t>(b)]; }
  Cost& at(std::vector<Cost>& v, int a, int b) { return v[static_cast<std::size_t>(a) * static_cast<std::size_t>(m) + static_cast<std::size_t>(b)]; }
};

bool build_graph(const Problem& p, const StopToken& stop, ClusterGraph& g) {
  const int m = p.cluster_count(), n = p.node_count();
  g.m = m;
  const auto mm = static_cast<std::size_t>(m) * static_cast<std::size_t>(m);
  g.step.assign(mm, kNo);
  g.arc.assign(mm, kNo);
  const int s0 = p.start_cluster().value();
  // Each node's cheapest arc and step into every other cluster: u's arcs to every node, in cluster
  // order, then the minima over each cluster's contiguous run. The row is read from the matrix,
  // priced against every node in one vectorised batch on planar costs (planar_rows.cpp, the same
  // ticks as Problem::planar_arc), or asked of arc_cost() otherwise. Forbidden arcs cost at least
  // kNo, so the minima need no test. Arc by arc through arc_cost()'s dispatch with an update of
  // both tables per arc, a 4 300-node nest (vrs_Lv10_SHEET_004) took 0.13 s; the planar graph of
  // d2g_DRAAK's 7 500 nodes priced one arc at a time, 0.2 s.
  const auto un = static_cast<std::size_t>(n);
  std::vector<NodeId> order;  // the nodes by cluster
  std::vector<std::size_t> begin{0};
  order.reserve(un);
  for (int c = 0; c < m; ++c) {
    for (NodeId v : p.nodes_of(ClusterId(c))) order.push_back(v);
    begin.push_back(order.size());
  }
  std::vector<Cost> slot_inner(un), prices(un);
  for (std::size_t j = 0; j < un; ++j) slot_inner[j] = p.inner_cost(order[j]);
  std::vector<double> xs, ys;  // planar entry points, in `order`
  const PlanarCosts* const pc = p.plain_planar() ? p.planar() : nullptr;
  if (pc)
    for (NodeId v : order) xs.push_back(pc->in[v.index()].x), ys.push_back(pc->in[v.index()].y);
  const Cost* const mat = p.matrix_data();
  for (int ui = 0; ui < n; ++ui) {
    if ((ui & 63) == 0 && stop.stop_requested()) return false;
    const NodeId u(ui);
    if (mat) {
      const Cost* r = mat + u.index() * un;
      for (std::size_t j = 0; j < un; ++j) prices[j] = r[order[j].index()];
    } else if (pc) {
      detail::planar_row(*pc, pc->out[u.index()], xs.data(), ys.data(), un, prices.data());
    } else {
      for (std::size_t j = 0; j < un; ++j) prices[j] = p.arc_cost(u, order[j]);
    }
    const int cu = p.cluster_of(u).value();
    for (int cv = 0; cv < m; ++cv) {
      if (cv == cu) continue;
      Cost best_step = kNo, best_arc = kNo;
      for (std::size_t j = begin[static_cast<std::size_t>(cv)]; j < begin[static_cast<std::size_t>(cv) + 1]; ++j) {
        best_step = std::min(best_step, prices[j] + slot_inner[j]);
        best_arc = std::min(best_arc, prices[j]);
      }
      Cost& st = g.at(g.step, cu, cv);
      st = std::min(st, best_step);
      Cost& ar = g.at(g.arc, cu, cv);
      ar = std::min(ar, best_arc);
    }
  }
  if (!p.closed()) {
    // The free closing arc of an open path: entering the start cluster costs its cheapest inner cost.
    Cost inner = kNo;
    for (NodeId s : p.nodes_of(ClusterId(s0))) inner = std::min(inner, p.inner_cost(s));
    for (int a = 0; a < m; ++a)
      if (a != s0) g.at(g.step, a, s0) = inner, g.at(g.arc, a, s0) = 0;
  }
  if (!p.has_precedence()) return true;
  // Transitive precedence as bit rows, the start cluster left out (it is first anyway).
  const std::size_t words = (static_cast<std::size_t>(m) + 63) / 64;
  std::vector<std::uint64_t> after(static_cast<std::size_t>(m) * words, 0), before(after.size(), 0);
  auto set = [&](std::vector<std::uint64_t>& bits, int row, int c) {
    bits[static_cast<std::size_t>(row) * words + static_cast<std::size_t>(c) / 64] |= std::uint64_t{1} << (c % 64);
  };
  std::vector<char> has_pred(static_cast<std::size_t>(m), 0), has_succ(static_cast<std::size_t>(m), 0);
  for (int c = 0; c < m; ++c) {
    for (ClusterId x : p.all_after(ClusterId(c)))
      if (x.value() != s0) set(after, c, x.value()), has_succ[static_cast<std::size_t>(c)] = 1;
    for (ClusterId x : p.all_before(ClusterId(c)))
      if (x.value() != s0) set(before, c, x.value()), has_pred[static_cast<std::size_t>(c)] = 1;
  }
  for (int a = 0; a < m; ++a) {
    if (stop.stop_requested()) return false;
    for (int b = 0; b < m; ++b) {
      if (a == b) continue;
      bool no = false;
      if (a == s0) no = has_pred[static_cast<std::size_t>(b)] != 0;
      else if (b == s0) no = has_succ[static_cast<std::size_t>(a)] != 0;
      else if (p.must_precede(ClusterId(b), ClusterId(a))) no = true;
      else
        for (std::size_t w = 0; w < words && !no; ++w)
          no = (after[static_cast<std::size_t>(a) * words + w] & before[static_cast<std::size_t>(b) * words + w]) != 0;
      if (no) g.at(g.step, a, b) = kNo, g.at(g.arc, a, b) = kNo;
    }
  }
  return true;
}

// The assignment on the cluster graph's steps; false when it needs an unusable arc (no cycle cover).
bool solve_assignment(const ClusterGraph& g, detail::Assignment& ap) {
  ap.reset(g.m);
  for (int a = 0; a < g.m; ++a)
    for (int b = 0; b < g.m; ++b) {
      const Cost c = g.at(g.step, a, b);
      ap.at(a, b) = a == b || c >= kNo ? detail::Assignment::kBig : c;
    }
  ap.solve_reduced();
  return ap.value() < kForbiddenCost;
}

// The assignment bound, and the share of clusters its cycle cover pairs into 2-cycles.
std::optional<Cost> assignment_bound(const ClusterGraph& g, double& two_cycle_share) {
  detail::Assignment ap;
  two_cycle_share = 0.0;
  if (!solve_assignment(g, ap)) return std::nullopt;
  int paired = 0;
  for (int a = 0; a < g.m; ++a)
    if (const int b = ap.col_of(a); b >= 0 && ap.col_of(b) == a) ++paired;
  two_cycle_share = static_cast<double>(paired) / g.m;
  return ap.value();
}

// A tour of the cluster graph (nearest neighbour from the root, then 2-opt), the ascent's target:
// the cluster graph's optimum lies far below a real route, and Polyak steps aimed at a route's cost
// overshoot (53pr264: 22 835 against 23 607 with this target).
double cluster_tour(const std::vector<double>& c, int m, int root) {
  const auto um = static_cast<std::size_t>(m);
  std::vector<int> t{root};
  std::vector<char> used(um, 0);
  used[static_cast<std::size_t>(root)] = 1;
  for (int k = 1; k < m; ++k) {
    const int u = t.back();
    int best = -1;
    for (int v = 0; v < m; ++v)
      if (!used[static_cast<std::size_t>(v)] && (best < 0 || c[static_cast<std::size_t>(u) * um + static_cast<std::size_t>(v)] < c[static_cast<std::size_t>(u) * um + static_cast<std::size_t>(best)])) best = v;
    used[static_cast<std::size_t>(best)] = 1;
    t.push_back(best);
  }
  auto d = [&](int a, int b) { return c[static_cast<std::size_t>(t[static_cast<std::size_t>(a)]) * um + static_cast<std::size_t>(t[static_cast<std::size_t>(b % m)])]; };
  for (int pass = 0; pass < 50; ++pass) {
    bool improved = false;
    for (int i = 0; i + 2 < m; ++i)
      for (int j = i + 2; j < m; ++j) {
        if (i == 0 && j == m - 1) continue;
        if (d(i, i + 1) + d(j, j + 1) > d(i, j) + d(i + 1, j + 1) + 1e-9) {
          std::reverse(t.begin() + i + 1, t.begin() + j + 1);
          improved = true;
        }
      }
    if (!improved) break;
  }
  double len = 0.0;
  for (int i = 0; i < m; ++i) len += d(i, i + 1);
  return len;
}

long long one_tree_steps(int m) {
  return std::clamp<long long>(30'000'000LL / (static_cast<long long>(m) * m), 50, 1000);
}

// Held–Karp: for node potentials pi, the cheapest 1-tree (a spanning tree of the clusters but the
// root, plus the root's two cheapest edges) under costs c(a, b) + pi(a) + pi(b), minus 2 sum pi, is
// below every tour; subgradient steps pi += t (degree - 2) raise it.
std::optional<Cost> held_karp_bound(const ClusterGraph& g, int root, Cost upper, const StopToken& stop) {
  const int m = g.m;
  if (m < 3) return std::nullopt;
  const auto um = static_cast<std::size_t>(m);
  constexpr double kUnusable = 1e15;
  std::vector<double> c(um * um);
  // Each edge at the cheaper of its two usable directions: a route passes it one way, so this
  // relaxes every problem to a symmetric one (on symmetric matrices it changes nothing).
  for (std::size_t a = 0; a < um; ++a)
    for (std::size_t b = 0; b < um; ++b) {
      const Cost e = std::min(g.arc[a * um + b], g.arc[b * um + a]);
      c[a * um + b] = e >= kNo ? kUnusable : static_cast<double>(e);
    }
  std::vector<double> pi(um, 0.0), key(um);
  std::vector<int> deg(um), parent(um), outside;
  outside.reserve(um);
  const double tour = cluster_tour(c, m, root);
  const double target = std::min(tour, upper < kMaxCost ? static_cast<double>(upper) : tour);
  double best = -1e300;
  double lambda = 2.0;
  int since_best = 0;
  const long long max_steps = one_tree_steps(m);
  for (long long it = 0; it < max_steps && lambda > 1e-4; ++it) {
    if ((it & 15) == 0 && stop.stop_requested()) break;
    // Prim on every cluster but the root, O(m^2): one pass over the clusters still outside the tree
    // (kept in ascending order, so ties go to the lowest index) updates their keys from the cluster
    // just added and finds the next one. Two passes over all clusters per step took 0.3 s of the
    // bound's 1.5 s on a 1 187-contour nest (d2g_DRAAK).
    std::fill(deg.begin(), deg.end(), 0);
    outside.clear();
    for (int v = 0; v < m; ++v)
      if (v != root) outside.push_back(v);
    std::fill(key.begin(), key.end(), 1e300);
    const int first = outside.front();
    key[static_cast<std::size_t>(first)] = 0.0;
    parent[static_cast<std::size_t>(first)] = -1;
    double w = 0.0;
    std::size_t next = 0;  // index in `outside` of the cheapest cluster to add
    while (!outside.empty()) {
      const int u = outside[next];
      outside.erase(outside.begin() + static_cast<std::ptrdiff_t>(next));
      w += key[static_cast<std::size_t>(u)];
      if (parent[static_cast<std::size_t>(u)] >= 0) ++deg[static_cast<std::size_t>(u)], ++deg[static_cast<std::size_t>(parent[static_cast<std::size_t>(u)])];
      const double* cu = &c[static_cast<std::size_t>(u) * um];
      const double pu = pi[static_cast<std::size_t>(u)];
      double best_key = 0.0;
      for (std::size_t i = 0; i < outside.size(); ++i) {
        const auto v = static_cast<std::size_t>(outside[i]);
        const double kv = cu[v] + pu + pi[v];
        if (kv < key[v]) key[v] = kv, parent[v] = u;
        if (i == 0 || key[v] < best_key) best_key = key[v], next = i;
      }
    }
    // The root's two cheapest edges.
    int e1 = -1, e2 = -1;
    auto root_cost = [&](int v) { return c[static_cast<std::size_t>(root) * um + static_cast<std::size_t>(v)] + pi[static_cast<std::size_t>(v)]; };
    for (int v = 0; v < m; ++v) {
      if (v == root) continue;
      if (e1 < 0 || root_cost(v) < root_cost(e1)) e2 = e1, e1 = v;
      else if (e2 < 0 || root_cost(v) < root_cost(e2)) e2 = v;
    }
    w += root_cost(e1) + root_cost(e2);
    ++deg[static_cast<std::size_t>(e1)], ++deg[static_cast<std::size_t>(e2)];
    deg[static_cast<std::size_t>(root)] = 2;
    double sum_pi = 0.0;
    for (double x : pi) sum_pi += x;
    w -= 2.0 * sum_pi;
    if (w > best) best = w, since_best = 0;
    else if (++since_best >= 20) lambda *= 0.5, since_best = 0;
    long long norm = 0;
    for (int d : deg) norm += static_cast<long long>(d - 2) * (d - 2);
    if (norm == 0) break;  // the 1-tree is a tour: nothing above it
    if (best >= target - 1e-9) break;
    const double t = lambda * (target - w) / static_cast<double>(norm);
    for (std::size_t v = 0; v < um; ++v) pi[v] += t * (deg[v] - 2);
    pi[static_cast<std::size_t>(root)] = 0.0;
  }
  if (best >= static_cast<double>(kForbiddenCost) || best < 0.0) return std::nullopt;
  // Integer routes: round up, after a margin for the sums' rounding errors.
  return static_cast<Cost>(std::ceil(best - 1e-9 * best - 1e-6));
}

}  // namespace

std::optional<ClusterPotentials> assignment_potentials(const Problem& p, const StopToken& stop) {
  if (p.cluster_count() > kMaxClusters || p.node_count() > kMaxNodes || p.cluster_count() < 2) return std::nullopt;
  ClusterGraph g;
  if (!build_graph(p, stop, g) || stop.stop_requested()) return std::nullopt;
  detail::Assignment ap;
  if (!solve_assignment(g, ap)) return std::nullopt;
  const int m = g.m;
  ClusterPotentials pot;
  pot.col.resize(static_cast<std::size_t>(m));
  for (int b = 0; b < m; ++b) pot.col[static_cast<std::size_t>(b)] = ap.col_potential(b);
  // Each row's potential recomputed as the tightest one the columns allow, over the usable arcs only:
  // the inequality then holds by construction, whatever the solver's own potentials on the
  // unusable entries.
  pot.row.assign(static_cast<std::size_t>(m), kNo);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      const Cost c = g.at(g.step, a, b);
      if (a != b && c < kNo) pot.row[static_cast<std::size_t>(a)] = std::min(pot.row[static_cast<std::size_t>(a)], c - pot.col[static_cast<std::size_t>(b)]);
    }
  for (Cost r : pot.row)
    if (r >= kNo) return std::nullopt;  // a cluster no route can leave
  return pot;
}

std::optional<Cost> entry_lower_bound(const Problem& p) {
  const int m = p.cluster_count();
  if (p.planar() == nullptr || m < 2) return std::nullopt;
  const std::vector<Cost> in = detail::planar_cheapest_arcs_in(p);
  const bool open_start = !p.closed();
  Cost sum = 0;
  for (int c = 0; c < m; ++c) {
    const bool start = open_start && ClusterId(c) == p.start_cluster();
    Cost least = std::numeric_limits<Cost>::max();
    for (NodeId v : p.nodes_of(ClusterId(c))) least = std::min(least, (start ? 0 : in[v.index()]) + p.inner_cost(v));
    sum += least;
  }
  return sum;
}

BoundSeconds estimate_bound_seconds(const Problem& p) {
  // Measured per solve (session 34): the graph 1.7-2.2 ns per node pair on planar
  // costs (vrs_Lv10_SHEET_001, 8 060 nodes: 0.11 s; d2g_DRAAK, 7 494 nodes: 0.12 s), the
  // assignment about 1.5e-8 s per cluster pair (DRAAK, 1 187 clusters: 0.02 s), a 1-tree step
  // 1.5 ns per cluster pair (DRAAK: 0.12 s for 50 steps).
  const double n = p.node_count(), m = p.cluster_count();
  BoundSeconds s;
  s.graph = 3.0e-9 * n * n + 2.0e-8 * m * m;
  s.one_tree = 2.5e-9 * static_cast<double>(one_tree_steps(std::max(1, p.cluster_count()))) * m * m;
  return s;
}

std::optional<Cost> route_lower_bound(const Problem& p, const StopToken& stop, Cost upper, bool one_tree) {
  if (p.cluster_count() > kMaxClusters || p.node_count() > kMaxNodes || p.cluster_count() < 2) return std::nullopt;
  ClusterGraph g;
  if (!build_graph(p, stop, g) || stop.stop_requested()) return std::nullopt;
  double two_cycles = 0.0;
  std::optional<Cost> bound = assignment_bound(g, two_cycles);
  // The 1-tree on the symmetric relaxation where the assignment is weak: it pairs clusters into
  // 2-cycles when arcs cost about the same both ways. TSPLIB SOP, share of clusters in 2-cycles and
  // bound before -> after: prob.100 0.80, 773 -> 993; ry48p.1 0.61, 12 531 -> 13 489; p43.1 0.23,
  // 900 -> 3 623. Below 0.2 (rbg, ft, esc: 0-0.15) the ascent found nothing and costs 10-40 ms.
  const bool symmetric_tour = p.symmetric() && p.closed() && !p.has_precedence();
  if (one_tree && (symmetric_tour || two_cycles >= kTwoCycleShare)) {
    Cost inner = 0;
    for (int c = 0; c < p.cluster_count(); ++c) {
      Cost least = kNo;
      for (NodeId v : p.nodes_of(ClusterId(c))) least = std::min(least, p.inner_cost(v));
      inner += least;
    }
    // The 1-tree prices arcs only: its target is the known route less the inner costs.
    const Cost arcs_upper = upper < kMaxCost ? upper - inner : kMaxCost;
    if (auto hk = held_karp_bound(g, p.start_cluster().value(), arcs_upper, stop)) bound = std::max(bound.value_or(0), *hk + inner);
  }
  return bound;
}

}  // namespace cutroute::solve
