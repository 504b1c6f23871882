#include <cutroute/solve/problem.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace cutroute::solve {

Cost Problem::arc_from_function(NodeId from, NodeId to) const {
  if (!forbidden_keys_.empty()) {
    const std::uint64_t key = from.index() * n_ + to.index();
    if (std::binary_search(forbidden_keys_.begin(), forbidden_keys_.end(), key)) return kForbiddenCost;
  }
  const Cost c = planar_ ? planar_arc(from, to) : (*fn_)(from, to);
  return c >= kForbiddenCost ? kForbiddenCost : c;
}

bool Problem::must_precede(ClusterId a, ClusterId b) const {
  const auto before = all_before(b);
  return std::binary_search(before.begin(), before.end(), a);
}

ProblemBuilder::ProblemBuilder(int node_count) : n_(node_count) {}

ProblemBuilder& ProblemBuilder::set_name(std::string name) {
  name_ = std::move(name);
  return *this;
}
ProblemBuilder& ProblemBuilder::set_cost_matrix(std::vector<Cost> matrix) {
  matrix_ = std::move(matrix);
  fn_.reset();
  planar_.reset();
  return *this;
}
ProblemBuilder& ProblemBuilder::set_cost_function(CostFn fn, bool symmetric) {
  fn_ = std::make_shared<const CostFn>(std::move(fn));
  fn_symmetric_ = symmetric;
  matrix_.clear();
  planar_.reset();
  return *this;
}
ProblemBuilder& ProblemBuilder::set_planar_costs(PlanarCosts costs) {
  planar_ = std::make_shared<const PlanarCosts>(std::move(costs));
  fn_.reset();
  fn_symmetric_ = false;
  matrix_.clear();
  return *this;
}
ProblemBuilder& ProblemBuilder::set_inner_cost(NodeId v, Cost c) {
  if (inner_.empty()) inner_.assign(static_cast<std::size_t>(std::max(n_, 0)), 0);
  if (v.valid() && v.value() < n_) inner_[v.index()] = c;
  else inner_.push_back(-1);  // reported by build()
  return *this;
}
ClusterId ProblemBuilder::add_cluster(std::vector<NodeId> nodes) {
  clusters_.push_back(std::move(nodes));
  return ClusterId(static_cast<int>(clusters_.size()) - 1);
}
ProblemBuilder& ProblemBuilder::add_precedence(ClusterId before, ClusterId after) {
  precedence_.emplace_back(before, after);
  return *this;
}
ProblemBuilder& ProblemBuilder::forbid_arc(NodeId from, NodeId to) {
  forbidden_.emplace_back(from, to);
  return *this;
}
ProblemBuilder& ProblemBuilder::set_start_cluster(ClusterId c) {
  start_ = c;
  return *this;
}
ProblemBuilder& ProblemBuilder::set_kind(RouteKind kind) {
  kind_ = kind;
  return *this;
}

namespace {

Diagnostic err(std::string msg) { return make_error(std::move(msg)); }
std::string str(long v) { return std::to_string(v); }

}  // namespace

