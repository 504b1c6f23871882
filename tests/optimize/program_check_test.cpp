// The program checker of the tests (support/program_check.hpp) on hand-written programs for two
// parts drawn edge to edge: it passes a right program and names each fault of a wrong one, even
// where a cut on the shared edge lies on both parts.
#include <gtest/gtest.h>

#include <string>

#include <cutroute/geometry/shapes.hpp>
#include <cutroute/model/nest.hpp>

#include "support/program_check.hpp"

namespace cutroute::test {
namespace {

model::Nest two_squares() {
  std::vector<model::SourceContour> in(2);
  in[0].contour = geometry::polygon({{10, 10}, {30, 10}, {30, 30}, {10, 30}});
  in[1].contour = geometry::polygon({{30, 10}, {50, 10}, {50, 30}, {30, 30}});
  return model::build_nest(std::move(in), model::NestOptions{});
}

// Each part from a lead-in in scrap below it, whole, counter-clockwise.
const std::string kCutA = "G0 X10 Y5\nM3\nG1 X10 Y10\nG1 X30 Y10\nG1 X30 Y30\nG1 X10 Y30\nG1 X10 Y10\nM5\n";
const std::string kCutB = "G0 X50 Y5\nM3\nG1 X50 Y10\nG1 X50 Y30\nG1 X30 Y30\nG1 X30 Y10\nG1 X50 Y10\nM5\n";

ProgramCheck check(const std::string& body) {
  return check_program(two_squares(), "G21 G90\n" + body + "M30\n", ProgramCheckOptions{});
}

bool names(const ProgramCheck& c, const std::string& what) {
  for (const auto& f : c.failures)
    if (f.find(what) != std::string::npos) return true;
  return false;
}

TEST(ProgramCheck, PartsDrawnEdgeToEdge) {
  const ProgramCheck right = check(kCutA + kCutB);
  for (const auto& f : right.failures) ADD_FAILURE() << f;
  EXPECT_EQ(right.contours_cut, 2);
  EXPECT_EQ(right.runs, 2);
  // B left out: A's cut runs along B's left side, and still B is not cut.
  EXPECT_TRUE(names(check(kCutA), "contour 2 (outer, length 80) is never cut"));
  // B cut without its bottom side; its shared side is cut twice, by A and by B.
  const std::string b_open = "G0 X50 Y5\nM3\nG1 X50 Y10\nG1 X50 Y30\nG1 X30 Y30\nG1 X30 Y10\nM5\n";
  EXPECT_TRUE(names(check(kCutA + b_open), "contour 2 (outer, length 80) is cut only over 60"));
  // A cut twice.
  EXPECT_TRUE(names(check(kCutA + kCutA + kCutB), "contour 1 (outer, length 80) is cut in 2 runs"));
  // A run along the shared side alone, after both parts were cut: a third run on the edge.
  const std::string edge = "G0 X30 Y5\nM3\nG1 X30 Y10\nG1 X30 Y30\nM5\n";
  const ProgramCheck extra = check(kCutA + kCutB + edge);
  EXPECT_TRUE(names(extra, "is cut in 2 runs") && names(extra, "twice?")) << ::testing::PrintToString(extra.failures);
}

}  // namespace
}  // namespace cutroute::test
