// SolveParams: plain solver settings with documented defaults, three presets, and a checker.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <cutroute/solve/problem.hpp>

namespace cutroute::solve {

enum class SolverKind {
  automatic,  // exact when the DP is estimated to finish fast (exact_auto_max_work), else heuristic
  exact,      // dynamic programming; at a limit returns its best route and a lower bound
  heuristic,  // construction + local search + adaptive large neighbourhood search, multi-start
};
const char* to_string(SolverKind k);

struct SolveParams {
  SolverKind solver = SolverKind::automatic;
  std::uint64_t seed = 1;              // same seed + threads + input -> same route (see docs/SOLVER.md)
  int threads = 0;                     // 0: std::thread::hardware_concurrency(), at most 8
  double time_limit_s = 60.0;          // wall-clock limit of solve() [s]; <= 0 means none
  std::optional<Cost> target_cost;     // stop as soon as a route this cheap is found

  // Heuristic (docs/SOLVER.md "Metaheuristic").
  // Synchronisation: threads work in rounds of `round_iterations` destroy/repair steps, then all
  // restart from the best route (lowest cost, lowest thread index on ties): deterministic.
  int round_iterations = 0;            // 0: automatic, 40 + m/2 (x 8/avg cluster size when above 8, >= 10)
  // Stop after this many rounds in a row without improving the best route. 0: automatic,
  // 6 below kLargeClusters clusters, 20 from there on, 22 on "wide" problems (see
  // max_removal_fraction), which work_budget also bounds (tuned on GTSPLIB for the time
  // targets: small instances converge in few rounds, large ones keep improving slowly; 22 lets a
  // wide run's epoch restart after 10 rounds catch up).
  int stagnation_rounds = 0;
  // Stop once the search has done this much work: iterations of all threads x node count x
  // (1 + size of the smallest cluster) / 2 (each iteration's cluster optimisation tries every node of
  // the smallest cluster as its start). Deterministic, unlike a time limit, and roughly
  // proportional to CPU time. 0: automatic, 9e6 on wide problems (about 1.5-2 s on 2 cores for
  // GTSPLIB's 200-cluster instances), none otherwise; < 0: none.
  double work_budget = 0.0;
  // Epochs: after this many rounds without improving the current epoch's best route, every thread
  // starts afresh from its own random construction (the overall best is kept and returned), instead
  // of searching on around a local optimum the destroy/repair steps no longer leave. 0: automatic,
  // 3 below kLargeClusters clusters without precedence and with at most 8 nodes per cluster on
  // average (GTSPLIB 35ftv170 and 87gr431: 1 seed in 5
  // stuck 3.5 % and 1.3 % above the optimum for the whole run, 5/5 at it with epochs), 8 with
  // precedence below 200 clusters (SOP kro124p.3: 1 seed in 5 1.35 % above its best known without;
  // prob.100, 2 threads, 10 s, seeds 1-30 and 91-150 on one machine and day: 18 of 90 runs more
  // than 1 % above its best known with 8 rounds, 40 with 15),
  // off otherwise (a fresh large route rarely catches up within a run); < 0: off.
  int epoch_rounds = 0;
  // ... and only after (iterations without progress, all threads) x (node count) x max(1, average
  // cluster size / 8) reaches this (a tenth of that counted on problems with precedence): tiny
  // instances, whose iterations cost microseconds, get thousands of them; large ones are governed
  // by stagnation_rounds alone.
  long long min_stagnation_work = 1000000;
  // Largest share of the clusters one destroy step may remove (at least 3 clusters). 0: automatic,
  // 0.3 below kLargeClusters clusters, with precedence below 200 clusters, and on "wide" problems
  // (kLargeClusters to 249 clusters, no precedence, <= 8 nodes per cluster on average); 0.05 otherwise
  // (large routes are improved by small, local repairs; big ones are mostly undone by the local
  // search, except where precedence blocks the small moves).
  double max_removal_fraction = 0.0;
  // Threshold acceptance: a worse route is accepted when it costs at most this many mean steps
  // (route cost / clusters) more than the current one; decays linearly to 0 over each round.
  // 0: automatic, 2.0 with precedence and on wide problems, else 0.5 below kLargeClusters clusters,
  // 1.0 from there on.
  double accept_threshold = 0.0;
  // Hybrid genetic search (docs/SOLVER.md "Population"): instead of continuing one route, every
  // iteration breeds a child from a population of this many routes kept diverse by distance (ordered
  // crossover of two, or a destroy/repair step of one, then local search). 0: automatic, 40 on
  // problems of 96-249 clusters without precedence (GTSPLIB 99-217 clusters, 25 seeds: mean gap
  // 0.118 % -> 0.006 %; 25 routes: 0.008 %, one run above 0.3 %), off otherwise (89rbg443 no
  // better, slower); < 0: off. Never on problems with precedence (SOP, most cutting routes): the
  // crossover ignores it.
  int population_size = 0;
  static constexpr int kLargeClusters = 96;

  // Exact DP (solve/exact_dp.hpp).
  std::size_t exact_memory_limit_bytes = std::size_t{1536} << 20;  // 1.5 GiB
  // automatic picks the DP when its estimated transition count is below this (about 1 s of work).
  double exact_auto_max_work = 4.0e8;

  static SolveParams fast();      // ~10x less search than default: quick answers for previews
  static SolveParams standard();  // the default: GTSPLIB <= 217 clusters within ~0.05 % in seconds
  static SolveParams thorough();  // ~4x more stagnation tolerance, larger neighbourhoods
};

// Human-readable problems with `p` (empty when valid), e.g. "threads must be >= 0 (got -1)".
std::vector<std::string> check(const SolveParams& p);

}  // namespace cutroute::solve
