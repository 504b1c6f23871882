// solve(): the one entry point: picks the exact DP or the metaheuristic and returns a validated Solution.
#pragma once

#include <cutroute/core/stop.hpp>
#include <cutroute/solve/params.hpp>
#include <cutroute/solve/problem.hpp>
#include <cutroute/solve/solution.hpp>

namespace cutroute::solve {

// Steps: 1. automatic -> exact when estimate_exact_work() is small, else heuristic;
// 2. exact: the cluster-graph bound when cheap (as in 3), a short heuristic run that gives the upper
//    bound the DP prunes with (stopped at that bound), then the DP; the larger bound is reported;
// 3. heuristic: multi-start ALNS until time limit, target, stagnation or cancel; in automatic mode
//    on precedence or asymmetric problems of at most 1 000 clusters and 3 000 nodes (1 500 with a
//    cost callback), and up to 1 500 clusters and 12 000 nodes when the time limit is at least 20
//    times its estimated cost (estimate_bound_seconds), the cluster-graph bound (lower_bound.hpp) is
//    computed first: the run stops when it reaches the bound (status optimal) and the Solution
//    reports it as its lower bound; other problems with planar costs (larger nests, or a time limit
//    too short for the graph) get the cheapest-entry bound (entry_lower_bound) instead;
// 4. the result is checked with validate() (a failure is a bug: it throws std::logic_error).
// `stop` adds an external cancel and deadline to params.time_limit_s.
Solution solve(const Problem& problem, const SolveParams& params, const StopToken& stop = {},
               const ProgressFn& progress = {});

}  // namespace cutroute::solve
