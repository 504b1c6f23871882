// Runs `cutroute optimize` in a test: temporary folders, the program and report read back.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cutroute/io/nest_loader.hpp>

#include "support/common_program_check.hpp"
#include "support/files.hpp"
#include "support/paths.hpp"
#include "support/program_check.hpp"

namespace cutroute::test {

inline std::filesystem::path temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("cutroute-opt-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline bool sanitized() { return std::getenv("CUTROUTE_SANITIZED") != nullptr; }

struct OptRun {
  CommandOutput cmd;
  std::string program;
  nlohmann::json report;
};

// Writes dir/out.ngc and dir/out.json (1 s solver limit, 3 s under the sanitizers, unless given).
inline OptRun optimize(const std::string& dxf, const std::filesystem::path& dir, const std::string& extra = "",
                       const char* time_limit = nullptr) {
  OptRun r;
  const auto prog = dir / "out.ngc", rep = dir / "out.json";
  if (!time_limit) time_limit = sanitized() ? "3" : "1";
  r.cmd = run_command(cli_path() + " optimize " + dxf + " -o " + prog.string() + " --report " + rep.string() +
                      " --quiet --time-limit " + time_limit + " " + extra);
  if (r.cmd.exit_code == 0) {
    r.program = read_text(prog);
    r.report = nlohmann::json::parse(read_text(rep));
  }
  return r;
}

// The program re-parsed and checked against the nest (support/program_check.hpp): every contour
// once, one pierce per basic segment; the report agrees with the program. kerf_offset_mm: --kerf-mode cam.
inline void expect_admissible(const std::string& dxf, const OptRun& run, double kerf_offset_mm = 0.0,
                              ProgramCheck* result = nullptr, double on_contour_mm = 1e-3) {
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  ASSERT_TRUE(loaded.ok());
  // Controller kerf: cuts the compensation would refuse are written on their kerf offset, outside
  // G41/G42 (report: compensation.written_on_offset).
  const bool offset_cuts = run.report.contains("compensation") && run.report["compensation"].value("written_on_offset", 0) > 0;
  const double half_kerf = run.report.value("kerf_mm", 0.0) / 2;
  if (run.report["chosen"] == "common") {
    // Shared edges are cut once, so contours are cut in pieces: the common-line checker (every
    // boundary point cut, holes and shared lines first, pierces and leads in scrap). 0.01 mm: the
    // corpus' shared edges are drawn touching (within tol::kCommonLineMm), and a looser tolerance
    // would take edges that merely run close (cut twice) for common lines. Without the group
    // rule: DRAAK's contours touch along stretches cut twice (see the checker); the order of
    // common lines before their group's outline is tested in tests/common_lines.
    // Cuts written on their offset pass a drawn point at kerf/2, and up to the deviation the report
    // gives where details finer than the kerf were straightened for the offset (d2g_DRAAK's
    // splines); where the kerf cannot reach (a cavity narrower than it), not at all.
    const double slack = offset_cuts ? half_kerf + run.report["compensation"].value("offset_deviation_mm", 0.0) : 0.0;
    const auto check = check_common_program(loaded->nest, run.program, 0.01 + slack, false, 0.0, offset_cuts ? half_kerf : 0.0);
    for (const auto& f : check.failures) ADD_FAILURE() << dxf << ": " << f;
    EXPECT_EQ(check.runs, run.report["basic_segments"].get<int>());
    EXPECT_EQ(run.report["pierces"].get<int>(), check.probe.pierces);
    EXPECT_NEAR(run.report["cut_length_mm"].get<double>(), check.probe.cut_length, 1e-6 * check.probe.cut_length + 1e-6);
    return;
  }
  ProgramCheckOptions opt;
  opt.clearance_mm = 1.0;  // kerf 0.15 + 1 mm for the default AMg3M 1 mm job
  opt.kerf_offset_mm = kerf_offset_mm;
  if (offset_cuts) opt.uncompensated_offset_mm = half_kerf;
  if (kerf_offset_mm > 0) opt.on_contour_mm = on_contour_mm;
  // Multi-segment cutting: a long contour in up to 8 pieces (--multi-pieces), covering it together.
  const bool multi = run.report["chosen"] == "multi";
  if (multi) opt.max_runs_per_contour = 8;
  const auto check = check_program(loaded->nest, run.program, opt);
  for (const auto& f : check.failures) ADD_FAILURE() << dxf << ": " << f;
  std::size_t cut_contours = 0;
  for (const auto& c : loaded->nest.contours) cut_contours += c.role != model::ContourRole::sheet;
  EXPECT_EQ(static_cast<std::size_t>(check.contours_cut), cut_contours);
  // One pierce per basic segment; a chain of k contours has k - 1 bridges; a contour cut in k pieces k runs.
  EXPECT_EQ(check.runs, run.report["basic_segments"].get<int>());
  std::size_t extra_pieces = 0;
  for (int r : check.runs_per_contour) extra_pieces += multi && r > 1 ? static_cast<std::size_t>(r - 1) : 0;
  EXPECT_EQ(static_cast<std::size_t>(check.runs + check.bridges), cut_contours + extra_pieces);
  if (!multi) {
    EXPECT_EQ(check.split_contours, 0);
  }
  if (run.report["chosen"] == "standard") {
    EXPECT_EQ(check.bridges, 0);
  }
  // The report agrees with the re-parsed program.
  EXPECT_EQ(run.report["pierces"].get<int>(), check.probe.pierces);
  EXPECT_NEAR(run.report["cut_length_mm"].get<double>(), check.cut_length, 1e-6 * check.cut_length + 1e-6);
  EXPECT_NEAR(run.report["rapid_length_mm"].get<double>(), check.rapid_length, 1e-6 * check.rapid_length + 1e-6);
  EXPECT_EQ(run.report["frames"].get<int>(), check.probe.frames);
  if (result) *result = check;
}

// Runs `optimize dxf` writing base.ngc, .svg, .html and .json with `args`, and returns what must
// be the same from run to run with the same seed: all four, the report without its wall times
// (timing_s, solver.time_s). "" after a failed run (reported as a test failure).
inline std::string reproducible_outputs(const std::string& dxf, const std::string& base, const std::string& args) {
  const auto r = run_command(cli_path() + " optimize " + dxf + " -o " + base + ".ngc --svg " + base + ".svg --html " + base +
                             ".html --report " + base + ".json --quiet " + args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  if (r.exit_code != 0) return {};
  auto rep = nlohmann::json::parse(read_text(base + ".json"));
  rep.erase("timing_s");
  rep["solver"].erase("time_s");
  return read_text(base + ".ngc") + read_text(base + ".svg") + read_text(base + ".html") + rep.dump();
}

// The generic dialect with 4 decimals (0.1 µm), written to `dir`: with 3 the written end points
// and arc centres (I, J) are rounded by up to 0.7 µm each, too coarse to measure kerf/2 ± 1 µm.
inline std::string fine_dialect(const std::filesystem::path& dir) {
  auto j = nlohmann::json::parse(read_text(test_data("../../data/dialects/generic.json")));
  j["name"] = "generic-0.1um";
  j["decimals"] = 4;
  const auto path = dir / "generic4.json";
  std::ofstream(path) << j.dump(2);
  return path.string();
}

// LinuxCNC's interpreter (package linuxcnc-uspace) accepts the program; nothing to check without it.
inline void expect_rs274_accepts(const std::filesystem::path& program) {
  if (std::system("command -v rs274 >/dev/null 2>&1") != 0) return;
  const auto rs = run_rs274(program.string());
  EXPECT_EQ(rs.exit_code, 0) << program << ": " << rs.out;
}

// The stems of every DXF file of ../shared/data/dxf, sorted.
inline std::vector<std::string> corpus() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(shared("data/dxf"))) {
    if (e.path().extension() == ".dxf") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace cutroute::test
