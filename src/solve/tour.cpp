#include "tour.hpp"

#include "planar_neighbours.hpp"

#include <cutroute/solve/params.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>

namespace cutroute::solve::detail {

namespace {
// Neighbour-list length: moves are only evaluated next to the closest clusters (as in LKH's
// candidate sets); 12 keeps GTSPLIB optima reachable while making a pass O(m * 12 * k).
constexpr int kNeighbours = 12;
// Nodes per cluster used to measure cluster distances (large clusters are sampled evenly).
constexpr std::size_t kSampleNodes = 12;
// Above this many evaluations for one cluster-optimisation pass, local search only re-optimises
// windows around the changes (large clusters: 100C10k.0 has 100 nodes per cluster).
constexpr double kMaxFullCoWork = 2.0e5;
// Symmetric planar problems up to this many clusters get sampled candidate lists (see Ops::Ops).
constexpr int kMaxSampledPlanarClusters = 1000;
// Precedence bit matrix up to this many clusters (2 MiB).
constexpr int kMaxPrecedenceBits = 4096;
// Cluster-blocked matrix copies up to this many nodes (2 x 32 MiB at most).
constexpr int kMaxBlockedNodes = 2048;
// Node-to-cluster bounds of the 2-opt with neighbour optimisation up to n * m entries (32 MiB).
constexpr std::size_t kMaxNeighbourBounds = std::size_t{1} << 22;
// Exact asymmetric 2-opt up to this many clusters: above it the O(L^2) scan costs more than it finds.
constexpr int kMaxAsymTwoOptClusters = 300;
// Precedence problems from this many clusters on, with at most kLocalPrecedencePairs closure pairs
// per cluster, get neighbour-list reinsertion, 2-opt, Or-opt, swap and repair (Ops::local_prec_):
// cutting nests, whose holes come before their outer contour (about one pair per cluster), from the
// size at which the metaheuristic already treats them as long routes (solve_heuristic). The
// SOP instances keep the window scans tuned on them: below 200 clusters (prob.100, kro124p), or
// dense (rbg253a: 120 pairs per cluster, where most candidate places break a pair; with the lists
// it ended at 2 951 instead of 2 950 in 1 of 3 seeds, and took 40 % longer).
constexpr int kLocalPrecedenceClusters = 200;
constexpr std::size_t kLocalPrecedencePairs = 8;
// A repair whose cluster has too few candidate neighbours left in a route longer than this looks
// for the nearest clusters present (at most kMaxRepairSearch visited) before scanning it whole.
constexpr int kFullScanRepairRoute = 2048;
constexpr std::size_t kMaxRepairSearch = 4096;
}  // namespace

Ops::Ops(const Problem& p, const StopToken* stop, int threads)
    : p_(p),
      mat_(p.matrix_data()),
      n_(static_cast<std::size_t>(p.node_count())),
      plain_mat_(mat_ != nullptr && !p.has_inner_costs()),
      plain_planar_(p.plain_planar()),
      stop_(stop), m_(p.cluster_count()), closed_(p.closed()), prec_(p.has_precedence()) {
  if (prec_ && m_ <= kMaxPrecedenceBits) {
    const auto mm = static_cast<std::size_t>(m_);
    prec_bits_.assign((mm * mm + 63) / 64, 0);
    for (int b = 0; b < m_; ++b)
      for (ClusterId a : p.all_before(ClusterId(b))) {
        const std::size_t k = static_cast<std::size_t>(b) * mm + a.index();
        prec_bits_[k >> 6] |= std::uint64_t{1} << (k & 63);
      }
  }
  // The innermost loops (insertion of a cluster between two nodes, cluster optimisation) read the
  // arcs between one node and every node of one cluster. GTSPLIB numbers a cluster's nodes far apart,
  // so in the row-major matrix (megabytes, beyond L2) each of those k reads is a cache miss; in the
  // copies below they are k neighbouring entries (200E1k.0: 1000 nodes, 8 MB matrix).
  // Planar problems keep their points in the same blocked order (below).
  const bool blocked_matrix = plain_mat_ && static_cast<int>(n_) <= kMaxBlockedNodes;
  if (blocked_matrix || plain_planar_) {
    blk_off_.assign(static_cast<std::size_t>(m_) + 1, 0);
    for (int c = 0; c < m_; ++c) blk_off_[static_cast<std::size_t>(c) + 1] = blk_off_[static_cast<std::size_t>(c)] + static_cast<std::size_t>(p.cluster_size(ClusterId(c)));
  }
  if (blocked_matrix) {
    std::vector<std::size_t> slot(n_);
    for (int c = 0; c < m_; ++c) {
      const auto nodes = p.nodes_of(ClusterId(c));
      for (std::size_t j = 0; j < nodes.size(); ++j) slot[nodes[j].index()] = blk_off_[static_cast<std::size_t>(c)] + j;
    }
    blk_out_.resize(n_ * n_);
    if (!p.symmetric()) blk_in_.resize(n_ * n_);
    for (std::size_t u = 0; u < n_; ++u)
      for (std::size_t v = 0; v < n_; ++v) {
        blk_out_[u * n_ + slot[v]] = mat_[u * n_ + v];
        if (!blk_in_.empty()) blk_in_[u * n_ + slot[v]] = mat_[v * n_ + u];
      }
  }
  if (plain_planar_) {
    const PlanarCosts& pc = *p.planar();
    pox_.reserve(n_), poy_.reserve(n_), pix_.reserve(n_), piy_.reserve(n_);
    if (p.has_inner_costs()) pinner_.reserve(n_);
    for (int c = 0; c < m_; ++c)
      for (NodeId v : p.nodes_of(ClusterId(c))) {
        pox_.push_back(pc.out[v.index()].x), poy_.push_back(pc.out[v.index()].y);
        pix_.push_back(pc.in[v.index()].x), piy_.push_back(pc.in[v.index()].y);
        if (p.has_inner_costs()) pinner_.push_back(p.inner_cost(v));
      }
  }
  // Asymmetric matrices that are symmetric but for small perturbations or the arcs precedence
  // forbids (SOP prob.100, kro124p, ry48p) get segment reversals priced exactly; on strongly
  // asymmetric ones (rbg, ft, p43: |c(a,b) - c(b,a)| 40-170 % of the mean) a reversed segment
  // practically never pays and the O(L^2) scan only costs time.
  if (mat_ && !p.symmetric() && m_ <= kMaxAsymTwoOptClusters) {
    double diff = 0, sum = 0;
    finite_symmetric_ = true;
    for (std::size_t u = 0; u < n_; ++u)
      for (std::size_t v = u + 1; v < n_; ++v) {
        const Cost a = mat_[u * n_ + v], b = mat_[v * n_ + u];
        if (a >= kForbiddenCost || b >= kForbiddenCost) continue;
        finite_symmetric_ = finite_symmetric_ && a == b;
        diff += static_cast<double>(a > b ? a - b : b - a);
        sum += 0.5 * static_cast<double>(a + b);
      }
    near_symmetric_ = diff <= 0.1 * sum;
  }
  kn_ = static_cast<std::size_t>(std::min(kNeighbours, std::max(0, m_ - 1)));
  if (prec_ && m_ >= kLocalPrecedenceClusters && static_cast<int>(kn_) * 4 < m_) {
    std::size_t pairs = 0;
    for (int c = 0; c < m_; ++c) pairs += p.all_before(ClusterId(c)).size();
    local_prec_ = pairs <= kLocalPrecedencePairs * static_cast<std::size_t>(m_);
  }
  // Nearly symmetric plain matrices (SOP prob.100, kro124p, ry48p; lin_kernighan.cpp), and
  // symmetric ones of at least 96 clusters without precedence (GTSPLIB 99-217, where the population
  // mode runs): the population's children need the deeper moves (GTSPLIB 99-217, 25 seeds: mean gap
  // 0.017 % -> 0.008 %, runs above 0.3 % 4 -> 1 of 500, at the same wall time since chains there
  // are priced in O(1)), while in single-route rounds they did not pay (seeds 1-12: 0.168 % against
  // 0.166 %), nor below 96 clusters (GTSPLIB <= 89: 419 against 420 of 425 runs at the best known,
  // 23 % more time). Not yet on cutting routes (inner costs), which were not measured.
  const bool large_sym = p.symmetric() && !prec_ && m_ >= SolveParams::kLargeClusters;
  lk_ = kn_ > 0 && (near_symmetric_ || large_sym) && plain_mat_;
  if (lk_)
    for (auto pr : p.precedence())
      if (pr.first != p.start_cluster()) lk_pairs_.push_back(pr);
  if (kn_ == 0) return;
  const double avg = static_cast<double>(p.node_count()) / m_;
  // One cluster-optimisation pass costs about m * (n/m)^2 evaluations per start node.
  expensive_co_ = static_cast<double>(m_) * avg * avg > kMaxFullCoWork;
  // 2-opt with neighbour optimisation (neighbour_opt.cpp): symmetric plain matrices without
  // precedence and with small clusters (GTSPLIB up to ~1 000 nodes). GTSPLIB 99-217 clusters,
  // seeds 6-13: 212u1060 0.34 -> 0.15 %, 217vm1084 0.29 -> 0.15 %, 134gr666 0.37 -> 0.17 % mean gap.
  no_ = plain_mat_ && p.symmetric() && !prec_ && !expensive_co_ && n_ * static_cast<std::size_t>(m_) <= kMaxNeighbourBounds;
  if (no_) build_neighbour_bounds();
  // k-d tree lists for the long routes of cutting nests; GTSPLIB's large EUC_2D instances (symmetric
  // planar costs, at most a few hundred clusters) keep the sampled lists below, which cost little
  // there and served them better (100C10k.0: 0.02 % mean gap over 5 seeds, 0.43 % with the tree's).
  if (p.planar() && !(p.symmetric() && m_ <= kMaxSampledPlanarClusters)) {
    planar_neighbours(p, kn_, pred_, succ_, threads > 1);
    return;
  }
  // The lists cost m^2 * samples^2 arc evaluations: fewer samples on very large problems (a nest of
  // 10^4 contours gets one node per cluster, ~2 * 10^8 evaluations).
  const double mm = static_cast<double>(m_) * m_;
  const auto samples = static_cast<std::size_t>(std::clamp(std::sqrt(4.0e7 / mm), 1.0, static_cast<double>(kSampleNodes)));
  std::vector<std::vector<NodeId>> sample(static_cast<std::size_t>(m_));
  for (int c = 0; c < m_; ++c) {
    const auto nodes = p.nodes_of(ClusterId(c));
    const std::size_t step = std::max<std::size_t>(1, nodes.size() / samples);
    for (std::size_t k = 0; k < nodes.size() && sample[static_cast<std::size_t>(c)].size() < samples; k += step)
      sample[static_cast<std::size_t>(c)].push_back(nodes[k]);
  }
  // For cluster a: the kn_ clusters b with the cheapest sampled arc b -> a (good predecessors) and
  // a -> b (good successors). On symmetric problems both lists are the same.
  auto build = [&](std::vector<ClusterId>& out, bool into) {
    out.resize(static_cast<std::size_t>(m_) * kn_);
    std::vector<std::pair<Cost, int>> d(static_cast<std::size_t>(m_));
    for (int a = 0; a < m_; ++a) {
      for (int b = 0; b < m_; ++b) {
        Cost best = kHuge;
        if (a != b)
          for (NodeId u : sample[static_cast<std::size_t>(a)])
            for (NodeId v : sample[static_cast<std::size_t>(b)]) best = std::min(best, into ? p.arc_cost(v, u) : p.arc_cost(u, v));
        d[static_cast<std::size_t>(b)] = {best, b};
      }
      std::partial_sort(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(kn_ + 1), d.end());
      std::size_t k = 0;
      for (std::size_t r = 0; r <= kn_ && k < kn_; ++r)
        if (d[r].second != a) out[static_cast<std::size_t>(a) * kn_ + k++] = ClusterId(d[r].second);
    }
  };
  build(pred_, true);
  if (p.symmetric()) succ_ = pred_;
  else build(succ_, false);
  exact_succs_ = n_ == static_cast<std::size_t>(m_);
  // Only LK's chains read these (lk_ implies a plain matrix).
  node_is_cluster_ = lk_ && exact_succs_;
  for (std::size_t v = 0; v < n_ && node_is_cluster_; ++v) node_is_cluster_ = p.cluster_of(NodeId(static_cast<int>(v))).index() == v;
  if (lk_ && exact_succs_) {
    succ_arc_.resize(succ_.size());
    for (int c = 0; c < m_; ++c)
      for (std::size_t k = 0; k < kn_; ++k) {
        const std::size_t i = static_cast<std::size_t>(c) * kn_ + k;
        succ_arc_[i] = arc(p.nodes_of(ClusterId(c))[0], p.nodes_of(succ_[i])[0]);
      }
  }
}

Cost Ops::full_cost(const std::vector<NodeId>& seq) const {
  if (seq.empty()) return 0;
  const std::size_t L = seq.size();
  Cost c = closed_ ? 0 : p_.inner_cost(seq[0]);
  for (std::size_t i = 0; i + 1 < L; ++i) c += link(seq[i], seq[i + 1]);
  if (closed_) c += link(seq[L - 1], seq[0]);
  return c;
}

void Ops::reverse_segment(Tour& t, int i, int j, Cost delta) const {
  std::reverse(t.seq.begin() + i, t.seq.begin() + j + 1);
  reindex(t, i, j + 1);
  t.cost += delta;
  mark_around(t, i);
  mark_around(t, j);
}

void Ops::reindex(Tour& t, int from, int to) const {
  for (int i = from; i < to; ++i) t.pos[cl(t.seq[static_cast<std::size_t>(i)]).index()] = i;
}

void Ops::init(Tour& t) const {
  t.pos.assign(static_cast<std::size_t>(m_), -1);
  reindex(t, 0, static_cast<int>(t.seq.size()));
  t.cost = full_cost(t.seq);
  t.dirty.assign(static_cast<std::size_t>(m_), 1);
  t.epoch = t.pass_start = 1;
  t.since = 0;
  t.touched.assign(static_cast<std::size_t>(m_), 1);
}

void Ops::mark(Tour& t, int i) const {
  const int L = static_cast<int>(t.seq.size());
  if (L == 0) return;
  if (i < 0 || i >= L) {
    if (!closed_) return;
    i = (i % L + L) % L;
  }
  const std::size_t c = cl(t.seq[static_cast<std::size_t>(i)]).index();
  t.dirty[c] = 1;
  t.touched[c] = t.epoch;
}

std::pair<int, int> Ops::window(const Tour& t, ClusterId c) const {
  int lo = 1, hi = static_cast<int>(t.seq.size());
  if (prec_) {
    for (ClusterId a : p_.all_before(c)) lo = std::max(lo, t.pos[a.index()] + 1);
    for (ClusterId b : p_.all_after(c))
      if (t.pos[b.index()] >= 0) hi = std::min(hi, t.pos[b.index()]);
  }
  return {lo, hi};
}

Ops::Insertion Ops::best_insertion(const Tour& t, ClusterId c, double noise, Rng* rng) const {
  const auto [lo, hi] = window(t, c);
  Insertion best;
  double best_key = std::numeric_limits<double>::infinity();
  Cost best_delta = kHuge;
  for (int at = lo; at <= hi; ++at) {
    const Insertion ins = insertion_at(t, c, at);
    if (noise > 0.0 && rng) {
      const double key = static_cast<double>(ins.delta) + noise * rng->uniform01();
      if (key < best_key) best_key = key, best = ins;
    } else if (ins.delta < best_delta) {
      best_delta = ins.delta;
      best = ins;
    }
  }
  return best;
}

// Inlined into both callers: called from insertion_at, 100C10k.0 took 10 % more CPU, most of it
// in window_optimise (this file's code generation, not the call).
[[gnu::always_inline]] inline Ops::Insertion Ops::insertion_impl(ClusterId c, NodeId prev, NodeId next, int at) const {
  const Cost base = next.valid() ? link(prev, next) : 0;
  Insertion best{at, NodeId{}, kHuge};
  const auto nodes = p_.nodes_of(c);
  if (!blk_out_.empty()) {  // same values, same order as the loop below (c is not in the route)
    const std::size_t off = blk_off_[c.index()];
    const Cost* in = blk_out_.data() + prev.index() * n_ + off;
    const Cost* out = next.valid() ? blk_in() + next.index() * n_ + off : nullptr;
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      const Cost d = in[j] + (out ? out[j] : 0) - base;
      if (d < best.delta) best.delta = d, best.node = nodes[j];
    }
    return best;
  }
  if (plain_planar_) {  // same values, same order as the loop below
    thread_local std::vector<Cost> in, out;
    in.resize(nodes.size()), out.resize(nodes.size());
    planar_from(prev, c, in.data());
    if (next.valid()) planar_into(next, c, out.data());
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      const Cost d = in[j] + (next.valid() ? out[j] : 0) - base;
      if (d < best.delta) best.delta = d, best.node = nodes[j];
    }
    return best;
  }
  for (NodeId v : nodes) {
    const Cost d = link(prev, v) + (next.valid() ? link(v, next) : 0) - base;
    if (d < best.delta) best.delta = d, best.node = v;
  }
  return best;
}

