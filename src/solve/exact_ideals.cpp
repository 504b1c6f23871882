// The exact DP over the precedence ideals only (exact_dp.hpp, "Ideals"): sparse layers, 128-bit sets.
#include <cutroute/solve/exact_dp.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_map>
#include <vector>

#include "exact_common.hpp"

namespace cutroute::solve {
namespace {

constexpr Cost kInf = detail::kDpInf;

struct Mask {
  std::array<std::uint64_t, 2> w{};
  bool test(int b) const { return (w[static_cast<std::size_t>(b >> 6)] >> (b & 63)) & 1u; }
  void set(int b) { w[static_cast<std::size_t>(b >> 6)] |= std::uint64_t{1} << (b & 63); }
  bool subset_of(const Mask& o) const { return (w[0] & ~o.w[0]) == 0 && (w[1] & ~o.w[1]) == 0; }
  Mask without(const Mask& o) const { return {{w[0] & ~o.w[0], w[1] & ~o.w[1]}}; }
  bool operator==(const Mask& o) const = default;
  // Calls f(b) for every set bit, lowest first.
  template <class F>
  void each(F&& f) const {
    for (std::size_t k = 0; k < 2; ++k)
      for (std::uint64_t r = w[k]; r; r &= r - 1) f(static_cast<int>(k * 64) + std::countr_zero(r));
  }
};
struct MaskHash {
  // Every bit reaches the low bits (the open-addressing index masks them): multiply, fold, multiply.
  std::size_t operator()(const Mask& m) const {
    std::uint64_t x = m.w[0] * 0x9E3779B97F4A7C15ull ^ std::rotl(m.w[1] * 0xC2B2AE3D27D4EB4Full, 31);
    x ^= x >> 32;
    x *= 0xD6E8FEB86659FD93ull;
    x ^= x >> 29;
    return static_cast<std::size_t>(x);
  }
};

// One ideal of a layer: its clusters, those of them that may have been added last (no successor in
// the set), the lower bound on what remains, and where its costs start in the value pool: one
// F(S, v) per node v of the `last` clusters, by cluster bit then node.
struct Ideal {
  Mask set, last;
  Cost rest = 0;  // the cheapest entries of the clusters outside, plus the closing arc
  Cost apr = 0;   // the assignment potentials' share of the clusters outside (see below)
  std::size_t row = 0;
};

// Bytes an ideal costs besides its values: its place in a layer and its index slots (twice each: both
// may double).
constexpr std::size_t kIdealBytes = 2 * sizeof(Ideal) + 16;

// A layer's index from set to position: open addressing with linear probing over positions + 1 in one
// flat array, the sets read from the layer itself. A node-based hash map took a second to free after an
// 8-s ry48p.1 run (millions of nodes) and 64 bytes an ideal.
class LayerIndex {
 public:
  void clear() { slot_.assign(16, 0), size_ = 0; }
  // The position of `set` in `layer`, or -1.
  long long find(const std::vector<Ideal>& layer, const Mask& set) const {
    for (std::size_t i = MaskHash{}(set) & (slot_.size() - 1);; i = (i + 1) & (slot_.size() - 1)) {
      if (slot_[i] == 0) return -1;
      if (layer[slot_[i] - 1].set == set) return static_cast<long long>(slot_[i] - 1);
    }
  }
  // Records layer.back() (not in the index yet).
  void add(const std::vector<Ideal>& layer) {
    if (2 * (size_ + 1) > slot_.size()) {
      std::vector<std::uint32_t> old(slot_.size() * 2, 0);
      old.swap(slot_);
      for (std::uint32_t v : old)
        if (v != 0) place(layer, v);
    }
    place(layer, static_cast<std::uint32_t>(layer.size()));
    ++size_;
  }

