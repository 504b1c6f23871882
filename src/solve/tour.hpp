// Private: a route under construction or improvement (nodes, cluster positions, cost) and the
// operators of solve/heuristic.hpp working on it without reallocating.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/core/stop.hpp>
#include <cutroute/solve/problem.hpp>

namespace cutroute::solve::detail {

// "No move yet": larger than any route's cost, and still far from overflow when a few are added.
inline constexpr Cost kHuge = std::numeric_limits<Cost>::max() / 4;

// A route over some (partial) or all (complete) clusters; seq[0] is always in the start cluster.
// Cost convention: closed tour = sum of link() around the cycle; open path = inner(seq[0]) + sum of
// link() along it. link(a, a) = inner(a) makes the one-node cycle consistent.
// Don't-look flags (Bentley 1992): local search only re-examines clusters whose neighbourhood in the
// route changed since they were last examined without success; a pass over a route that a small
// destroy/repair changed in a few places then costs O(changes), not O(m).
struct Tour {
  std::vector<NodeId> seq;
  std::vector<int> pos;          // by cluster: index in seq, -1 when absent
  std::vector<char> dirty;       // by cluster: reinsertion should look at it again
  std::vector<int> touched;      // by cluster: epoch of the last change next to it (2-opt / Or-opt)
  int epoch = 1;                 // current change epoch
  int since = 0;                 // 2-opt / Or-opt look at clusters touched at or after this epoch
  int pass_start = 1;            // epoch at which the last 2-opt / Or-opt round began
  Cost cost = 0;
};

// Reversal prices on asymmetric costs for one route (Ops::reversal_table): prefix sums of its link
// costs forwards (F) and backwards (B), and where precedence ends a reversible stretch.
struct ReversalTable {
  std::vector<Cost> F, B;
  std::vector<int> first_after;  // first later position seq[q] must precede (L if none; with precedence)
  // Cost of the path seq[x..y] (x <= y) as it runs, and run backwards from seq[y] to seq[x].
  Cost fwd(int x, int y) const { return F[static_cast<std::size_t>(y)] - F[static_cast<std::size_t>(x)]; }
  Cost bwd(int x, int y) const { return B[static_cast<std::size_t>(y)] - B[static_cast<std::size_t>(x)]; }
  int after_of(int q) const { return first_after[static_cast<std::size_t>(q)]; }
};

class Ops {
 public:
  // `stop` (optional) ends local search early: on huge routes one descent can take seconds.
  // `threads` > 1 lets the planar candidate lists be built on two threads.
  explicit Ops(const Problem& p, const StopToken* stop = nullptr, int threads = 1);
  bool stopped() const { return stop_ && stop_->stop_requested(); }

  const Problem& problem() const { return p_; }
  // The innermost operations of every move evaluation. Matrix problems (GTSPLIB, SOP) read the
  // matrix directly; always inlined because GCC kept link() out of line in the hot loops (10 % of
  // 212u1060's profile as calls; inlined, 132d657 needs 4 % less CPU).
  [[gnu::always_inline]] Cost arc(NodeId a, NodeId b) const { return mat_ ? mat_[a.index() * n_ + b.index()] : p_.arc_cost(a, b); }
  [[gnu::always_inline]] Cost link(NodeId a, NodeId b) const {
    if (plain_mat_) return a == b ? 0 : mat_[a.index() * n_ + b.index()];
    // Plain planar costs: the formula inline, without step()'s dispatch and forbidden check (on a
    // large nest step() was 17 % of the profile, called out of line from Or-opt and swap).
    if (plain_planar_ && a != b) return p_.planar_arc(a, b) + p_.inner_cost(b);
    return a == b ? p_.inner_cost(b) : p_.step(a, b);
  }
  ClusterId cl(NodeId v) const { return p_.cluster_of(v); }
  // Calls f(lnk) where lnk(a, b) == link(a, b) for a != b: on plain matrices the entry read through
  // local copies of the matrix pointer and size (in O(L^2) loops GCC otherwise reloads the members
  // at every step), elsewhere link() itself. For loops that never price a node's arc to itself.
  template <class F>
  void with_distinct_link(F&& f) const {
    if (plain_mat_) {
      const Cost* mat = mat_;
      const std::size_t n = n_;
      f([mat, n](NodeId a, NodeId b) { return mat[a.index() * n + b.index()]; });
    } else {
      f([this](NodeId a, NodeId b) { return link(a, b); });
    }
  }