Ops::Insertion Ops::insertion_at(const Tour& t, ClusterId c, int at) const {
  const int L = static_cast<int>(t.seq.size());
  const NodeId prev = t.seq[static_cast<std::size_t>(at - 1)];
  const NodeId next = at < L ? t.seq[static_cast<std::size_t>(at)] : (closed_ ? t.seq[0] : NodeId{});
  return insertion_impl(c, prev, next, at);
}

Ops::Insertion Ops::insertion_between(ClusterId c, NodeId prev, NodeId next, int at) const { return insertion_impl(c, prev, next, at); }

void Ops::candidate_positions(const Tour& t, ClusterId c, std::vector<int>& out) const {
  for (ClusterId x : preds(c))
    if (t.pos[x.index()] >= 0) out.push_back(t.pos[x.index()] + 1);
  for (ClusterId y : succs(c))
    if (t.pos[y.index()] > 0) out.push_back(t.pos[y.index()]);
}

Ops::Insertion Ops::best_local_insertion(const Tour& t, ClusterId c, int old_at) const {
  const int L = static_cast<int>(t.seq.size());
  // With dense precedence (SOP) the window is often narrow and the candidates mostly fall outside it:
  // scan it all. Long routes (local_prec_): the candidates inside the window, and old_at, which is.
  if ((prec_ && !local_prec_) || static_cast<int>(kn_) * 2 + 1 >= L) return best_insertion(t, c, 0.0, nullptr);
  thread_local std::vector<int> cand;  // Ops is shared by the search threads
  cand.assign(1, old_at);
  candidate_positions(t, c, cand);
  int lo = 1, hi = L;
  if (prec_) std::tie(lo, hi) = window(t, c);
  Insertion best;
  best.delta = kHuge;
  for (int at : cand) {
    if (at < lo || at > hi) continue;
    const Insertion ins = insertion_at(t, c, at);
    if (ins.delta < best.delta) best = ins;
  }
  return best;
}

