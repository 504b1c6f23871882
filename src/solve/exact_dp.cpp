#include <cutroute/solve/exact_dp.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cassert>
#include <cstdint>
#include <limits>
#include <vector>

#include <cutroute/solve/lower_bound.hpp>

#include "exact_common.hpp"

namespace cutroute::solve {
namespace {

constexpr Cost kInf = detail::kDpInf;
constexpr int kMaxDpClusters = 30;

// The start cluster the DP enumerates: the problem's own, or for a closed tour without precedence
// the smallest cluster (any rotation of a closed tour costs the same; fewer start nodes = fewer runs).
ClusterId dp_start_cluster(const Problem& p) {
  if (!p.closed() || p.has_precedence()) return p.start_cluster();
  ClusterId best = p.start_cluster();
  for (int c = 0; c < p.cluster_count(); ++c)
    if (p.cluster_size(ClusterId(c)) < p.cluster_size(best)) best = ClusterId(c);
  return best;
}

// The dense DP's layout: the shared one plus the predecessors of each bit as a 32-bit mask.
struct Layout : detail::DpLayout {
  std::vector<std::uint32_t> pred;  // bit -> mask of bits that must come earlier
};

Layout make_layout(const Problem& p) {
  Layout L;
  static_cast<detail::DpLayout&>(L) = detail::dp_layout(p, dp_start_cluster(p));
  if (L.mp > kMaxDpClusters) return L;
  L.pred.assign(static_cast<std::size_t>(L.mp), 0);
  for (int b = 0; b < L.mp; ++b)
    for (ClusterId a : p.all_before(L.cluster[b]))
      if (L.bit_of[a.index()] >= 0) L.pred[b] |= std::uint32_t{1} << L.bit_of[a.index()];
  return L;
}

}  // namespace

double estimate_exact_work(const Problem& p) {
  const ClusterId s = dp_start_cluster(p);
  const double mp = p.cluster_count() - 1;
  if (mp > kMaxDpClusters) return std::numeric_limits<double>::infinity();
  const double a = mp > 0 ? (p.node_count() - p.cluster_size(s)) / mp : 0.0;
  return p.cluster_size(s) * std::ldexp(1.0, static_cast<int>(mp)) * std::max(1.0, mp * (mp - 1) / 4.0) * a * a;
}

std::size_t estimate_exact_memory(const Problem& p) {
  const ClusterId s = dp_start_cluster(p);
  const int mp = p.cluster_count() - 1;
  if (mp > kMaxDpClusters) return std::numeric_limits<std::size_t>::max();
  const auto subsets = std::size_t{1} << mp;
  const auto np = static_cast<std::size_t>(p.node_count() - p.cluster_size(s));
  return subsets * np * sizeof(Cost) + subsets + subsets * sizeof(std::uint32_t);
}

namespace {
constexpr std::size_t kDenseMemoryBeforeIdeals = std::size_t{64} << 20;
constexpr std::size_t kIdealsInsteadOfDense = 1'000'000;
}  // namespace

Solution solve_exact(const Problem& p, std::size_t memory_limit_bytes, const StopToken& stop, const Solution* incumbent,
                     const ProgressFn& progress, std::optional<Cost> known_bound) {
  Solution out;
  Cost ub = detail::dp_take_incumbent(p, incumbent, out);
  // The cluster-graph bound (lower_bound.hpp) proves the incumbent optimal when it reaches it (the
  // stacker-crane instances' assignment bound often does), and stands in for the DP's own bound when
  // the DP cannot run or stops: beyond the DP's limits that bound is only the cheapest entries.
  const std::optional<Cost> global_lb =
      known_bound ? known_bound : p.cluster_count() > 1 ? route_lower_bound(p, stop, ub < kInf ? ub : kMaxCost) : std::nullopt;
  if (global_lb && ub < kInf && *global_lb >= ub) {
    out.status = SolveStatus::optimal;
    out.lower_bound = out.cost;
    return out;
  }
  auto with_global = [&](Cost lb) { return global_lb ? std::max(lb, *global_lb) : lb; };
  const Layout L = make_layout(p);
  const int mp = L.mp;
  const int np = L.np;
  const auto start_nodes = p.nodes_of(L.start);

  // Cheapest step into each cluster from anywhere outside it (the LB(S) terms).
  const std::vector<Cost> min_in = detail::dp_min_in(p, L);
  const Cost min_in_all = detail::dp_sum(min_in);
  auto closing_lb = [&](NodeId s) { return detail::dp_closing_lb(p, L, s); };

  auto fail_to_run = [&](bool limit) {
    Cost lb = kInf;
    for (NodeId s : start_nodes) lb = std::min(lb, p.inner_cost(s) + min_in_all + closing_lb(s));
    lb = with_global(lb);
    if (lb < kInf) out.lower_bound = std::min(lb, out.route.empty() ? lb : out.cost);
    out.stats.stopped_by_limit = limit;
    return out;
  };
  const std::size_t dense_bytes = estimate_exact_memory(p);
  if (mp > kMaxDpClusters || dense_bytes > memory_limit_bytes ||
      (p.has_precedence() && dense_bytes > kDenseMemoryBeforeIdeals &&
       estimate_ideal_work(p, kIdealsInsteadOfDense) < std::numeric_limits<double>::infinity())) {
    if (!p.has_precedence() || mp > kMaxIdealClusters) return fail_to_run(true);
    Solution s = solve_exact_ideals(p, memory_limit_bytes, stop, out.route.empty() ? nullptr : &out, progress);
    if (s.lower_bound && global_lb) s.lower_bound = std::min(with_global(*s.lower_bound), s.route.empty() ? kInf : s.cost);
    return s;
  }

  if (mp == 0) return detail::dp_single_cluster(p, L.start, out);

  const auto subsets = std::size_t{1} << mp;
  const std::uint32_t full = static_cast<std::uint32_t>(subsets - 1);
  const auto unp = static_cast<std::size_t>(np);
  // Local step matrix: the DP's inner loop reads it sequentially.
  const std::vector<Cost> w = detail::dp_local_steps(p, L);
  std::vector<Cost> F(subsets * unp);
  std::vector<std::uint8_t> seen(subsets);
  std::vector<std::uint32_t> layer, next;
  // LB(S) from in_s, the sum of min_in over S.
  auto rest_from = [&](Cost in_s, Cost close_lb) {
    const Cost rest = min_in_all - in_s;
    return rest >= kInf || close_lb >= kInf ? kInf : rest + close_lb;
  };
  auto lb_rest = [&](std::uint32_t S, Cost close_lb) {
    Cost in_s = 0;
    for (std::uint32_t r = S; r; r &= r - 1) in_s += min_in[std::countr_zero(r)];
    return rest_from(in_s, close_lb);
  };
  // The larger of LB(T) and the potentials' bound once the route has reached cluster b, T = S + b,
  // from the sums over S of min_in (in_s) and of row + col (rc_s): computed once per S, not per T.
  const detail::DpPotentials pot = detail::dp_potentials(p, L, stop);
  auto rest_after = [&](Cost in_s, Cost rc_s, int b, Cost close_lb, Cost apr0) {
    const Cost rest = rest_from(in_s + min_in[b], close_lb);
    return pot.ok ? pot.remaining(rest, b, apr0 - rc_s - pot.rc[static_cast<std::size_t>(b)]) : rest;
  };

  // Progress by the work of the layers rather than their count: layer k holds up to C(mp, k) sets,
  // each expanded by mp - k clusters from its k, so the middle layers take nearly all the time (16
  // clusters, mp = 15: layers 1-4 are 3 % of the work; counted by layers, the display said 33 %).
  std::vector<double> layer_end(static_cast<std::size_t>(mp) + 1, 0.0);  // work share up to layer k
  {
    double binom = 1.0, sum = 0.0;
    for (int k = 1; k < mp; ++k) {
      binom = binom * (mp - k + 1) / k;
      sum += binom * k * (mp - k);
      layer_end[static_cast<std::size_t>(k)] = sum;
    }
    for (double& x : layer_end) x = sum > 0.0 ? x / sum : 1.0;
  }
  auto done_in_layer = [&](int k, double share) {
    const double lo = layer_end[static_cast<std::size_t>(k) - 1], hi = layer_end[static_cast<std::size_t>(k)];
    return lo + (hi - lo) * share;
  };

  Cost lower_bound = kInf;  // min over start nodes handled so far (finished ones contribute ub later)
  bool stopped = false;
  long long expanded = 0;
  std::size_t si = 0;
  for (; si < start_nodes.size() && !stopped; ++si) {
    const NodeId s = start_nodes[si];
    const Cost close_lb = closing_lb(s);
    const Cost apr0 = pot.ok ? pot.apr0(p, s) : 0;
    std::fill(F.begin(), F.end(), kInf);
    std::fill(seen.begin(), seen.end(), 0);
    layer.clear();
    for (int b = 0; b < mp; ++b) {
      if (L.pred[b] != 0) continue;
      const std::uint32_t T = std::uint32_t{1} << b;
      const Cost rest = rest_after(0, 0, b, close_lb, apr0);
      for (int j = L.first[b]; j < L.first[b] + L.size[b]; ++j) {
        const Cost st = p.step(s, L.node[j]);
        if (st >= kForbiddenCost) continue;
        const Cost val = p.inner_cost(s) + st;
        if (rest < kInf && val + rest >= ub) continue;
        F[T * unp + static_cast<std::size_t>(j)] = val;
        if (!seen[T]) seen[T] = 1, layer.push_back(T);
      }
    }
    // Layers 1 .. mp-1 expand into the next; layer mp is the full set.
    for (int k = 1; k < mp && !layer.empty(); ++k) {
      next.clear();
      for (std::size_t li = 0; li < layer.size(); ++li) {
        if ((li & 255) == 0 && stop.stop_requested()) {
          stopped = true;
          break;
        }
        if ((li & 16383) == 16383)
          detail::dp_progress(progress, static_cast<double>(si) + done_in_layer(k, static_cast<double>(li) / static_cast<double>(layer.size())), start_nodes.size(), ub);
        const std::uint32_t S = layer[li];
        const Cost* FS = &F[S * unp];
        Cost in_s = 0, rc_s = 0;
        for (std::uint32_t r = S; r; r &= r - 1) {
          const int a = std::countr_zero(r);
          in_s += min_in[a];
          if (pot.ok) rc_s += pot.rc[static_cast<std::size_t>(a)];
        }
        for (std::uint32_t avail = full & ~S; avail; avail &= avail - 1) {
          const int b = std::countr_zero(avail);
          if ((L.pred[b] & ~S) != 0) continue;
          const std::uint32_t T = S | (std::uint32_t{1} << b);
          const Cost rest = rest_after(in_s, rc_s, b, close_lb, apr0);
          if (rest >= kInf) continue;
          Cost* FT = &F[T * unp];
          const int jb = L.first[b], je = L.first[b] + L.size[b];
          bool any = false;
          for (std::uint32_t in = S; in; in &= in - 1) {
            const int a = std::countr_zero(in);
            for (int i = L.first[a]; i < L.first[a] + L.size[a]; ++i) {
              const Cost fi = FS[i];
              if (fi >= kInf || fi + rest >= ub) continue;
              const Cost* wi = &w[static_cast<std::size_t>(i) * unp];
              ++expanded;
              for (int j = jb; j < je; ++j) {
                const Cost val = fi + wi[j];
                if (val < FT[j] && val + rest < ub) FT[j] = val, any = true;
              }
            }
          }
          if (any && !seen[T]) seen[T] = 1, next.push_back(T);
        }
      }
      if (stopped) {
        // Layer k is final (all its predecessors were expanded): every route from s passes it.
        Cost lb_s = ub;
        for (std::uint32_t S : layer) {
          const Cost rest = lb_rest(S, close_lb);
          for (std::uint32_t in = S; in; in &= in - 1) {
            const int a = std::countr_zero(in);
            for (int i = L.first[a]; i < L.first[a] + L.size[a]; ++i)
              if (F[S * unp + static_cast<std::size_t>(i)] < kInf) lb_s = std::min(lb_s, F[S * unp + static_cast<std::size_t>(i)] + rest);
          }
        }
        lower_bound = std::min(lower_bound, lb_s);
        break;
      }
      layer.swap(next);
      detail::dp_progress(progress, static_cast<double>(si) + layer_end[static_cast<std::size_t>(k)], start_nodes.size(), ub);
    }
    if (stopped) break;
    // Close the routes of the full layer.
    if (seen[full]) {
      Cost best = kInf;
      int arg = -1;
      for (int j = 0; j < np; ++j) {
        const Cost f = F[full * unp + static_cast<std::size_t>(j)];
        if (f >= kInf) continue;
        Cost total = f;
        if (p.closed()) {
          const Cost c = p.arc_cost(L.node[j], s);
          if (c >= kForbiddenCost) continue;
          total += c;
        }
        if (total < best) best = total, arg = j;
      }
      if (arg >= 0 && best < ub) {
        // Walk back: the predecessor u of v in S is any with F(S \ b, u) + w(u, v) == F(S, v).
        std::vector<NodeId> rev;
        std::uint32_t S = full;
        int v = arg;
        while (true) {
          rev.push_back(L.node[v]);
          const std::uint32_t R = S & ~(std::uint32_t{1} << L.bit_of_local[v]);
          if (R == 0) break;
          const Cost target = F[S * unp + static_cast<std::size_t>(v)];
          int found = -1;
          for (int i = 0; i < np && found < 0; ++i)
            if (((R >> L.bit_of_local[i]) & 1u) && F[R * unp + static_cast<std::size_t>(i)] < kInf &&
                F[R * unp + static_cast<std::size_t>(i)] + w[static_cast<std::size_t>(i) * unp + static_cast<std::size_t>(v)] == target)
              found = i;
          assert(found >= 0 && "DP table inconsistent");
          if (found < 0) break;
          S = R;
          v = found;
        }
        ub = detail::dp_keep_route(out, rev, s, best);
      }
    }
  }
  out.stats.iterations = expanded;
  // Rotate a closed tour so it begins in the problem's start cluster (the DP may have used another).
  if (!out.route.empty() && p.cluster_of(out.route[0]) != p.start_cluster()) {
    auto it = std::find_if(out.route.begin(), out.route.end(), [&](NodeId v) { return p.cluster_of(v) == p.start_cluster(); });
    std::rotate(out.route.begin(), it, out.route.end());
  }
  if (!stopped) return detail::dp_proven(out);
  // Start nodes not begun: their trivial bound.
  for (std::size_t k = si + 1; k < start_nodes.size(); ++k)
    lower_bound = std::min(lower_bound, p.inner_cost(start_nodes[k]) + lb_rest(0, closing_lb(start_nodes[k])));
  lower_bound = std::min(lower_bound, ub);  // finished start nodes: nothing below ub
  if (lower_bound < kInf) out.lower_bound = std::min(with_global(lower_bound), ub);
  out.stats.stopped_by_limit = true;
  return out;
}

}  // namespace cutroute::solve
