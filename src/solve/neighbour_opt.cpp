// 2-opt with neighbour optimisation: a segment reversal priced with the best nodes of the four
// clusters at its ends for the new order.
#include <algorithm>
#include <vector>

#include "tour.hpp"

namespace cutroute::solve::detail {

// nmin_[v * m + c]: the cheapest arc from node v into cluster c; cmin_[a * m + c]: the cheapest arc
// between clusters a and c. Symmetric plain matrices only, so "into" and "out of" are the same.
// O(n^2) once per solve (10^6 reads for 1 000 nodes).
void Ops::build_neighbour_bounds() {
  const auto m = static_cast<std::size_t>(m_);
  nmin_.assign(n_ * m, kForbiddenCost);
  for (std::size_t v = 0; v < n_; ++v)
    for (std::size_t w = 0; w < n_; ++w) {
      if (w == v) continue;
      Cost& slot = nmin_[v * m + cl(NodeId(static_cast<int>(w))).index()];
      slot = std::min(slot, mat_[v * n_ + w]);
    }
  cmin_.assign(m * m, kForbiddenCost);
  for (std::size_t v = 0; v < n_; ++v) {
    const std::size_t a = cl(NodeId(static_cast<int>(v))).index();
    for (std::size_t c = 0; c < m; ++c) cmin_[a * m + c] = std::min(cmin_[a * m + c], nmin_[v * m + c]);
  }
}

// Route ... p A B b2 ... c2 C D q ... with the segment B..C reversed becomes ... p A C c2 ... b2 B D q ...
// (i = index of B, j = index of C, j >= i + 2). The arcs p-A-C-c2 and b2-B-D-q are independent
// two-layer shortest paths: min over x in A, y in C of arc(p, x) + arc(x, y) + arc(y, c2), the same
// for B and D. Without it a reversal that pays only with other nodes at its ends is never made:
// cluster optimisation re-chooses nodes for a fixed order, 2-opt reorders for fixed nodes, and a
// route can be optimal for both and still improvable by the joint move (Karapetyan & Gutin 2012,
// "2-opt with neighbours optimisation"). Bounds from nmin_ / cmin_ skip most candidate moves in
// O(1); an evaluation costs |A||C| + |B||D| arcs.
bool Ops::two_opt_no(Tour& t, int i, int j) const {
  // Position 0 keeps its node; j + 1 is the last cluster whose node may change.
  if (i < 2 || j < i + 2 || j + 1 >= static_cast<int>(t.seq.size())) return false;
  auto at = [&](int k) { return t.seq[static_cast<std::size_t>(k)]; };
  const NodeId a = at(i - 1), b = at(i), b2 = at(i + 1), c2 = at(j - 1), c = at(j), d = at(j + 1);
  const NodeId pp = at(i - 2);
  const NodeId q = after(t, j + 1);
  const auto m = static_cast<std::size_t>(m_);
  const std::size_t ca = cl(a).index(), cb = cl(b).index(), cc = cl(c).index(), cd = cl(d).index();
  Cost old = arc(pp, a) + arc(a, b) + arc(b, b2) + arc(c2, c) + arc(c, d);
  if (q.valid()) old += arc(d, q);
  // Lower bounds of x -> C -> c2 (any x in A) and of b2 -> B -> w (any w in D).
  const Cost tail1 = cmin_[ca * m + cc] + nmin_[c2.index() * m + cc];
  const Cost head2 = cmin_[cb * m + cd] + nmin_[b2.index() * m + cb];
  const Cost lb1 = nmin_[pp.index() * m + ca] + tail1;
  const Cost lb2 = head2 + (q.valid() ? nmin_[q.index() * m + cd] : 0);
  if (lb1 + lb2 >= old) return false;
  // Best p-x-y-c2 (x in A, y in C), then the best b2-u-w-q (u in B, w in D) that still pays.
  Cost best1 = old - lb2;
  NodeId bx, by;
  for (NodeId x : p_.nodes_of(cl(a))) {
    const Cost px = arc(pp, x);
    if (px + tail1 >= best1) continue;
    for (NodeId y : p_.nodes_of(cl(c))) {
      const Cost v = px + arc(x, y) + arc(y, c2);
      if (v < best1) best1 = v, bx = x, by = y;
    }
  }
  if (!bx.valid()) return false;
  Cost best2 = old - best1;
  NodeId bu, bw;
  for (NodeId w : p_.nodes_of(cl(d))) {
    const Cost wq = q.valid() ? arc(w, q) : 0;
    if (wq + head2 >= best2) continue;
    for (NodeId u : p_.nodes_of(cl(b))) {
      const Cost v = wq + arc(u, w) + arc(b2, u);
      if (v < best2) best2 = v, bu = u, bw = w;
    }
  }
  if (!bu.valid()) return false;
  t.seq[static_cast<std::size_t>(i - 1)] = bx;
  t.seq[static_cast<std::size_t>(i)] = bu;
  t.seq[static_cast<std::size_t>(j)] = by;
  t.seq[static_cast<std::size_t>(j + 1)] = bw;
  reverse_segment(t, i, j, best1 + best2 - old);
  mark_around(t, i - 1);
  mark_around(t, j + 1);
  return true;
}

}  // namespace cutroute::solve::detail
