// `cutroute optimize` end to end: the written program re-parsed and checked against the nest.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include <cutroute/io/nest_loader.hpp>

#include "support/files.hpp"
#include "support/paths.hpp"
#include "support/program_check.hpp"

namespace cutroute::test {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) { return fresh_temp_dir("opt", name); }

bool sanitized() { return std::getenv("CUTROUTE_SANITIZED") != nullptr; }

struct OptRun {
  CommandOutput cmd;
  std::string program;
  nlohmann::json report;
};

OptRun optimize(const std::string& dxf, const fs::path& dir, const std::string& extra = "") {
  OptRun r;
  const auto prog = dir / "out.ngc", rep = dir / "out.json";
  r.cmd = run_command(cli_path() + " optimize " + dxf + " -o " + prog.string() + " --report " + rep.string() +
                      " --quiet --time-limit " + (sanitized() ? "3" : "1") + " " + extra);
  if (r.cmd.exit_code == 0) {
    r.program = slurp(prog);
    r.report = nlohmann::json::parse(slurp(rep));
  }
  return r;
}

void expect_admissible(const std::string& dxf, const OptRun& run) {
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  ASSERT_TRUE(loaded.ok());
  ProgramCheckOptions opt;
  opt.clearance_mm = 1.0;  // kerf 0.15 + 1 mm for the default AMg3M 1 mm job
  const auto check = check_program(loaded->nest, run.program, opt);
  for (const auto& f : check.failures) ADD_FAILURE() << dxf << ": " << f;
  std::size_t cut_contours = 0;
  for (const auto& c : loaded->nest.contours) cut_contours += c.role != model::ContourRole::sheet;
  EXPECT_EQ(static_cast<std::size_t>(check.contours_cut), cut_contours);
  EXPECT_EQ(static_cast<std::size_t>(check.runs), cut_contours);  // one pierce per contour
  // The report agrees with the re-parsed program.
  EXPECT_EQ(run.report["pierces"].get<int>(), check.probe.pierces);
  EXPECT_NEAR(run.report["cut_length_mm"].get<double>(), check.cut_length, 1e-6 * check.cut_length + 1e-6);
  EXPECT_NEAR(run.report["rapid_length_mm"].get<double>(), check.rapid_length, 1e-6 * check.rapid_length + 1e-6);
  EXPECT_EQ(run.report["frames"].get<int>(), check.probe.frames);
}

TEST(OptimizeCli, DemoSheetProgramIsAdmissibleAndReportIsHonest) {
  const auto dir = temp_dir("demo");
  const auto dxf = (dir / "demo.dxf").string();
  ASSERT_EQ(run_command(cli_path() + " demo " + dxf).exit_code, 0);
  const OptRun run = optimize(dxf, dir);
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  expect_admissible(dxf, run);
  EXPECT_EQ(run.report["pierces"], 21);
  // eq. 10 from the report's own numbers: L_on / V_on*(n) + L_off / V_off + N_pt t_pt.
  const auto& r = run.report;
  const double t = r["cut_length_mm"].get<double>() / 1000 / r["v_on_m_s"].get<double>() +
                   r["rapid_length_mm"].get<double>() / 1000 / 1.0 + 21 * 0.3;
  EXPECT_NEAR(r["t_cut_s"].get<double>(), t, 1e-6);
  EXPECT_LT(r["v_on_m_s"].get<double>(), r["v_on_set_m_s"].get<double>());  // hundreds of frames: slower

  // The independent statistics script agrees (pierces exact, lengths within 0.01 %).
  const auto stats = run_command("python3 " + shared("tools/gcode_stats.py") + " --json " + (dir / "out.ngc").string());
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  const auto j = nlohmann::json::parse(stats.out)[0];
  EXPECT_EQ(j["pierces"], 21);
  EXPECT_EQ(j["precedence_violations"], 0);
  EXPECT_NEAR(j["Lon"].get<double>(), r["cut_length_mm"].get<double>(), 1e-4 * j["Lon"].get<double>());
  EXPECT_NEAR(j["Loff_rapid"].get<double>(), r["rapid_length_mm"].get<double>(), 1e-4 * j["Loff_rapid"].get<double>() + 1e-3);

  // LinuxCNC's interpreter accepts the program.
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    const auto rs = run_command("rs274 -g " + (dir / "out.ngc").string() + " < /dev/null");
    EXPECT_EQ(rs.exit_code, 0) << rs.out;
  }
  fs::remove_all(dir);
}