  Cost full_cost(const std::vector<NodeId>& seq) const;
  void init(Tour& t) const;                      // pos and cost from seq; every cluster dirty
  void mark(Tour& t, int i) const;               // flags the cluster at index i (wraps on a tour)
  void mark_around(Tour& t, int i) const { mark(t, i - 1), mark(t, i), mark(t, i + 1); }
  static bool touched(const Tour& t, std::size_t c) { return t.touched[c] >= t.since; }
  // Starts a 2-opt / Or-opt round: it looks at what changed since the previous round began.
  static void begin_round(Tour& t) {
    t.since = t.pass_start;
    t.pass_start = ++t.epoch;
  }
  void reindex(Tour& t, int from, int to) const; // pos for seq[from, to)
  // Reverses seq[i..j] whose cost change `delta` the caller priced; flags the ends for local search.
  void reverse_segment(Tour& t, int i, int j, Cost delta) const;
  // The node after index i: the next one, the first one (closed tour), or an invalid id (path end).
  NodeId after(const Tour& t, int i) const {
    const int L = static_cast<int>(t.seq.size());
    if (i + 1 < L) return t.seq[static_cast<std::size_t>(i + 1)];
    return p_.closed() ? t.seq[0] : NodeId{};
  }

  struct Insertion {
    int at = -1;  // index the node will have
    NodeId node;
    Cost delta = 0;
  };
  // Indices at which cluster c may be inserted keeping precedence with the clusters present: [lo, hi].
  std::pair<int, int> window(const Tour& t, ClusterId c) const;
  // Best (position, node) for c; with noise > 0 each position's cost gets + noise * u (u uniform in [0, 1)).
  Insertion best_insertion(const Tour& t, ClusterId c, double noise, Rng* rng) const;
  // Like best_insertion, but only next to c's neighbour clusters and at old_at (the local-search move).
  Insertion best_local_insertion(const Tour& t, ClusterId c, int old_at) const;
  // The repair step's insertion: like best_insertion, but on long routes without precedence only
  // next to c's neighbour clusters (O(24 k) instead of O(L k)); the whole route when few are present.
  Insertion best_repair_insertion(const Tour& t, ClusterId c, double noise, Rng& rng) const;
  void insert(Tour& t, const Insertion& ins) const;
  Cost removal_gain(const Tour& t, int i) const;
  void remove_at(Tour& t, int i) const;
  // remove_at(t, i) then insert(t, ins) (ins.at a place of the route without seq[i]): the same
  // route, cost and marks, but only the positions between the two places shift.
  void move_to(Tour& t, int i, const Insertion& ins) const;

  // Candidate lists (LKH-style): the clusters with the cheapest arcs into c (preds) and out of c
  // (succs), measured between up to 12 sampled nodes per cluster; moves are only tried next to them.
  std::span<const ClusterId> preds(ClusterId c) const { return {pred_.data() + static_cast<std::size_t>(c.value()) * kn_, kn_}; }
  std::span<const ClusterId> succs(ClusterId c) const { return {succ_.data() + static_cast<std::size_t>(c.value()) * kn_, kn_}; }

  // a must come before b (Problem::must_precede), O(1) from a bit matrix on problems of at most
  // kMaxPrecedenceBits clusters (the Or-opt and swap scans ask it once per step).
  bool precedes(ClusterId a, ClusterId b) const {
    if (prec_bits_.empty()) return p_.must_precede(a, b);
    const std::size_t k = b.index() * static_cast<std::size_t>(m_) + a.index();
    return (prec_bits_[k >> 6] >> (k & 63)) & 1u;
  }

  // Does a cluster that must come before c stand at a position in [lo, hi) of t? (A move that
  // takes c back over that stretch, or reverses it with c, would break the pair.)
  bool before_within(const Tour& t, ClusterId c, int lo, int hi) const {
    for (ClusterId a : p_.all_before(c)) {
      const int pa = t.pos[a.index()];
      if (pa >= lo && pa < hi) return true;
    }
    return false;
  }

