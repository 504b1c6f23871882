// The start route: clusters in a random topological order, each at its cheapest place, and the
// linked-list completion of a construction stopped by the time limit.
#include "tour.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace cutroute::solve::detail {

namespace {
// A stopped construction still scans routes of up to this many clusters whole: cheap enough there
// (about 0.1 s on 10 000 circles), the first clusters placed are rarely anyone's candidate
// neighbours, and the nests of the corpus (at most 1 186 contours) keep the routes they had.
constexpr int kFullScanRoute = 2048;
// Problems of more clusters than this complete every construction next to candidate neighbours
// once kFullScanRoute clusters are placed, stopped or not: the whole-window scans are O(m^2 k) (a
// plate of 10 000 holes: 2.1 s of a 4.3-s run with --time-limit 0; 40 000 holes: about 16 times
// that), the nearby places O(m k) (10 000 circles: T_cut within 0.003 %, before local search).
constexpr int kFullConstructionClusters = 4096;
// Clusters a stopped construction visits in the candidate graph looking for a placed one.
constexpr std::size_t kMaxSearched = 4096;
// Places a stopped construction prices in whole-window scans (about 0.08 s on planar singletons).
constexpr std::size_t kFallbackScans = 2'000'000;

// Takes a random cluster out of `avail` (the clusters whose predecessors are all placed).
ClusterId take_random(std::vector<int>& avail, Rng& rng) {
  const std::size_t k = rng.below(avail.size());
  const int c = avail[k];
  avail[k] = avail.back();
  avail.pop_back();
  return ClusterId(c);
}

// c is placed: its successors whose predecessors are now all placed become available.
void release_after(const Problem& p, ClusterId c, std::vector<int>& indeg, std::vector<int>& avail) {
  for (ClusterId b : p.all_after(c))
    if (--indeg[b.index()] == 0) avail.push_back(b.value());
}
}  // namespace

void Ops::construct(Tour& t, Rng& rng) const {
  // Random topological order of the non-start clusters.
  // A cluster is available when all its (transitive) predecessors are placed.
  std::vector<int> indeg(static_cast<std::size_t>(m_), 0);
  for (int c = 0; c < m_; ++c) indeg[static_cast<std::size_t>(c)] = static_cast<int>(p_.all_before(ClusterId(c)).size());
  const ClusterId s = p_.start_cluster();
  std::vector<int> avail;
  for (ClusterId b : p_.all_after(s)) --indeg[b.index()];
  for (int c = 0; c < m_; ++c)
    if (ClusterId(c) != s && indeg[static_cast<std::size_t>(c)] == 0) avail.push_back(c);
  // Start node: the start cluster's node with the cheapest inner cost (cluster optimisation fixes it later).
  NodeId first = p_.nodes_of(s)[0];
  for (NodeId v : p_.nodes_of(s))
    if (p_.inner_cost(v) < p_.inner_cost(first)) first = v;
  t.seq.assign(1, first);
  init(t);
  t.cost = p_.inner_cost(first);  // one-node route, closed or open
  while (!avail.empty()) {
    // Cheapest insertion over the whole route is O(m^2 k): on a nest of 10 000 small circles
    // `optimize --time-limit 1` took 4.0 s, most of it here. Once the run is stopped (or on more
    // than kFullConstructionClusters clusters) the rest goes next to its candidate neighbours:
    // 1.5 s, T_cut 17 002.9 s against 17 002.4 s (clusters whose nodes lie far apart lose more;
    // Heuristic.StoppedConstruction...).
    if (static_cast<int>(t.seq.size()) > kFullScanRoute && (stopped() || m_ > kFullConstructionClusters)) {
      complete_nearby(t, rng, avail, indeg);
      return;
    }
    const ClusterId c = take_random(avail, rng);
    insert(t, best_insertion(t, c, 0.0, nullptr));
    release_after(p_, c, indeg, avail);
  }
}