TEST(OptimizeCli, SameSeedSameBytes) {
  const auto dir = temp_dir("det");
  const auto dxf = (dir / "demo.dxf").string();
  ASSERT_EQ(run_command(cli_path() + " demo " + dxf).exit_code, 0);
  std::string outs[2];
  for (int i = 0; i < 2; ++i) {
    const auto base = (dir / ("run" + std::to_string(i))).string();
    const auto r = run_command(cli_path() + " optimize " + dxf + " -o " + base + ".ngc --svg " + base + ".svg --html " +
                               base + ".html --report " + base + ".json --quiet --seed 7 --threads 2");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto rep = nlohmann::json::parse(slurp(base + ".json"));
    rep.erase("timing_s");
    rep["solver"].erase("time_s");
    outs[i] = slurp(base + ".ngc") + slurp(base + ".svg") + slurp(base + ".html") + rep.dump();
  }
  EXPECT_EQ(outs[0], outs[1]);
  fs::remove_all(dir);
}

TEST(OptimizeCli, BadInputsFailCleanlyAndLeaveNothing) {
  const auto dir = temp_dir("bad");
  const auto dxf = (dir / "demo.dxf").string();
  ASSERT_EQ(run_command(cli_path() + " demo " + dxf).exit_code, 0);
  const auto prog = (dir / "p.ngc").string();
  auto r = run_command(cli_path() + " optimize " + dxf + " -o " + prog + " --material Unobtainium --quiet");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("Unobtainium"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("AMg3M"), std::string::npos) << r.err;  // lists what exists
  r = run_command(cli_path() + " optimize " + dxf + " -o " + prog + " --thickness 7 --quiet");
  EXPECT_EQ(r.exit_code, 2);
  r = run_command(cli_path() + " optimize " + dxf + " -o " + prog + " --dialect nosuch --quiet");
  EXPECT_EQ(r.exit_code, 2);
  r = run_command(cli_path() + " optimize " + dxf + " -o " + prog + " --start 1 --quiet");
  EXPECT_EQ(r.exit_code, 1);
  r = run_command(cli_path() + " optimize /nonexistent.dxf -o " + prog + " --quiet");
  EXPECT_EQ(r.exit_code, 2);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename(), "demo.dxf") << "left behind: " << e.path();
  fs::remove_all(dir);
}

TEST(OptimizeCli, SeveralNestsInParallelEachToItsOwnOutputs) {
  const auto dir = temp_dir("batch");
  const auto a = (dir / "a.dxf").string(), b = (dir / "b.dxf").string();
  ASSERT_EQ(run_command(cli_path() + " demo " + a).exit_code, 0);
  fs::copy_file(a, b);
  const auto out = dir / "out";
  const auto r = run_command(cli_path() + " optimize " + a + " " + b + " -o " + out.string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* stem : {"a", "b"}) {
    for (const char* ext : {".ngc", ".json", ".svg", ".html"}) {
      EXPECT_TRUE(fs::exists(out / (std::string(stem) + ext))) << stem << ext;
    }
  }
  fs::remove_all(dir);
}

// Every drawing of the shared corpus: the program cuts every closed contour exactly once, holes
// and inner parts first, leads clear of other contours.
class CorpusOptimize : public ::testing::TestWithParam<std::string> {};

// Drawings whose contours really overlap (measured depth above the curve tolerance): the default
// refuses them naming the pair; --allow-crossing cuts them, each contour once.
const std::map<std::string, std::string> kOverlapping = {
    {"d2g_pumpenteile", "a milling drawing: pocket outlines drawn over the rings, 0.45 mm deep"},
    {"deepnestsharp_ReadMeExampleSmall", "DeepNest placed parts up to ~0.2 mm into each other"},
};

TEST_P(CorpusOptimize, ProgramIsAdmissible) {
  const std::string dxf = shared("data/dxf/" + GetParam() + ".dxf");
  const auto dir = temp_dir(GetParam());
  std::string extra;
  if (kOverlapping.count(GetParam())) {
    const OptRun refused = optimize(dxf, dir);
    EXPECT_EQ(refused.cmd.exit_code, 2) << kOverlapping.at(GetParam());
    EXPECT_NE(refused.cmd.err.find("cross or overlap"), std::string::npos) << refused.cmd.err;
    EXPECT_NE(refused.cmd.err.find("--allow-crossing"), std::string::npos) << refused.cmd.err;
    extra = "--allow-crossing";
  }
  const OptRun run = optimize(dxf, dir, extra);
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  expect_admissible(dxf, run);
  fs::remove_all(dir);
}

std::vector<std::string> corpus() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(shared("data/dxf"))) {
    if (e.path().extension() == ".dxf") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(AllFiles, CorpusOptimize, ::testing::ValuesIn(corpus()),
                         [](const auto& param_info) {
                           std::string n = param_info.param;
                           for (char& c : n) if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

}  // namespace
}  // namespace cutroute::test
