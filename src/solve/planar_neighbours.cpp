#include "planar_neighbours.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include <nanoflann.hpp>

#include <cutroute/core/parallel.hpp>
#include <cutroute/solve/heuristic.hpp>

namespace cutroute::solve::detail {

namespace {

// nanoflann's dataset interface over one point table of the problem.
struct Cloud {
  const std::vector<PlanarPoint>& pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return dim == 0 ? pts[i].x : pts[i].y; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
constexpr std::size_t kQueries = 8;  // per cluster

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 2, std::uint32_t>;

// nanoflann result set keeping the kn nearest distinct clusters other than `self` seen by the queries
// since reset():
// a plain k-nearest query would return mostly the entries of the query's own contour and of one
// neighbour, and would need a k of hundreds (nanoflann's sorted result set costs O(k) per point).
class ClusterResults {
 public:
  ClusterResults(const Problem& p, std::size_t kn) : p_(p), kn_(kn) { items_.reserve(kn + 1); }
  void reset(int self) {
    self_ = self;
    items_.clear();
  }
  bool addPoint(double d2, std::uint32_t i) {
    const int b = p_.cluster_of(NodeId(static_cast<int>(i))).value();
    if (b == self_) return true;
    std::size_t at = items_.size();
    for (std::size_t r = 0; r < items_.size(); ++r)
      if (items_[r].second == b) {
        if (!(d2 < items_[r].first)) return true;
        at = r;
        break;
      }
    if (at == items_.size()) {  // a new cluster: in when there is room, else in place of the worst
      if (items_.size() < kn_) items_.emplace_back();
      else if (!(d2 < items_.back().first)) return true;
      at = items_.size() - 1;
    }
    items_[at] = {d2, b};
    // Keep nearest first: the changed entry moves up to its place.
    for (; at > 0 && items_[at] < items_[at - 1]; --at) std::swap(items_[at], items_[at - 1]);
    return true;
  }
  // Just below the worst kept distance once full: nanoflann reads every branch and point not
  // farther than worstDist(), and those at exactly the worst distance could not get in (a tie is
  // refused above), so the lists are the same. At the worst distance itself, points at one spot
  // made every query read all of them: 40 000 such points took 5 s of candidate lists.
  double worstDist() const {
    return items_.size() < kn_ ? std::numeric_limits<double>::max() : std::nextafter(items_.back().first, -std::numeric_limits<double>::infinity());
  }
  bool full() const { return items_.size() == kn_; }
  const std::vector<std::pair<double, int>>& items() const { return items_; }

 private:
  const Problem& p_;
  std::size_t kn_;
  int self_ = -1;
  std::vector<std::pair<double, int>> items_;  // (squared distance, cluster), nearest first
};

// Rows of kn clusters for every cluster a: the clusters owning the points of `targets` nearest to
// the points of `sources` that belong to a's nodes (each cluster by its nearest point), a excluded.
// a's queries share one result set: the row is the kn clusters nearest to any of them, and each
// query after the first starts from the distance the row already holds, so the tree cuts off what
// lies farther (a result set per query, merged afterwards, read a third more points: on 24 000
// parts with 2 holes each, 816 000 candidates, the two lists took 1.8 s instead of 1.2 s).
void lists(const Problem& p, std::size_t kn, const std::vector<PlanarPoint>& sources, const std::vector<PlanarPoint>& targets,
           std::vector<ClusterId>& out) {
  const int m = p.cluster_count();
  out.assign(static_cast<std::size_t>(m) * kn, ClusterId(0));
  const Cloud cloud{targets};
  const Tree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  ClusterResults res(p, kn);
  std::vector<std::pair<double, int>> row;
  for (int a = 0; a < m; ++a) {
    // Up to kQueries of a's nodes, evenly spread (entries along one contour: the neighbours seen
    // from a few of them are those seen from all, and each query visits ~kn clusters' points).
    const auto nodes = p.nodes_of(ClusterId(a));
    const std::size_t step = std::max<std::size_t>(1, (nodes.size() + kQueries - 1) / kQueries);
    res.reset(a);
    for (std::size_t r = 0; r < nodes.size(); r += step) {
      const PlanarPoint q = sources[nodes[r].index()];
      const double qp[2] = {q.x, q.y};
      tree.findNeighbors(res, qp, nanoflann::SearchParams());
    }
    // By distance, ties by cluster id.
    row.assign(res.items().begin(), res.items().end());
    std::sort(row.begin(), row.end());
    // The first query sees kn clusters when there are (kn < m), so the row is full.
    for (std::size_t r = 0; r < kn; ++r)
      out[static_cast<std::size_t>(a) * kn + r] = ClusterId(row[std::min(r, row.size() - 1)].second);
  }
}

}  // namespace

std::vector<Cost> planar_cheapest_arcs_in(const Problem& p) {
  const PlanarCosts& pc = *p.planar();
  const Cloud cloud{pc.out};
  const Tree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  ClusterResults res(p, 1);  // the nearest point of another cluster
  std::vector<Cost> cheapest(static_cast<std::size_t>(p.node_count()));
  for (int v = 0; v < p.node_count(); ++v) {
    const PlanarPoint q = pc.in[static_cast<std::size_t>(v)];
    const double qp[2] = {q.x, q.y};
    res.reset(p.cluster_of(NodeId(v)).value());
    tree.findNeighbors(res, qp, nanoflann::SearchParams());
    // The price as Problem::planar_arc forms it, from a length and a price a few ulps short of the
    // tree's: its sum of squares may round otherwise than planar_arc's.
    double t = (pc.base + pc.per_unit * std::sqrt(res.items().front().first) * (1.0 - 1e-12)) * pc.scale;
    t -= std::abs(t) * 1e-12;
    cheapest[static_cast<std::size_t>(v)] = static_cast<Cost>(std::clamp(t, 0.0, static_cast<double>(kMaxCost)) + 0.5);
  }
  return cheapest;
}

void planar_neighbours(const Problem& p, std::size_t kn, std::vector<ClusterId>& pred, std::vector<ClusterId>& succ,
                       bool two_threads) {
  const PlanarCosts& pc = *p.planar();
  // Each list reads the problem only: about 0.4 s each on a plate of 40 000 holes of 12 candidates.
  deal(2, two_threads ? 2 : 1, 1, [&](std::size_t k) {
    if (k == 0) lists(p, kn, pc.out, pc.in, succ);  // a -> b: leave a at out, enter b at in
    else lists(p, kn, pc.in, pc.out, pred);         // b -> a: the out points nearest to a's in points
  });
}

}  // namespace cutroute::solve::detail

namespace cutroute::solve {

CandidateLists planar_candidate_lists(const Problem& p, std::size_t kn) {
  CandidateLists l;
  detail::planar_neighbours(p, kn, l.pred, l.succ);
  return l;
}

}  // namespace cutroute::solve