Ops::Insertion Ops::best_repair_insertion(const Tour& t, ClusterId c, double noise, Rng& rng) const {
  const int L = static_cast<int>(t.seq.size());
  // Large clusters: cluster optimisation dominates an iteration, a full scan costs little more.
  // Asymmetric problems (GTSPLIB rbg: many zero-cost arcs, so the sampled candidate lists are a poor
  // guide) lost their best-known values in 1-2 seeds out of 5 with the restricted scan.
  // Long routes with sparse precedence (local_prec_: cutting nests, planar and asymmetric, whose
  // cluster optimisation counts as expensive from about 3 000 contours of 8 candidates on): the
  // candidates inside c's window. A plate of 40 000 holes spent 1.7 s of a 6-s descent in repairs
  // that scanned every place before the outer contour.
  const bool lists = local_prec_ || !(prec_ || expensive_co_ || !p_.symmetric());
  if (!lists || static_cast<int>(kn_) * 4 >= L) return best_insertion(t, c, noise, &rng);
  thread_local std::vector<int> cand;
  cand.clear();
  candidate_positions(t, c, cand);
  int lo = 1, hi = L;
  if (prec_) {
    std::tie(lo, hi) = window(t, c);
    std::erase_if(cand, [lo, hi](int at) { return at < lo || at > hi; });
  }
  // Neighbours of c mostly removed too (large destroys): the whole route, or on long routes the
  // places next to the nearest clusters still in it (a related removal of 5 000 of 100 000
  // clusters scanned the whole route for each: one iteration of 3 s, which no time limit stops).
  if (cand.size() < kn_ / 2 && L > kFullScanRepairRoute) nearest_present_positions(t, c, lo, hi, cand);
  if (cand.size() < kn_ / 2) return best_insertion(t, c, noise, &rng);
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  Insertion best;
  double best_key = std::numeric_limits<double>::infinity();
  for (int at : cand) {
    const Insertion ins = insertion_at(t, c, at);
    const double key = static_cast<double>(ins.delta) + (noise > 0.0 ? noise * rng.uniform01() : 0.0);
    if (key < best_key) best_key = key, best = ins;
  }
  return best;
}