 private:
  void place(const std::vector<Ideal>& layer, std::uint32_t v) {
    std::size_t i = MaskHash{}(layer[v - 1].set) & (slot_.size() - 1);
    while (slot_[i] != 0) i = (i + 1) & (slot_.size() - 1);
    slot_[i] = v;
  }
  std::vector<std::uint32_t> slot_ = std::vector<std::uint32_t>(16, 0);
  std::size_t size_ = 0;
};

// The rows, in blocks of 2^20 costs that never move (a growing vector would copy the whole table and
// briefly hold it twice, over the memory limit); a row never straddles two blocks.
class RowPool {
 public:
  static constexpr int kShift = 20;
  static constexpr std::size_t kBlock = std::size_t{1} << kShift;
  void clear() { blocks_.clear(), used_ = kBlock; }
  // Bytes held once a row of `n` is allocated.
  std::size_t bytes_with(std::size_t n) const { return (blocks_.size() + (used_ + n > kBlock ? 1 : 0)) * kBlock * sizeof(Cost); }
  std::size_t alloc(std::size_t n) {
    if (used_ + n > kBlock) {
      blocks_.push_back(std::make_unique<Cost[]>(kBlock));
      used_ = 0;
    }
    const std::size_t at = ((blocks_.size() - 1) << kShift) | used_;
    std::fill_n(&blocks_.back()[used_], n, kInf);
    used_ += n;
    return at;
  }
  Cost& operator[](std::size_t at) { return blocks_[at >> kShift][at & (kBlock - 1)]; }

