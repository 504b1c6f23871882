// `cutroute machining` end to end: the worked examples, outputs, bad input (exit 2), infeasible (exit 0).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "examples.hpp"
#include "support/paths.hpp"

namespace cutroute::machining {
namespace {

using nlohmann::json;

test::CommandOutput run(const std::string& args) {
  return test::run_command(test::cli_path() + " machining " + args);
}

TEST(MachiningCli, WorkedExamplesReproduceTheOptimum) {
  const struct {
    const char* file;
    double vc, f, ct;
    const char* active;
  } cases[] = {{test::kE1, 332.44714, 0.1431084, 1.2497633, "roughness"},
               {test::kE2, 286.89815, 0.1967386, 1.2388572, "accuracy"},
               {test::kE3, 143.44518, 0.4918536, 1.1866075, "power"}};
  for (const auto& c : cases) {
    const auto r = run(test::machining_example_path(c.file) + " --json");
    ASSERT_EQ(r.exit_code, 0) << c.file << "\n" << r.err;
    const json j = json::parse(r.out);
    EXPECT_NEAR(j["vc_m_min"].get<double>() / c.vc, 1.0, 1e-5) << c.file;
    EXPECT_NEAR(j["f_mm_rev"].get<double>() / c.f, 1.0, 1e-5) << c.file;
    EXPECT_NEAR(j["cost"]["total_cu"].get<double>() / c.ct, 1.0, 1e-7) << c.file;
    const auto active = j["active"].get<std::vector<std::string>>();
    EXPECT_NE(std::find(active.begin(), active.end(), c.active), active.end()) << c.file;
  }
}

TEST(MachiningCli, WritesSvgAndCsv) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("cutroute-machining-cli-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto svg = (dir / "e2.svg").string(), csv = (dir / "e2.csv").string();
  const auto r = run(test::machining_example_path(test::kE2) + " --svg " + svg + " --csv " + csv);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("status: optimal"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ACTIVE"), std::string::npos);
  ASSERT_TRUE(std::filesystem::exists(svg));
  ASSERT_TRUE(std::filesystem::exists(csv));
  std::ifstream s(svg);
  std::string first;
  std::getline(s, first);
  EXPECT_EQ(first.rfind("<svg", 0), 0u);
  EXPECT_GT(std::filesystem::file_size(csv), 241u * 241u * 40u);
  // One file named twice (found by fuzzing, session 39): the CSV silently replaced the picture.
  const auto same = run(test::machining_example_path(test::kE2) + " --svg " + svg + " --csv " + (dir / "." / "e2.svg").string());
  EXPECT_EQ(same.exit_code, 1);
  EXPECT_NE(same.err.find("--svg and --csv name the same output"), std::string::npos) << same.err;
  std::filesystem::remove_all(dir);
}

TEST(MachiningCli, BadInputExitsTwoNamingTheField) {
  const struct {
    const char* file;
    const char* field;
  } cases[] = {{"bad-missing-field.json", "operation.D"},
               {"bad-negative-length.json", "operation.L"},
               {"bad-fmin-gt-fmax.json", "search.f_min"},
               {"bad-unknown-model.json", "tool_life.model"},
               {"bad-syntax.json", "bad-syntax.json:3"}};
  for (const auto& c : cases) {
    const auto r = run(test::test_data(std::string("machining/") + c.file) + " --json");
    EXPECT_EQ(r.exit_code, 2) << c.file;
    EXPECT_NE(r.err.find(c.field), std::string::npos) << c.file << ": " << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  const auto missing = run("/nonexistent/problem.json");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(run("").exit_code, 1);  // usage error: no problem file
}

TEST(MachiningCli, InfeasibleIsAnAnswer) {
  const auto r = run(test::test_data("machining/infeasible-E2-tight-accuracy.json") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["status"], "infeasible");
  EXPECT_EQ(j["infeasible"]["least_violated"], "accuracy");
  EXPECT_FALSE(j["infeasible"]["suggestions"].empty());
}

// The transitions' pictures were written one by one: where the second could not be written (here
// its name is taken by a folder), the first was left behind for a run that failed (exit 2).
TEST(MachiningCli, TransitionsWriteTheirFilesAllOrNone) {
  const auto dir = std::filesystem::temp_directory_path() / ("cutroute-machining-all-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "map.t2.svg");
  const auto r = run(test::machining_example_path("boring-two-transitions-E2-E1.json") + " --no-fig5 --svg " +
                     (dir / "map.svg").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "map.t1.svg"));
  std::filesystem::remove(dir / "map.t2.svg");
  const auto ok = run(test::machining_example_path("boring-two-transitions-E2-E1.json") + " --no-fig5 --svg " +
                      (dir / "map.svg").string());
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "map.t1.svg"));
  EXPECT_TRUE(std::filesystem::exists(dir / "map.t2.svg"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cutroute::machining

namespace cutroute::machining {
namespace {

TEST(MachiningCli, TransitionsSumTheirCost) {
  const auto r = run(test::machining_example_path("boring-two-transitions-E2-E1.json") + " --json --no-fig5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["transitions"].size(), 2u);
  const double a = j["transitions"][0]["cost"]["total_cu"].get<double>();
  const double b = j["transitions"][1]["cost"]["total_cu"].get<double>();
  EXPECT_NEAR(j["total_cost_cu"].get<double>(), a + b, 1e-15);
  EXPECT_NEAR(a, 1.2388572, 1.2388572 * 1e-7);  // E2 as it stands
  EXPECT_NEAR(b, 1.2497633 - 1.1, 1e-7);        // E1 without the fixed share
  EXPECT_NEAR(j["transitions"][1]["vc_m_min"].get<double>() / 332.44714, 1.0, 1e-5);
}

}  // namespace
}  // namespace cutroute::machining
