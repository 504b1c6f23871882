// The reader against an independent count: ../shared/tools/gcode_stats.py (Python, written
// separately) on programs made by Debian's dxf2gcode and on our hand-written ones.
// Lengths within 0.01 %, pierce counts exact.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <cutroute/nc/gcode_reader.hpp>

#include "support/paths.hpp"

namespace cutroute::nc {
namespace {

// gcode_stats rounds its lengths to 0.001 mm; below ~10 mm that rounding exceeds 0.01 %.
bool close(double ours, double theirs) {
  return std::abs(ours - theirs) <= std::max(1e-4 * std::abs(theirs), 0.0005 + 1e-9);
}

nlohmann::json gcode_stats(const std::string& path) {
  const auto out = test::run_command("/usr/bin/python3 " + test::shared("tools/gcode_stats.py") +
                                     " --json '" + path + "'");
  EXPECT_EQ(out.exit_code, 0) << out.err;
  auto j = nlohmann::json::parse(out.out, nullptr, false);
  if (j.is_discarded() || !j.is_array() || j.empty()) {
    ADD_FAILURE() << "gcode_stats.py gave no JSON for " << path << ": " << out.out << out.err;
    return {};
  }
  return j[0];
}

void compare(const std::string& path) {
  SCOPED_TRACE(path);
  auto ours = read_gcode_file(path, ReadOptions{});
  ASSERT_TRUE(ours.ok()) << format(ours.error());
  const auto theirs = gcode_stats(path);
  ASSERT_TRUE(theirs.contains("Lon")) << theirs.dump();
  EXPECT_EQ(ours->pierces, theirs["pierces"].get<std::size_t>());
  EXPECT_PRED2(close, ours->cut_length_mm, theirs["Lon"].get<double>());
  EXPECT_PRED2(close, ours->rapid_length_mm, theirs["Loff_rapid"].get<double>());
  EXPECT_PRED2(close, ours->feed_off_length_mm, theirs["Loff_feed"].get<double>());
}

TEST(GcodeStatsCompare, Dxf2gcodePrograms) {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(test::test_data("nc/dxf2gcode")))
    if (e.path().extension() == ".ngc") files.push_back(e.path().string());
  ASSERT_GE(files.size(), 10u);
  for (const auto& f : files) compare(f);
}

// Hand-written programs whose conventions gcode_stats shares. Not compared: cutter_comp_misc.nc
// (gcode_stats executes the unknown G12 block) and m7m9_beam.nc (gcode_stats always treats M3
// as beam on); their hand-computed values are checked in gcode_reader_test.cpp.
TEST(GcodeStatsCompare, HandWrittenPrograms) {
  for (const char* f : {"square_abs_mm.nc", "square_inc_inch.nc", "arcs_ij.nc", "arcs_absolute_centre.nc",
                        "arcs_r.nc", "dwell_comments_crlf.nc", "beam_off_feed.nc"})
    compare(test::test_data(std::string("nc/") + f));
}

// Frames against a separate Python count of the docs/FRAMES.md rule (tests/nc/count_frames.py).
TEST(GcodeStatsCompare, FramesAgainstAnIndependentCount) {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(test::test_data("nc/dxf2gcode")))
    files.push_back(e.path().string());
  for (const char* f : {"square_abs_mm.nc", "square_inc_inch.nc", "arcs_ij.nc", "arcs_r.nc",
                        "dwell_comments_crlf.nc", "cutter_comp_misc.nc", "m7m9_beam.nc"})
    files.push_back(test::test_data(std::string("nc/") + f));
  for (const auto& f : files) {
    SCOPED_TRACE(f);
    const auto out = test::run_command("/usr/bin/python3 " + std::string(CUTROUTE_TEST_DATA_DIR) +
                                       "/../nc/count_frames.py '" + f + "'");
    ASSERT_EQ(out.exit_code, 0) << out.err;
    auto ours = read_gcode_file(f, ReadOptions{});
    ASSERT_TRUE(ours.ok());
    EXPECT_EQ(std::to_string(ours->frames) + "\n", out.out);
  }
}

}  // namespace
}  // namespace cutroute::nc
