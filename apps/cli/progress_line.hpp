// The progress line of long commands on a terminal (optimize, gtsp): rewritten in place on stderr.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

#include <cutroute/core/stop.hpp>

namespace cutroute::cli {

// One line per job ("name: stage  best X  T s"), rewritten in place at most 5 times a second;
// silent when off (not a terminal, or --quiet). Safe to call from several threads.
// "name: rest" shortened to fit `columns` - 1 characters: the name loses its front first.
std::string fit_progress_line(const std::string& name, const std::string& rest, std::size_t columns);

class ProgressLine {
 public:
  // decimals: of the best value shown (2 for seconds of T_cut, 0 for integer costs).
  explicit ProgressLine(bool on, int decimals = 2) : on_(on), decimals_(decimals), t0_(std::chrono::steady_clock::now()) {}
  ProgressFn for_job(const std::string& name);
  // Clears the line (call before printing results).
  void done();

 private:
  bool on_;
  int decimals_;
  std::mutex mu_;
  std::chrono::steady_clock::time_point t0_, last_{};
};

}  // namespace cutroute::cli