void Ops::nearest_present_positions(const Tour& t, ClusterId c, int lo, int hi, std::vector<int>& out) const {
  thread_local std::vector<std::uint32_t> seen;
  thread_local std::uint32_t stamp = 0;
  // A new size, or the stamp wrapping round after 2^32 searches (a run of hours): clear the marks.
  if (seen.size() != static_cast<std::size_t>(m_) || ++stamp == 0) seen.assign(static_cast<std::size_t>(m_), 0), stamp = 1;
  breadth_first(c, kMaxRepairSearch, seen, stamp, [&] { return out.size() >= kn_ / 2; }, [&](ClusterId x) {
    const int q = t.pos[x.index()];
    if (q < 0) return;
    for (int at : {q + 1, q})
      if (at >= std::max(lo, 1) && at <= hi) out.push_back(at);
  });
}

void Ops::insert(Tour& t, const Insertion& ins) const {
  t.seq.insert(t.seq.begin() + ins.at, ins.node);
  reindex(t, ins.at, static_cast<int>(t.seq.size()));
  t.cost += ins.delta;
  mark_around(t, ins.at);
}

Cost Ops::removal_gain(const Tour& t, int i) const {
  const NodeId prev = t.seq[static_cast<std::size_t>(i - 1)];
  const NodeId v = t.seq[static_cast<std::size_t>(i)];
  const NodeId next = after(t, i);
  return link(prev, v) + (next.valid() ? link(v, next) - link(prev, next) : 0);
}

