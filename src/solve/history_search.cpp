#include <cutroute/solve/history_search.hpp>

#include <algorithm>
#include <queue>
#include <tuple>

namespace cutroute::solve {
namespace {

// Positions of the clusters in a route (-1: not visited), reused across candidates.
void fill_positions(const Problem& p, std::span<const NodeId> route, std::vector<int>& pos) {
  pos.assign(static_cast<std::size_t>(p.cluster_count()), -1);
  for (std::size_t i = 0; i < route.size(); ++i) pos[p.cluster_of(route[i]).index()] = static_cast<int>(i);
}

bool keeps(const Problem& p, std::span<const NodeId> route, std::vector<int>& pos) {
  fill_positions(p, route, pos);
  // The given pairs suffice: if each holds, their transitive consequences hold by transitivity.
  for (auto [a, b] : p.precedence()) {
    const int pa = pos[a.index()], pb = pos[b.index()];
    if (pa >= 0 && pb >= 0 && pa > pb) return false;
  }
  return true;
}

class Search {
 public:
  Search(const Problem& p, const SequenceCost& cost, const HistorySearchParams& params, const StopToken& stop)
      : p_(p), cost_(cost), params_(params), stop_(stop) {}

  HistorySearchResult run(std::vector<NodeId> route, Cost start_cost) {
    res_.route = std::move(route);
    res_.cost = start_cost;
    res_.initial_cost = start_cost;
    const int m = static_cast<int>(res_.route.size());
    bool improved = true;
    while (improved && !out_of_budget()) {
      improved = false;
      for (int i = 1; i < m && !out_of_budget(); ++i) {
        // Each candidate costs an O(m) copy before it is priced: the loops stop with the budget
        // instead of building, to the end of the position, candidates that can no longer be priced.
        for (int len = 1; len <= params_.max_block && i + len <= m; ++len) improved |= or_opt(i, len);
        for (int j = i + 1; j < m && !out_of_budget(); ++j) improved |= swap(i, j);
        for (int j = i + 1; j < m && !out_of_budget(); ++j) improved |= reverse(i, j);
      }
    }
    res_.local_optimum = !improved;
    return std::move(res_);
  }

 private:
  bool out_of_budget() const {
    return res_.evaluations >= params_.max_evaluations || stop_.stop_requested();
  }

  // Prices cand_ when it keeps precedence; takes it when strictly cheaper.
  bool try_candidate() {
    if (out_of_budget() || !keeps(p_, cand_, pos_)) return false;
    ++res_.evaluations;
    const Cost c = cost_(cand_);
    if (c >= res_.cost) return false;
    res_.route.swap(cand_);
    res_.cost = c;
    ++res_.improvements;
    return true;
  }

  // Block [i, i+len) removed and inserted before position j of what remains (j >= 1).
  bool or_opt(int i, int len) {
    const auto& r = res_.route;
    const int m = static_cast<int>(r.size());
    bool any = false;
    for (int j = 1; j <= m - len && !out_of_budget(); ++j) {
      if (j == i) continue;  // the same route
      const auto& cur = res_.route;
      rest_.clear();
      rest_.insert(rest_.end(), cur.begin(), cur.begin() + i);
      rest_.insert(rest_.end(), cur.begin() + i + len, cur.end());
      cand_.assign(rest_.begin(), rest_.begin() + j);
      cand_.insert(cand_.end(), cur.begin() + i, cur.begin() + i + len);
      cand_.insert(cand_.end(), rest_.begin() + j, rest_.end());
      any |= try_candidate();
    }
    return any;
  }

  bool swap(int i, int j) {
    cand_ = res_.route;
    std::swap(cand_[static_cast<std::size_t>(i)], cand_[static_cast<std::size_t>(j)]);
    return try_candidate();
  }

  bool reverse(int i, int j) {
    if (j - i < 2) return false;  // a reversal of two is the swap of two neighbours
    cand_ = res_.route;
    std::reverse(cand_.begin() + i, cand_.begin() + j + 1);
    return try_candidate();
  }

