#include "assignment.hpp"

#include <algorithm>
#include <vector>

namespace cutroute::solve::detail {

namespace {
constexpr Assignment::Cost kInf = std::numeric_limits<Assignment::Cost>::max() / 4;
}

void Assignment::reset(int m) {
  m_ = m;
  const auto n = static_cast<std::size_t>(m);
  c_.assign(n * n, 0);
  u_.assign(n, 0);
  v_.assign(n, 0);
  d_.assign(n, 0);
  row_of_.assign(n, -1);
  col_of_.assign(n, -1);
  pred_.assign(n, -1);
  scanned_.clear();
  value_ = 0;
}

void Assignment::solve() {
  for (int i = 0; i < m_; ++i)
    if (col_of_[static_cast<std::size_t>(i)] < 0) augment(i, kNoLimit);
}

void Assignment::solve_reduced() {
  const auto m = static_cast<std::size_t>(m_);
  // Column reduction: each column's potential is its cheapest entry (the first row on ties, found
  // row by row for the cache); its row takes it when still free.
  std::vector<int> arg(m, 0);
  for (std::size_t j = 0; j < m; ++j) v_[j] = c_[j];
  for (std::size_t i = 1; i < m; ++i) {
    const Cost* ci = c_.data() + i * m;
    for (std::size_t j = 0; j < m; ++j)
      if (ci[j] < v_[j]) v_[j] = ci[j], arg[j] = static_cast<int>(i);
  }
  for (std::size_t j = 0; j < m; ++j) {
    const auto i = static_cast<std::size_t>(arg[j]);
    if (col_of_[i] < 0) {
      col_of_[i] = static_cast<int>(j);
      row_of_[j] = static_cast<int>(i);
      value_ += v_[j];
    }
  }
  // No reduction transfer (JV's next step): it takes a matched row's slack from its second-best
  // column, which is often a kBig entry (an unusable arc, the diagonal), and the potentials then
  // carry kBig where the exact DPs read them as bounds on usable arcs.
  for (int i = 0; i < m_; ++i)
    if (col_of_[static_cast<std::size_t>(i)] < 0) augment(i, kNoLimit);
}

// Dijkstra over the columns from free row r to the nearest free column on reduced costs
// c(i, j) - u(i) - v(j) (matched pairs at 0), then the matching flips along the path. The matching
// cost grows by the path length + u(r) + v(sink), so with a single free column (the sink) the search
// can stop once that reaches `limit`. Potentials move only at the end, for the scanned columns.
bool Assignment::augment(int r, Cost limit) {
  const auto m = static_cast<std::size_t>(m_);
  const Cost* cr = c_.data() + static_cast<std::size_t>(r) * m;
  Cost ur = kInf;
  for (std::size_t j = 0; j < m; ++j) ur = std::min(ur, cr[j] - v_[j]);
  u_[static_cast<std::size_t>(r)] = ur;
  int free_cols = 0, free_col = -1;
  Cost best = kInf;
  std::size_t jmin = 0, pos = 0;  // the nearest column and its index in open_
  open_.resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    d_[j] = cr[j] - ur - v_[j];
    pred_[j] = r;
    open_[j] = static_cast<int>(j);
    if (row_of_[j] < 0) ++free_cols, free_col = static_cast<int>(j);
    if (d_[j] < best) best = d_[j], jmin = j, pos = j;
  }
  const Cost fixed =
      free_cols == 1 && limit != kNoLimit ? value_ + ur + v_[static_cast<std::size_t>(free_col)] : kNoLimit;
  scanned_.clear();
  Cost mu = 0;
  int sink = -1;
  // One pass a step: relaxing the arcs of the row just reached also finds the next nearest column.
  // The columns not yet reached stay in open_ in ascending order, so ties go to the lowest index
  // as in a scan of all columns that skips the reached ones; without that test in the loop and
  // with the list shrinking, 89rbg443 (whose node-set search is most of the time spent here) runs
  // with 6 % less CPU (paired runs, median ratio 0.94), the same route.
  for (;;) {
    mu = best;
    if (fixed != kNoLimit && fixed + mu >= limit) return false;
    if (row_of_[jmin] < 0) {
      sink = static_cast<int>(jmin);
      break;
    }
    open_.erase(open_.begin() + static_cast<std::ptrdiff_t>(pos));
    scanned_.push_back(static_cast<int>(jmin));
    const auto i = static_cast<std::size_t>(row_of_[jmin]);
    const Cost* ci = c_.data() + i * m;
    const Cost base = mu - u_[i];
    best = kInf;
    const int* open = open_.data();
    const std::size_t count = open_.size();
    for (std::size_t q = 0; q < count; ++q) {
      const auto j = static_cast<std::size_t>(open[q]);
      const Cost nd = base + ci[j] - v_[j];
      if (nd < d_[j]) d_[j] = nd, pred_[j] = static_cast<int>(i);
      if (d_[j] < best) best = d_[j], jmin = j, pos = q;
    }
  }
  for (int j : scanned_) {
    const auto sj = static_cast<std::size_t>(j);
    const Cost t = mu - d_[sj];
    v_[sj] -= t;
    u_[static_cast<std::size_t>(row_of_[sj])] += t;
  }
  u_[static_cast<std::size_t>(r)] += mu;
  for (int j = sink;;) {
    const int i = pred_[static_cast<std::size_t>(j)];
    const int old = col_of_[static_cast<std::size_t>(i)];
    row_of_[static_cast<std::size_t>(j)] = i;
    col_of_[static_cast<std::size_t>(i)] = j;
    value_ += at(i, j) - (old >= 0 ? at(i, old) : 0);
    if (i == r) break;
    j = old;
  }
  return true;
}