void Ops::remove_at(Tour& t, int i) const {
  t.cost -= removal_gain(t, i);
  t.pos[cl(t.seq[static_cast<std::size_t>(i)]).index()] = -1;
  t.seq.erase(t.seq.begin() + i);
  reindex(t, i, static_cast<int>(t.seq.size()));
  mark(t, i - 1);
  mark(t, i);
}

void Ops::move_to(Tour& t, int i, const Insertion& ins) const {
  t.cost -= removal_gain(t, i);
  // remove_at's marks: the old neighbours (the one after wraps to the start on a closed tour).
  mark(t, i - 1);
  mark(t, i + 1);
  const auto first = t.seq.begin();
  if (ins.at <= i) std::rotate(first + ins.at, first + i, first + i + 1);
  else std::rotate(first + i, first + i + 1, first + ins.at + 1);
  t.seq[static_cast<std::size_t>(ins.at)] = ins.node;
  reindex(t, std::min(i, ins.at), std::max(i, ins.at) + 1);
  t.cost += ins.delta;
  mark_around(t, ins.at);
}

// Reinsertion (Or-opt of one cluster with node re-selection), e.g. cluster C in
//   S a1 B2 C3 D1 E2  ->  S a1 B2 D1 C1 E2   (C moved after D, entered at its node 1 instead of 3).
// Fixed: position 0. Precedence: C only between its last predecessor and first successor present.
bool Ops::reinsertion_pass(Tour& t) const {
  bool improved = false;
  const int L = static_cast<int>(t.seq.size());
  // Where best_local_insertion would take the candidate places (long routes), they are priced with
  // the cluster still in place, on the route as it would be without it, and the cluster moves only
  // when that pays: taking it out and putting it back shifts the route's vector twice, O(L) per
  // cluster, O(L^2) a pass (a plate of 40 000 holes: 1.5 s a descent). The same places in the same
  // order, so the same moves and flags as removing it.
  const bool in_place = (!prec_ || local_prec_) && static_cast<int>(kn_) * 2 + 1 < L - 1;
  for (int c = 0; c < m_ && L > 1; ++c) {
    if (ClusterId(c) == p_.start_cluster()) continue;
    if (!t.dirty[static_cast<std::size_t>(c)]) continue;
    t.dirty[static_cast<std::size_t>(c)] = 0;
    const int i = t.pos[static_cast<std::size_t>(c)];
    if (in_place) {
      const ClusterId cc(c);
      const int Lr = L - 1;  // places q in [1, Lr] of the route without c: between r[q - 1] and r[q]
      auto r = [&](int k) { return t.seq[static_cast<std::size_t>(k < i ? k : k + 1)]; };
      auto rpos = [&](ClusterId x) { return t.pos[x.index()] > i ? t.pos[x.index()] - 1 : t.pos[x.index()]; };
      int lo = 1, hi = Lr;
      if (prec_) {
        const auto [wl, wh] = window(t, cc);  // c's predecessors lie before i, its successors after
        lo = wl, hi = wh - 1;
      }
      auto price = [&](int q) { return insertion_between(cc, r(q - 1), q < Lr ? r(q) : (closed_ ? r(0) : NodeId{}), q); };
      Insertion best = price(i);  // the old place first: ties keep it
      auto consider = [&](int q) {
        if (q < lo || q > hi) return;
        const Insertion ins = price(q);
        if (ins.delta < best.delta) best = ins;
      };
      for (ClusterId x : preds(cc))
        if (t.pos[x.index()] >= 0) consider(rpos(x) + 1);
      for (ClusterId y : succs(cc))
        if (t.pos[y.index()] >= 0 && rpos(y) > 0) consider(rpos(y));
      if (best.delta < removal_gain(t, i)) {
        move_to(t, i, best);
        improved = true;
      }
      continue;
    }
    const int touched_before = t.touched[static_cast<std::size_t>(c)];
    const Cost before = t.cost;
    const NodeId old = t.seq[static_cast<std::size_t>(i)];
    // Flags of the neighbours, restored when the cluster goes back where it was.
    const int Lc = static_cast<int>(t.seq.size());
    const std::size_t nprev = cl(t.seq[static_cast<std::size_t>(i - 1)]).index();
    const std::size_t nnext = cl(t.seq[static_cast<std::size_t>((i + 1) % Lc)]).index();
    const int saved[4] = {t.dirty[nprev], t.touched[nprev], t.dirty[nnext], t.touched[nnext]};
    remove_at(t, i);
    Insertion ins = best_local_insertion(t, ClusterId(c), i);
    // Keep the old place on ties so that a pass without improvement leaves the route unchanged.
    if (t.cost + ins.delta >= before) {
      Tour& u = t;
      const NodeId prev = u.seq[static_cast<std::size_t>(i - 1)];
      const NodeId next = i < static_cast<int>(u.seq.size()) ? u.seq[static_cast<std::size_t>(i)] : (closed_ ? u.seq[0] : NodeId{});
      ins = {i, old, link(prev, old) + (next.valid() ? link(old, next) - link(prev, next) : 0)};
      insert(t, ins);
      t.dirty[nprev] = static_cast<char>(saved[0]), t.touched[nprev] = saved[1];
      t.dirty[nnext] = static_cast<char>(saved[2]), t.touched[nnext] = saved[3];
      t.dirty[static_cast<std::size_t>(c)] = 0;
      t.touched[static_cast<std::size_t>(c)] = touched_before;
    } else {
      improved = true;
      insert(t, ins);
    }
  }
  return improved;
}

