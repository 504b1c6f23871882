// Private: the population of the hybrid genetic search (routes kept diverse by distance, after
// Vidal et al. 2012) and its ordered crossover.
#pragma once

#include <vector>

#include <cutroute/core/random.hpp>

#include "tour.hpp"

namespace cutroute::solve::detail {

// Survivor selection keeps `mu` routes: once `mu + lambda` are held, the routes with the worst
// biased fitness (rank by cost + (1 - elite / size) x rank by diversity, the mean broken-pairs
// distance to the `close` nearest others) are dropped one by one, clones first. A route that is good
// or unlike the rest survives; near copies of one optimum do not crowd out the other basins, whose
// recombination is what finds routes no local move reaches.
class Population {
 public:
  Population(int mu, int lambda, int elite = 4, int close = 5) : mu_(mu), lambda_(lambda), elite_(elite), close_(close) {}

  // Adds a copy of the complete route t; runs survivor selection when full. Call refresh() after
  // the last add and before select().
  void add(const Ops& ops, const Tour& t);
  void refresh();
  void clear() { members_.clear(); dist_.clear(); }
  int size() const { return static_cast<int>(members_.size()); }
  const Tour& at(int i) const { return members_[static_cast<std::size_t>(i)].tour; }
  double fitness(int i) const { return members_[static_cast<std::size_t>(i)].fitness; }
  // Binary tournament on biased fitness (lower is better); needs size() >= 1.
  int select(Rng& rng) const;
  // Broken-pairs distance in [0, 1]: the share of one route's cluster-level arcs (either direction
  // on symmetric problems) the other lacks. Both routes visit every cluster, so it is symmetric.
  double distance(int a, int b) const { return dist_[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)]; }

 private:
  struct Member {
    Tour tour;
    std::vector<int> succ, pred;  // by cluster, -1 when none
    // Distances to every other member, ascending: survivor selection removes one member at a time
    // and re-ranks the rest, and re-sorting every row each time was most of the serial step
    // between rounds (about 0.1 s of a 2.8-s 200E1k.0 run).
    std::vector<double> near;
    double fitness = 0.0;
  };
  double compute_distance(const Member& a, const Member& b) const;
  bool clone(int i) const;
  void remove(int i);

  int mu_, lambda_, elite_, close_;
  bool sym_ = true;
  std::vector<Member> members_;
  std::vector<std::vector<double>> dist_;
};

// Ordered crossover (Oliver et al. 1987) on the cluster sequence, position 0 fixed: child gets
// a.seq[i..j] in place and the other clusters in b's order from after that stretch in b, with b's
// nodes. Needs complete routes a, b (pos valid) and 1 <= i <= j < size. Only the clusters next to
// an arc that neither parent has are flagged for local search (as after a destroy/repair step).
void order_crossover(const Ops& ops, const Tour& a, const Tour& b, int i, int j, Tour& child);

}  // namespace cutroute::solve::detail
