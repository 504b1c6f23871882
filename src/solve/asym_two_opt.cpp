// 2-opt on asymmetric costs: segment reversal priced arc by arc in the new direction.
#include <algorithm>
#include <vector>

#include "tour.hpp"

namespace cutroute::solve::detail {

// One O(L) pass for F and B, plus O(sum of successor lists) for first_after with precedence.
void Ops::reversal_table(const Tour& t, ReversalTable& r) const {
  const int L = static_cast<int>(t.seq.size());
  auto at = [&](int k) { return t.seq[static_cast<std::size_t>(k)]; };
  r.F.assign(static_cast<std::size_t>(L), 0);
  r.B.assign(static_cast<std::size_t>(L), 0);
  for (int k = 1; k < L; ++k) {
    r.F[static_cast<std::size_t>(k)] = r.F[static_cast<std::size_t>(k - 1)] + link(at(k - 1), at(k));
    r.B[static_cast<std::size_t>(k)] = r.B[static_cast<std::size_t>(k - 1)] + link(at(k), at(k - 1));
  }
  r.first_after.assign(static_cast<std::size_t>(L), L);
  if (!prec_) return;
  for (int q = 0; q < L; ++q)
    for (ClusterId y : p_.all_after(cl(at(q)))) {
      const int py = t.pos[y.index()];
      if (py > q) r.first_after[static_cast<std::size_t>(q)] = std::min(r.after_of(q), py);
    }
}

// Reversing seq[i..j] on an asymmetric matrix changes every arc inside the segment, not only the two
// boundary arcs. Prefix sums of the route's link costs forwards (F) and backwards (B) price it in O(1):
//   old = link(a, b) + F[j] - F[i] + link(c, d),  new = link(a, c) + B[j] - B[i] + link(b, d)
// for a = seq[i-1], b = seq[i], c = seq[j], d = the node after j. Each node is still entered once, so
// inner costs cancel. Many "asymmetric" instances are nearly symmetric (SOP prob.100: 4 712 of 4 950
// pairs equal; kro124p and ry48p are perturbed symmetric ones), where reversals are the TSP's
// strongest simple move and Or-opt / segment exchange cannot emulate them. Pairs are examined when a
// boundary next to them changed since the last round (don't-look flags).
bool Ops::asym_two_opt_pass(Tour& t) const {
  const int L = static_cast<int>(t.seq.size());
  if (L < 4) return false;
  thread_local ReversalTable r;
  thread_local std::vector<int> hot;
  auto at = [&](int k) { return t.seq[static_cast<std::size_t>(k)]; };
  // Boundary k lies between positions k-1 and k (k = L: the closing arc, or the open end).
  auto boundary_touched = [&](int k) {
    return touched(t, cl(at(k - 1)).index()) || (k < L && touched(t, cl(at(k)).index()));
  };
  reversal_table(t, r);
  bool improved = false;
  for (int i = 1; i + 1 < L; ++i) {
    // The longest reversible seq[i..max_j].
    int low = r.after_of(i), max_j = i;
    while (max_j + 1 < L && std::min(low, r.after_of(max_j + 1)) > max_j + 1) low = std::min(low, r.after_of(++max_j));
    if (max_j == i) continue;
    const bool all_j = boundary_touched(i);
    hot.clear();
    if (!all_j)
      for (int k = i + 2; k <= max_j + 1; ++k)
        if (boundary_touched(k)) hot.push_back(k - 1);
    if (!all_j && hot.empty()) continue;
    const int count = all_j ? L - i - 1 : static_cast<int>(hot.size());
    for (int k = 0; k < count; ++k) {
      const int j = all_j ? i + 1 + k : hot[static_cast<std::size_t>(k)];
      if (j > max_j) break;  // a precedence pair inside the segment (and inside every longer one)
      const NodeId a = at(i - 1), b = at(i), c = at(j);
      const NodeId d = after(t, j);
      Cost delta = link(a, c) - link(a, b) + r.bwd(i, j) - r.fwd(i, j);
      if (d.valid()) delta += link(b, d) - link(c, d);
      if (delta < 0) {
        reverse_segment(t, i, j, delta);
        improved = true;
        reversal_table(t, r);
        break;  // seq[i] changed: the next i-loop step continues from the new route
      }
    }
  }
  return improved;
}

}  // namespace cutroute::solve::detail