// 2-opt: reverse seq[i..j], e.g. S a b c d e -> S a d c b e (i = 2, j = 4). Symmetric arcs only,
// so only the two boundary arcs change (inner costs are unchanged: each node is still entered once).
// No precedence pair may lie inside the reversed segment.
bool Ops::two_opt_pass(Tour& t) const {
  if (!p_.symmetric()) return near_symmetric_ && asym_two_opt_pass(t);
  const int L = static_cast<int>(t.seq.size());
  bool improved = false;
  if ((!prec_ || local_prec_) && static_cast<int>(kn_) * 4 < L) {
    // Neighbour-list 2-opt: the new arc (a, c) or (b, d) joins a cluster to one of its neighbours.
    // With precedence (local_prec_) an improving reversal is checked for a pair inside seq[i..j]:
    // O(j - i) like the reversal itself, and a stretch that holds a hole and its outer contour
    // stops at the hole.
    auto reversible = [&](int i, int j) {
      for (int q = i; q < j; ++q)
        for (ClusterId b : p_.all_after(cl(t.seq[static_cast<std::size_t>(q)])))
          if (t.pos[b.index()] > q && t.pos[b.index()] <= j) return false;
      return true;
    };
    auto try_move = [&](int i, int j) {
      if (j <= i || j >= L) return;
      const NodeId a = t.seq[static_cast<std::size_t>(i - 1)], b = t.seq[static_cast<std::size_t>(i)];
      const NodeId c = t.seq[static_cast<std::size_t>(j)];
      const NodeId d = after(t, j);
      Cost delta = arc(a, c) - arc(a, b);
      if (d.valid()) delta += arc(b, d) - arc(c, d);
      if (delta < 0 && (!prec_ || reversible(i, j))) {
        reverse_segment(t, i, j, delta);
        improved = true;
        return;
      }
      // With precedence the candidate branch does not run.
      if (no_ && two_opt_no(t, i, j)) improved = true;
    };
    for (int i = 1; i + 1 < L; ++i) {
      const std::size_t ca = cl(t.seq[static_cast<std::size_t>(i - 1)]).index(), cb = cl(t.seq[static_cast<std::size_t>(i)]).index();
      if (!touched(t, ca) && !touched(t, cb)) continue;
      for (ClusterId x : succs(cl(t.seq[static_cast<std::size_t>(i - 1)]))) try_move(i, t.pos[x.index()]);
      for (ClusterId x : succs(cl(t.seq[static_cast<std::size_t>(i)]))) try_move(i, t.pos[x.index()] - 1);
    }
    return improved;
  }
  for (int i = 1; i + 1 < L; ++i) {
    for (int j = i + 1; j < L; ++j) {
      const NodeId a = t.seq[static_cast<std::size_t>(i - 1)], b = t.seq[static_cast<std::size_t>(i)];
      const NodeId c = t.seq[static_cast<std::size_t>(j)];
      if (prec_ && before_within(t, cl(c), i, j)) break;  // any longer segment contains the same pair
      const NodeId d = after(t, j);
      Cost delta = arc(a, c) - arc(a, b);
      if (d.valid() && d != b) delta += arc(b, d) - arc(c, d);
      if (delta < 0) {
        reverse_segment(t, i, j, delta);
        improved = true;
      }
    }
  }
  return improved;
}

