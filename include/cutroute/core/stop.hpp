// StopToken (deadline + cancel flag + target cost) and Progress reporting for long runs.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

namespace cutroute {

class StopToken {
 public:
  using Clock = std::chrono::steady_clock;

  StopToken() : cancel_(std::make_shared<std::atomic<bool>>(false)) {}

  // A token sharing this one's cancel flag, with its own deadline `seconds` from now
  // (the earlier of the two when this token already has one).
  StopToken with_time_limit(double seconds) const;
  StopToken with_target(std::int64_t target_cost) const;

  void request_stop() const { cancel_->store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancel_->load(std::memory_order_relaxed); }
  bool deadline_passed() const { return deadline_ && Clock::now() >= *deadline_; }
  bool stop_requested() const { return cancelled() || deadline_passed(); }
  bool target_reached(std::int64_t cost) const { return target_ && cost <= *target_; }
  std::optional<Clock::time_point> deadline() const { return deadline_; }
  double seconds_left() const;  // +inf without a deadline

  // The process-wide token that SIGINT/SIGTERM cancel (installed by the CLI).
  static StopToken& global();

 private:
  std::shared_ptr<std::atomic<bool>> cancel_;
  std::optional<Clock::time_point> deadline_;
  std::optional<std::int64_t> target_;
};

// Progress callback: stage name, fraction done in [0,1] (negative when unknown),
// best objective so far (when there is one). Must be cheap and thread-safe.
struct ProgressEvent {
  std::string_view stage;
  double fraction = -1.0;
  std::optional<double> best;
};
using ProgressFn = std::function<void(const ProgressEvent&)>;

}  // namespace cutroute
