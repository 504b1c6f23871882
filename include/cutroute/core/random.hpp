// Rng: the one random engine (xoshiro256**), seeded explicitly, identical on every platform.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>

namespace cutroute {

// Written by hand because std::uniform_int_distribution and friends are implementation-defined:
// the same seed must give the same G-code with any standard library (STYLE.md #12).
class Rng {
 public:
  explicit Rng(std::uint64_t seed = 1);

  std::uint64_t next();                                   // uniform 64-bit
  std::uint64_t below(std::uint64_t n);                   // uniform in [0, n), n > 0 (Lemire, unbiased)
  std::int64_t between(std::int64_t lo, std::int64_t hi); // uniform in [lo, hi]
  double uniform01();                                     // uniform in [0, 1), 53 bits
  bool chance(double p) { return uniform01() < p; }
  Rng split();                                            // an independent child stream (per thread)

  template <class It>
  void shuffle(It first, It last) {
    const auto n = static_cast<std::uint64_t>(last - first);
    for (std::uint64_t i = n; i > 1; --i) {
      using std::swap;
      swap(first[i - 1], first[below(i)]);
    }
  }

 private:
  std::uint64_t s_[4];
};

}  // namespace cutroute