bool Ops::sequence_passes(Tour& t) const {
  bool improved = reinsertion_pass(t);
  begin_round(t);
  // A stop is looked at between the passes too: each costs about 0.1 s on 100 000 clusters.
  auto run = [&](bool (Ops::*pass)(Tour&) const) {
    if (!stopped()) improved = (this->*pass)(t) || improved;
  };
  run(&Ops::two_opt_pass);
  if (!stopped()) improved = lk_pass(t) || improved;
  run(&Ops::or_opt_pass);
  run(&Ops::segment_exchange_pass);
  run(&Ops::reversing_exchange_pass);
  if (prec_) run(&Ops::swap_pass);
  return improved;
}

void Ops::local_search(Tour& t) const {
  if (expensive_co_) {
    // Large clusters: a full cluster optimisation costs more than all other moves together, so only
    // the stretches around what changed are re-optimised (solve_heuristic runs full passes at the
    // start and on the final route).
    const int start_epoch = t.pass_start;
    windows_optimise(t, start_epoch);
    for (int guard = 0; guard < 100; ++guard) {
      const int round_epoch = t.epoch;
      for (int inner = 0; inner < 100 && !stopped(); ++inner)
        if (!sequence_passes(t)) break;
      if (stopped() || !windows_optimise(t, round_epoch)) break;
    }
    return;
  }
  // Cluster optimisation first (a perturbed order often only pays off with other nodes; the sequence
  // moves, which keep nodes, would otherwise undo it), then sequence moves until none improves, then
  // cluster optimisation again; repeat while it improves. Bounded so a plateau cannot loop forever.
  cluster_optimise(t, 2.0e6);
  for (int guard = 0; guard < 100; ++guard) {
    for (int inner = 0; inner < 100 && !stopped(); ++inner)
      if (!sequence_passes(t)) break;
    if (stopped() || !cluster_optimise(t, 2.0e6)) break;
  }
}

}  // namespace cutroute::solve::detail