Result<Problem> ProblemBuilder::build() {
  const int m = static_cast<int>(clusters_.size());
  if (n_ <= 0) return err("problem has no nodes");
  if (m == 0) return err("problem has no clusters");
  const auto n = static_cast<std::size_t>(n_);
  if (matrix_.empty() && !fn_ && !planar_) return err("problem has no costs (neither matrix nor cost function nor points)");
  if (planar_) {
    if (planar_->out.size() != n || planar_->in.size() != n)
      return err("planar costs give " + str(static_cast<long>(planar_->out.size())) + " out and " +
                 str(static_cast<long>(planar_->in.size())) + " in points for " + str(n_) + " nodes");
    if (!(planar_->per_unit >= 0) || !(planar_->base >= 0) || !(planar_->scale > 0) || !std::isfinite(planar_->base) ||
        !std::isfinite(planar_->per_unit) || !std::isfinite(planar_->scale))
      return err("planar costs need finite base >= 0, per_unit >= 0 and scale > 0");
    for (const auto* pts : {&planar_->out, &planar_->in})
      for (const PlanarPoint& q : *pts)
        if (!std::isfinite(q.x) || !std::isfinite(q.y)) return err("planar costs have a point that is not finite");
  }
  if (!matrix_.empty() && matrix_.size() != n * n)
    return err("cost matrix has " + str(static_cast<long>(matrix_.size())) + " entries, expected " +
               str(static_cast<long>(n * n)));
  if (inner_.size() > n) return err("inner cost given for a node id outside [0, " + str(n_) + ")");

  Problem p;
  p.n_ = n;
  p.name_ = name_;
  p.kind_ = kind_;
  p.cluster_of_.assign(n, ClusterId{});
  for (int c = 0; c < m; ++c) {
    if (clusters_[c].empty()) return err("cluster " + str(c) + " is empty");
    for (NodeId v : clusters_[c]) {
      if (!v.valid() || v.value() >= n_)
        return err("cluster " + str(c) + " names node " + str(v.value()) + " outside [0, " + str(n_) + ")");
      if (p.cluster_of_[v].valid())
        return err("node " + str(v.value()) + " is in clusters " + str(p.cluster_of_[v].value()) + " and " + str(c));
      p.cluster_of_[v] = ClusterId(c);
      p.members_.push_back(v);
    }
    p.cluster_begin_.push_back(static_cast<int>(p.members_.size()));
  }
  for (std::size_t v = 0; v < n; ++v)
    if (!p.cluster_of_[NodeId(static_cast<int>(v))].valid()) return err("node " + str(static_cast<long>(v)) + " is in no cluster");
  for (std::size_t v = 0; v < inner_.size(); ++v)
    if (inner_[v] < 0 || inner_[v] > kMaxCost)
      return err("inner cost of node " + str(static_cast<long>(v)) + " is outside [0, 2^40]");
  bool any_inner = false;
  for (Cost c : inner_) any_inner = any_inner || c != 0;
  if (any_inner) p.inner_ = inner_;

  if (!start_.valid() || start_.value() >= m) return err("start cluster " + str(start_.value()) + " does not exist");
  p.start_ = start_;

  if (!matrix_.empty()) {
    Cost dearest = 0;
    bool any_forbidden = !forbidden_.empty();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        Cost& c = matrix_[i * n + j];
        if (i == j) continue;
        if (c < 0) return err("cost of arc " + str(static_cast<long>(i)) + " -> " + str(static_cast<long>(j)) + " is negative");
        if (c > kMaxCost && c != kForbiddenCost)
          return err("cost of arc " + str(static_cast<long>(i)) + " -> " + str(static_cast<long>(j)) + " exceeds 2^40");
        if (c == kForbiddenCost) any_forbidden = true;
        else dearest = std::max(dearest, c);
      }
    for (auto [a, b] : forbidden_) {
      if (!a.valid() || !b.valid() || a.value() >= n_ || b.value() >= n_) return err("forbidden arc names a node outside the problem");
      matrix_[a.index() * n + b.index()] = kForbiddenCost;
    }
    // The heuristics price a forbidden arc at kForbiddenCost: a route of allowed arcs must cost less,
    // or one through a forbidden arc would look the cheaper (4 arcs of 2^40 against one of 2^41).
    if (any_forbidden && dearest > (kForbiddenCost - 1) / m)
      return err("arc costs up to " + str(static_cast<long>(dearest)) + " with " + str(m) +
                 " clusters: a route could cost more than a forbidden arc is priced (2^41); with forbidden arcs, costs up to " +
                 str(static_cast<long>((kForbiddenCost - 1) / m)) + " are supported");
    bool sym = true;
    for (std::size_t i = 0; i < n && sym; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (matrix_[i * n + j] != matrix_[j * n + i]) {
          sym = false;
          break;
        }
    p.symmetric_ = sym;
    p.matrix_ = std::move(matrix_);
  } else {
    p.fn_ = fn_;
    p.planar_ = planar_;
    for (auto [a, b] : forbidden_) {
      if (!a.valid() || !b.valid() || a.value() >= n_ || b.value() >= n_) return err("forbidden arc names a node outside the problem");
      p.forbidden_keys_.push_back(a.index() * n + b.index());
    }
    std::sort(p.forbidden_keys_.begin(), p.forbidden_keys_.end());
    // Planar costs with the same in and out point per node are symmetric (TSPLIB EUC_2D coordinates).
    const bool planar_sym = planar_ && std::equal(planar_->out.begin(), planar_->out.end(), planar_->in.begin(),
                                                  [](PlanarPoint a, PlanarPoint b) { return a.x == b.x && a.y == b.y; });
    p.symmetric_ = (fn_symmetric_ || planar_sym) && forbidden_.empty();
  }

  // Precedence: drop duplicates and pairs starting at the start cluster (always kept), reject
  // anything that must come before the start, self loops and cycles.
  std::vector<std::vector<int>> succ(static_cast<std::size_t>(m));
  std::sort(precedence_.begin(), precedence_.end());
  precedence_.erase(std::unique(precedence_.begin(), precedence_.end()), precedence_.end());
  for (auto [a, b] : precedence_) {
    if (!a.valid() || !b.valid() || a.value() >= m || b.value() >= m)
      return err("precedence " + str(a.value()) + " -> " + str(b.value()) + " names a cluster that does not exist");
    if (a == b) return err("cluster " + str(a.value()) + " must precede itself");
    if (b == start_) return err("cluster " + str(a.value()) + " must precede the start cluster " + str(b.value()));
    p.precedence_.emplace_back(a, b);
    succ[a.index()].push_back(b.value());
  }
  if (!p.precedence_.empty()) {
    // Topological order (Kahn), then closure by a DFS from each cluster: O(m * pairs in closure).
    std::vector<int> indeg(static_cast<std::size_t>(m), 0);
    for (auto [a, b] : p.precedence_) ++indeg[b.index()];
    std::vector<int> order;
    for (int c = 0; c < m; ++c)
      if (indeg[c] == 0) order.push_back(c);
    for (std::size_t k = 0; k < order.size(); ++k)
      for (int s : succ[order[k]])
        if (--indeg[s] == 0) order.push_back(s);
    if (static_cast<int>(order.size()) != m) {
      for (int c = 0; c < m; ++c)
        if (indeg[c] > 0) return err("precedence constraints form a cycle through cluster " + str(c));
    }
    std::vector<std::vector<ClusterId>> after(static_cast<std::size_t>(m)), before(static_cast<std::size_t>(m));
    std::vector<int> mark(static_cast<std::size_t>(m), -1);
    std::vector<int> stack;
    std::size_t pairs = 0;
    for (int c = 0; c < m; ++c) {
      stack.assign(succ[c].begin(), succ[c].end());
      while (!stack.empty()) {
        const int x = stack.back();
        stack.pop_back();
        if (mark[x] == c) continue;
        mark[x] = c;
        // The closure is kept as lists (the heuristics read them in their inner loops): quadratic
        // in the length of the chains. A chain through 8 000 clusters took 1.2 GB.
        if (++pairs > kMaxClosurePairs)
          return err("the precedence pairs imply more than " + str(static_cast<long>(kMaxClosurePairs)) +
                     " ordered pairs of clusters (chains through thousands of clusters); that many are not supported");
        after[c].push_back(ClusterId(x));
        before[x].push_back(ClusterId(c));
        for (int s : succ[x])
          if (mark[s] != c) stack.push_back(s);
      }
    }
    auto pack = [m](std::vector<std::vector<ClusterId>>& lists, Problem::Closure& out) {
      out.begin.assign(1, 0);
      for (int c = 0; c < m; ++c) {
        std::sort(lists[c].begin(), lists[c].end());
        out.items.insert(out.items.end(), lists[c].begin(), lists[c].end());
        out.begin.push_back(static_cast<int>(out.items.size()));
      }
    };
    pack(after, p.after_);
    pack(before, p.before_);
  }
  return p;
}

}  // namespace cutroute::solve
