// Swap passes of the route operators: two clusters exchange places, precedence kept.
#include "tour.hpp"

#include <algorithm>
#include <utility>

namespace cutroute::solve::detail {
// Inlined into both swap passes, whose inner loops price one exchange per step.
[[gnu::always_inline]] inline Cost Ops::swap_delta(const Tour& t, int i, int j) const {
  auto val = [&](NodeId a, NodeId b) { return a.valid() && b.valid() ? link(a, b) : 0; };
  const NodeId x = t.seq[static_cast<std::size_t>(i)], y = t.seq[static_cast<std::size_t>(j)];
  const NodeId a = t.seq[static_cast<std::size_t>(i - 1)], d = after(t, j);
  if (j == i + 1) return link(a, y) + link(y, x) + val(x, d) - link(a, x) - link(x, y) - val(y, d);
  const NodeId b = t.seq[static_cast<std::size_t>(i + 1)], c = t.seq[static_cast<std::size_t>(j - 1)];
  return link(a, y) + link(y, b) + link(c, x) + val(x, d) - link(a, x) - link(x, b) - link(c, y) - val(y, d);
}

void Ops::apply_swap(Tour& t, int i, int j, Cost delta) const {
  std::swap(t.seq[static_cast<std::size_t>(i)], t.seq[static_cast<std::size_t>(j)]);
  reindex(t, i, i + 1);
  reindex(t, j, j + 1);
  t.cost += delta;
  mark_around(t, i);
  mark_around(t, j);
}

// Swap: exchange two clusters, keeping their nodes, e.g. S a [b] c d [e] f -> S a [e] c d [b] f.
// Needed on precedence-heavy routes (SOP) where single moves are blocked but exchanges are not.
// Forbidden: b must not have to precede anything in (b, e], e nothing in [b, e) must precede.
// O(m^2) a pass (each pair one O(1) evaluation plus the precedence look-ups).
bool Ops::swap_pass(Tour& t) const {
  const int L = static_cast<int>(t.seq.size());
  if (local_prec_ && static_cast<int>(kn_) * 4 < L) return swap_pass_local(t);
  bool improved = false;
  for (int i = 1; i + 1 < L; ++i) {
    if (!touched(t, cl(t.seq[static_cast<std::size_t>(i)]).index()) && !touched(t, cl(t.seq[static_cast<std::size_t>(i - 1)]).index()))
      continue;
    for (int j = i + 1; j < L; ++j) {
      const NodeId x = t.seq[static_cast<std::size_t>(i)], y = t.seq[static_cast<std::size_t>(j)];
      if (prec_) {
        // x moves over everything in (i, j]: stop at the first cluster x must precede.
        if (precedes(cl(x), cl(y))) break;
        // y moves over everything in [i, j): skip it if one of them must precede y.
        if (before_within(t, cl(y), i, j)) continue;
      }
      const Cost delta = swap_delta(t, i, j);
      if (delta < 0) {
        apply_swap(t, i, j, delta);
        improved = true;
      }
    }
  }
  return improved;
}

// swap_pass on long routes with precedence: the cluster x at i is exchanged only with a cluster y
// whose new place is next to a candidate neighbour, either y's (y between x's route neighbours) or
// x's (x next to one of its candidates); each i takes its best such exchange. Precedence is checked,
// through the closure lists of x and y, only for an exchange that would improve.
bool Ops::swap_pass_local(Tour& t) const {
  const int L = static_cast<int>(t.seq.size());
  bool improved = false;
  // x = seq[i] moves over (i, j], y = seq[j] over [i, j): none of them may be x's successor or y's
  // predecessor.
  auto allowed = [&](int i, int j) {  // i < j
    for (ClusterId b : p_.all_after(cl(t.seq[static_cast<std::size_t>(i)])))
      if (t.pos[b.index()] > i && t.pos[b.index()] <= j) return false;
    return !before_within(t, cl(t.seq[static_cast<std::size_t>(j)]), i, j);
  };
  for (int i = 1; i < L; ++i) {
    const ClusterId cx = cl(t.seq[static_cast<std::size_t>(i)]);
    if (!touched(t, cx.index()) && !touched(t, cl(t.seq[static_cast<std::size_t>(i - 1)]).index())) continue;
    Cost best = 0;
    int best_lo = -1, best_hi = -1;
    auto consider = [&](int j) {
      if (j < 1 || j >= L || j == i) return;
      const int lo = std::min(i, j), hi = std::max(i, j);
      const Cost delta = swap_delta(t, lo, hi);
      if (delta < best && allowed(lo, hi)) best = delta, best_lo = lo, best_hi = hi;
    };
    for (ClusterId y : succs(cl(t.seq[static_cast<std::size_t>(i - 1)]))) consider(t.pos[y.index()]);
    if (i + 1 < L)
      for (ClusterId y : preds(cl(t.seq[static_cast<std::size_t>(i + 1)]))) consider(t.pos[y.index()]);
    for (ClusterId w : preds(cx))
      if (t.pos[w.index()] >= 0) consider(t.pos[w.index()] + 1);
    for (ClusterId w : succs(cx))
      if (t.pos[w.index()] >= 0) consider(t.pos[w.index()] - 1);
    if (best_lo < 0) continue;
    apply_swap(t, best_lo, best_hi, best);
    improved = true;
  }
  return improved;
}

}  // namespace cutroute::solve::detail
