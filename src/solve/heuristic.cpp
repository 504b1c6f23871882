#include <cutroute/solve/heuristic.hpp>

#include <algorithm>
#include <barrier>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "node_sets.hpp"
#include "population.hpp"
#include "tour.hpp"

namespace cutroute::solve {

using detail::Ops;
using detail::Population;
using detail::Tour;

std::vector<NodeId> construct_route(const Problem& p, Rng& rng) {
  Ops ops(p);
  Tour t;
  ops.construct(t, rng);
  return t.seq;
}

namespace {

template <class F>
bool on_route(const Problem& p, std::vector<NodeId>& route, F&& f) {
  Ops ops(p);
  Tour t;
  t.seq = route;
  ops.init(t);
  const bool improved = f(ops, t);
  route = t.seq;
  return improved;
}

}  // namespace

bool reinsertion_pass(const Problem& p, std::vector<NodeId>& r) {
  return on_route(p, r, [](const Ops& o, Tour& t) { return o.reinsertion_pass(t); });
}
bool two_opt_pass(const Problem& p, std::vector<NodeId>& r) {
  return on_route(p, r, [](const Ops& o, Tour& t) { return o.two_opt_pass(t); });
}
bool or_opt_pass(const Problem& p, std::vector<NodeId>& r) {
  return on_route(p, r, [](const Ops& o, Tour& t) { return o.or_opt_pass(t); });
}
bool swap_pass(const Problem& p, std::vector<NodeId>& r) {
  return on_route(p, r, [](const Ops& o, Tour& t) { return o.swap_pass(t); });
}
bool segment_exchange_pass(const Problem& p, std::vector<NodeId>& r) {
  return on_route(p, r, [](const Ops& o, Tour& t) { return o.segment_exchange_pass(t); });
}
bool reversing_exchange_pass(const Problem& p, std::vector<NodeId>& r) {
  return on_route(p, r, [](const Ops& o, Tour& t) { return o.reversing_exchange_pass(t); });
}
bool lk_pass(const Problem& p, std::vector<NodeId>& r, Cost* tracked_cost, std::span<const int> breadth) {
  return on_route(p, r, [tracked_cost, breadth](const Ops& o, Tour& t) {
    const bool improved = o.lk_pass(t, breadth);
    if (tracked_cost) *tracked_cost = t.cost;
    return improved;
  });
}
bool cluster_optimise(const Problem& p, std::vector<NodeId>& r, double max_work) {
  return on_route(p, r, [max_work](const Ops& o, Tour& t) { return o.cluster_optimise(t, max_work); });
}
bool two_opt_neighbour_move(const Problem& p, std::vector<NodeId>& route, int i, int j, Cost& tracked_cost) {
  return on_route(p, route, [&](const Ops& o, Tour& t) {
    const bool moved = o.neighbour_opt() && o.two_opt_no(t, i, j);
    tracked_cost = t.cost;
    return moved;
  });
}
std::vector<ClusterId> remove_differences(const Problem& p, std::vector<NodeId>& route, const std::vector<NodeId>& elite,
                                          Cost& tracked_cost) {
  std::vector<ClusterId> removed;
  on_route(p, route, [&](const Ops& o, Tour& t) {
    o.remove_differences(t, elite, removed);
    tracked_cost = t.cost;
    return true;
  });
  return removed;
}
std::vector<NodeId> order_crossover(const Problem& p, const std::vector<NodeId>& a, const std::vector<NodeId>& b, int i,
                                    int j) {
  const Ops ops(p);
  Tour ta, tb, child;
  ta.seq = a;
  tb.seq = b;
  ops.init(ta);
  ops.init(tb);
  detail::order_crossover(ops, ta, tb, i, j, child);
  return child.seq;
}
std::vector<std::vector<NodeId>> population_survivors(const Problem& p, const std::vector<std::vector<NodeId>>& routes,
                                                      int mu, int lambda) {
  const Ops ops(p);
  Population pop(mu, lambda);
  Tour t;
  for (const auto& r : routes) {
    t.seq = r;
    ops.init(t);
    pop.add(ops, t);
  }
  std::vector<std::vector<NodeId>> out;
  for (int k = 0; k < pop.size(); ++k) out.push_back(pop.at(k).seq);
  return out;
}
void local_search(const Problem& p, std::vector<NodeId>& r) {
  on_route(p, r, [](const Ops& o, Tour& t) {
    o.local_search(t);
    return true;
  });
}

namespace {

// Evaluation budget of a full cluster optimisation with every node of the smallest cluster as the
// cyclic start; above it only the current start node is tried.
constexpr double kFullCoWork = 2.0e6;

// Population mode: share of children made by crossover (the rest by a destroy/repair step of one
// parent, which keeps local variation in the population), and the children per generation. GTSPLIB
// 132-217 clusters, 10 seeds: 0.9 and 1.0 within noise (0.034 / 0.042 % mean gap), 0.9 without
// 1.0's one run stuck 0.8 % above 134gr666's optimum.
constexpr double kCrossover = 0.9;
constexpr int kGeneration = 40;

// One search thread: its own random stream, current and best route.
class Worker {
 public:
  // `elite` (kept by solve_heuristic between rounds, read-only during a round) feeds the
  // elite-difference destroy, drawn with probability `elite_destroy`.
  Worker(const Ops& ops, const SolveParams& params, Rng rng, const std::vector<Tour>& elite, double elite_destroy)
      : ops_(ops), params_(params), rng_(rng), elite_(elite), elite_destroy_(elite_destroy) {}

