// solve::Problem: clusters of nodes, integer arc costs, precedence and forbidden arcs, built once and immutable.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <cutroute/core/ids.hpp>
#include <cutroute/core/result.hpp>

namespace cutroute::solve {

struct NodeTag;
struct ClusterTag;
using NodeId = Id<NodeTag>;        // 0-based; io/ maps file ids (1-based) to these
using ClusterId = Id<ClusterTag>;  // 0-based
using Cost = std::int64_t;         // one fixed unit chosen by the caller (ticks for cutting, see core/units.hpp)

// Every arc and inner cost must lie in [0, kMaxCost]. 2^40 ticks are 12.7 days of machine time, far
// above any real arc, and sums of up to 2^22 arcs of kForbiddenCost still fit in int64 (no overflow
// checks in the hot loops of the heuristics).
inline constexpr Cost kMaxCost = Cost{1} << 40;
// What arc_cost() returns for a forbidden arc (a cost callback returns it to forbid one). Larger than
// any allowed arc, so the heuristics avoid forbidden arcs as very expensive ones without a special
// case; validate() rejects them outright.
inline constexpr Cost kForbiddenCost = Cost{1} << 41;
// Most ordered pairs the precedence closure may hold (a before b, transitively): about 130 MB for
// both directions' lists; a single chain through 5 800 clusters. Cutting nests hold a few per
// contour (holes, parts in holes); SOPLIB's largest instances a quarter of a million.
inline constexpr std::size_t kMaxClosurePairs = std::size_t{1} << 24;

// Cost of travelling from one node to another (not including the inner cost of the target).
// Must be pure and thread-safe: the heuristics call it from several threads.
using CostFn = std::function<Cost(NodeId from, NodeId to)>;

// Arc costs of a route in the plane (cutting): leaving node v at out[v] and entering node w at
// in[w] costs round((base + per_unit * |in[w] - out[v]|) * scale). Computed inline on demand: no
// matrix (n^2 memory) and no callback (an indirect call per arc); the solver also builds its
// neighbour lists from the points with a k-d tree instead of m^2 sampled arcs.
struct PlanarPoint {
  double x = 0, y = 0;
};
struct PlanarCosts {
  std::vector<PlanarPoint> out, in;  // per node
  double base = 0, per_unit = 0;     // per_unit >= 0: the cost grows with the distance
  double scale = 1;
};

// closed_tour: the route returns from its last node to its first (the arc is paid);
// open_path: it ends at its last node (SOP, cutting routes that end anywhere).
enum class RouteKind { closed_tour, open_path };

class ProblemBuilder;

// The routing problem: visit exactly one node of every cluster, starting in the start cluster,
// keeping every precedence "cluster a before cluster b" (counted from the start of the route),
// using no forbidden arc; minimise the sum of arc costs plus the inner cost of every visited node.
// Immutable once built: only ProblemBuilder::build() makes one, after checking it.
class Problem {
 public:
  Problem() = default;

  int node_count() const { return static_cast<int>(cluster_of_.size()); }
  int cluster_count() const { return static_cast<int>(cluster_begin_.size()) - 1; }
  ClusterId cluster_of(NodeId v) const { return cluster_of_[v]; }
  // cluster_of() of every node, indexed by node: for hot loops that keep the pointer in a local.
  std::span<const ClusterId> cluster_of_nodes() const { return cluster_of_; }
  // The nodes of a cluster, in the order given to the builder.
  std::span<const NodeId> nodes_of(ClusterId c) const {
    return {members_.data() + cluster_begin_[c.index()], members_.data() + cluster_begin_[c.index() + 1]};
  }
  int cluster_size(ClusterId c) const { return cluster_begin_[c.index() + 1] - cluster_begin_[c.index()]; }

  // Travel cost from -> to; kForbiddenCost for a forbidden arc.
  Cost arc_cost(NodeId from, NodeId to) const {
    if (!matrix_.empty()) return matrix_[from.index() * n_ + to.index()];
    if (planar_) return forbidden_keys_.empty() ? planar_arc(from, to) : arc_from_function(from, to);
    return arc_from_function(from, to);
  }
  bool forbidden(NodeId from, NodeId to) const { return arc_cost(from, to) >= kForbiddenCost; }
  Cost inner_cost(NodeId v) const { return inner_.empty() ? 0 : inner_[v.index()]; }
  // What the solvers add when the route enters `to` from `from`: arc plus inner cost of `to`,
  // or kForbiddenCost. Every route cost is a sum of these (plus the first node's inner cost on a path).
  Cost step(NodeId from, NodeId to) const {
    const Cost a = arc_cost(from, to);
    return a >= kForbiddenCost ? kForbiddenCost : a + inner_cost(to);
  }

