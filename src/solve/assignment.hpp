// Private: a linear assignment problem (each row matched to one column, minimum total cost) that is
// re-solved in O(m^2) after one row and the column of the same index change.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace cutroute::solve::detail {

// Written by hand: the AP is the inner loop of the node-set search (node_sets.cpp), which changes one
// row and column thousands of times per second and needs the O(m^2) re-solve, not a fresh O(m^3)
// solve; no Debian package offers an incremental LAP. Shortest augmenting paths with potentials
// (Dijkstra on reduced costs, as in Jonker & Volgenant 1987), so reduced costs stay >= 0 between
// changes. The diagonal is the caller's: to read the AP as the cycle-cover bound of a tour, put
// kBig there.
class Assignment {
 public:
  using Cost = std::int64_t;
  static constexpr Cost kBig = Cost{1} << 42;
  static constexpr Cost kNoLimit = std::numeric_limits<Cost>::max();

  // m x m, every entry 0 and nothing assigned; fill with at() and call solve().
  void reset(int m);
  Cost& at(int i, int j) {
    return c_[static_cast<std::size_t>(i) * static_cast<std::size_t>(m_) + static_cast<std::size_t>(j)];
  }
  Cost at(int i, int j) const {
    return c_[static_cast<std::size_t>(i) * static_cast<std::size_t>(m_) + static_cast<std::size_t>(j)];
  }
  void solve();  // assigns every free row, O(m^2) each
  // The same optimum from an empty matching (right after reset() and filling), with Jonker &
  // Volgenant's column reduction first: most rows start matched, and only the rest need a shortest
  // augmenting path (a 1 187-cluster nest: 1.0 s -> 0.02 s). The matching and potentials may
  // differ from solve()'s among equal optima.
  void solve_reduced();
  Cost value() const { return value_; }
  // Row and column potentials after solve(): c(i, j) - row(i) - col(j) >= 0 on every entry.
  Cost row_potential(int i) const { return u_[static_cast<std::size_t>(i)]; }
  Cost col_potential(int j) const { return v_[static_cast<std::size_t>(j)]; }
  // The column assigned to row i after solve() (-1 while free).
  int col_of(int i) const { return col_of_[static_cast<std::size_t>(i)]; }

  // Sets row k and column k to row[] and col[] (row[k], col[k] ignored: the diagonal stays) and
  // re-solves from the current matching, O(m^2). With a limit, gives up (false, state undefined
  // until restore()) as soon as the optimum is known to be >= limit.
  bool replace(int k, const Cost* row, const Cost* col, Cost limit = kNoLimit);
  // A lower bound on the optimum after replace(k, row, col), from the current (optimal) potentials
  // with the best ones for the new row and column, O(m).
  Cost bound_with(int k, const Cost* row, const Cost* col) const;

  // What replace(k, ...) changes, to undo a trial in O(m).
  struct Saved {
    std::vector<Cost> u, v, row, col;
    std::vector<int> row_of, col_of;
    Cost value = 0;
  };
  void save(int k, Saved& s) const;
  void restore(int k, const Saved& s);

 private:
  bool augment(int row, Cost limit);
  int m_ = 0;
  std::vector<Cost> c_;
  std::vector<Cost> u_, v_, d_;       // row and column potentials, Dijkstra distances
  std::vector<int> row_of_, col_of_;  // -1: free
  std::vector<int> pred_, scanned_;
  std::vector<int> open_;  // columns augment() has not reached yet, ascending
  Cost value_ = 0;
};

}  // namespace cutroute::solve::detail