  void start() {
    ops_.construct(cur_, rng_);
    ops_.local_search(cur_);
    if (ops_.cluster_optimise(cur_, kFullCoWork)) ops_.local_search(cur_);
    best_ = cur_;
  }

  // When a round starts from a fresh construction instead of the best route: each thread with its
  // own chance, every thread together, or none.
  enum class Fresh { maybe, all, none };

  // `iterations` destroy/repair steps; returns early when `stop` fires or the target is reached.
  // `cap`: iterations after which this round ends early (an explicit work budget), the acceptance
  // threshold still decaying over `iterations`.
  void round(int iterations, const StopToken& stop, Fresh fresh, int cap) {
    const Problem& p = ops_.problem();
    // After a round without progress, some rounds (half on small instances, fewer on large ones,
    // where a fresh start rarely catches up within a round) start from a fresh random construction
    // instead of the best route (the best is kept): local search funnels similar routes back
    // into the same optimum, a new start reaches other basins.
    if (fresh == Fresh::all || (fresh == Fresh::maybe && rng_.chance(std::min(0.5, 16.0 / p.cluster_count())))) {
      ops_.construct(cur_, rng_);
      ops_.local_search(cur_);
      if (cur_.cost < best_.cost) best_ = cur_;
    }
    if (p.cluster_count() < 2) return;
    for (int it = 0; it < std::min(iterations, cap); ++it) {
      if (stop.stop_requested() || stop.target_reached(best_.cost)) return;
      ++iterations_;
      trial_ = cur_;
      destroy(trial_, removal_size());
      repair(trial_);
      ops_.local_search(trial_);
      // Threshold acceptance in units of the mean step of the route, decaying over the round.
      const double mean_step = static_cast<double>(cur_.cost) / static_cast<double>(p.cluster_count());
      const double thr = params_.accept_threshold * mean_step * (1.0 - static_cast<double>(it) / iterations);
      if (static_cast<double>(trial_.cost) <= static_cast<double>(cur_.cost) + thr) std::swap(cur_, trial_);
      if (cur_.cost < best_.cost) best_ = cur_;
    }
  }

  // Population mode: `count` fresh constructions with local search, kept as children (fewer when
  // `stop` fires: on a long route each costs a full descent).
  void seed_population(int count, const StopToken& stop) {
    for (int i = 0; i < count && !stop.stop_requested(); ++i) {
      ops_.construct(trial_, rng_);
      ops_.local_search(trial_);
      ++iterations_;
      if (trial_.cost < best_.cost) best_ = trial_;
      children_.push_back(trial_);
    }
  }

