// deal(): independent work items dealt round-robin to a few threads, deterministic by construction.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace cutroute {

// Runs work(k) for every k in [0, count), item k on thread k mod w, where w is `threads` (at least
// 1) but at most one thread per `min_items` items (a few items are not worth a thread), the
// caller's thread being one of them; returns when all are done, then rethrows the first exception
// a thread threw. Each work(k) must write only its own result slot, so the outcome is the same
// whatever the thread count. Hand-written over std::jthread: a handful of
// threads over coarse items (one contour's or one chain's geometry each), where a thread-pool
// library would add nothing.
template <class Work>
void deal(std::size_t count, int threads, std::size_t min_items, Work&& work) {
  const std::size_t most = std::max<std::size_t>(1, count / std::max<std::size_t>(min_items, 1));
  const std::size_t workers = std::min(static_cast<std::size_t>(std::max(threads, 1)), most);
  std::vector<std::exception_ptr> failed(workers);
  auto run = [&](std::size_t w) {
    try {
      for (std::size_t k = w; k < count; k += workers) work(k);
    } catch (...) {
      failed[w] = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> pool;
    for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(run, w);
    run(0);
  }
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
}

}  // namespace cutroute
