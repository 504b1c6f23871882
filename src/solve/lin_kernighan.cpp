// Lin–Kernighan chains of 2-opt moves on nearly symmetric matrices, with or without precedence.
#include <algorithm>
#include <array>
#include <span>
#include <type_traits>
#include <vector>

#include "tour.hpp"

namespace cutroute::solve::detail {

namespace {
constexpr int kMaxDepth = 10;     // 2-opt moves in one chain (6: prob.100 worse; 20: no better)
// Alternatives tried for the arc added at each step of a chain, from the first; the steps beyond
// the list are greedy. Only the first step branches where every closing is priced from scratch
// (asymmetric matrices: SOP kro124p.3 fell from 5/5 to 1/5 runs at its best known with the deeper
// list) or already in O(1) (GTSPLIB 99-217, tuned with it). On matrices symmetric but for the arcs
// precedence forbids (`checked_gain`: SOP prob.100, prob.42) four steps branch: a chain there must
// often pass through routes that break pairs to reach a feasible better one, which the greedy chain
// rarely finds, and its closings are priced in O(1) until one would improve. SOP prob.100, 2
// threads, 10 s, runs above 1174 of seeds 1-30 / mean: {5} 12 / 1176.4, {5,3} 14 / 1174.5,
// {5,5,3} 13 / 1169.0, {5,5,3,2} 5 / 1157.5 (seeds 31-60: 6 / 1162.1), {5,5,3,3} 7 / 1164.3,
// {5,5,2,2} 10 / 1165.3, {5,5,3,2,2} 11 / 1170.8; {5,5,3,2} makes 4-6 times fewer iterations.
constexpr int kBreadth[] = {5};
constexpr int kCheckedBreadth[] = {5, 5, 3, 2};
constexpr std::size_t kMaxNeighbours = 16;  // at least the candidate lists' length (kNeighbours, tour.cpp)
}  // namespace

// Lin & Kernighan (1973) in the 2-opt-move form of Johnson & McGeoch's implementation: from t1 and a
// route neighbour t2, each step adds (t2, t3) with t3 next to t2's candidate clusters and removes
// (t3, t4), t4 the neighbour of t3 that keeps one cycle; the route is then t1 ... t4 closed by
// (t4, t1), and the chain goes on from t2 := t4 while the partial gain (removed minus added, before
// closing) stays positive. The best closed route along the chain is kept, the rest undone; when no
// closing improved, the chain backs up to try the next alternatives of its first steps (kBreadth).
// 2-opt, Or-opt and the exchanges stop at three changed arcs; a chain reaches up to kMaxDepth + 1,
// the deeper moves that separate 2-opt/3-opt local optima from LK's on Euclidean tours (Johnson &
// McGeoch 1997: about 5 % against 2 % above the Held–Karp bound). Only the chosen nodes' arcs are
// priced: cluster optimisation re-picks the nodes afterwards. Arcs added by the chain are not removed
// again in it, removed ones not added back (LK's rule), so a chain ends.
bool Ops::lk_pass(Tour& t, std::span<const int> breadth) const {
  const int L = static_cast<int>(t.seq.size());
  if (!lk_ || L < 8 || kn_ > kMaxNeighbours) return false;
  // The node -> cluster table through a local pointer: GCC reloaded it through p_ at every use
  // inside the chain's lambdas.
  const ClusterId* const cluster_of = p_.cluster_of_nodes().data();
  auto clu = [cluster_of](NodeId v) { return cluster_of[v.index()]; };
  auto P = [&](NodeId v) { return t.pos[clu(v).index()]; };
  auto wrap = [&](int i) { return i < 0 ? i + L : i >= L ? i - L : i; };
  auto at = [&](int i) { return t.seq[static_cast<std::size_t>(wrap(i))]; };
  auto succ = [&](NodeId v) { return at(P(v) + 1); };
  auto pred = [&](NodeId v) { return at(P(v) - 1); };
  // Each route of the chain is priced from scratch (a reversal changes every inner arc's direction)
  // and checked against the precedence pairs, O(L) next to the O(L) flip; the gain criterion only
  // guides the chain, with the arcs priced in one direction. Intermediate routes may break
  // precedence: only feasible ones are kept (LKH-3 likewise lets a move pass through infeasible
  // routes), which is what lets a chain get past the pairs that block 2-opt.
  // On symmetric closed tours without precedence a chain's route costs the old cost minus the
  // partial gain plus the closing arc: O(1) instead of an O(L) pricing (LK was 18 % of a 200E1k.0
  // run priced from scratch, 14 % of it in full_cost). On matrices symmetric but for forbidden arcs
  // (SOP prob.100) the same O(1) gain is exact unless the route now uses a forbidden arc or breaks
  // precedence, so only a chain about to become the best is checked and priced from scratch: the
  // same chains as pricing every step, 3 % more iterations on prob.100.
  // A reversal can leave a pair's clusters next to each other the wrong way round; removing that arc
  // adds kForbiddenCost to the partial gain, and the chain then runs to its full depth and breadth
  // (40 % of prob.100's chain steps). Kept on purpose: pricing such arcs at their reverse cost made
  // LK three times cheaper per iteration and the 10-s runs no better (15 against 16 of 90 above
  // 1174; docs/solver-bench-2026-11-27-session25.md).
  const bool sym_gain = p_.symmetric() && closed_ && !prec_;
  const bool checked_gain = !sym_gain && finite_symmetric_;
  const auto& pairs = lk_pairs_;
  // The pair found broken last is tried first: a chain that has broken a pair mostly keeps it
  // broken for several steps, and a long chain checks every step (its gain counts a forbidden arc).
  std::size_t last_broken = 0;
  auto feasible = [&]() {
    const int* const ps = t.pos.data();
    if (last_broken < pairs.size() && ps[pairs[last_broken].first.index()] > ps[pairs[last_broken].second.index()]) return false;
    for (std::size_t i = 0; i < pairs.size(); ++i)
      if (ps[pairs[i].first.index()] > ps[pairs[i].second.index()]) {
        last_broken = i;
        return false;
      }
    return true;
  };
  // On an open path the cycle closes through a dummy arc last -> first, which no move may remove.
  auto dummy_at = [&](int px, int py) { return !closed_ && ((px == L - 1 && py == 0) || (py == L - 1 && px == 0)); };
  auto dummy = [&](NodeId x, NodeId y) { return dummy_at(P(x), P(y)); };
  // Reverses the cyclic run seq[i..j] (forward from i to j), or its complement when the run holds
  // index 0 (the start cluster stays first); the cycle is the same either way, its direction not.
  struct Flip {
    int lo, hi;
  };
  std::vector<Flip> flips;
  // Flips and their undoing move about 36 clusters each on prob.100, 20 M times in a 5-s run: the
  // reversal and the position update run as one loop over local pointers.
  NodeId* const seq = t.seq.data();
  int* const pos = t.pos.data();
  // Where node v is cluster v (SOP) the loop skips the node -> cluster load, which each position
  // update waited for.
  const bool node_is_cluster = node_is_cluster_;
  auto raw = [seq, pos, cluster_of, node_is_cluster](int lo, int hi) {
    if (node_is_cluster) {
      for (int a = lo, b = hi; a < b; ++a, --b) {
        const NodeId x = seq[b], y = seq[a];
        seq[a] = x, seq[b] = y;
        pos[x.index()] = a, pos[y.index()] = b;
      }
      return;
    }
    for (int a = lo, b = hi; a < b; ++a, --b) {
      const NodeId x = seq[b], y = seq[a];
      seq[a] = x, seq[b] = y;
      pos[cluster_of[x.index()].index()] = a, pos[cluster_of[y.index()].index()] = b;
    }
  };
  auto run = [&](int i, int j) {
    if (i > j || i == 0) return Flip{j + 1, i - 1 + (i == 0 ? L : 0)};
    return Flip{i, j};
  };
  auto undo_to = [&](std::size_t keep) {
    while (flips.size() > keep) {
      const Flip f = flips.back();
      flips.pop_back();
      if (f.lo < f.hi) raw(f.lo, f.hi);
    }
  };
  // The 2-opt move removes (t1, t2), (t4, t3) and adds (t2, t3), (t4, t1), where t4 is t3's
  // neighbour on the side that keeps one cycle (chosen in candidates()).
  auto move_run = [&](NodeId t1, NodeId t2, NodeId t4) { return succ(t1) == t2 ? run(P(t2), P(t4)) : run(P(t4), P(t2)); };
  auto apply = [&](NodeId t1, NodeId t2, NodeId t4) {
    const Flip f = move_run(t1, t2, t4);
    if (f.lo < f.hi) raw(f.lo, f.hi);
    flips.push_back(f);
  };
  // Whether the pair feasible() tries first is broken once the move is made, read from the
  // positions the flip would give (the route's last step needs its flip only to be checked).
  auto breaks_last = [&](NodeId t1, NodeId t2, NodeId t4) {
    if (last_broken >= pairs.size()) return false;
    const Flip f = move_run(t1, t2, t4);
    auto after = [&f](int p) { return p >= f.lo && p <= f.hi ? f.lo + f.hi - p : p; };
    return after(pos[pairs[last_broken].first.index()]) > after(pos[pairs[last_broken].second.index()]);
  };
  struct Arc {
    NodeId a, b;
  };
  std::vector<Arc> added, removed;
  // The clusters joined to each cluster by an arc the chain added (removed), 2 slots each: a route
  // has one node per cluster, so comparing clusters compares the arcs. An added arc stays in the
  // route for the rest of the chain (it may not be removed) and a removed one was an arc of the
  // starting route (closings end at t1, which a removal never touches), so a cluster has at most 2
  // of each. A lookup reads two slots: scanning the chain's arc lists took 17 % of a prob.100 run,
  // even when a count per cluster skipped the clusters without arcs.
  const std::size_t m = static_cast<std::size_t>(p_.cluster_count());
  std::vector<int> add_slot(2 * m, -1), rem_slot(2 * m, -1);
  auto link_slot = [&](std::vector<int>& s, std::size_t x, int y) { s[2 * x + (s[2 * x] >= 0 ? 1 : 0)] = y; };
  auto unlink_slot = [&](std::vector<int>& s, std::size_t x) { s[2 * x + (s[2 * x + 1] >= 0 ? 1 : 0)] = -1; };
  auto push = [&](std::vector<Arc>& v, std::vector<int>& s, Arc e) {
    v.push_back(e);
    link_slot(s, clu(e.a).index(), clu(e.b).value()), link_slot(s, clu(e.b).index(), clu(e.a).value());
  };
  // Arcs leave in the reverse order they came, so each cluster's last filled slot is the arc's.
  auto cut = [&](std::vector<Arc>& v, std::vector<int>& s, std::size_t keep) {
    while (v.size() > keep) {
      unlink_slot(s, clu(v.back().a).index()), unlink_slot(s, clu(v.back().b).index());
      v.pop_back();
    }
  };
  struct Choice {
    Cost rank;
    NodeId t3, t4;
  };
  std::vector<Choice> choices;
  // Candidates for the next step from t2 with partial gain g, best first by g - c(t2,t3) + c(t3,t4);
  // `all` = false: only the best is wanted (a greedy step, most steps), kept alone. This scan is
  // LK's hot loop (about 40 % of a prob.100 run), so t3's index and the side of t4 are used directly
  // instead of looking them up again through succ()/pred(). The best is the first maximum, as
  // std::sort puts it in front: on at most 12 elements (kNeighbours) it is a stable insertion sort.
  // The scan reads the route, the slots and the lists through pointers held by value: captured by
  // reference, GCC reloaded each through the closure at every candidate.
  const int* const add_s = add_slot.data();
  const int* const rem_s = rem_slot.data();
  const ClusterId* const succ_list = succ_.data();
  const Cost* const succ_cost = succ_arc_.empty() ? nullptr : succ_arc_.data();
  const std::size_t kn = kn_;
  const bool sorted_lists = exact_succs_;
  const bool open_path = !closed_;
  const Cost* const mat = mat_;
  const std::size_t n = n_;
  auto candidates = [&choices, seq, pos, cluster_of, add_s, rem_s, succ_list, succ_cost, kn, sorted_lists, open_path,
                     node_is_cluster, L, mat, n](auto one_node, auto all_of, NodeId t1, NodeId t2, Cost g) {
    constexpr bool all = decltype(all_of)::value;
    // Kept in a local array until the scan ends: stores into the vector made GCC reload every
    // captured value at each candidate.
    std::array<Choice, kMaxNeighbours> found;
    std::size_t nf = 0;
    Choice best{0, NodeId(), NodeId()};
    bool any = false;
    auto take = [&](const Choice& c) {
      if constexpr (all) found[nf++] = c;
      else if (!any || c.rank > best.rank) best = c, any = true;
    };
    if constexpr (decltype(one_node)::value) {
      // Node v is cluster v and the lists are sorted with their arcs stored (SOP): the same
      // candidates in the same order as below, cheaper (prob.100: 13 % fewer instructions in all,
      // though only 2 % less time: the scan waits on loads more than it computes). Positions stand
      // for clusters (one cluster a place), the gain test comes first (every later candidate fails
      // it too), and on an open path the dummy arc is the one t4 would wrap around to.
      const int c1 = t1.value(), c2 = t2.value();
      const int p1 = pos[c1], p2 = pos[c2];
      const bool before_t3 = (p1 + 1 == L ? 0 : p1 + 1) == p2;
      const int dir = before_t3 ? -1 : 1;
      const int edge = !open_path ? -1 : before_t3 ? 0 : L - 1;
      const std::size_t row = static_cast<std::size_t>(c2) * kn;
      const int r0 = rem_s[2 * static_cast<std::size_t>(c2)], r1 = rem_s[2 * static_cast<std::size_t>(c2) + 1];
      for (std::size_t k = 0; k < kn; ++k) {
        const Cost g1 = g - succ_cost[row + k];
        if (g1 <= 0) break;
        const int x = succ_list[row + k].value();
        const int q = pos[x];
        if (q < 0 || q == p1 || q == p2 || q == edge) continue;
        int q4 = q + dir;
        q4 = q4 < 0 ? L - 1 : q4 == L ? 0 : q4;
        if (q4 == p1 || q4 == p2) continue;
        const int c4 = seq[q4].value();
        const std::size_t i3 = 2 * static_cast<std::size_t>(x);
        if (add_s[i3] == c4 || add_s[i3 + 1] == c4 || r0 == x || r1 == x) continue;
        take({g1 + mat[static_cast<std::size_t>(x) * n + static_cast<std::size_t>(c4)], NodeId(x), NodeId(c4)});
      }
    } else {
      const int p1 = pos[cluster_of[t1.index()].index()], p2 = pos[cluster_of[t2.index()].index()];
      const bool before_t3 = (p1 + 1 == L ? 0 : p1 + 1) == p2;  // t4 = pred(t3) when t2 follows t1, else succ(t3)
      const std::size_t row = cluster_of[t2.index()].index() * kn;
      const int c1 = cluster_of[t1.index()].value(), c2 = cluster_of[t2.index()].value();
      for (std::size_t k = 0; k < kn; ++k) {
        const ClusterId x = succ_list[row + k];
        const int q = pos[x.index()];
        if (q < 0) continue;
        const NodeId t3 = seq[q];
        if (x.value() == c1 || x.value() == c2) continue;
        const Cost g1 = g - (succ_cost ? succ_cost[row + k] : mat[t2.index() * n + t3.index()]);
        // Lists in ascending arc order (SOP): every later candidate fails the gain criterion too.
        if (g1 <= 0) {
          if (sorted_lists) break;
          continue;
        }
        const int q4 = before_t3 ? (q == 0 ? L - 1 : q - 1) : (q + 1 == L ? 0 : q + 1);
        const NodeId t4 = seq[q4];
        const int c4 = node_is_cluster ? t4.value() : cluster_of[t4.index()].value();
        if (c4 == c2 || c4 == c1) continue;
        if (open_path && ((q == L - 1 && q4 == 0) || (q4 == L - 1 && q == 0))) continue;
        const std::size_t i3 = 2 * x.index(), i2 = 2 * static_cast<std::size_t>(c2);
        if (add_s[i3] == c4 || add_s[i3 + 1] == c4 || rem_s[i2] == x.value() || rem_s[i2 + 1] == x.value()) continue;
        take({g1 + mat[t3.index() * n + t4.index()], t3, t4});
      }
    }
    if constexpr (all) {
      std::sort(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(nf), [](const Choice& a, const Choice& b) { return a.rank > b.rank; });
      choices.assign(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(nf));
    } else {
      choices.clear();
      if (any) choices.push_back(best);
    }
  };
  auto scan = [&candidates, node_is_cluster](NodeId t1, NodeId t2, Cost g, bool all) {
    if (node_is_cluster) {
      if (all) candidates(std::true_type{}, std::true_type{}, t1, t2, g);
      else candidates(std::true_type{}, std::false_type{}, t1, t2, g);
    } else {
      if (all) candidates(std::false_type{}, std::true_type{}, t1, t2, g);
      else candidates(std::false_type{}, std::false_type{}, t1, t2, g);
    }
  };

  bool improved = false;
  std::vector<NodeId> ends;
  if (breadth.empty()) breadth = checked_gain ? std::span<const int>(kCheckedBreadth) : std::span<const int>(kBreadth);
  auto breadth_at = [&](int d) { return d < std::ssize(breadth) ? breadth[static_cast<std::size_t>(d)] : 1; };
  std::vector<std::vector<Choice>> level(breadth.size());
  // A chain that closes no better leaves its flips in place: the branching step above it (or the
  // start of the next chain) copies the route back from a snapshot, O(L) memmoves instead of undoing
  // each flip one element at a time (prob.100: 11 % of the instructions, 12 % of the CPU time).
  const std::size_t pm = t.pos.size(), sl = static_cast<std::size_t>(L);
  std::vector<NodeId> snap_seq((breadth.size() + 1) * sl);
  std::vector<int> snap_pos((breadth.size() + 1) * pm);
  auto save = [&](std::size_t k) {
    std::copy(seq, seq + sl, snap_seq.begin() + static_cast<std::ptrdiff_t>(k * sl));
    std::copy(pos, pos + pm, snap_pos.begin() + static_cast<std::ptrdiff_t>(k * pm));
  };
  auto restore = [&](std::size_t k) {
    std::copy_n(snap_seq.begin() + static_cast<std::ptrdiff_t>(k * sl), sl, seq);
    std::copy_n(snap_pos.begin() + static_cast<std::ptrdiff_t>(k * pm), pm, pos);
  };
  const std::size_t base_snap = breadth.size();  // the route the chains start from
  save(base_snap);
  Cost best_gain = 0;
  std::size_t best_len = 0;
  NodeId t1;
  // Depth-first over the chain's steps, breadth_at(d) alternatives at step d; returns true once a
  // closing improved (the chain then goes on greedily below it, as at breadth 1, and stops there).
  // Returning false, it leaves its flips, arcs and ends in place for the caller to drop.
  auto step = [&](auto&& self, int depth, NodeId t2, Cost g) -> bool {
    const int B = breadth_at(depth);
    scan(t1, t2, g, B > 1);
    if (choices.empty()) return false;
    // Deeper steps overwrite `choices`: a branching step keeps its alternatives in level[depth],
    // a greedy one (most steps) only its best.
    Choice only = choices.front();
    std::span<const Choice> alternatives(&only, 1);
    if (B > 1) {
      auto& mine = level[static_cast<std::size_t>(depth)];
      mine.assign(choices.begin(), choices.begin() + std::min<std::ptrdiff_t>(B, std::ssize(choices)));
      alternatives = mine;
    }
    const std::size_t f0 = flips.size(), a0 = added.size(), r0 = removed.size(), e0 = ends.size();
    if (alternatives.size() > 1) save(static_cast<std::size_t>(depth));
    bool dirty = false;
    for (const Choice& c : alternatives) {
      // The chain's last step leaves nothing to go on from: when its closing cannot be the best,
      // or feasible() would refuse the route at its first pair, the flip and its arcs would only be
      // undone (an eighth of the chain's steps on prob.100).
      if (depth + 1 == kMaxDepth && (sym_gain || checked_gain)) {
        const Cost closing = c.rank - arc(c.t4, t1);
        if (closing <= best_gain || (!sym_gain && breaks_last(t1, t2, c.t4))) {
          if (best_gain > 0) return true;
          continue;
        }
      }
      if (dirty) {
        restore(static_cast<std::size_t>(depth));
        flips.resize(f0);
        cut(added, add_slot, a0), cut(removed, rem_slot, r0), ends.resize(e0);
      }
      dirty = true;
      apply(t1, t2, c.t4);
      push(added, add_slot, {t2, c.t3});
      push(removed, rem_slot, {c.t3, c.t4});
      ends.push_back(c.t3), ends.push_back(c.t4);
      Cost closing = sym_gain || checked_gain ? c.rank - arc(c.t4, t1) : 0;
      if (!sym_gain && (!checked_gain || closing > best_gain))
        closing = feasible() ? t.cost - full_cost(t.seq) : 0;
      if (closing > best_gain) best_gain = closing, best_len = flips.size();
      if (depth + 1 < kMaxDepth) self(self, depth + 1, c.t4, c.rank);
      if (best_gain > 0) return true;
    }
    return false;
  };
  for (int base = 0; base < L; ++base) {
    t1 = t.seq[static_cast<std::size_t>(base)];
    if (!touched(t, clu(t1).index())) continue;
    bool done = false;
    for (int side = 0; side < 2 && !done; ++side) {
      const NodeId t2_0 = side == 0 ? succ(t1) : pred(t1);
      if (dummy(t1, t2_0)) continue;
      flips.clear();
      cut(added, add_slot, 0), cut(removed, rem_slot, 0);
      push(removed, rem_slot, {t1, t2_0});
      ends.assign({t1, t2_0});  // then t3, t4 of each step: 2 + 2 * (steps kept) ends changed
      best_gain = 0;
      best_len = 0;
      if (step(step, 0, t2_0, arc(t1, t2_0))) {
        undo_to(best_len);
        save(base_snap);
        t.cost -= best_gain;
        for (std::size_t e = 0; e < 2 + 2 * best_len; ++e) mark_around(t, P(ends[e]));
        improved = done = true;
      } else if (!flips.empty()) {
        restore(base_snap);
      }
    }
  }
  return improved;
}

}  // namespace cutroute::solve::detail