  ClusterId start_cluster() const { return start_; }
  RouteKind kind() const { return kind_; }
  bool closed() const { return kind_ == RouteKind::closed_tour; }
  // True when arc_cost(a, b) == arc_cost(b, a) for all nodes (checked for matrices, declared for callbacks).
  bool symmetric() const { return symmetric_; }
  bool has_matrix() const { return !matrix_.empty(); }
  // Row-major node_count x node_count costs (forbidden arcs at kForbiddenCost), or null without a
  // matrix: the solvers' inner loops read it directly (arc_cost's dispatch is not inlined there).
  const Cost* matrix_data() const { return matrix_.empty() ? nullptr : matrix_.data(); }
  bool has_inner_costs() const { return !inner_.empty(); }
  // The points and prices behind the arc costs when they were given that way, else null.
  const PlanarCosts* planar() const { return planar_.get(); }
  // arc_cost() is exactly the planar formula (planar costs and no forbidden arc), so a solver may
  // evaluate many arcs at once from the points.
  bool plain_planar() const { return planar_ && forbidden_keys_.empty(); }
  // The arc's planar price (planar() only; arc_cost() without the forbidden-arc look-up). Always
  // inlined: GCC kept it out of line in Or-opt and swap, 31 % of a d2g_DRAAK run as calls; inlined,
  // the same program with 8 % less CPU.
  [[gnu::always_inline]] Cost planar_arc(NodeId from, NodeId to) const {
    const PlanarPoint a = planar_->out[from.index()], b = planar_->in[to.index()];
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double t = (planar_->base + planar_->per_unit * std::sqrt(dx * dx + dy * dy)) * planar_->scale;
    // + 0.5 and truncation rounds like llround for t >= 0, several times faster (a hot loop).
    return static_cast<Cost>(std::min(t, static_cast<double>(kMaxCost)) + 0.5);
  }

  // Precedence as given to the builder (before, after), without duplicates.
  const std::vector<std::pair<ClusterId, ClusterId>>& precedence() const { return precedence_; }
  bool has_precedence() const { return !precedence_.empty(); }
  // Transitive closure: every cluster that must come before c / after c, sorted by id.
  std::span<const ClusterId> all_before(ClusterId c) const { return closure(before_, c); }
  std::span<const ClusterId> all_after(ClusterId c) const { return closure(after_, c); }
  bool must_precede(ClusterId a, ClusterId b) const;  // O(log) in the closure of b

  const std::string& name() const { return name_; }

 private:
  friend class ProblemBuilder;
  Cost arc_from_function(NodeId from, NodeId to) const;
  struct Closure {
    std::vector<int> begin;  // size cluster_count + 1
    std::vector<ClusterId> items;
  };
  static std::span<const ClusterId> closure(const Closure& cl, ClusterId c) {
    if (cl.begin.empty()) return {};
    return {cl.items.data() + cl.begin[c.index()], cl.items.data() + cl.begin[c.index() + 1]};
  }

  std::size_t n_ = 0;
  std::vector<Cost> matrix_;  // row-major n x n travel costs (kForbiddenCost folded in); empty with a callback
  std::shared_ptr<const CostFn> fn_;
  std::shared_ptr<const PlanarCosts> planar_;  // set instead of fn_ for planar costs
  std::vector<std::uint64_t> forbidden_keys_;  // sorted from*n+to, only used with a callback
  std::vector<Cost> inner_;                    // empty when all zero
  IdVector<NodeId, ClusterId> cluster_of_;
  std::vector<int> cluster_begin_{0};
  std::vector<NodeId> members_;
  ClusterId start_{0};
  RouteKind kind_ = RouteKind::closed_tour;
  bool symmetric_ = false;
  std::vector<std::pair<ClusterId, ClusterId>> precedence_;
  Closure before_, after_;
  std::string name_;
};

// Collects the parts of a Problem and checks them in build(): every node in exactly one cluster,
// costs within [0, kMaxCost] (or forbidden), precedence acyclic and never before the start cluster.
class ProblemBuilder {
 public:
  explicit ProblemBuilder(int node_count);

  ProblemBuilder& set_name(std::string name);
  // Row-major node_count x node_count travel costs; negative entries are rejected, entries equal to
  // kForbiddenCost forbid the arc. The diagonal is never used.
  ProblemBuilder& set_cost_matrix(std::vector<Cost> matrix);
  // On-demand costs (large nests); `symmetric` is the caller's promise that cost(a,b) == cost(b,a).
  ProblemBuilder& set_cost_function(CostFn fn, bool symmetric);
  // Costs from points (see PlanarCosts): one out and one in point per node.
  ProblemBuilder& set_planar_costs(PlanarCosts costs);
  ProblemBuilder& set_inner_cost(NodeId v, Cost c);
  ClusterId add_cluster(std::vector<NodeId> nodes);
  ProblemBuilder& add_precedence(ClusterId before, ClusterId after);
  ProblemBuilder& forbid_arc(NodeId from, NodeId to);
  ProblemBuilder& set_start_cluster(ClusterId c);
  ProblemBuilder& set_kind(RouteKind kind);

  // The checked, closed Problem, or the first problem found (message names the node/cluster).
  Result<Problem> build();

 private:
  int n_;
  std::vector<Cost> matrix_;
  std::shared_ptr<const CostFn> fn_;
  std::shared_ptr<const PlanarCosts> planar_;
  bool fn_symmetric_ = false;
  std::vector<Cost> inner_;
  std::vector<std::vector<NodeId>> clusters_;
  std::vector<std::pair<ClusterId, ClusterId>> precedence_;
  std::vector<std::pair<NodeId, NodeId>> forbidden_;
  ClusterId start_{0};
  RouteKind kind_ = RouteKind::closed_tour;
  std::string name_;
};

}  // namespace cutroute::solve
