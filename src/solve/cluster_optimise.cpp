// Cluster optimisation of the route operators: the best node of every cluster for a fixed order,
// over the whole route or over windows around what changed.
#include "tour.hpp"

#include <algorithm>
#include <vector>

namespace cutroute::solve::detail {
// Cluster optimisation: the order of clusters stays, each cluster's node is chosen by a shortest
// path through the layered graph C_r -> C_r+1 -> ... -> C_r (closed: starting from each node of the
// smallest cluster C_r; open: from all nodes of the start cluster at once).
bool Ops::cluster_optimise(Tour& t, double max_work) const {
  const int L = static_cast<int>(t.seq.size());
  if (L == 0) return false;
  if (L == 1) {
    // A route of one cluster costs its node's inner cost alone (run() below prices it the same
    // way, but from each node in turn: a single cluster of 20 000 nodes took 2.4 s).
    NodeId best = t.seq[0];
    for (NodeId v : p_.nodes_of(cl(best)))
      if (p_.inner_cost(v) < p_.inner_cost(best)) best = v;
    if (best == t.seq[0]) return false;
    t.seq[0] = best;
    t.cost = p_.inner_cost(best);
    mark_around(t, 0);
    return true;
  }
  int r = 0;
  if (closed_) {
    for (int i = 1; i < L; ++i)
      if (p_.cluster_size(cl(t.seq[static_cast<std::size_t>(i)])) < p_.cluster_size(cl(t.seq[static_cast<std::size_t>(r)]))) r = i;
  }
  auto layer_cluster = [&](int l) { return cl(t.seq[static_cast<std::size_t>((r + l) % L)]); };
  std::vector<int> off(static_cast<std::size_t>(L) + 1, 0);
  double work = 0;
  for (int l = 0; l < L; ++l) {
    off[static_cast<std::size_t>(l) + 1] = off[static_cast<std::size_t>(l)] + p_.cluster_size(layer_cluster(l));
    if (l > 0) work += static_cast<double>(p_.cluster_size(layer_cluster(l))) * p_.cluster_size(layer_cluster(l - 1));
  }
  const int total = off[static_cast<std::size_t>(L)];
  std::vector<Cost> D(static_cast<std::size_t>(total));
  std::vector<int> pred(static_cast<std::size_t>(total));
  Cost best = t.cost;
  std::vector<NodeId> best_seq;
  std::vector<int> chain(static_cast<std::size_t>(L));
  std::vector<Cost> row;
  auto run = [&](std::span<const NodeId> sources) {
    const auto s0 = p_.nodes_of(layer_cluster(0));
    for (std::size_t a = 0; a < s0.size(); ++a) {
      const bool src = std::find(sources.begin(), sources.end(), s0[a]) != sources.end();
      D[a] = src ? (closed_ ? 0 : p_.inner_cost(s0[a])) : kHuge;
      pred[a] = -1;
    }
    for (int l = 1; l < L; ++l) {
      const auto A = p_.nodes_of(layer_cluster(l - 1));
      const auto B = p_.nodes_of(layer_cluster(l));
      const int oa = off[static_cast<std::size_t>(l - 1)], ob = off[static_cast<std::size_t>(l)];
      const std::size_t blk_a = blk_out_.empty() ? 0 : blk_off_[layer_cluster(l - 1).index()];
      for (std::size_t b = 0; b < B.size(); ++b) {
        Cost bv = kHuge;
        int arg = -1;
        // A and B are different clusters, so link() is the plain arc: read from the blocked copy.
        const Cost* into_b = blk_out_.empty() ? nullptr : blk_in() + B[b].index() * n_ + blk_a;
        if (plain_planar_) {
          row.resize(A.size());
          planar_into(B[b], layer_cluster(l - 1), row.data());
          into_b = row.data();
        }
        for (std::size_t a = 0; a < A.size(); ++a) {
          const Cost da = D[static_cast<std::size_t>(oa) + a];
          if (da >= kHuge) continue;
          const Cost v = da + (into_b ? into_b[a] : link(A[a], B[b]));
          if (v < bv) bv = v, arg = oa + static_cast<int>(a);
        }
        D[static_cast<std::size_t>(ob) + b] = bv;
        pred[static_cast<std::size_t>(ob) + b] = arg;
      }
    }
    const auto Z = p_.nodes_of(layer_cluster(L - 1));
    const int oz = off[static_cast<std::size_t>(L - 1)];
    for (std::size_t z = 0; z < Z.size(); ++z) {
      Cost v = D[static_cast<std::size_t>(oz) + z];
      if (v >= kHuge) continue;
      int idx = oz + static_cast<int>(z);
      NodeId first;
      // Walk back to find the source when closed (the closing link depends on it).
      for (int l = L - 1; l >= 0; --l) {
        chain[static_cast<std::size_t>(l)] = idx;
        if (l > 0) idx = pred[static_cast<std::size_t>(idx)];
      }
      first = s0[static_cast<std::size_t>(chain[0])];
      if (closed_) v += L == 1 ? p_.inner_cost(first) : link(Z[z], first);
      if (v < best) {
        best = v;
        best_seq.assign(static_cast<std::size_t>(L), NodeId{});
        for (int l = 0; l < L; ++l) {
          const int li = chain[static_cast<std::size_t>(l)] - off[static_cast<std::size_t>(l)];
          best_seq[static_cast<std::size_t>((r + l) % L)] = p_.nodes_of(layer_cluster(l))[static_cast<std::size_t>(li)];
        }
      }
    }
  };
  const auto s0 = p_.nodes_of(layer_cluster(0));
  if (!closed_) {
    run(s0);
  } else if (work * static_cast<double>(s0.size()) <= max_work) {
    for (const NodeId& s : s0) run(std::span<const NodeId>(&s, 1));
  } else {
    const NodeId cur = t.seq[static_cast<std::size_t>(r)];
    run(std::span<const NodeId>(&cur, 1));
  }
  if (best_seq.empty()) return false;
  for (int i = 0; i < L; ++i)
    if (best_seq[static_cast<std::size_t>(i)] != t.seq[static_cast<std::size_t>(i)]) {
      t.seq[static_cast<std::size_t>(i)] = best_seq[static_cast<std::size_t>(i)];
      mark_around(t, i);
    }
  t.cost = best;
  return true;
}

bool Ops::window_optimise(Tour& t, int lo, int hi) const {
  const int L = static_cast<int>(t.seq.size());
  lo = std::max(lo, 1);
  hi = std::min(hi, L - 1);
  if (lo > hi) return false;
  const NodeId first = t.seq[static_cast<std::size_t>(lo - 1)];
  const NodeId last = after(t, hi);
  Cost old = last.valid() ? link(t.seq[static_cast<std::size_t>(hi)], last) : 0;
  for (int i = lo; i <= hi; ++i) old += link(t.seq[static_cast<std::size_t>(i - 1)], t.seq[static_cast<std::size_t>(i)]);
  thread_local std::vector<Cost> D;
  thread_local std::vector<int> pred, off;
  off.assign(1, 0);
  for (int i = lo; i <= hi; ++i) off.push_back(off.back() + p_.cluster_size(cl(t.seq[static_cast<std::size_t>(i)])));
  D.assign(static_cast<std::size_t>(off.back()), kHuge);
  pred.assign(static_cast<std::size_t>(off.back()), -1);
  for (int i = lo; i <= hi; ++i) {
    const auto B = p_.nodes_of(cl(t.seq[static_cast<std::size_t>(i)]));
    const std::size_t ob = static_cast<std::size_t>(off[static_cast<std::size_t>(i - lo)]);
    if (i == lo) {
      if (plain_planar_) planar_from(first, cl(B[0]), D.data() + ob);
      else
        for (std::size_t b = 0; b < B.size(); ++b) D[ob + b] = link(first, B[b]);
      continue;
    }
    const auto A = p_.nodes_of(cl(t.seq[static_cast<std::size_t>(i - 1)]));
    const std::size_t oa = static_cast<std::size_t>(off[static_cast<std::size_t>(i - 1 - lo)]);
    if (plain_planar_) {  // same values, same order as the loop below
      thread_local std::vector<Cost> row;
      row.resize(A.size());
      for (std::size_t b = 0; b < B.size(); ++b) {
        planar_into(B[b], cl(A[0]), row.data());
        for (std::size_t a = 0; a < A.size(); ++a) {
          const Cost v = D[oa + a] + row[a];
          if (v < D[ob + b]) D[ob + b] = v, pred[ob + b] = static_cast<int>(oa + a);
        }
      }
      continue;
    }
    for (std::size_t b = 0; b < B.size(); ++b)
      for (std::size_t a = 0; a < A.size(); ++a) {
        const Cost v = D[oa + a] + link(A[a], B[b]);
        if (v < D[ob + b]) D[ob + b] = v, pred[ob + b] = static_cast<int>(oa + a);
      }
  }
  const auto Z = p_.nodes_of(cl(t.seq[static_cast<std::size_t>(hi)]));
  const std::size_t oz = static_cast<std::size_t>(off[static_cast<std::size_t>(hi - lo)]);
  Cost best = kHuge;
  int arg = -1;
  for (std::size_t z = 0; z < Z.size(); ++z) {
    const Cost v = D[oz + z] + (last.valid() ? link(Z[z], last) : 0);
    if (v < best) best = v, arg = static_cast<int>(oz + z);
  }
  if (best >= old) return false;
  for (int i = hi; i >= lo; --i) {
    const int li = arg - off[static_cast<std::size_t>(i - lo)];
    const NodeId v = p_.nodes_of(cl(t.seq[static_cast<std::size_t>(i)]))[static_cast<std::size_t>(li)];
    if (v != t.seq[static_cast<std::size_t>(i)]) {
      t.seq[static_cast<std::size_t>(i)] = v;
      mark_around(t, i);
    }
    arg = pred[static_cast<std::size_t>(arg)];
  }
  t.cost += best - old;
  return true;
}

bool Ops::windows_optimise(Tour& t, int since_epoch) const {
  // Windows of +-2 positions around every cluster changed since `since_epoch`, merged when they overlap.
  const int L = static_cast<int>(t.seq.size());
  bool improved = false;
  int lo = -1, hi = -1;
  for (int i = 0; i <= L; ++i) {
    const bool changed = i < L && t.touched[cl(t.seq[static_cast<std::size_t>(i)]).index()] >= since_epoch;
    if (changed) {
      if (lo >= 0 && i - 2 <= hi + 1) hi = i + 2;
      else {
        if (lo >= 0) improved = window_optimise(t, lo, hi) || improved;
        lo = i - 2, hi = i + 2;
      }
    }
  }
  if (lo >= 0) improved = window_optimise(t, lo, hi) || improved;
  return improved;
}

}  // namespace cutroute::solve::detail