  // Population mode: `iterations` children from parents drawn from `pop` (read-only during the
  // round), each the ordered crossover of two (with probability kCrossover) or a destroy/repair of
  // one, then local search. They join the population between rounds. `cap`: as in round().
  void breed(int iterations, const StopToken& stop, const Population& pop, int cap) {
    const Problem& p = ops_.problem();
    if (p.cluster_count() < 4 || pop.size() == 0) return;
    for (int it = 0; it < std::min(iterations, cap); ++it) {
      if (stop.stop_requested() || stop.target_reached(best_.cost)) return;
      ++iterations_;
      const int a = pop.select(rng_);
      int b = a;
      if (pop.size() >= 2 && rng_.chance(kCrossover))
        for (int t = 0; t < 4 && b == a; ++t) b = pop.select(rng_);
      if (b != a) {
        const auto L = static_cast<std::uint64_t>(p.cluster_count());
        int i = 1 + static_cast<int>(rng_.below(L - 1)), j = 1 + static_cast<int>(rng_.below(L - 1));
        if (i > j) std::swap(i, j);
        detail::order_crossover(ops_, pop.at(a), pop.at(b), i, j, trial_);
      } else {
        trial_ = pop.at(a);
        destroy(trial_, removal_size());
        repair(trial_);
      }
      ops_.local_search(trial_);
      if (trial_.cost < best_.cost) best_ = trial_;
      children_.push_back(trial_);
    }
  }
  std::vector<Tour>& children() { return children_; }

  void restart_from(const Tour& t) {
    cur_ = t;
    best_ = t;
  }
  const Tour& best() const { return best_; }
  long long iterations() const { return iterations_; }

 private:
  // Clusters one destroy removes: 1 + floor(u^2 * kmax), kmax the removal fraction of the movable
  // clusters but at least 3 (when there are), so tiny instances get perturbations local search
  // cannot undo.
  int removal_size() {
    const int movable = ops_.problem().cluster_count() - 1;
    const int kmax = std::max(std::min(movable, 3), static_cast<int>(params_.max_removal_fraction * movable));
    const double u = rng_.uniform01();
    return std::min(movable, 1 + static_cast<int>(u * u * kmax));
  }