// The rest of the clusters, in the same random order, each at the cheapest of the places next to
// its placed candidate neighbours that precedence allows and the two ends of its window (O(24 k)
// instead of best_insertion's O(L k)), the first place on ties. On a doubly linked list whose order
// is kept as integer labels (order maintenance by midpoints, relabelled evenly when two neighbours
// leave no room): inserting into the route's vector moved and re-indexed everything behind the new
// place, and on 100 000 singleton clusters stopped after 1 s those O(L) insertions made the run end
// after 4.2 s. Here an insertion is O(k) for its candidate places; a relabelling is O(L) and comes
// after about 40 insertions into the same gap at worst.
void Ops::complete_nearby(Tour& t, Rng& rng, std::vector<int>& avail, std::vector<int>& indeg) const {
  const std::size_t m = static_cast<std::size_t>(m_);
  constexpr int kNone = -1;
  constexpr std::uint64_t kTop = std::uint64_t{1} << 63;  // above every label: the end of the route
  std::vector<int> nxt(m, kNone), prv(m, kNone);
  std::vector<std::uint64_t> label(m, 0);
  std::vector<NodeId> node(m);
  std::vector<char> placed(m, 0);
  const std::uint64_t spacing = (std::uint64_t{1} << 62) / (static_cast<std::uint64_t>(m) + 1);
  const int head = cl(t.seq[0]).value();
  int tail = head;
  for (std::size_t i = 0; i < t.seq.size(); ++i) {
    const int c = cl(t.seq[i]).value();
    node[static_cast<std::size_t>(c)] = t.seq[i];
    placed[static_cast<std::size_t>(c)] = 1;
    label[static_cast<std::size_t>(c)] = (i + 1) * spacing;
    if (i > 0) nxt[static_cast<std::size_t>(tail)] = c, prv[static_cast<std::size_t>(c)] = tail;
    tail = c;
  }
  auto relabel = [&] {
    std::uint64_t l = spacing;
    for (int c = head; c != kNone; c = nxt[static_cast<std::size_t>(c)], l += spacing) label[static_cast<std::size_t>(c)] = l;
  };
  auto lab = [&](int c) { return label[static_cast<std::size_t>(c)]; };
  // The place after cluster a: between a's node and the next one (the first on a closed tour).
  auto price = [&](ClusterId c, int a) {
    const int b = nxt[static_cast<std::size_t>(a)];
    const NodeId next = b != kNone ? node[static_cast<std::size_t>(b)] : (closed_ ? node[static_cast<std::size_t>(head)] : NodeId{});
    return insertion_between(c, node[static_cast<std::size_t>(a)], next, 0);
  };
  std::vector<int> cand;
  std::vector<std::uint32_t> seen(m, 0);
  std::uint32_t stamp = 0;
  std::size_t scanned = 0;
  while (!avail.empty()) {
    const ClusterId c = take_random(avail, rng);
    // window(): after the last placed predecessor, up to the place before the first placed successor.
    int lo = head, hi = tail;
    for (ClusterId x : p_.all_before(c))
      if (placed[x.index()] && lab(x.value()) > lab(lo)) lo = x.value();
    std::uint64_t first_after = kTop;
    for (ClusterId y : p_.all_after(c))
      if (placed[y.index()] && y.value() != head && lab(y.value()) < first_after) first_after = lab(y.value()), hi = prv[y.index()];
    // candidate_positions(): after a placed predecessor-neighbour, before a placed successor-neighbour
    // (not before the start cluster).
    cand.assign({lo, hi});
    for (ClusterId x : preds(c))
      if (placed[x.index()]) cand.push_back(x.value());
    for (ClusterId y : succs(c))
      if (placed[y.index()] && y.value() != head) cand.push_back(prv[y.index()]);
    Insertion best;
    best.delta = kHuge;
    int best_a = kNone, near = 0;
    auto in_window = [&](int a) { return lab(a) >= lab(lo) && lab(a) <= lab(hi); };
    // The cheaper place, the first one on ties.
    auto consider = [&](int a) {
      const Insertion ins = price(c, a);
      if (ins.delta < best.delta || (ins.delta == best.delta && best_a != kNone && lab(a) < lab(best_a))) best = ins, best_a = a;
    };
    for (std::size_t i = 0; i < cand.size(); ++i) {
      if (!in_window(cand[i])) continue;
      near += i >= 2;
      consider(cand[i]);
    }
    // No neighbour placed yet (most clusters while few are placed). The window's ends alone are far
    // away (10 000 circles stopped at a fifth: a route with 6.6 times the rapids), so every place
    // of the window, as long as those scans stay within kFallbackScans places in all; then the
    // places next to the nearest placed clusters of the candidate graph, found breadth first.
    // Scanning every time took 2.6 s on 100 000 singleton clusters stopped at 2 048 placed; the
    // nearest places alone cost 1-11 % more on 2 600 clusters (Heuristic.StoppedConstruction...),
    // where the scans stay cheap.
    if (near == 0 && scanned >= kFallbackScans)
      breadth_first(c, kMaxSearched, seen, ++stamp, [&] { return near > 0; }, [&](ClusterId x) {
        if (!placed[x.index()]) return;
        // Both sides of a placed cluster, as the candidate lists give them one way or the other.
        for (int a : {x.value(), x.value() == head ? kNone : prv[x.index()]}) {
          if (a == kNone || !in_window(a)) continue;
          ++near;
          consider(a);
        }
      });
    if (near == 0) {  // every place in the window, the first cheapest
      best.delta = kHuge;
      for (int a = lo;; a = nxt[static_cast<std::size_t>(a)]) {
        ++scanned;
        const Insertion ins = price(c, a);
        if (ins.delta < best.delta) best = ins, best_a = a;
        if (a == hi) break;
      }
    }
    const std::size_t ci = c.index(), ai = static_cast<std::size_t>(best_a);
    const int b = nxt[ai];
    // Appended at the end: one spacing further, so that a route growing at its end relabels rarely.
    auto upper = [&] { return b != kNone ? lab(b) : std::min(kTop, label[ai] + 2 * spacing); };
    std::uint64_t up = upper();
    if (up - label[ai] < 2) {
      relabel();
      up = upper();
    }
    label[ci] = label[ai] + (up - label[ai]) / 2;
    node[ci] = best.node;
    placed[ci] = 1;
    nxt[ci] = b, prv[ci] = best_a, nxt[ai] = c.value();
    if (b != kNone) prv[static_cast<std::size_t>(b)] = c.value();
    else tail = c.value();
    release_after(p_, c, indeg, avail);
  }
  t.seq.clear();
  for (int c = head; c != kNone; c = nxt[static_cast<std::size_t>(c)]) t.seq.push_back(node[static_cast<std::size_t>(c)]);
  init(t);  // every cluster flagged, as the insertions left them; the cost from scratch
}

}  // namespace cutroute::solve::detail