  bool reinsertion_pass(Tour& t) const;
  bool two_opt_pass(Tour& t) const;
  bool asym_two_opt_pass(Tour& t) const;  // two_opt_pass on asymmetric costs (asym_two_opt.cpp)
  // Fills r for t (asym_two_opt.cpp). A stretch seq[x..y] holds no precedence pair (may be
  // reversed) iff min(r.after_of(x..y)) > y.
  void reversal_table(const Tour& t, ReversalTable& r) const;
  bool or_opt_pass(Tour& t) const;
  bool swap_pass(Tour& t) const;
  bool swap_pass_local(Tour& t) const;  // swap_pass next to candidate neighbours (local_prec_)
  Cost swap_delta(const Tour& t, int i, int j) const;  // exchanging seq[i] and seq[j], 1 <= i < j
  void apply_swap(Tour& t, int i, int j, Cost delta) const;
  bool segment_exchange_pass(Tour& t) const;  // segment_exchange.cpp
  bool reversing_exchange_pass(Tour& t) const;  // reversing_exchange.cpp (nearly symmetric matrices)
  // lin_kernighan.cpp (nearly symmetric plain matrices); `breadth` empty: kBreadth or kCheckedBreadth.
  bool lk_pass(Tour& t, std::span<const int> breadth = {}) const;
  // Removes (into `removed`) every cluster but position 0 next to an arc of t that route e lacks
  // (cluster level, either direction when symmetric); returns how many (elite_destroy.cpp).
  int remove_differences(Tour& t, const std::vector<NodeId>& e, std::vector<ClusterId>& removed) const;
  bool cluster_optimise(Tour& t, double max_work) const;
  // Best nodes for positions [lo, hi] with the nodes around them fixed. O(sum |C_i||C_i+1|) there.
  bool window_optimise(Tour& t, int lo, int hi) const;
  // window_optimise around every cluster touched at or after `since_epoch`.
  bool windows_optimise(Tour& t, int since_epoch) const;
  // One round of reinsertion, 2-opt, LK, Or-opt, the exchanges and swap; true when one improved.
  bool sequence_passes(Tour& t) const;
  void local_search(Tour& t) const;
  // Random topological order, each cluster at its cheapest place (construction.cpp).
  void construct(Tour& t, Rng& rng) const;
  // 2-opt with neighbour optimisation (neighbour_opt.cpp) applies: symmetric plain matrix, no
  // precedence, small clusters.
  bool neighbour_opt() const { return no_; }
  // seq[i..j] reversed with the best nodes at its four ends; applied (true) only when that is
  // cheaper. Needs neighbour_opt(); false unless 2 <= i, i + 2 <= j, j + 1 < L.
  bool two_opt_no(Tour& t, int i, int j) const;

 private:
  Insertion insertion_at(const Tour& t, ClusterId c, int at) const;  // best node of c at index `at`
  // Best node of c between prev and next (next invalid: the end of an open path); `at` is copied.
  Insertion insertion_between(ClusterId c, NodeId prev, NodeId next, int at) const;
  Insertion insertion_impl(ClusterId c, NodeId prev, NodeId next, int at) const;
  // The rest of a stopped construction, each cluster next to a candidate neighbour (construction.cpp).
  void complete_nearby(Tour& t, Rng& rng, std::vector<int>& avail, std::vector<int>& indeg) const;
  // Indices next to c's candidate neighbours present in the route (appended to out, may repeat).
  void candidate_positions(const Tour& t, ClusterId c, std::vector<int>& out) const;
  // Indices in [lo, hi] next to the clusters present in the route that are nearest to c in the
  // candidate graph (breadth first), appended to out until it holds kn_ / 2.
  void nearest_present_positions(const Tour& t, ClusterId c, int lo, int hi, std::vector<int>& out) const;
  // Breadth first over the candidate lists (predecessors, then successors) from c: visit(x) for
  // each cluster reached, layer by layer, until done() after a layer or max_visited clusters are
  // reached. seen[x] == stamp marks a reached cluster (the caller's buffer, m_ entries, with a
  // stamp no entry holds yet).
  template <class Done, class Visit>
  void breadth_first(ClusterId c, std::size_t max_visited, std::vector<std::uint32_t>& seen, std::uint32_t stamp, Done&& done,
                     Visit&& visit) const {
    std::vector<ClusterId> frontier{c}, next;
    seen[c.index()] = stamp;
    std::size_t visited = 1;
    while (!done() && !frontier.empty() && visited < max_visited) {
      next.clear();
      for (ClusterId u : frontier)
        for (auto list : {preds(u), succs(u)})
          for (ClusterId x : list) {
            if (seen[x.index()] == stamp) continue;
            seen[x.index()] = stamp, ++visited;
            next.push_back(x);
            visit(x);
          }
      frontier.swap(next);
    }
  }

