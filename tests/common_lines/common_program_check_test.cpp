// check_common_program() itself: hand-written programs for two parts sharing an edge, each
// admissible or broken in exactly one way.
#include <gtest/gtest.h>

#include <string>

#include <cutroute/geometry/shapes.hpp>

#include "support/common_program_check.hpp"

namespace cutroute::test {
namespace {

model::Nest two_parts() {
  std::vector<model::SourceContour> in;
  for (const auto& b : {geometry::Box{0, 0, 100, 50}, geometry::Box{100, 0, 250, 50}})
    in.push_back(model::SourceContour{geometry::rectangle(b), "0", {}, {}, {}});
  model::NestOptions o;
  o.detect_sheet = false;
  return model::build_nest(std::move(in), o);
}

const std::string kTrail = "G0 X100 Y-5\nM3\nG1 X100 Y0\nG1 X100 Y50\nG1 X100 Y55\nM5\n";
const std::string kLoop = "G0 X-5 Y0\nM3\nG1 X0 Y0\nG1 X250 Y0\nG1 X250 Y50\nG1 X0 Y50\nG1 X0 Y0\nM5\n";

std::string program(const std::string& body) { return "G21\nG90\n" + body + "M30\n"; }

bool has(const CommonProgramCheck& c, const std::string& what) {
  for (const auto& f : c.failures)
    if (f.find(what) != std::string::npos) return true;
  return false;
}

TEST(CommonProgramCheck, TrailThenOutline) {
  const auto c = check_common_program(two_parts(), program(kTrail + kLoop), 0.005);
  EXPECT_TRUE(c.failures.empty()) << c.failures.front();
  EXPECT_EQ(c.runs, 2);
  EXPECT_NEAR(c.boundary_cut_mm, 2 * 250 + 2 * 50 + 50, 1e-9);
}

TEST(CommonProgramCheck, OutlineBeforeTrailFails) {
  EXPECT_TRUE(has(check_common_program(two_parts(), program(kLoop + kTrail), 0.005), "after the group's outer boundary"));
}

TEST(CommonProgramCheck, MissingCommonLineFails) {
  EXPECT_TRUE(has(check_common_program(two_parts(), program(kLoop), 0.005), "never cut"));
}

TEST(CommonProgramCheck, LeadThroughAPartFails) {
  const std::string bad_trail = "G0 X90 Y25\nM3\nG1 X100 Y25\nG1 X100 Y50\nM5\nG0 X100 Y-5\nM3\nG1 X100 Y0\nG1 X100 Y25\nM5\n";
  const auto c = check_common_program(two_parts(), program(bad_trail + kLoop), 0.005);
  EXPECT_TRUE(has(c, "pierce inside a part"));
  EXPECT_TRUE(has(c, "runs through a part"));
}

}  // namespace
}  // namespace cutroute::test