bool Assignment::replace(int k, const Cost* row, const Cost* col, Cost limit) {
  const auto K = static_cast<std::size_t>(k);
  // Release row k and column k.
  const int jk = col_of_[K], ik = row_of_[K];
  if (jk >= 0) {
    value_ -= at(k, jk);
    row_of_[static_cast<std::size_t>(jk)] = -1;
    col_of_[K] = -1;
  }
  if (ik >= 0 && ik != k) {
    value_ -= at(ik, k);
    col_of_[static_cast<std::size_t>(ik)] = -1;
  }
  row_of_[K] = -1;
  for (int j = 0; j < m_; ++j)
    if (j != k) at(k, j) = row[j], at(j, k) = col[j];
  // Column k's potential: the largest that keeps its reduced costs >= 0 for the matched rows (the
  // free rows get theirs in augment()).
  Cost best = kInf;
  for (int i = 0; i < m_; ++i)
    if (col_of_[static_cast<std::size_t>(i)] >= 0)
      best = std::min(best, at(i, k) - u_[static_cast<std::size_t>(i)]);
  v_[K] = best == kInf ? 0 : best;
  if (!augment(k, kNoLimit)) return false;
  if (ik >= 0 && ik != k && !augment(ik, limit)) return false;
  return true;
}

Assignment::Cost Assignment::bound_with(int k, const Cost* row, const Cost* col) const {
  const auto K = static_cast<std::size_t>(k);
  Cost uk = kInf, vk = kInf;
  for (int j = 0; j < m_; ++j) {
    if (j == k) continue;
    const auto J = static_cast<std::size_t>(j);
    uk = std::min(uk, row[j] - v_[J]);
    vk = std::min(vk, col[j] - u_[J]);
  }
  // The new row and column meet on the diagonal (kBig), which these potentials cannot exceed.
  return value_ - u_[K] - v_[K] + uk + vk;
}

void Assignment::save(int k, Saved& s) const {
  s.u = u_, s.v = v_, s.row_of = row_of_, s.col_of = col_of_, s.value = value_;
  s.row.resize(static_cast<std::size_t>(m_)), s.col.resize(static_cast<std::size_t>(m_));
  for (int j = 0; j < m_; ++j)
    s.row[static_cast<std::size_t>(j)] = at(k, j), s.col[static_cast<std::size_t>(j)] = at(j, k);
}

void Assignment::restore(int k, const Saved& s) {
  u_ = s.u, v_ = s.v, row_of_ = s.row_of, col_of_ = s.col_of, value_ = s.value;
  for (int j = 0; j < m_; ++j)
    at(k, j) = s.row[static_cast<std::size_t>(j)], at(j, k) = s.col[static_cast<std::size_t>(j)];
}

}  // namespace cutroute::solve::detail