  void destroy(Tour& t, int k) {
    removed_.clear();
    const Problem& p = ops_.problem();
    const int L = static_cast<int>(t.seq.size());
    const bool bridge_ok = L >= 8;
    if (elite_destroy_ > 0.0 && !elite_.empty() && rng_.chance(elite_destroy_)) {
      const Tour& e = elite_[static_cast<std::size_t>(rng_.below(elite_.size()))];
      if (e.cost != t.cost && ops_.remove_differences(t, e.seq, removed_) > 0) return;
    }
    switch (rng_.below(bridge_ok ? 5 : 4)) {
      case 4: {  // double bridge: S A B C D -> S A C B D (segment exchange that 2-opt/Or-opt rarely undo)
        // With precedence: a few random tries for B and C such that nothing in B must precede C.
        for (int attempt = 0; attempt < 8; ++attempt) {
          int cut[3];
          for (int& c : cut) c = 1 + static_cast<int>(rng_.below(static_cast<std::uint64_t>(L - 1)));
          std::sort(cut, cut + 3);
          if (cut[0] == cut[1] || cut[1] == cut[2]) continue;
          if (!bridge_feasible(t, cut[0], cut[1], cut[2])) continue;
          // Only the three junctions change: mark them instead of re-examining the whole route.
          const int b = cut[0], c = cut[1], e = cut[2];
          auto at = [&](int i) { return t.seq[static_cast<std::size_t>(i)]; };
          const NodeId after_e = e < L ? at(e) : ops_.after(t, L - 1);
          Cost delta = ops_.link(at(b - 1), at(c)) + ops_.link(at(e - 1), at(b)) - ops_.link(at(b - 1), at(b)) - ops_.link(at(c - 1), at(c));
          if (after_e.valid()) delta += ops_.link(at(c - 1), after_e) - ops_.link(at(e - 1), after_e);
          std::rotate(t.seq.begin() + b, t.seq.begin() + c, t.seq.begin() + e);
          ops_.reindex(t, b, e);
          t.cost += delta;
          ops_.mark_around(t, b - 1);
          ops_.mark_around(t, b + e - c - 1);
          ops_.mark_around(t, e - 1);
          ops_.mark_around(t, e);
          break;
        }
        break;
      }
      case 0: {  // random clusters
        for (int r = 0; r < k; ++r) {
          const int i = 1 + static_cast<int>(rng_.below(static_cast<std::uint64_t>(t.seq.size() - 1)));
          removed_.push_back(ops_.cl(t.seq[static_cast<std::size_t>(i)]));
          ops_.remove_at(t, i);
        }
        break;
      }
      case 1: {  // a segment of consecutive clusters
        const int i = 1 + static_cast<int>(rng_.below(static_cast<std::uint64_t>(L - k)));
        for (int r = 0; r < k; ++r) {
          removed_.push_back(ops_.cl(t.seq[static_cast<std::size_t>(i)]));
          ops_.remove_at(t, i);
        }
        break;
      }
      case 2: {  // worst: the clusters whose removal saves most, randomised (Ropke & Pisinger 2006)
        scored_.clear();
        for (int i = 1; i < L; ++i) scored_.emplace_back(-ops_.removal_gain(t, i), ops_.cl(t.seq[static_cast<std::size_t>(i)]).value());
        pick_biased(t, k);
        break;
      }
      default: {  // related: the clusters whose nodes are closest to a random seed node
        const NodeId seed = t.seq[static_cast<std::size_t>(1 + rng_.below(static_cast<std::uint64_t>(L - 1)))];
        scored_.clear();
        for (int i = 1; i < L; ++i) {
          const NodeId v = t.seq[static_cast<std::size_t>(i)];
          const Cost d = v == seed ? 0 : std::min(p.arc_cost(seed, v), p.arc_cost(v, seed));
          scored_.emplace_back(d, ops_.cl(v).value());
        }
        pick_biased(t, k);
        break;
      }
    }
  }

  // Exchanging seq[b, c) and seq[c, e) keeps precedence iff no cluster of the first must precede one of the second.
  bool bridge_feasible(const Tour& t, int b, int c, int e) const {
    const Problem& p = ops_.problem();
    if (!p.has_precedence()) return true;
    for (int i = b; i < c; ++i)
      for (ClusterId y : p.all_after(ops_.cl(t.seq[static_cast<std::size_t>(i)]))) {
        const int q = t.pos[y.index()];
        if (q >= c && q < e) return false;
      }
    return true;
  }

  // Removes k clusters from scored_ (lower score first), the r-th pick drawn at rank floor(u^3 * size).
  void pick_biased(Tour& t, int k) {
    std::sort(scored_.begin(), scored_.end());
    for (int r = 0; r < k && !scored_.empty(); ++r) {
      const double u = rng_.uniform01();
      const auto idx = static_cast<std::size_t>(u * u * u * static_cast<double>(scored_.size()));
      const ClusterId c(scored_[idx].second);
      scored_.erase(scored_.begin() + static_cast<std::ptrdiff_t>(idx));
      removed_.push_back(c);
      ops_.remove_at(t, t.pos[c.index()]);
    }
  }

