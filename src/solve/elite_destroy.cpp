// Elite-difference removal: the clusters where a route and a good other route disagree.
#include <vector>

#include "tour.hpp"

namespace cutroute::solve::detail {

// An arc of t (cluster level; either direction on symmetric problems) is shared when e has it too.
// Every cluster at an end of an arc that is not shared is removed, except position 0. Two local
// optima usually agree on most of the route: what they agree on is likely right, and rebuilding
// only what they disagree on searches where the two basins differ (the idea behind partition
// crossover for the TSP, here as a destroy step of the large neighbourhood search). O(m).
int Ops::remove_differences(Tour& t, const std::vector<NodeId>& e, std::vector<ClusterId>& removed) const {
  thread_local std::vector<int> succ, pred;
  thread_local std::vector<char> flag;
  succ.assign(static_cast<std::size_t>(m_), -1);
  pred.assign(static_cast<std::size_t>(m_), -1);
  const int Le = static_cast<int>(e.size());
  for (int i = 0; i < Le; ++i) {
    const int j = i + 1 < Le ? i + 1 : closed_ ? 0 : -1;
    if (j < 0 || j == i) continue;
    const int a = cl(e[static_cast<std::size_t>(i)]).value(), b = cl(e[static_cast<std::size_t>(j)]).value();
    succ[static_cast<std::size_t>(a)] = b;
    pred[static_cast<std::size_t>(b)] = a;
  }
  const bool sym = p_.symmetric();
  const int L = static_cast<int>(t.seq.size());
  flag.assign(static_cast<std::size_t>(L), 0);
  int count = 0;
  for (int i = 0; i < L; ++i) {
    const int j = i + 1 < L ? i + 1 : closed_ ? 0 : -1;
    if (j < 0 || j == i) continue;
    const int a = cl(t.seq[static_cast<std::size_t>(i)]).value(), b = cl(t.seq[static_cast<std::size_t>(j)]).value();
    if (succ[static_cast<std::size_t>(a)] == b || (sym && pred[static_cast<std::size_t>(a)] == b)) continue;
    for (int q : {i, j})
      if (q > 0 && flag[static_cast<std::size_t>(q)] == 0) flag[static_cast<std::size_t>(q)] = 1, ++count;
  }
  for (int i = L - 1; i > 0; --i)
    if (flag[static_cast<std::size_t>(i)] != 0) {
      removed.push_back(cl(t.seq[static_cast<std::size_t>(i)]));
      remove_at(t, i);
    }
  return count;
}

}  // namespace cutroute::solve::detail
