// Population of the hybrid genetic search: distances, biased fitness, survivor selection, and the
// ordered crossover.
#include "population.hpp"

#include <algorithm>
#include <numeric>

namespace cutroute::solve::detail {

double Population::compute_distance(const Member& a, const Member& b) const {
  // Branch-free so that GCC vectorises it: every child is compared with the whole population in
  // the serial step between rounds (7.5 % of the run on 200E1k.0 with the branches).
  const std::size_t m = a.succ.size();
  const int* as = a.succ.data();
  const int* bs = b.succ.data();
  const int* bp = b.pred.data();
  const int sym = sym_ ? 1 : 0;
  int arcs = 0, broken = 0;
  for (std::size_t c = 0; c < m; ++c) {
    const int s = as[c];
    const int has = static_cast<int>(s >= 0);
    arcs += has;
    broken += has & static_cast<int>(bs[c] != s) & (1 - (sym & static_cast<int>(bp[c] == s)));
  }
  return arcs == 0 ? 0.0 : static_cast<double>(broken) / arcs;
}

void Population::add(const Ops& ops, const Tour& t) {
  const Problem& p = ops.problem();
  sym_ = p.symmetric();
  Member nm;
  nm.tour = t;
  const auto m = static_cast<std::size_t>(p.cluster_count());
  nm.succ.assign(m, -1);
  nm.pred.assign(m, -1);
  const int L = static_cast<int>(t.seq.size());
  for (int i = 0; i < L; ++i) {
    const int j = i + 1 < L ? i + 1 : p.closed() ? 0 : -1;
    if (j < 0 || j == i) continue;
    const int a = ops.cl(t.seq[static_cast<std::size_t>(i)]).value(), b = ops.cl(t.seq[static_cast<std::size_t>(j)]).value();
    nm.succ[static_cast<std::size_t>(a)] = b;
    nm.pred[static_cast<std::size_t>(b)] = a;
  }
  const std::size_t k = members_.size();
  std::vector<double> row(k + 1, 0.0);
  nm.near.reserve(static_cast<std::size_t>(mu_ + lambda_));
  for (std::size_t i = 0; i < k; ++i) {
    row[i] = compute_distance(nm, members_[i]);
    dist_[i].push_back(row[i]);
    std::vector<double>& near = members_[i].near;
    near.insert(std::upper_bound(near.begin(), near.end(), row[i]), row[i]);
    nm.near.push_back(row[i]);
  }
  std::sort(nm.near.begin(), nm.near.end());
  dist_.push_back(std::move(row));
  members_.push_back(std::move(nm));
  if (size() < mu_ + lambda_) return;
  while (size() > mu_) {
    refresh();
    // A clone (no broken pair to a member at most as cheap, the earlier one kept on ties) goes
    // first, else the worst biased fitness.
    int worst = -1;
    bool worst_clone = false;
    for (int i = 0; i < size(); ++i) {
      const bool c = clone(i);
      if (worst < 0 || (c && !worst_clone) || (c == worst_clone && fitness(i) > fitness(worst))) {
        worst = i;
        worst_clone = c;
      }
    }
    remove(worst);
  }
}

bool Population::clone(int i) const {
  // Most members are at a positive distance from all others: their nearest tells at once.
  const std::vector<double>& near = members_[static_cast<std::size_t>(i)].near;
  if (near.empty() || near.front() > 0.0) return false;
  for (int j = 0; j < size(); ++j)
    if (j != i && distance(i, j) == 0.0 && (at(j).cost < at(i).cost || (at(j).cost == at(i).cost && j < i))) return true;
  return false;
}

void Population::remove(int i) {
  for (int j = 0; j < size(); ++j) {
    if (j == i) continue;
    // Equal distances are equal doubles, so which copy goes does not matter.
    std::vector<double>& near = members_[static_cast<std::size_t>(j)].near;
    near.erase(std::lower_bound(near.begin(), near.end(), distance(i, j)));
  }
  members_.erase(members_.begin() + i);
  dist_.erase(dist_.begin() + i);
  for (auto& row : dist_) row.erase(row.begin() + i);
}

void Population::refresh() {
  const int n = size();
  if (n <= 1) {
    for (Member& x : members_) x.fitness = 0.0;
    return;
  }
  const auto un = static_cast<std::size_t>(n);
  std::vector<double> div(un);
  const int c = std::min(close_, n - 1);
  for (int i = 0; i < n; ++i) {
    const std::vector<double>& near = members_[static_cast<std::size_t>(i)].near;
    div[static_cast<std::size_t>(i)] = std::accumulate(near.begin(), near.begin() + c, 0.0) / c;
  }
  std::vector<int> by_cost(un), by_div(un);
  std::iota(by_cost.begin(), by_cost.end(), 0);
  std::iota(by_div.begin(), by_div.end(), 0);
  std::stable_sort(by_cost.begin(), by_cost.end(), [&](int a, int b) { return at(a).cost < at(b).cost; });
  std::stable_sort(by_div.begin(), by_div.end(),
                   [&](int a, int b) { return div[static_cast<std::size_t>(a)] > div[static_cast<std::size_t>(b)]; });
  const double w = std::max(0.0, 1.0 - static_cast<double>(elite_) / n);
  for (Member& x : members_) x.fitness = 0.0;
  for (int r = 0; r < n; ++r) {
    const double rank = static_cast<double>(r) / (n - 1);
    members_[static_cast<std::size_t>(by_cost[static_cast<std::size_t>(r)])].fitness += rank;
    members_[static_cast<std::size_t>(by_div[static_cast<std::size_t>(r)])].fitness += w * rank;
  }
}

int Population::select(Rng& rng) const {
  const auto n = static_cast<std::uint64_t>(size());
  const int a = static_cast<int>(rng.below(n)), b = static_cast<int>(rng.below(n));
  return fitness(a) <= fitness(b) ? a : b;
}

void order_crossover(const Ops& ops, const Tour& a, const Tour& b, int i, int j, Tour& child) {
  const Problem& p = ops.problem();
  const int L = static_cast<int>(a.seq.size());
  child.seq = a.seq;
  thread_local std::vector<char> in_stretch;
  in_stretch.assign(static_cast<std::size_t>(p.cluster_count()), 0);
  for (int q = i; q <= j; ++q) in_stretch[ops.cl(a.seq[static_cast<std::size_t>(q)]).index()] = 1;
  // Positions 1..L-1 taken cyclically: b's order from after a.seq[j]'s place in b fills the child
  // from after j.
  auto next = [L](int q) { return q + 1 < L ? q + 1 : 1; };
  int w = next(j);
  const int start = b.pos[ops.cl(a.seq[static_cast<std::size_t>(j)]).index()];
  for (int r = 1, q = next(start); r < L; ++r, q = next(q)) {
    const NodeId v = b.seq[static_cast<std::size_t>(q)];
    if (in_stretch[ops.cl(v).index()] != 0) continue;
    child.seq[static_cast<std::size_t>(w)] = v;
    w = next(w);
  }
  ops.init(child);
  std::fill(child.dirty.begin(), child.dirty.end(), 0);
  std::fill(child.touched.begin(), child.touched.end(), 0);
  const bool sym = p.symmetric();
  auto has = [&](const Tour& t, ClusterId x, ClusterId y) {
    const int d = t.pos[y.index()] - t.pos[x.index()];
    if (d == 1 || (sym && d == -1)) return true;
    return p.closed() && (d == -(L - 1) || (sym && d == L - 1));
  };
  const int last = p.closed() ? L : L - 1;
  for (int q = 0; q < last; ++q) {
    const ClusterId x = ops.cl(child.seq[static_cast<std::size_t>(q)]);
    const ClusterId y = ops.cl(child.seq[static_cast<std::size_t>(q + 1 < L ? q + 1 : 0)]);
    if (!has(a, x, y) && !has(b, x, y)) ops.mark_around(child, q), ops.mark_around(child, q + 1);
  }
}

}  // namespace cutroute::solve::detail
