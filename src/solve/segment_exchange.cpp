// Segment exchange (SOP-3-exchange, Gambardella & Dorigo 2000): swap two adjacent segments of the
// route, the orientation-preserving 3-opt move, with the lexicographic precedence check.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "tour.hpp"

namespace cutroute::solve::detail {

namespace {
// With precedence the full enumeration costs O(L^2) per examined position; above this route length
// it would dominate the local search (large cutting nests), so only the other moves run there.
constexpr int kMaxPrecedenceLength = 160;
// Without precedence, candidate lists from routes of more than 2 x 12 clusters on (the other moves
// switch at 4 x 12): the full enumeration costs O(L^2) per examined position, 40 % of the run time
// on GTSPLIB 45ts225; with the lists GTSPLIB <= 89 clusters needs 7 % less CPU in all (30-40 % less
// at 40-45 clusters) for the same results in 5 seeds.
constexpr int kListRouteFactor = 2;
}  // namespace

// Exchange left = seq[i+1..j] and right = seq[j+1..h] (0 <= i < j < h < L):
//   S a [b c] [d e f] g  ->  S a [d e f] [b c] g        (i = 1, j = 3, h = 6)
// Three arcs change: (s_i, s_i+1), (s_j, s_j+1), (s_h, after) become (s_i, s_j+1), (s_h, s_i+1),
// (s_j, after); every node is still entered once, so the inner costs do not change. The move is
// feasible iff no cluster of `left` must precede a cluster of `right`. Lexicographic search: for a
// fixed i, growing j adds one cluster to `left` and its successors to a marked set; for a fixed j,
// growing h adds one cluster to `right` and stops at the first marked one (every longer `right`
// contains it too). The mirror search from a fixed h grows `right` leftwards and marks predecessors.
// Without precedence on long routes only moves whose two first new arcs join candidate neighbours
// are tried (O(k^2) per position).
bool Ops::segment_exchange_pass(Tour& t) const {
  const int L = static_cast<int>(t.seq.size());
  if (L < 3) return false;
  if (prec_ && L > kMaxPrecedenceLength) return false;
  bool improved = false;
  auto at = [&](int i) { return t.seq[static_cast<std::size_t>(i)]; };
  auto delta_of = [&](int i, int j, int h) {
    const NodeId a = at(i), b = at(i + 1), c = at(j), d = at(j + 1), e = at(h);
    const NodeId f = after(t, h);
    Cost dl = link(a, d) + link(e, b) - link(a, b) - link(c, d);
    if (f.valid()) dl += link(c, f) - link(e, f);
    return dl;
  };
  auto apply = [&](int i, int j, int h, Cost dl) {
    std::rotate(t.seq.begin() + i + 1, t.seq.begin() + j + 1, t.seq.begin() + h + 1);
    reindex(t, i + 1, h + 1);
    t.cost += dl;
    improved = true;
    mark_around(t, i + 1);
    mark_around(t, i + h - j);
    mark_around(t, h);
  };
  auto is_touched = [&](int i) { return touched(t, cl(at(i)).index()); };

  if (!prec_ && static_cast<int>(kn_) * kListRouteFactor < L) {
    for (int i = 0; i + 2 < L; ++i) {
      if (!is_touched(i) && !is_touched(i + 1)) continue;
      const ClusterId ca = cl(at(i)), cb = cl(at(i + 1));
      Cost best = 0;
      int bj = -1, bh = -1;
      for (ClusterId x : succs(ca)) {
        const int p = t.pos[x.index()];  // p = j + 1
        if (p < i + 2) continue;
        for (ClusterId y : preds(cb)) {
          const int h = t.pos[y.index()];
          if (h < p) continue;
          const Cost dl = delta_of(i, p - 1, h);
          if (dl < best) best = dl, bj = p - 1, bh = h;
        }
      }
      if (bj >= 0) apply(i, bj, bh, best);
    }
    return improved;
  }

  // Full enumeration. nxt[q]: cost of the arc leaving position q (0 at the end of a path); cq[q]: the
  // cluster at position q. mark[c] == stamp flags the clusters that may not join the growing
  // opposite segment.
  thread_local std::vector<Cost> nxt;
  thread_local std::vector<int> cq;
  thread_local std::vector<std::uint64_t> mark;
  thread_local std::uint64_t stamp = 0;
  if (mark.size() != static_cast<std::size_t>(m_)) mark.assign(static_cast<std::size_t>(m_), 0);
  auto refresh = [&] {
    nxt.resize(static_cast<std::size_t>(L));
    cq.resize(static_cast<std::size_t>(L));
    for (int q = 0; q < L; ++q) {
      const NodeId f = after(t, q);
      nxt[static_cast<std::size_t>(q)] = f.valid() ? link(at(q), f) : 0;
      cq[static_cast<std::size_t>(q)] = cl(at(q)).value();
    }
  };
  refresh();
  // The O(L^2) loops read the route, its clusters, the marks and (plain matrices) the matrix through
  // local pointers: with the members and thread-locals GCC reloaded them at every step (this pass
  // took 16 % of a prob.100 run). Every arc priced here joins two different positions, so it never
  // meets link(a, a), the one case where link() differs from the matrix entry.
  auto enumerate = [&](auto lnk) {
    const NodeId* s = t.seq.data();
    const int* cs = cq.data();
    const Cost* out = nxt.data();
    std::uint64_t* mk = mark.data();
    const bool prec = prec_, closed = closed_;
    auto mark_all = [&](std::span<const ClusterId> span, std::uint64_t st) {
      for (ClusterId c : span) mk[c.index()] = st;
    };
    // Forward from a touched i.
    for (int i = 0; i + 2 < L; ++i) {
      if (!is_touched(i) && !is_touched(i + 1)) continue;
      const std::uint64_t st = ++stamp;
      const NodeId a = s[i], b = s[i + 1];
      Cost best = 0;
      int bj = -1, bh = -1;
      for (int j = i + 1; j + 1 < L; ++j) {
        if (prec) mark_all(p_.all_after(ClusterId(cs[j])), st);
        const NodeId c = s[j];
        const Cost x = lnk(a, s[j + 1]) - out[i] - out[j];
        for (int h = j + 1; h < L; ++h) {
          if (prec && mk[cs[h]] == st) break;
          Cost dl = x + lnk(s[h], b);
          if (h + 1 < L) dl += lnk(c, s[h + 1]) - out[h];
          else if (closed) dl += lnk(c, s[0]) - out[h];
          if (dl < best) best = dl, bj = j, bh = h;
        }
      }
      if (bj >= 0) {
        apply(i, bj, bh, best), refresh();
        s = t.seq.data(), cs = cq.data(), out = nxt.data();
      }
    }
    // Backward from a touched h.
    for (int h = L - 1; h >= 2; --h) {
      if (!is_touched(h)) continue;
      const std::uint64_t st = ++stamp;
      const NodeId e = s[h];
      const NodeId f = after(t, h);
      Cost best = 0;
      int bi = -1, bj = -1;
      for (int j = h - 1; j >= 1; --j) {
        if (prec) mark_all(p_.all_before(ClusterId(cs[j + 1])), st);
        const NodeId c = s[j], d = s[j + 1];
        const Cost x = (f.valid() ? lnk(c, f) - out[h] : 0) - out[j];
        for (int i = j - 1; i >= 0; --i) {
          if (prec && mk[cs[i + 1]] == st) break;
          const Cost dl = x + lnk(s[i], d) + lnk(e, s[i + 1]) - out[i];
          if (dl < best) best = dl, bi = i, bj = j;
        }
      }
      if (bi >= 0) {
        apply(bi, bj, h, best), refresh();
        s = t.seq.data(), cs = cq.data(), out = nxt.data();
      }
    }
  };
  with_distinct_link(enumerate);
  return improved;
}

}  // namespace cutroute::solve::detail