 private:
  std::vector<std::unique_ptr<Cost[]>> blocks_;
  std::size_t used_ = kBlock;
};

}  // namespace

double estimate_ideal_work(const Problem& p, std::size_t max_ideals) {
  constexpr double kTooMuch = std::numeric_limits<double>::infinity();
  const detail::DpLayout lay = detail::dp_layout(p, p.start_cluster());
  const ClusterId start = lay.start;
  const auto& bit_of = lay.bit_of;
  const auto& size = lay.size;
  const int mp = lay.mp;
  if (mp > kMaxIdealClusters) return kTooMuch;
  // Clusters free of any precedence form an antichain: 2^count ideals at least, so most cutting nests
  // (many parts without holes) are turned away here in O(m).
  int free_clusters = 0;
  std::vector<Mask> pred(static_cast<std::size_t>(mp)), succ(static_cast<std::size_t>(mp));
  for (int c = 0; c < p.cluster_count(); ++c) {
    const int b = bit_of[static_cast<std::size_t>(c)];
    if (b < 0) continue;
    bool any = false;
    for (ClusterId a : p.all_before(ClusterId(c)))
      if (bit_of[a.index()] >= 0) pred[static_cast<std::size_t>(b)].set(bit_of[a.index()]), any = true;
    for (ClusterId a : p.all_after(ClusterId(c)))
      if (bit_of[a.index()] >= 0) succ[static_cast<std::size_t>(b)].set(bit_of[a.index()]), any = true;
    if (!any) ++free_clusters;
  }
  auto too_wide = [&](int width) { return width >= 63 || (std::size_t{1} << width) > max_ideals; };
  if (too_wide(free_clusters)) return kTooMuch;
  // Every antichain's subsets are ideals (with what precedes them): 2^width at least, the width being
  // m' minus a maximum matching of the comparability pairs (Dilworth, Fulkerson); Kuhn's augmenting
  // paths, O(m'^3) at most. This turns SOP prob.100 (41 independent pairs) away in about a
  // millisecond instead of a tenth of a second of enumeration.
  std::vector<int> match_of(static_cast<std::size_t>(mp), -1);
  std::vector<char> seen(static_cast<std::size_t>(mp));
  auto augment = [&](auto&& self, int a) -> bool {
    bool found = false;
    succ[static_cast<std::size_t>(a)].each([&](int b) {
      if (found || seen[static_cast<std::size_t>(b)]) return;
      seen[static_cast<std::size_t>(b)] = 1;
      if (match_of[static_cast<std::size_t>(b)] < 0 || self(self, match_of[static_cast<std::size_t>(b)])) match_of[static_cast<std::size_t>(b)] = a, found = true;
    });
    return found;
  };
  int matched = 0;
  for (int a = 0; a < mp; ++a) {
    std::fill(seen.begin(), seen.end(), 0);
    if (augment(augment, a)) ++matched;
  }
  if (too_wide(mp - matched)) return kTooMuch;
  // Enumerate the ideals layer by layer with their `last` clusters; every transition S -> S + b costs
  // (nodes of S's last clusters) x |b| relaxations before pruning.
  std::unordered_map<Mask, Mask, MaskHash> layer{{Mask{}, Mask{}}}, next;
  std::size_t ideals = 1;
  double work = 0.0;
  for (int k = 0; k < mp; ++k) {
    next.clear();
    for (const auto& [S, last] : layer) {
      double from = 0.0;
      last.each([&](int a) { from += size[static_cast<std::size_t>(a)]; });
      if (k == 0) from = static_cast<double>(p.cluster_size(start));
      for (int b = 0; b < mp; ++b) {
        if (S.test(b) || !pred[static_cast<std::size_t>(b)].subset_of(S)) continue;
        work += from * size[static_cast<std::size_t>(b)];
        Mask T = S;
        T.set(b);
        if (next.contains(T)) continue;
        Mask l = last.without(pred[static_cast<std::size_t>(b)]);
        l.set(b);
        next.emplace(T, l);
        if (++ideals > max_ideals) return kTooMuch;
      }
    }
    layer.swap(next);
  }
  return work;
}

Solution solve_exact_ideals(const Problem& p, std::size_t memory_limit_bytes, const StopToken& stop, const Solution* incumbent,
                            const ProgressFn& progress) {
  Solution out;
  Cost ub = detail::dp_take_incumbent(p, incumbent, out);
  const detail::DpLayout lay = detail::dp_layout(p, p.start_cluster());
  const ClusterId start = lay.start;
  const auto& cluster = lay.cluster;
  const auto& first = lay.first;
  const auto& size = lay.size;
  const auto& bit_of = lay.bit_of;
  const auto& bit_of_local = lay.bit_of_local;
  const auto& node = lay.node;
  const int mp = lay.mp;
  const int np = lay.np;
  const auto start_nodes = p.nodes_of(start);
  if (mp == 0) return detail::dp_single_cluster(p, start, out);
  if (mp > kMaxIdealClusters) {
    out.stats.stopped_by_limit = true;
    return out;
  }
  std::vector<Mask> pred(static_cast<std::size_t>(mp));
  for (int b = 0; b < mp; ++b)
    for (ClusterId a : p.all_before(cluster[static_cast<std::size_t>(b)]))
      if (bit_of[a.index()] >= 0) pred[static_cast<std::size_t>(b)].set(bit_of[a.index()]);
  const auto unp = static_cast<std::size_t>(np);
  const std::vector<Cost> w = detail::dp_local_steps(p, lay);
  // LB(S) as in the dense DP: the cheapest step into each cluster outside S, plus the closing arc.
  const std::vector<Cost> min_in = detail::dp_min_in(p, lay);
  const Cost min_in_all = detail::dp_sum(min_in);
  auto closing_lb = [&](NodeId s) { return detail::dp_closing_lb(p, lay, s); };
  const detail::DpPotentials pot = detail::dp_potentials(p, lay, stop);
  auto remaining = [&](Cost rest, int b, Cost apr) { return pot.remaining(rest, b, apr); };
  // Offset of cluster b's nodes in the row of an ideal whose `last` clusters are `last`.
  auto offset_in = [&](const Mask& last, int b) {
    std::size_t off = 0;
    last.each([&](int a) {
      if (a < b) off += static_cast<std::size_t>(size[static_cast<std::size_t>(a)]);
    });
    return off;
  };
  auto row_size = [&](const Mask& last) {
    std::size_t n = 0;
    last.each([&](int a) { n += static_cast<std::size_t>(size[static_cast<std::size_t>(a)]); });
    return n;
  };

  Cost lower_bound = kInf;
  bool stopped = false, over_memory = false;
  long long expanded = 0;
  std::size_t si = 0;
  std::vector<std::vector<Ideal>> layers;
  std::vector<LayerIndex> index;
  RowPool vals;
  std::size_t ideals = 0;
  for (; si < start_nodes.size() && !stopped; ++si) {
    const NodeId s = start_nodes[si];
    const Cost close_lb = closing_lb(s);
    layers.assign(static_cast<std::size_t>(mp) + 1, {});
    index.assign(static_cast<std::size_t>(mp) + 1, LayerIndex{});
    vals.clear();
    const Cost apr0 = pot.ok ? pot.apr0(p, s) : 0;
    ideals = 0;
    // Adds (or finds) T in layer k; returns its index, or -1 when memory runs out.
    auto ideal_at = [&](int k, const Mask& set, const Mask& last, Cost rest, Cost apr) -> long long {
      auto& idx = index[static_cast<std::size_t>(k)];
      auto& L = layers[static_cast<std::size_t>(k)];
      if (const long long at = idx.find(L, set); at >= 0) return at;
      const std::size_t rs = row_size(last);
      if (rs > RowPool::kBlock || vals.bytes_with(rs) + (ideals + 1) * kIdealBytes > memory_limit_bytes) return -1;
      L.push_back({set, last, rest, apr, vals.alloc(rs)});
      ++ideals;
      idx.add(L);
      return static_cast<long long>(L.size() - 1);
    };
    // Layer 1: a first cluster with no predecessor but the start.
    for (int b = 0; b < mp && !over_memory; ++b) {
      if (pred[static_cast<std::size_t>(b)] != Mask{}) continue;
      Mask T;
      T.set(b);
      const Cost rest_in = min_in_all >= kInf || close_lb >= kInf ? kInf : min_in_all - min_in[static_cast<std::size_t>(b)] + close_lb;
      if (rest_in >= kInf) continue;
      const Cost apr = pot.ok ? apr0 - pot.rc[static_cast<std::size_t>(b)] : 0;
      const Cost rest = remaining(rest_in, b, apr);
      long long id = -2;
      for (int j = first[static_cast<std::size_t>(b)]; j < first[static_cast<std::size_t>(b)] + size[static_cast<std::size_t>(b)]; ++j) {
        const Cost st = p.step(s, node[static_cast<std::size_t>(j)]);
        if (st >= kForbiddenCost) continue;
        const Cost val = p.inner_cost(s) + st;
        if (val + rest >= ub) continue;
        if (id == -2) id = ideal_at(1, T, T, rest_in, apr);
        if (id < 0) {
          over_memory = true;
          break;
        }
        vals[layers[1][static_cast<std::size_t>(id)].row + static_cast<std::size_t>(j - first[static_cast<std::size_t>(b)])] = val;
      }
    }
    int done_layer = over_memory ? 0 : 1;  // every layer up to this one is complete
    std::vector<Cost> best_j;
    for (int k = 1; k < mp && !over_memory; ++k) {
      const std::size_t count = layers[static_cast<std::size_t>(k)].size();
      for (std::size_t li = 0; li < count; ++li) {
        if ((li & 255) == 0 && stop.stop_requested()) {
          stopped = true;
          break;
        }
        // Middle layers of a large poset take seconds each: report within them too.
        if ((li & 16383) == 16383)
          detail::dp_progress(progress, static_cast<double>(si) + (k + static_cast<double>(li) / static_cast<double>(count)) / mp, start_nodes.size(), ub);
        const Ideal S = layers[static_cast<std::size_t>(k)][li];
        for (int b = 0; b < mp && !over_memory; ++b) {
          if (S.set.test(b) || !pred[static_cast<std::size_t>(b)].subset_of(S.set)) continue;
          const Cost rest_in = S.rest - min_in[static_cast<std::size_t>(b)];
          const Cost apr = pot.ok ? S.apr - pot.rc[static_cast<std::size_t>(b)] : 0;
          const Cost rest = remaining(rest_in, b, apr);
          const int jb = first[static_cast<std::size_t>(b)], nb = size[static_cast<std::size_t>(b)];
          best_j.assign(static_cast<std::size_t>(nb), kInf);
          bool any = false;
          std::size_t off = S.row;
          S.last.each([&](int a) {
            for (int i = first[static_cast<std::size_t>(a)]; i < first[static_cast<std::size_t>(a)] + size[static_cast<std::size_t>(a)]; ++i, ++off) {
              const Cost fi = vals[off];
              if (fi >= kInf || fi + rest >= ub) continue;
              ++expanded;
              const Cost* wi = &w[static_cast<std::size_t>(i) * unp + static_cast<std::size_t>(jb)];
              for (int j = 0; j < nb; ++j) {
                const Cost val = fi + wi[j];
                if (val < best_j[static_cast<std::size_t>(j)] && val + rest < ub) best_j[static_cast<std::size_t>(j)] = val, any = true;
              }
            }
          });
          if (!any) continue;
          Mask T = S.set;
          T.set(b);
          Mask last = S.last.without(pred[static_cast<std::size_t>(b)]);
          last.set(b);
          const long long id = ideal_at(k + 1, T, last, rest_in, apr);
          if (id < 0) {
            over_memory = true;
            break;
          }
          const Ideal& I = layers[static_cast<std::size_t>(k + 1)][static_cast<std::size_t>(id)];
          Cost* FT = &vals[I.row + offset_in(I.last, b)];
          for (int j = 0; j < nb; ++j) FT[j] = std::min(FT[j], best_j[static_cast<std::size_t>(j)]);
        }
        if (over_memory) break;
      }
      if (stopped || over_memory) break;
      done_layer = k + 1;
      detail::dp_progress(progress, static_cast<double>(si) + static_cast<double>(done_layer) / mp, start_nodes.size(), ub);
    }
    if (stopped || over_memory) {
      // Every route from s passes through one state of the last complete layer.
      Cost lb_s = ub;
      if (done_layer == 0 && min_in_all < kInf && close_lb < kInf) lb_s = std::min(lb_s, p.inner_cost(s) + min_in_all + close_lb);
      for (const Ideal& S : layers[static_cast<std::size_t>(done_layer)]) {
        std::size_t off = S.row;
        S.last.each([&](int a) {
          const Cost rest = remaining(S.rest, a, S.apr);
          for (int i = 0; i < size[static_cast<std::size_t>(a)]; ++i, ++off)
            if (vals[off] < kInf) lb_s = std::min(lb_s, vals[off] + rest);
        });
      }
      lower_bound = std::min(lower_bound, lb_s);
      stopped = true;
      break;
    }
    // The full set (layer mp): close the routes.
    const auto& full = layers[static_cast<std::size_t>(mp)];
    if (full.empty()) continue;
    const Ideal& F = full[0];
    Cost best = kInf;
    int arg = -1;
    {
      std::size_t off = F.row;
      F.last.each([&](int a) {
        for (int j = first[static_cast<std::size_t>(a)]; j < first[static_cast<std::size_t>(a)] + size[static_cast<std::size_t>(a)]; ++j, ++off) {
          if (vals[off] >= kInf) continue;
          Cost total = vals[off];
          if (p.closed()) {
            const Cost c = p.arc_cost(node[static_cast<std::size_t>(j)], s);
            if (c >= kForbiddenCost) continue;
            total += c;
          }
          if (total < best) best = total, arg = j;
        }
      });
    }
    if (arg < 0 || best >= ub) continue;
    // Walk back: the predecessor of v in T is a node u of a `last` cluster of T \ b(v) with
    // F(T \ b, u) + w(u, v) == F(T, v).
    std::vector<NodeId> rev;
    Mask T = F.set;
    int v = arg;
    Cost target = kInf;
    {
      const std::size_t off = F.row + offset_in(F.last, bit_of_local[static_cast<std::size_t>(v)]) + static_cast<std::size_t>(v - first[static_cast<std::size_t>(bit_of_local[static_cast<std::size_t>(v)])]);
      target = vals[off];
    }
    for (int k = mp; k >= 1; --k) {
      rev.push_back(node[static_cast<std::size_t>(v)]);
      if (k == 1) break;
      Mask R = T;
      R.w[static_cast<std::size_t>(bit_of_local[static_cast<std::size_t>(v)] >> 6)] &= ~(std::uint64_t{1} << (bit_of_local[static_cast<std::size_t>(v)] & 63));
      const long long at = index[static_cast<std::size_t>(k - 1)].find(layers[static_cast<std::size_t>(k - 1)], R);
      assert(at >= 0 && "DP table inconsistent");
      if (at < 0) break;
      const Ideal& S = layers[static_cast<std::size_t>(k - 1)][static_cast<std::size_t>(at)];
      int found = -1;
      Cost found_val = kInf;
      std::size_t off = S.row;
      S.last.each([&](int a) {
        for (int i = first[static_cast<std::size_t>(a)]; i < first[static_cast<std::size_t>(a)] + size[static_cast<std::size_t>(a)]; ++i, ++off)
          if (found < 0 && vals[off] < kInf && vals[off] + w[static_cast<std::size_t>(i) * unp + static_cast<std::size_t>(v)] == target)
            found = i, found_val = vals[off];
      });
      assert(found >= 0 && "DP table inconsistent");
      if (found < 0) break;
      T = R;
      v = found;
      target = found_val;
    }
    ub = detail::dp_keep_route(out, rev, s, best);
  }
  out.stats.iterations = expanded;
  if (!stopped) return detail::dp_proven(out);
  for (std::size_t k = si + 1; k < start_nodes.size(); ++k) {
    const Cost c = closing_lb(start_nodes[k]);
    if (min_in_all < kInf && c < kInf) lower_bound = std::min(lower_bound, p.inner_cost(start_nodes[k]) + min_in_all + c);
  }
  lower_bound = std::min(lower_bound, ub);
  if (lower_bound < kInf) out.lower_bound = lower_bound;
  out.stats.stopped_by_limit = true;
  return out;
}

}  // namespace cutroute::solve
