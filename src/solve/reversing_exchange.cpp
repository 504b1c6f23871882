// Reversing segment exchange: the two 3-opt moves that swap adjacent segments and reverse one of
// them, for nearly symmetric asymmetric matrices (SOP prob.100, kro124p, ry48p).
#include <algorithm>
#include <vector>

#include "tour.hpp"

namespace cutroute::solve::detail {

namespace {
// O(L^2) per examined position, as the orientation-preserving exchange with precedence.
constexpr int kMaxLength = 160;
}  // namespace

// With left = seq[i+1..j] = [b..c], right = seq[j+1..h] = [d..e], a = seq[i], f = after h:
//   A: a [b..c] [d..e] f  ->  a [d..e] [c..b] f      (left moved behind right, reversed)
//   B: a [b..c] [d..e] f  ->  a [e..d] [b..c] f      (right moved before left, reversed)
// Segment exchange (segment_exchange.cpp) keeps both directions and Or-opt reverses only 2-3
// clusters; these are the longer reversing moves a nearly symmetric matrix makes worthwhile. The
// reversed segment is priced from prefix sums of forward (F) and backward (B) link costs; every node
// is still entered once, so inner costs cancel. Feasible iff no cluster of left must precede one of
// right and no precedence pair lies inside the reversed segment: for a fixed i, growing j marks the
// successors of left's clusters and growing h stops at the first marked one (as segment exchange);
// first_after[q] (the first later position that seq[q] must precede) tells whether a segment holds a
// pair: [x..y] does iff min(first_after[x..y]) <= y.
bool Ops::reversing_exchange_pass(Tour& t) const {
  const int L = static_cast<int>(t.seq.size());
  if (!near_symmetric_ || L < 4 || L > kMaxLength) return false;
  thread_local ReversalTable r;
  thread_local std::vector<char> mark;
  auto at = [&](int q) { return t.seq[static_cast<std::size_t>(q)]; };
  reversal_table(t, r);
  bool improved = false;
  // Local pointers and (plain matrices) direct matrix reads in the O(L^2) loops, as in
  // segment_exchange.cpp; no arc priced here joins a position to itself.
  auto enumerate = [&](auto lnk) {
    const bool prec = prec_, closed = closed_;
    for (int i = 0; i + 2 < L; ++i) {
      if (!touched(t, cl(at(i)).index()) && !touched(t, cl(at(i + 1)).index())) continue;
      if (prec) mark.assign(static_cast<std::size_t>(m_), 0);
      const NodeId* s = t.seq.data();
      const Cost* F = r.F.data();
      const Cost* B = r.B.data();
      const int* first_after = r.first_after.data();
      char* mk = mark.data();
      auto fwd = [F](int x, int y) { return F[y] - F[x]; };
      auto bwd = [B](int x, int y) { return B[y] - B[x]; };
      const NodeId a = s[i], b = s[i + 1];
      Cost best = 0;
      int bj = -1, bh = -1;
      bool b_variant = false;
      int left_low = L;  // min(first_after[i+1..j])
      for (int j = i + 1; j + 1 < L; ++j) {
        if (prec)
          for (ClusterId y : p_.all_after(cl(s[j]))) mk[y.index()] = 1;
        left_low = std::min(left_low, first_after[j]);
        const bool left_rev = left_low > j;
        const NodeId c = s[j], d = s[j + 1];
        const Cost old_left = lnk(a, b) + fwd(i + 1, j) + lnk(c, d);
        int right_low = L;
        for (int h = j + 1; h < L; ++h) {
          if (prec && mk[cl(s[h]).index()]) break;
          right_low = std::min(right_low, first_after[h]);
          if (!left_rev && right_low <= h) break;  // neither variant for this or any longer right
          const NodeId e = s[h];
          const NodeId f = h + 1 < L ? s[h + 1] : closed ? s[0] : NodeId{};
          const Cost old = old_left + fwd(j + 1, h) + (f.valid() ? lnk(e, f) : 0);
          if (left_rev) {
            const Cost dl = lnk(a, d) + fwd(j + 1, h) + lnk(e, c) + bwd(i + 1, j) + (f.valid() ? lnk(b, f) : 0) - old;
            if (dl < best) best = dl, bj = j, bh = h, b_variant = false;
          }
          if (right_low > h) {
            const Cost dl = lnk(a, e) + bwd(j + 1, h) + lnk(d, b) + fwd(i + 1, j) + (f.valid() ? lnk(c, f) : 0) - old;
            if (dl < best) best = dl, bj = j, bh = h, b_variant = true;
          }
        }
      }
      if (bj < 0) continue;
      std::rotate(t.seq.begin() + i + 1, t.seq.begin() + bj + 1, t.seq.begin() + bh + 1);
      const int split = i + bh - bj;  // right now at [i+1, split], left at [split+1, bh]
      if (b_variant) std::reverse(t.seq.begin() + i + 1, t.seq.begin() + split + 1);
      else std::reverse(t.seq.begin() + split + 1, t.seq.begin() + bh + 1);
      reindex(t, i + 1, bh + 1);
      t.cost += best;
      improved = true;
      mark_around(t, i + 1);
      mark_around(t, split);
      mark_around(t, split + 1);
      mark_around(t, bh);
      reversal_table(t, r);
    }
  };
  with_distinct_link(enumerate);
  return improved;
}

}  // namespace cutroute::solve::detail