  const Problem& p_;
  const SequenceCost& cost_;
  const HistorySearchParams& params_;
  const StopToken& stop_;
  HistorySearchResult res_;
  std::vector<NodeId> cand_, rest_;
  std::vector<int> pos_;
};

}  // namespace

bool keeps_precedence(const Problem& p, std::span<const NodeId> route) {
  std::vector<int> pos;
  return keeps(p, route, pos);
}

std::vector<NodeId> order_by_priority(const Problem& p, std::span<const NodeId> route, std::span<const double> priority) {
  const std::size_t m = route.size();
  std::vector<int> pos;
  fill_positions(p, route, pos);
  std::vector<int> waiting(static_cast<std::size_t>(p.cluster_count()), 0);
  std::vector<std::vector<ClusterId>> after(static_cast<std::size_t>(p.cluster_count()));
  for (auto [a, b] : p.precedence()) {
    if (pos[a.index()] < 0 || pos[b.index()] < 0) continue;
    ++waiting[b.index()];
    after[a.index()].push_back(b);
  }
  using Key = std::tuple<double, int>;  // (priority, position in route)
  std::priority_queue<Key, std::vector<Key>, std::greater<>> ready;
  std::vector<NodeId> out;
  out.reserve(m);
  auto release = [&](ClusterId c) {
    for (ClusterId b : after[c.index()])
      if (--waiting[b.index()] == 0) ready.emplace(priority[b.index()], pos[b.index()]);
  };
  if (m == 0) return out;
  out.push_back(route[0]);  // the start stays first
  for (std::size_t i = 1; i < m; ++i) {
    const ClusterId c = p.cluster_of(route[i]);
    if (waiting[c.index()] == 0) ready.emplace(priority[c.index()], static_cast<int>(i));
  }
  // After the scan: releasing the start first queued its successors twice (SOP: node 1 precedes all).
  release(p.cluster_of(route[0]));
  while (!ready.empty()) {
    const auto [prio, at] = ready.top();
    ready.pop();
    const NodeId v = route[static_cast<std::size_t>(at)];
    out.push_back(v);
    release(p.cluster_of(v));
  }
  return out;  // shorter than route only if route broke precedence (a cycle cannot exist in a Problem)
}

std::vector<NodeId> greedy_route(const Problem& p, const SequenceCost& cost, std::span<const NodeId> nodes) {
  std::vector<NodeId> route;
  if (nodes.empty()) return route;
  std::vector<int> waiting(static_cast<std::size_t>(p.cluster_count()), 0);
  std::vector<int> pos;
  fill_positions(p, nodes, pos);
  for (auto [a, b] : p.precedence())
    if (pos[a.index()] >= 0 && pos[b.index()] >= 0) ++waiting[b.index()];
  std::vector<char> placed(nodes.size(), 0);
  auto place = [&](std::size_t i) {
    placed[i] = 1;
    route.push_back(nodes[i]);
    const ClusterId c = p.cluster_of(nodes[i]);
    for (auto [a, b] : p.precedence())
      if (a == c && pos[b.index()] >= 0) --waiting[b.index()];
  };
  place(0);
  for (std::size_t step = 1; step < nodes.size(); ++step) {
    std::size_t best = nodes.size();
    Cost best_cost = 0;
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      if (placed[i] || waiting[p.cluster_of(nodes[i]).index()] > 0) continue;
      route.push_back(nodes[i]);
      const Cost c = cost(route);
      route.pop_back();
      if (best == nodes.size() || c < best_cost) {
        best = i;
        best_cost = c;
      }
    }
    if (best == nodes.size()) break;  // only when `nodes` breaks precedence
    place(best);
  }
  return route;
}

HistorySearchResult history_search(const Problem& p, const SequenceCost& cost, const std::vector<std::vector<NodeId>>& starts,
                                   const HistorySearchParams& params, const StopToken& stop) {
  std::vector<NodeId> best;
  Cost best_cost = 0;
  long long evals = 0;
  for (const auto& s : starts) {
    if (!keeps_precedence(p, s)) continue;
    const Cost c = cost(s);
    ++evals;
    if (best.empty() || c < best_cost) {
      best = s;
      best_cost = c;
    }
  }
  HistorySearchResult res;
  if (best.empty()) return res;
  Search search(p, cost, params, stop);
  res = search.run(std::move(best), best_cost);
  res.evaluations += evals;
  return res;
}

}  // namespace cutroute::solve