  void repair(Tour& t) {
    rng_.shuffle(removed_.begin(), removed_.end());
    // Additive noise on insertion costs, in units of the mean step of the route: without it,
    // cheapest reinsertion of what was just removed mostly rebuilds the same route.
    const double mean_step = static_cast<double>(t.cost) / static_cast<double>(ops_.problem().cluster_count());
    static constexpr double kNoise[4] = {0.0, 0.3, 1.0, 2.0};
    const double noise = kNoise[rng_.below(4)] * mean_step;
    // Precedence: insert predecessors first when both were removed (a topological order of the removed set).
    const Problem& p = ops_.problem();
    if (p.has_precedence())
      std::stable_sort(removed_.begin(), removed_.end(), [&](ClusterId a, ClusterId b) {
        return p.all_before(a).size() < p.all_before(b).size();
      });
    for (ClusterId c : removed_) ops_.insert(t, ops_.best_repair_insertion(t, c, noise, rng_));
  }

  const Ops& ops_;
  const SolveParams& params_;
  Rng rng_;
  Tour cur_, best_, trial_;
  const std::vector<Tour>& elite_;
  double elite_destroy_;
  std::vector<ClusterId> removed_;
  std::vector<std::pair<Cost, int>> scored_;
  std::vector<Tour> children_;
  long long iterations_ = 0;
};

}  // namespace

Solution solve_heuristic(const Problem& p, const SolveParams& params_in, const StopToken& stop_in, const ProgressFn& progress) {
  SolveParams params = params_in;
  const bool large = p.cluster_count() >= SolveParams::kLargeClusters;
  const double avg_k = static_cast<double>(p.node_count()) / p.cluster_count();
  // Large GTSPLIB-like routes (96-250 clusters of a few nodes, no precedence) leave their basins
  // only through large destroys and a wide acceptance, like precedence problems (measured on the
  // 99-217 cluster set: mean gap 0.33 % -> ~0.1 %). Not for large clusters (100C10k.0: each
  // iteration re-optimises 100-node clusters; small local repairs do better there) nor for long
  // routes (cutting nests: a destroy of 30 % of 1000 clusters costs seconds).
  const bool wide = large && !p.has_precedence() && p.cluster_count() < 250 && avg_k <= 8.0;
  // Their iterations cost more (up to 30 % of the route rebuilt) and some runs keep improving for
  // long: a work budget bounds them instead of a short stagnation count (10 rounds from 150 clusters
  // on left 207si1032 at 3-5 s and stopped others early). GTSPLIB 99-217 clusters, seeds 1-5, with
  // the 2-opt neighbour optimisation: mean gap 0.139 % -> 0.108 %, max wall 5.4 s -> 2.2 s.
  // Since the population mode (and its epochs of 10 rounds) a wide run that stalls either gets out
  // within an epoch restart and the 10-12 rounds a fresh population takes to catch up, or not at
  // all: the stagnation count is 22, not 40. Traces of seeds 1-15 on the 99-217 cluster set (300
  // runs): the longest stall before a later improvement was 20 rounds but for one of 30 (132d657,
  // 0.013 %). 40 -> 22 rounds, seeds 1-15 / held-out seeds 16-20: mean gap 0.0059 / 0.0085 % ->
  // 0.0059 / 0.0086 %, at the best known 256 / 87 -> 255 / 86 runs, mean wall 2.47 / 2.87 s ->
  // 2.01 / 2.33 s (docs/solver-bench-2026-11-28-session28.md).
  if (params.stagnation_rounds == 0) params.stagnation_rounds = wide ? 22 : large ? 20 : 6;
  // A budget the caller gave is kept to the iteration (`round_cap`: rounds end early once their
  // share of it is spent; on a large nest one round is ~20 s); the automatic one, tuned with
  // whole rounds, to the round.
  const bool exact_budget = params.work_budget > 0.0;
  if (params.work_budget == 0.0) params.work_budget = wide ? 9.0e6 : -1.0;
  int k_min = p.node_count();
  for (int c = 0; c < p.cluster_count(); ++c) k_min = std::min(k_min, p.cluster_size(ClusterId(c)));
  const double work_per_iteration = p.node_count() * (1.0 + k_min) / 2.0;
  // Precedence-constrained routes up to a few hundred clusters (SOP) need large destroys to leave a
  // basin (kro124p.3: 0.05 stays 2-4 % above the best known, 0.3 reaches it).
  if (params.max_removal_fraction == 0.0)
    params.max_removal_fraction = large && !(p.has_precedence() && p.cluster_count() < 200) && !wide ? 0.05 : 0.3;
  // Precedence blocks most moves, so local optima are deeper: a wider acceptance (measured on SOP:
  // kro124p.2 reaches its best known in 10 s with 2.0, stays 1-5 % above it with 0.5).
  if (params.accept_threshold == 0.0) params.accept_threshold = p.has_precedence() || wide ? 2.0 : large ? 1.0 : 0.5;
  const auto t0 = std::chrono::steady_clock::now();
  StopToken stop = params.time_limit_s > 0 ? stop_in.with_time_limit(params.time_limit_s) : stop_in;
  if (params.target_cost) stop = stop.with_target(*params.target_cost);
  int threads = params.threads > 0 ? params.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min(threads, params.threads > 0 ? 256 : 8);
  if (p.cluster_count() <= 3) threads = 1;
  // Automatic round length: 40 + m/2 iterations, shortened for large clusters (avg > 8 nodes), whose
  // iterations cost up to (avg/8)^2 times more (cluster optimisation is quadratic in cluster size).
  const int round_iters = params.round_iterations > 0
                              ? params.round_iterations
                              : std::max(10, static_cast<int>((40 + p.cluster_count() / 2) * std::min(1.0, 8.0 / avg_k)));

  const Ops ops(p, &stop, threads);
  Rng master(params.seed);
  std::vector<Worker> workers;
  workers.reserve(static_cast<std::size_t>(threads));
  // Elite pool: the best distinct routes (by cost) the threads ended rounds with, for the
  // elite-difference destroy on wide problems. GTSPLIB 99-217 clusters, 2 x 12 seeds each: mean gap
  // 0.175 / 0.182 % -> 0.166 / 0.155 %, runs at the best known 90 / 90 -> 108 / 122 of 240, 5-10 %
  // more CPU (destroy probability 0.2; 0.4 gave 0.192 %, a pool of 8 the same as 4).
  std::vector<Tour> elite;
  constexpr std::size_t kEliteSize = 4;
  const double elite_destroy = wide ? 0.2 : 0.0;
  for (int i = 0; i < threads; ++i) workers.emplace_back(ops, params, master.split(), elite, elite_destroy);
  // Population mode (hybrid genetic search, docs/SOLVER.md "Population") on large problems without
  // precedence below 250 clusters (wide ones and large clusters such as 100C10k.0). The crossover
  // ignores precedence; tiny routes have nothing to recombine.
  const bool pop_auto = large && !p.has_precedence() && p.cluster_count() < 250;
  const int pop_mu = p.has_precedence() || p.cluster_count() < 5 ? 0
                     : params.population_size > 0 ? params.population_size
                     : params.population_size == 0 && pop_auto ? 40 : 0;
  Population pop(pop_mu, kGeneration);

  Tour global, epoch;
  int stagnant = 0, epoch_stagnant = 0;
  bool done = false;
  bool first = true;
  bool new_epoch = false;
  // Automatic epochs: short ones on small problems without precedence, longer ones on precedence
  // problems below 200 clusters (SOP: kro124p.3 ended 1.35 % above its best known in 1 seed of 5
  // without them); 8 rounds rather than 15 because prob.100's good routes all come from a run's
  // first trajectories and later restarts come too late to catch up (figures at
  // SolveParams::epoch_rounds); none on the rest (a fresh large route
  // rarely catches up with the best within a run) nor on large clusters (a fresh start costs a
  // full cluster optimisation: 31C3k.0, 100-node clusters, 3-10 % more CPU with epochs, always at
  // its optimum without). In the population mode on wide problems an epoch of 10 rounds replaces
  // the whole population with fresh routes (the best is kept): a population sometimes converged
  // on one basin within a few thousand iterations and then spent the run there (134gr666 at
  // +0.45 % or +0.82 % in 4 of 15 seeds; with epochs 1 of 15). GTSPLIB 99-217 without 100C10k.0,
  // seeds 1-5 / 6-15: mean gap 0.029 / 0.020 % -> 0.021 / 0.013 %. Not on 100C10k.0 (0.02 % ->
  // 0.07 %: a fresh population of 100-node clusters takes too long to catch up).
  const int epoch_patience = params.epoch_rounds != 0 ? std::max(0, params.epoch_rounds)
                             : p.has_precedence() ? (p.cluster_count() < 200 ? 8 : 0)
                             : pop_mu > 0 ? (wide ? 10 : 0)
                             : !large && avg_k <= 8.0 ? 3 : 0;
  // Small problems without precedence (those with epochs) take the fresh-start decision for all
  // threads at once: a thread that alone rebuilds its route from scratch made the other wait at the
  // barrier (45ts225: each of 2 threads waited 25-30 % of the run; 45ts225 and 40d198 ran 0.60 and
  // 0.34 s on 2 threads, 0.48 s on one).
  const bool fresh_together = epoch_patience > 0 && !p.has_precedence() && pop_mu == 0;
  Rng fresh_rng = master.split();
  // Asymmetric matrices (GTSPLIB AGTSP): the search starts from the node-set search's route. On
  // 89rbg443 the route search alone stalled at 633-639 (optimum 632; each seed reached it only after
  // 3-10 s), in node sets 3-7 clusters from the optimum's, while the node-set search finds a set of
  // bound 632 in about 0.1 s (docs/SOLVER.md "Node sets").
  Tour ns_start;
  if (detail::node_sets_apply(p)) {
    Rng ns_rng = master.split();
    ns_start.seq = detail::node_set_start(p, threads, ns_rng, stop);
    if (!ns_start.seq.empty()) ops.init(ns_start);
  }
  Worker::Fresh fresh = Worker::Fresh::none;
  // Iterations each thread may still do in the next round under an explicit work budget (rounds
  // synchronise, so every thread's share is known at the barrier: deterministic).
  int round_cap = std::numeric_limits<int>::max();
  auto set_round_cap = [&](long long done_iterations) {
    if (!exact_budget) return;
    const double left = std::max(0.0, params.work_budget - static_cast<double>(done_iterations) * work_per_iteration);
    const double per_thread = std::ceil(std::ceil(left / work_per_iteration) / threads);
    round_cap = static_cast<int>(std::clamp(per_thread, 1.0, static_cast<double>(std::numeric_limits<int>::max())));
  };
  set_round_cap(0);
  // Runs between rounds on one thread: picks the best route (ties: lowest thread index), decides stop.
  auto combine = [&]() noexcept {
    if (pop_mu > 0) {
      for (Worker& w : workers) {
        for (const Tour& c : w.children()) pop.add(ops, c);
        w.children().clear();
      }
      pop.refresh();
    }
    if (elite_destroy > 0.0)
      for (const Worker& w : workers) {
        const Tour& b = w.best();
        if (std::any_of(elite.begin(), elite.end(), [&](const Tour& e) { return e.cost == b.cost; })) continue;
        if (elite.size() < kEliteSize) {
          elite.push_back(b);
          continue;
        }
        auto worst = std::max_element(elite.begin(), elite.end(), [](const Tour& x, const Tour& y) { return x.cost < y.cost; });
        if (b.cost < worst->cost) *worst = b;
      }
    const Tour* best = &workers[0].best();
    for (const Worker& w : workers)
      if (w.best().cost < best->cost) best = &w.best();
    if (first || new_epoch || best->cost < epoch.cost) {
      epoch = *best;
      epoch_stagnant = 0;
    } else {
      ++epoch_stagnant;
    }
    if (first || epoch.cost < global.cost) {
      global = epoch;
      stagnant = 0;
    } else {
      ++stagnant;
    }
    first = false;
    new_epoch = epoch_patience > 0 && epoch_stagnant >= epoch_patience;
    if (new_epoch && pop_mu > 0) pop.clear();
    if (!fresh_together) fresh = epoch_stagnant > 0 ? Worker::Fresh::maybe : Worker::Fresh::none;
    else if (epoch_stagnant == 0 || new_epoch) fresh = Worker::Fresh::none;
    else fresh = fresh_rng.chance(std::min(0.5, 16.0 / p.cluster_count())) ? Worker::Fresh::all : Worker::Fresh::none;
    if (!new_epoch && pop_mu == 0)
      for (Worker& w : workers) w.restart_from(epoch);
    // Stagnation: enough rounds without progress, and enough iterations in them (tiny instances have
    // short rounds; a few thousand iterations on them cost milliseconds).
    // An iteration costs about n * max(1, avg/8) (cluster optimisation is quadratic in the cluster
    // size; the automatic round is shortened by the same factor).
    // Open paths with precedence (SOP) keep improving for longer, so their work counts a tenth.
    // Not cutting routes (closed tours) nor tiny paths: they would search ten times longer for nothing.
    const double work_scale =
        std::max(1.0, avg_k / 8.0) * (p.has_precedence() && !p.closed() && p.cluster_count() > 16 ? 0.1 : 1.0);
    const long long stagnant_work =
        static_cast<long long>(static_cast<double>(stagnant) * round_iters * threads * p.node_count() * work_scale);
    long long total_iterations = 0;
    for (const Worker& w : workers) total_iterations += w.iterations();
    const bool budget_spent = params.work_budget > 0.0 && static_cast<double>(total_iterations) * work_per_iteration >= params.work_budget;
    set_round_cap(total_iterations);
    done = budget_spent || stop.stop_requested() || stop.target_reached(global.cost) ||
           (stagnant >= params.stagnation_rounds && stagnant_work >= params.min_stagnation_work);
    if (progress) progress({"heuristic", -1.0, static_cast<double>(global.cost)});
  };

  // Population mode: twice the population size in fresh routes, shared evenly among the threads.
  const int seed_share = (2 * pop_mu + threads - 1) / threads;
  auto body = [&](int i, auto&& sync) {
    Worker& w = workers[static_cast<std::size_t>(i)];
    w.start();
    if (!ns_start.seq.empty() && ns_start.cost < w.best().cost) w.restart_from(ns_start);
    if (pop_mu > 0) {
      w.seed_population(seed_share, stop);
      w.children().push_back(w.best());  // each thread's start route joins too
    }
    sync();
    while (!done) {
      if (pop_mu == 0) {
        if (new_epoch) w.start();  // the worker's best restarts from a fresh route
        w.round(round_iters, stop, fresh, round_cap);
      } else if (new_epoch) {
        w.seed_population(seed_share, stop);  // combine() emptied the population
      } else {
        w.breed(round_iters, stop, pop, round_cap);
      }
      sync();
    }
  };
  if (threads == 1) {
    body(0, combine);
  } else {
    std::barrier bar(threads, combine);
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back([&, i] { body(i, [&] { bar.arrive_and_wait(); }); });
    body(0, [&] { bar.arrive_and_wait(); });
    for (auto& th : pool) th.join();
  }

  // Final polish: a full cluster optimisation (local search may have used windows only).
  if (ops.cluster_optimise(global, kFullCoWork)) ops.local_search(global);
  Solution s;
  s.route = global.seq;
  s.cost = ops.full_cost(global.seq);
  s.status = uses_forbidden_arc(p, s.route) ? SolveStatus::no_solution : SolveStatus::feasible;
  if (s.status == SolveStatus::no_solution) s.route.clear(), s.cost = 0;
  s.stats.solver = "heuristic";
  s.stats.threads = threads;
  for (const Worker& w : workers) s.stats.iterations += w.iterations();
  s.stats.work = static_cast<double>(s.stats.iterations) * work_per_iteration;
  s.stats.stopped_by_limit = stop.stop_requested();
  s.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

}  // namespace cutroute::solve
