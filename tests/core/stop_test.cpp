#include <gtest/gtest.h>

#include <thread>

#include <cutroute/core/stop.hpp>

namespace cutroute {
namespace {

TEST(StopToken, CancelIsSharedWithDerivedTokens) {
  StopToken root;
  StopToken limited = root.with_time_limit(1000);
  EXPECT_FALSE(limited.stop_requested());
  root.request_stop();
  EXPECT_TRUE(limited.stop_requested());
}

TEST(StopToken, DeadlinePasses) {
  StopToken t = StopToken{}.with_time_limit(0.0);
  EXPECT_TRUE(t.deadline_passed());
  StopToken none;
  EXPECT_FALSE(none.deadline_passed());
  EXPECT_GT(none.seconds_left(), 1e300);
}

TEST(StopToken, TargetReached) {
  StopToken t = StopToken{}.with_target(100);
  EXPECT_TRUE(t.target_reached(100));
  EXPECT_FALSE(t.target_reached(101));
}

}  // namespace
}  // namespace cutroute
