// `cutroute gtsp`: JSON output, optimal status on small files, exit 2 with a line number on bad files.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/paths.hpp"

namespace cutroute {
namespace {

std::string instances_dir() { return std::string(CUTROUTE_INSTANCES_DIR) + "/"; }

TEST(CliGtsp, JsonForTinyPcglns) {
  const auto r = test::run_command(test::cli_path() + " gtsp " + instances_dir() + "tiny.pcglns --json --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["objective"], 15);
  EXPECT_EQ(j["status"], "optimal");
  EXPECT_EQ(j["lower_bound"], 15);
  ASSERT_EQ(j["tour"].size(), 4u);
  EXPECT_EQ(j["tour"][0], 3);  // node 3 is the only node of start group 2
  EXPECT_TRUE(j["time_s"].is_number());
}

TEST(CliGtsp, HeuristicOnAGtsplibFile) {
  const auto r = test::run_command(test::cli_path() + " gtsp " + test::shared("data/gtsplib/20kroA100.gtsp") +
                                   " --solver heuristic --threads 2 --seed 1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["status"], "feasible");
  EXPECT_GE(j["objective"].get<long>(), 9711);  // best known (optimal) value
  EXPECT_EQ(j["tour"].size(), 20u);
}

// The stacker-crane AGTSP where the route search alone stalled at 633-639 in 0.3 s: with the
// node-set start, default settings reach the optimum (seeded: no clock involved).
TEST(CliGtsp, NodeSetStartSolves89rbg443) {
  const auto r = test::run_command(test::cli_path() + " gtsp " + test::shared("data/gtsplib/89rbg443.gtsp") +
                                   " --threads 2 --seed 1 --time-limit 0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["objective"].get<long>(), 632);
  EXPECT_EQ(j["tour"].size(), 89u);
}

TEST(CliGtsp, MalformedFileExitsTwoWithLine) {
  const auto path = std::filesystem::temp_directory_path() / "cutroute_bad_instance.gtsp";
  std::ofstream(path) << "NAME : b\nTYPE : GTSP\nDIMENSION : 2\nGTSP_SETS : 1\nEDGE_WEIGHT_TYPE : EUC_2D\n"
                         "NODE_COORD_SECTION\n1 0 0\n2 zero 0\n";
  const auto r = test::run_command(test::cli_path() + " gtsp " + path.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(path.string() + ":8: error:"), std::string::npos) << r.err;
  std::filesystem::remove(path);
}

TEST(CliGtsp, TextOutput) {
  const auto r = test::run_command(test::cli_path() + " gtsp " + instances_dir() + "tiny.sop");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("objective: 14"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("status:    optimal"), std::string::npos) << r.out;
}

// A heuristic route with a bound: the text names the gap, recomputed here from the two figures.
TEST(CliGtsp, TextOutputGivesTheGapToTheBound) {
  const auto r = test::run_command(test::cli_path() + " gtsp " + test::shared("data/sop/ry48p.1.sop") +
                                   " --threads 2 --seed 1 --time-limit 0 --work-limit 0.05");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto number_after = [&](const std::string& label) {
    const auto at = r.out.find(label);
    EXPECT_NE(at, std::string::npos) << r.out;
    return at == std::string::npos ? 0L : std::stol(r.out.substr(at + label.size()));
  };
  const long objective = number_after("objective: "), bound = number_after("lower bound: ");
  ASSERT_GT(objective, bound) << r.out;
  ASSERT_GT(bound, 0) << r.out;
  char gap[32];
  std::snprintf(gap, sizeof gap, "%.2f", 100.0 * static_cast<double>(objective - bound) / static_cast<double>(objective));
  std::string text = gap;
  while (text.back() == '0') text.pop_back();  // format_fixed drops trailing zeros
  if (text.back() == '.') text.pop_back();
  EXPECT_NE(r.out.find("lower bound: " + std::to_string(bound) + " (gap " + text + " % of the objective)"), std::string::npos)
      << r.out;
}

// --work-limit: the heuristic stops once that much work is done (millions of units: iterations x
// nodes x (1 + smallest cluster) / 2, prob.100: 100 per iteration), to the iteration, whatever
// the machine's speed: the same seed gives the same tour.
TEST(CliGtsp, WorkLimitIsExactAndReproducible) {
  const std::string cmd = test::cli_path() + " gtsp " + test::shared("data/sop/prob.100.sop") +
                          " --threads 2 --seed 4 --time-limit 0 --work-limit 0.05 --json";
  const auto a = test::run_command(cmd), b = test::run_command(cmd);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  EXPECT_EQ(ja["iterations"], 500);  // 50 000 units / 100 per iteration, 250 per thread
  EXPECT_DOUBLE_EQ(ja["work_m"].get<double>(), 0.05);
  EXPECT_EQ(ja["tour"], jb["tour"]);
  EXPECT_EQ(ja["objective"], jb["objective"]);
  EXPECT_EQ(test::run_command(test::cli_path() + " gtsp " + instances_dir() + "tiny.sop --work-limit nan").exit_code, 1);
}

// On a terminal (script(1) from bsdutils, part of every Debian system, gives the command one) the
// best cost so far is shown on a line rewritten in place; not with --quiet, never into a pipe.
TEST(CliGtsp, ProgressOnATerminalOnly) {
  ASSERT_EQ(std::system("command -v script >/dev/null 2>&1"), 0) << "script(1) (bsdutils) is missing";
  const std::string cmd = test::cli_path() + " gtsp " + test::shared("data/sop/prob.100.sop") + " --threads 1 --time-limit 1";
  const auto tty = test::run_command("script -qec '" + cmd + "' /dev/null");
  ASSERT_EQ(tty.exit_code, 0) << tty.out << tty.err;
  EXPECT_NE(tty.out.find("\rprob.100.sop: heuristic  best "), std::string::npos) << tty.out;
  EXPECT_NE(tty.out.find("objective: "), std::string::npos) << tty.out;
  const auto quiet = test::run_command("script -qec '" + cmd + " --quiet' /dev/null");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.out << quiet.err;
  EXPECT_EQ(quiet.out.find("heuristic  best"), std::string::npos) << quiet.out;
  const auto pipe = test::run_command(cmd);
  ASSERT_EQ(pipe.exit_code, 0) << pipe.err;
  EXPECT_TRUE(pipe.err.empty()) << pipe.err;
}

}  // namespace
}  // namespace cutroute