  const Problem& p_;
  const Cost* mat_;
  std::size_t n_;
  bool plain_mat_;  // matrix and no inner costs
  bool plain_planar_;  // Problem::plain_planar(): single arcs inline, cluster rows batched (planar_rows.cpp)
  const StopToken* stop_;
  int m_;
  bool closed_;
  bool prec_;
  // Long routes with precedence (cutting nests of kLocalPrecedenceClusters and more): reinsertion,
  // Or-opt and swap try only the places next to candidate neighbours and check precedence only for a
  // move that would improve, instead of scanning every place precedence allows (every hole of a
  // plate may go anywhere before its outer contour: O(m^2) a pass).
  bool local_prec_ = false;
  std::size_t kn_ = 0;
  bool expensive_co_ = false;
  std::vector<ClusterId> pred_, succ_;
  std::vector<std::uint64_t> prec_bits_;  // row b, bit a: a must precede b
  // Cluster-blocked copies of a plain matrix (see Ops::Ops): blk_out_[u * n + s] = arc(u, v) and
  // blk_in_[u * n + s] = arc(v, u), where s = blk_off_[cluster of v] + v's index in nodes_of(cluster).
  // blk_in_ stays empty on symmetric problems (it would equal blk_out_).
  std::vector<Cost> blk_out_, blk_in_;
  std::vector<std::size_t> blk_off_;
  const Cost* blk_in() const { return blk_in_.empty() ? blk_out_.data() : blk_in_.data(); }
  // Plain planar problems (Problem::plain_planar): out and in points and inner costs per node in
  // the blocked order above (slot blk_off_[c] + index in nodes_of(c)), so the arcs between one node
  // and every node of a cluster are one loop the compiler vectorises (planar_rows.cpp).
  std::vector<double> pox_, poy_, pix_, piy_;
  std::vector<Cost> pinner_;
  // out[j] = link(nodes_of(a)[j], b) for a cluster a other than b's (plain_planar_ only).
  void planar_into(NodeId b, ClusterId a, Cost* out) const;
  // out[j] = link(u, nodes_of(c)[j]) for a cluster c other than u's (plain_planar_ only).
  void planar_from(NodeId u, ClusterId c, Cost* out) const;
  void build_neighbour_bounds();
  bool no_ = false;
  std::vector<Cost> nmin_, cmin_;  // cheapest arc node -> cluster, cluster -> cluster (neighbour_opt.cpp)
  bool near_symmetric_ = false;  // asymmetric matrix within 10 % of symmetric (asym_two_opt.cpp)
  bool finite_symmetric_ = false;  // c(a,b) == c(b,a) wherever both arcs are allowed (SOP prob.100)
  // One node per cluster and lists built from the matrix: succs(c) are in ascending order of arc(c's node, x's node).
  bool exact_succs_ = false;
  // With lk_ and exact_succs_: succ_arc_[c * kn_ + k] = the arc from c's node to succs(c)[k]'s,
  // read next to the list in LK's candidate scan instead of from the matrix (the scan's main stall).
  std::vector<Cost> succ_arc_;
  bool node_is_cluster_ = false;  // node v is the only node of cluster v (SOP): LK's flips skip the lookup
  bool lk_ = false;              // Lin-Kernighan chains apply (lin_kernighan.cpp)
  // The precedence pairs LK's chains can break: those not starting at the start cluster, which stays
  // first: 139 of the 238 of SOP prob.100, checked once per improving closing.
  std::vector<std::pair<ClusterId, ClusterId>> lk_pairs_;
};

}  // namespace cutroute::solve::detail
