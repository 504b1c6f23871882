#include "progress_line.hpp"

#include <iostream>

#include <cutroute/core/number_format.hpp>

namespace cutroute::cli {

ProgressFn ProgressLine::for_job(const std::string& name) {
  if (!on_) return {};
  return [this, name](const ProgressEvent& e) {
    std::lock_guard lock(mu_);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(200)) return;
    last_ = now;
    std::string line = "\r" + name + ": " + std::string(e.stage);
    if (e.fraction >= 0.0) {
      line += ' ';
      line += format_fixed(100.0 * e.fraction, 0);
      line += " %";
    }
    if (e.best) line += "  best " + format_fixed(*e.best, decimals_);
    line += "  " + format_fixed(std::chrono::duration<double>(now - t0_).count(), 1) + " s      ";
    std::cerr << line << std::flush;
  };
}

void ProgressLine::done() {
  if (on_) std::cerr << "\r" << std::string(79, ' ') << "\r" << std::flush;
}

}  // namespace cutroute::cli
