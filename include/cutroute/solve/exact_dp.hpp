// Exact dynamic programming for the generalized TSP with precedence (Held–Karp over clusters).
//
// Problem. Clusters C_0..C_m (C_0 = the start cluster, renumbered here), nodes v with step costs
// w(u, v) = arc(u, v) + inner(v) (inner(s) is paid once for the start node s), a precedence
// relation P on clusters (transitively closed) and forbidden arcs (w = +inf). Find a sequence
// s, v_1, ..., v_m with s in C_0, exactly one v_i in each other cluster, every (a, b) in P kept,
// minimising inner(s) + sum_i w(v_{i-1}, v_i) [+ arc(v_m, s) for a closed tour].
//
// Recurrence (Held & Karp 1962, generalised to clusters; with precedence it is the "megalopolis"
// routing DP of A. G. Chentsov, e.g. Chentsov, Khachai & Khachai, Proc. Steklov Inst. Math. 2016,
// used for cutting by Petunin et al., ../shared/PAPERS.md §2). For a fixed start node s:
//   F(S, v) = cheapest path from s through exactly the clusters of S, ending in v (cluster(v) in S).
//   F({b}, v) = inner(s) + w(s, v)                         if b has no predecessor except C_0
//   F(S, v)   = min over u in S \ b of F(S \ b, u) + w(u, v),   b = cluster(v),
//   only for "ideals" S: every predecessor of every cluster of S is in S (or is C_0), and
//   b may be added last only when all its predecessors are in S \ b.
//   OPT(s) = min over v of F(all, v) [+ arc(v, s)];  OPT = min over s in C_0 of OPT(s).
//
// Complexity. With m' = m non-start clusters, N' non-start nodes and k_0 = |C_0|:
//   time   O(k_0 * 2^m' * N'^2 / 4)  (each ideal S: nodes in S times nodes that may follow),
//   memory 2^m' * N' * 8 bytes for one table (reused for every start node) + 2^m' bytes.
//   estimate_exact_work() / estimate_exact_memory() give these numbers for a problem.
// Limits. m' <= 30 (subsets are 32-bit masks) and the table must fit in
// SolveParams::exact_memory_limit_bytes (checked before allocating); solve() in automatic mode uses
// the DP only when estimate_exact_work() <= exact_auto_max_work (about one second). Precedence
// shrinks the set of ideals a lot, and the bound below prunes most of the rest.
//
// Bounds. A state is dropped when F(S, v) + LB(S) >= UB, where UB is the cost of the best route known
// (an incumbent from the heuristic, then each better DP route) and LB(S) = sum over clusters b not
// in S of min over u outside b of w(u, v in b), plus the cheapest closing arc into s. Routes of cost
// UB are never lost: the incumbent is one of them.
//
// Memory layout. F is one flat array indexed [S * N' + local node]: the nodes of cluster b occupy a
// contiguous range of local ids, so the inner relaxation loop walks contiguous memory, and S is a
// plain bitmask (no hashing). Subsets are processed layer by layer (by size) from explicit lists,
// which is also what makes the anytime lower bound below valid.
//
// Anytime. When stopped (time limit, cancel), the lower bound is the minimum over start nodes of:
// UB for finished start nodes; for the interrupted one, the minimum of F(S, v) + LB(S) over its last
// completed layer (every route passes through exactly one state of each layer); for start nodes not
// yet begun, inner(s) + LB(empty set). The larger of that and the cluster-graph bound of
// lower_bound.hpp is reported; that bound is computed before the DP, and when it reaches the
// incumbent the incumbent is returned as optimal without running the DP.
#pragma once

#include <cstddef>
#include <optional>

#include <cutroute/core/stop.hpp>
#include <cutroute/solve/problem.hpp>
#include <cutroute/solve/solution.hpp>

namespace cutroute::solve {

// Estimated relaxations (time) and bytes (memory) of solve_exact() on `p`, ignoring precedence
// and pruning (both only make it smaller). Infinity / SIZE_MAX when beyond the 30-cluster limit.
double estimate_exact_work(const Problem& p);
std::size_t estimate_exact_memory(const Problem& p);

// Runs the DP. `incumbent` (optional, must be valid) is the initial upper bound. Returns status
// optimal with the optimum; infeasible when no route exists; or, when stopped or over the memory
// limit, the incumbent (status feasible, or no_solution without one) with lower_bound set.
// `progress` hears of each finished layer: stage "exact", fraction = (start nodes done + layers done /
// clusters) / start nodes, best = the best route's cost when there is one. `known_bound`: the
// caller's route_lower_bound() (lower_bound.hpp), used instead of computing it again here.
Solution solve_exact(const Problem& p, std::size_t memory_limit_bytes, const StopToken& stop,
                     const Solution* incumbent = nullptr, const ProgressFn& progress = {},
                     std::optional<Cost> known_bound = std::nullopt);

// Ideals. The same recurrence over the ideals alone (exact_ideals.cpp), for precedence problems
// beyond the dense table (more than 30 non-start clusters, or a table over the memory limit), where
// the ideals are often few although 2^m' is not: TSPLIB SOP p43.4 (43 clusters) has 37 921 ideals,
// ry48p.4 68 657, ft53.4 154 689. Each layer (ideals of one size) is a hash map from the 128-bit set to
// its row, which holds F(S, v) only for the nodes of clusters that may come last in S (those with no
// successor in S): memory about (sum over ideals of those nodes) * 8 bytes + 100 bytes per ideal,
// checked against the limit as the layers grow. Ideals are created when a state first survives the
// bound, so pruned ones cost nothing. Up to kMaxIdealClusters non-start clusters. solve_exact() calls
// it for precedence problems beyond its own limits, and for those whose dense table would take more
// than 64 MB while they have at most a million ideals (cutting nests of 20-27 contours: the demo
// sheet 444 → 36 MB, faster); the returns are as solve_exact()'s (a memory stop
// reports the bound of the last complete layer).
inline constexpr int kMaxIdealClusters = 128;
// Relaxations of solve_exact_ideals() before pruning, from an enumeration of the ideals; infinity
// when there are more than `max_ideals` (or kMaxIdealClusters clusters), most often found in O(m) from
// the clusters free of precedence.
double estimate_ideal_work(const Problem& p, std::size_t max_ideals);
Solution solve_exact_ideals(const Problem& p, std::size_t memory_limit_bytes, const StopToken& stop,
                            const Solution* incumbent = nullptr, const ProgressFn& progress = {});

}  // namespace cutroute::solve
