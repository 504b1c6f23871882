#include <cutroute/core/stop.hpp>

#include <limits>

namespace cutroute {

StopToken StopToken::with_time_limit(double seconds) const {
  StopToken t = *this;
  const auto d = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  t.deadline_ = deadline_ ? std::min(*deadline_, d) : d;
  return t;
}

StopToken StopToken::with_target(std::int64_t target_cost) const {
  StopToken t = *this;
  t.target_ = target_cost;
  return t;
}

double StopToken::seconds_left() const {
  if (!deadline_) return std::numeric_limits<double>::infinity();
  return std::chrono::duration<double>(*deadline_ - Clock::now()).count();
}

StopToken& StopToken::global() {
  static StopToken token;
  return token;
}

}  // namespace cutroute
