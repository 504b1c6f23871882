// `cutroute optimize` on nests of parts sharing edges: the written program re-parsed and checked
// (every edge cut, every part separated, holes first, shared stretches before the group's outline).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include <cutroute/geometry/shapes.hpp>
#include <cutroute/io/nest_loader.hpp>

#include "support/common_program_check.hpp"
#include "support/dxf_builder.hpp"
#include "support/files.hpp"
#include "support/paths.hpp"

namespace cutroute::test {
namespace {

namespace fs = std::filesystem;
using geometry::Vec2;
using geometry::Vertex;

struct Layout {
  std::string dxf;
  double perimeters = 0;  // sum over every drawn contour [mm]
  double shared = 0;      // length of the stretches two parts share [mm]
};

// cols x rows rectangles of w x h drawn touching on a 1000 x 600 sheet, each with a round hole
// of radius r (none when r = 0). Shared length: (cols - 1) * rows * h + (rows - 1) * cols * w.
// With `lines` each rectangle is four LINE entities, so a shared edge is drawn once per part.
Layout grid(const fs::path& dir, int cols, int rows, double w, double h, double r, bool lines = false) {
  DxfBuilder b;
  b.insunits(4);
  b.lwpolyline({Vertex{{0, 0}, 0}, Vertex{{1000, 0}, 0}, Vertex{{1000, 600}, 0}, Vertex{{0, 600}, 0}}, true, "SHEET");
  Layout l;
  const Vec2 o{100, 100};
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const double x = o.x + i * w, y = o.y + j * h;
      if (lines) {
        const Vec2 c[4] = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
        for (int k = 0; k < 4; ++k) b.line(c[k], c[(k + 1) % 4], "PARTS");
      } else {
        b.lwpolyline({Vertex{{x, y}, 0}, Vertex{{x + w, y}, 0}, Vertex{{x + w, y + h}, 0}, Vertex{{x, y + h}, 0}}, true,
                     "PARTS");
      }
      l.perimeters += 2 * (w + h);
      if (r > 0) {
        b.circle({x + w / 2, y + h / 2}, r, "PARTS");
        l.perimeters += 2 * std::numbers::pi * r;
      }
    }
  l.shared = (cols - 1) * rows * h + (rows - 1) * cols * w;
  l.dxf = (dir / "grid.dxf").string();
  std::ofstream(l.dxf) << b.str();
  return l;
}

struct OptRun {
  CommandOutput cmd;
  std::string program;
};

OptRun optimize(const std::string& dxf, const fs::path& dir, const std::string& extra) {
  OptRun r;
  const auto prog = dir / "out.ngc";
  const std::string limit = extra.find("--time-limit") == std::string::npos ? " --time-limit 1 " : " ";
  r.cmd = run_command(cli_path() + " optimize " + dxf + " -o " + prog.string() + " --quiet" + limit + extra);
  if (r.cmd.exit_code == 0) r.program = read_text(prog);
  return r;
}

model::Nest load(const std::string& dxf) {
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  EXPECT_TRUE(loaded.ok());
  return loaded->nest;
}

// Runs `optimize` and checks the written program against the nest; every failure is reported.
CommonProgramCheck optimize_and_check(const std::string& dxf, const fs::path& dir, const std::string& extra,
                                      double on_mm, std::string* program = nullptr) {
  const OptRun run = optimize(dxf, dir, extra);
  EXPECT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  if (program) *program = run.program;
  auto check = check_common_program(load(dxf), run.program, on_mm);
  for (const auto& f : check.failures) ADD_FAILURE() << f;
  return check;
}

// Today's standard technique on the same nest, as the baseline: each part's outline cut whole,
// so the shared edges are cut twice and the boundary cut length is the sum of the perimeters.
TEST(CommonOptimize, StandardCutsSharedEdgesTwice) {
  const auto dir = fresh_temp_dir("common-standard");
  const Layout l = grid(dir, 3, 2, 120, 80, 15);
  const auto check = optimize_and_check(l.dxf, dir, "--technique standard", 0.005);
  EXPECT_NEAR(check.boundary_cut_mm, l.perimeters, 0.01);
  EXPECT_EQ(check.runs, 12);
  std::filesystem::remove_all(dir);
}

// Blocks that switch the controller's kerf compensation on (G41 / G42).
int compensated_runs(const std::string& program) {
  int n = 0;
  std::istringstream in(program);
  for (std::string line; std::getline(in, line);)
    n += line.find("G41") != std::string::npos || line.find("G42") != std::string::npos;
  return n;
}

// 3 x 2 parts with a hole each, drawn touching: the cut along part boundaries drops by exactly the
// shared length, every edge is still cut, every part separated, holes and common lines first.
TEST(CommonOptimize, CommonCutsSharedEdgesOnce) {
  const auto dir = fresh_temp_dir("common-common");
  const Layout l = grid(dir, 3, 2, 120, 80, 15);
  std::string program;
  const auto rep = dir / "out.json";
  const auto check = optimize_and_check(l.dxf, dir, "--technique common --report " + rep.string(), 0.005, &program);
  const auto report = nlohmann::json::parse(read_text(rep));
  EXPECT_NEAR(l.shared, 2 * 160 + 360, 1e-9);  // two vertical lines through both rows, one horizontal
  // The report names every part a common line separates: the vertical lines 4 parts each (both
  // sides, both rows), the horizontal one all 6.
  std::vector<std::size_t> parts_per_line;
  for (const auto& e : report.at("sequence")) {
    if (!e.contains("pieces")) continue;
    bool only_common = true;
    for (const auto& k : e["pieces"]) only_common &= k == "common_edge" || k == "bridge";
    if (!only_common) continue;
    std::set<int> parts;
    for (const auto& p : e["parts"]) parts.insert(p.get<int>());
    EXPECT_EQ(parts.size(), e["parts"].size()) << e;  // each once
    parts_per_line.push_back(parts.size());
  }
  std::sort(parts_per_line.begin(), parts_per_line.end());
  EXPECT_EQ(parts_per_line, (std::vector<std::size_t>{4, 4, 6}));
  EXPECT_NEAR(check.boundary_cut_mm, l.perimeters - l.shared, 0.01);
  // 6 holes, the outline of the group, 2 vertical and 1 horizontal common line.
  EXPECT_EQ(check.runs, 6 + 1 + 3);
  EXPECT_EQ(check.pierces_on_a_cut, 0);
  // Common lines are centre lines: cut without compensation; everything else with it.
  EXPECT_EQ(compensated_runs(program), 6 + 1);
  std::filesystem::remove_all(dir);
}

// The parts in the middle of 6 x 6 touch no edge of the group's outline: the last common line
// around each cuts it free, so its hole must come before all of them, not only before the outline
// (the checker fails a hole finished after its part). Before, a short search cut 1 to 4 holes in
// freed parts, depending on the seed. Three seeds, three routes; then the standard technique.
TEST(CommonOptimize, HolesOfInnerPartsBeforeTheLinesAroundThem) {
  const auto dir = fresh_temp_dir("common-inner-holes");
  const Layout l = grid(dir, 6, 6, 20, 12, 3);
  for (const int seed : {1, 2, 3}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto check = optimize_and_check(
        l.dxf, dir, "--technique common --time-limit 0 --work-limit 0.05 --threads 1 --seed " + std::to_string(seed), 0.005);
    EXPECT_EQ(check.runs, 36 + 1 + 5 + 5);  // holes, the outline, 5 vertical and 5 horizontal lines
  }
  // The standard technique cuts each part whole, but its neighbours' cuts free a middle part
  // before its own (the shared edges are cut twice): its hole comes before them as well. The
  // check's group rule is for common lines only. Seeds 1-8 on 2 threads: seed 7 cut a hole in a
  // free part before.
  for (const int seed : {1, 2, 3, 4, 5, 6, 7, 8}) {
    SCOPED_TRACE("standard, seed " + std::to_string(seed));
    const OptRun run = optimize(l.dxf, dir, "--technique standard --time-limit 0 --work-limit 0.05 --threads 2 --seed " + std::to_string(seed));
    ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
    const auto check = check_common_program(load(l.dxf), run.program, 0.005, false);
    for (const auto& f : check.failures) ADD_FAILURE() << f;
    EXPECT_EQ(check.runs, 36 + 36);
  }
  std::filesystem::remove_all(dir);
}

// Parts drawn edge to edge with LINE entities draw each shared edge twice, once per part. Every
// part is read closed from its own lines (before, the second copy was dropped as a duplicate and
// one part of each pair left open, uncut), and both techniques cut every part and hole.
TEST(CommonOptimize, PartsDrawnWithLinesEdgeToEdge) {
  const auto dir = fresh_temp_dir("common-lines-drawn");
  const Layout l = grid(dir, 4, 3, 20, 12, 3, true);
  const model::Nest nest = load(l.dxf);
  std::size_t outers = 0, holes = 0;
  for (const auto& c : nest.contours) {
    outers += c.role == model::ContourRole::outer;
    holes += c.role == model::ContourRole::hole;
  }
  EXPECT_EQ(outers, 12u);
  EXPECT_EQ(holes, 12u);
  const auto common = optimize_and_check(l.dxf, dir, "--technique common --time-limit 0 --work-limit 0.05 --threads 1", 0.005);
  EXPECT_NEAR(common.boundary_cut_mm, l.perimeters - l.shared, 0.01);
  EXPECT_EQ(common.runs, 12 + 1 + 3 + 2);  // holes, the outline, 3 vertical and 2 horizontal lines
  const OptRun standard = optimize(l.dxf, dir, "--technique standard --time-limit 0 --work-limit 0.05 --threads 1");
  ASSERT_EQ(standard.cmd.exit_code, 0) << standard.cmd.err;
  const auto check = check_common_program(nest, standard.program, 0.005, false);
  for (const auto& f : check.failures) ADD_FAILURE() << f;
  EXPECT_EQ(check.runs, 12 + 12);
  std::filesystem::remove_all(dir);
}

// With the technique chosen automatically both alternatives are reported and the faster one is
// kept; on this grid that is common-line cutting (less cut, fewer pierces).
TEST(CommonOptimize, AutoReportsAlternativesAndKeepsTheFaster) {
  const auto dir = fresh_temp_dir("common-auto");
  const Layout l = grid(dir, 3, 2, 120, 80, 15);
  const auto rep = dir / "out.json";
  const auto check = optimize_and_check(l.dxf, dir, "--report " + rep.string(), 0.005);
  EXPECT_NEAR(check.boundary_cut_mm, l.perimeters - l.shared, 0.01);
  const auto report = nlohmann::json::parse(read_text(rep));
  const nlohmann::json* standard = nullptr;
  const nlohmann::json* common = nullptr;
  double best = 1e300;
  std::string best_name;
  for (const auto& a : report.at("alternatives")) {
    if (!a.value("available", true)) continue;
    if (a.at("name") == "standard") standard = &a;
    if (a.at("name") == "common") common = &a;
    if (a.at("t_cut_s").get<double>() < best) {
      best = a.at("t_cut_s").get<double>();
      best_name = a.at("name").get<std::string>();
    }
  }
  ASSERT_TRUE(standard && common);
  EXPECT_EQ(standard->at("pierces").get<int>(), 12);
  EXPECT_EQ(common->at("pierces").get<int>(), 10);
  EXPECT_EQ(common->at("basic_segments").get<int>(), 10);
  // L_on includes leads, whose number changes with the pierces: 2 lead pairs fewer here.
  EXPECT_LT(common->at("cut_length_mm").get<double>(), standard->at("cut_length_mm").get<double>() - l.shared + 1.0);
  EXPECT_EQ(report.at("chosen"), best_name);
  EXPECT_EQ(best_name, "common");
  std::filesystem::remove_all(dir);
}

// The order rules (heat, tip-up, sheet rigidity) with common lines: each common line counts as
// every part it runs along. The program stays admissible (every edge, holes and common lines
// first), the rules' search never makes the route's price under them worse, the same bytes twice.
TEST(CommonOptimize, OrderRulesKeepTheProgramAdmissible) {
  const auto dir = fresh_temp_dir("common-rules");
  const Layout l = grid(dir, 3, 2, 120, 80, 15);
  const auto rep = dir / "out.json";
  const std::string rules = "--technique common --heat-distance 30 --sheet-clamp left --avoid-tip-up --threads 1 --report " + rep.string();
  std::string first, second;
  const auto check = optimize_and_check(l.dxf, dir, rules, 0.005, &first);
  EXPECT_NEAR(check.boundary_cut_mm, l.perimeters - l.shared, 0.01);
  EXPECT_EQ(check.runs, 6 + 1 + 3);
  const auto report = nlohmann::json::parse(read_text(rep));
  EXPECT_EQ(report.at("chosen"), "common");
  const auto& r = report.at("rules");
  EXPECT_EQ(r.at("active"), nlohmann::json::array({"heat", "tip_up", "sheet_rigidity"}));
  EXPECT_GT(r.at("search").at("evaluations").get<int>(), 0);
  EXPECT_LE(r.at("search").at("final_s").get<double>(), r.at("search").at("solver_route_s").get<double>() + 1e-9);
  // A common line runs along two to six parts: cutting the next contour of any of them is "near".
  EXPECT_GT(r.at("search").at("solver_route").at("heat").at("consecutive_closer_than_d").get<int>(), 0);
  optimize_and_check(l.dxf, dir, rules, 0.005, &second);
  EXPECT_EQ(first, second);
  std::filesystem::remove_all(dir);
}

// The drawn contours (the sheet excluded, in nest order, as check_common_program() counts them):
// outer or not, and whose part.
struct DrawnContour {
  bool outer;
  int part;  // 1-based, as the report names parts
};
std::vector<DrawnContour> drawn_contours(const model::Nest& nest) {
  std::vector<DrawnContour> v;
  for (const auto& c : nest.contours)
    if (c.role != model::ContourRole::sheet) v.push_back({c.role == model::ContourRole::outer, c.part.value() + 1});
  return v;
}

// Micro-joints with common lines: each part is held to the skeleton by N gaps of width w on its own
// edges (its stretches of the group's outline, away from the junctions), never on a common line or
// a hole; the common lines are still cut whole and before the outline. Measured on the program.
TEST(CommonOptimize, TabsHoldEachPartByItsOwnEdges) {
  const auto dir = fresh_temp_dir("common-tabs");
  const Layout l = grid(dir, 3, 2, 120, 80, 15);
  const auto rep = dir / "out.json";
  const int n = 2;
  const double w = 2.0;
  const OptRun run = optimize(l.dxf, dir, "--technique common --tabs 2 --tab-width 2 --threads 1 --report " + rep.string());
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  const auto nest = load(l.dxf);
  const auto check = check_common_program(nest, run.program, 0.005, true, w);
  for (const auto& f : check.failures) ADD_FAILURE() << f;
  const auto contours = drawn_contours(nest);
  ASSERT_EQ(check.uncut.size(), contours.size());
  for (std::size_t k = 0; k < contours.size(); ++k) {
    if (!contours[k].outer) {
      EXPECT_TRUE(check.uncut[k].empty()) << "hole " << k;
      continue;
    }
    ASSERT_EQ(check.uncut[k].size(), static_cast<std::size_t>(n)) << "part " << contours[k].part;
    for (const double gap : check.uncut[k]) EXPECT_NEAR(gap, w, 0.05) << "part " << contours[k].part;
  }
  EXPECT_NEAR(check.boundary_cut_mm, l.perimeters - l.shared - 6 * n * w, 0.05);
  // 6 holes, 3 common lines and the outline, which resumes after each of the 12 gaps.
  EXPECT_EQ(check.runs, 6 + 3 + 1 + 6 * n);
  const auto report = nlohmann::json::parse(read_text(rep));
  const auto& tabs = report["rules"]["tabs"];
  EXPECT_EQ(tabs["contours"], 6);
  EXPECT_EQ(tabs["tabs"], 6 * n);
  EXPECT_EQ(tabs["contours_too_short"], 0);
  EXPECT_FALSE(tabs.contains("parts_without_skeleton_edge"));
  EXPECT_EQ(report["pierces"], check.runs);
  // The outline keeps the controller's compensation over its gaps (one G41/G42 for it), which
  // LinuxCNC, with the kerf as its tool, accepts; the common lines are cut without.
  EXPECT_EQ(compensated_runs(run.program), 6 + 1);
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    const auto rs = run_rs274((dir / "out.ngc").string(), report["kerf_mm"].get<double>());
    EXPECT_EQ(rs.exit_code, 0) << rs.out;
  }

  // Plasma: every cut after a gap enters from the scrap by a lead-in, none pierces the edge.
  const OptRun plasma = optimize(l.dxf, dir, "--technique common --tabs 2 --tab-width 2 --threads 1 --dialect plasma-thc "
                                             "--kerf 1.5 --report " + rep.string());
  ASSERT_EQ(plasma.cmd.exit_code, 0) << plasma.cmd.err;
  const auto pc = check_common_program(nest, plasma.program, 0.005, true, w);
  for (const auto& f : pc.failures) ADD_FAILURE() << "plasma: " << f;
  const auto preport = nlohmann::json::parse(read_text(rep));
  EXPECT_EQ(preport["rules"]["tabs"]["lead_ins"], 6 * n);
  EXPECT_EQ(preport["rules"]["tabs"]["resumed_on_path"], 0);
  EXPECT_EQ(pc.pierces_on_a_cut, 0);
  for (std::size_t k = 0; k < contours.size(); ++k)
    EXPECT_EQ(pc.uncut[k].size(), contours[k].outer ? static_cast<std::size_t>(n) : 0u) << "plasma, contour " << k;
  std::filesystem::remove_all(dir);
}

// A part whose whole outline is shared (the middle of 3 x 3 parts drawn touching) has no edge on
// the skeleton: it gets no tab, the report and a warning name it, its neighbours get theirs.
TEST(CommonOptimize, TabsNamePartsWithoutAnEdgeOnTheSkeleton) {
  const auto dir = fresh_temp_dir("common-tabs-enclosed");
  const Layout l = grid(dir, 3, 3, 100, 60, 0);
  const auto rep = dir / "out.json";
  const OptRun run = optimize(l.dxf, dir, "--technique common --tabs 1 --tab-width 2 --threads 1 --report " + rep.string());
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  const auto nest = load(l.dxf);
  const auto report = nlohmann::json::parse(read_text(rep));
  const auto& tabs = report["rules"]["tabs"];
  ASSERT_TRUE(tabs.contains("parts_without_skeleton_edge")) << tabs;
  ASSERT_EQ(tabs["parts_without_skeleton_edge"].size(), 1u);
  const int middle = tabs["parts_without_skeleton_edge"][0].get<int>();
  const auto centre = nest.contours[nest.parts[model::PartId(middle - 1)].outer].box.center();
  EXPECT_NEAR(centre.x, 100 + 150, 1e-9);
  EXPECT_NEAR(centre.y, 100 + 90, 1e-9);
  EXPECT_EQ(tabs["tabs"], 8);
  EXPECT_EQ(tabs["contours_too_short"], 1);
  bool warned = false;
  for (const auto& d : report["diagnostics"]) warned |= d.value("code", "") == "tabs.part_without_skeleton_edge";
  EXPECT_TRUE(warned) << report["diagnostics"];
  const auto check = check_common_program(nest, run.program, 0.005, true, 2.0);
  for (const auto& f : check.failures) ADD_FAILURE() << f;
  const auto contours = drawn_contours(nest);
  for (std::size_t k = 0; k < contours.size(); ++k)
    EXPECT_EQ(check.uncut[k].size(), contours[k].part == middle ? 0u : 1u) << "part " << contours[k].part;
  std::filesystem::remove_all(dir);
}

// The standard technique on parts drawn touching cuts every shared edge twice: a gap there is cut
// away by the neighbour's cut. Three gaps 53 mm apart round the middle one of three 40-mm squares
// in a row cannot all miss its two shared edges (two would have to share a free edge); each moves
// within its own third of the loop to where it holds (the checker fails any gap within half a tab
// of another part). The middle part of 3 x 3 has nowhere to go: its tab is counted and warned of.
TEST(CommonOptimize, StandardTabsMoveOffSharedEdges) {
  const auto dir = fresh_temp_dir("standard-tabs-shared");
  const Layout row = grid(dir, 3, 1, 40, 40, 0);
  const auto rep = dir / "out.json";
  OptRun run = optimize(row.dxf, dir, "--technique standard --tabs 3 --threads 1 --report " + rep.string());
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  const auto nest = load(row.dxf);
  const auto check = check_common_program(nest, run.program, 0.005, false, 1.0);
  for (const auto& f : check.failures) ADD_FAILURE() << f;
  for (std::size_t k = 0; k < check.uncut.size(); ++k) {
    ASSERT_EQ(check.uncut[k].size(), 3u) << k;
    for (const double gap : check.uncut[k]) EXPECT_NEAR(gap, 1.0, 0.05) << k;
  }
  auto report = nlohmann::json::parse(read_text(rep));
  EXPECT_EQ(report["rules"]["tabs"]["tabs"], 9);
  EXPECT_EQ(report["rules"]["tabs"]["on_a_neighbours_cut"], 0);

  const Layout square = grid(dir, 3, 3, 40, 40, 0);
  run = optimize(square.dxf, dir, "--technique standard --tabs 1 --threads 1 --report " + rep.string());
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  report = nlohmann::json::parse(read_text(rep));
  EXPECT_EQ(report["rules"]["tabs"]["on_a_neighbours_cut"], 1);
  bool warned = false;
  for (const auto& d : report["diagnostics"]) warned |= d.value("code", "") == "tabs.on_a_neighbours_cut";
  EXPECT_TRUE(warned) << report["diagnostics"];
  std::filesystem::remove_all(dir);
}

// deepnestsharp_TopsNest (23 parts with 204 holes, placed edge to edge) with common lines and two
// 1-mm tabs each: every part with room on its own edges gets its two gaps there, each 1 mm wide,
// none on a common line or within half a tab of another part, and the program stays admissible
// (everything else cut, holes and common lines first).
TEST(CommonOptimize, TabsOnTopsNestStayOffTheCommonLines) {
  const auto dir = fresh_temp_dir("common-tabs-tops");
  const std::string dxf = shared("data/dxf/deepnestsharp_TopsNest.dxf");
  const auto rep = dir / "out.json";
  const OptRun run = optimize(dxf, dir, "--technique common --tabs 2 --threads 1 --report " + rep.string());
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  const auto nest = load(dxf);
  const auto check = check_common_program(nest, run.program, 0.005, true, 1.0);
  for (const auto& f : check.failures) ADD_FAILURE() << f;
  const auto report = nlohmann::json::parse(read_text(rep));
  const auto& tabs = report["rules"]["tabs"];
  const auto contours = drawn_contours(nest);
  std::set<int> enclosed;
  for (const auto& p : tabs["parts_without_skeleton_edge"]) enclosed.insert(p.get<int>());
  int outers = 0, tabbed = 0;
  for (std::size_t k = 0; k < contours.size(); ++k) {
    if (!contours[k].outer) {
      EXPECT_TRUE(check.uncut[k].empty()) << "contour " << k + 1;
      continue;
    }
    ++outers;
    // Left whole: a part enclosed by its neighbours, or one whose own edges are too short.
    if (check.uncut[k].empty()) continue;
    EXPECT_EQ(enclosed.count(contours[k].part), 0u) << "part " << contours[k].part;
    ASSERT_EQ(check.uncut[k].size(), 2u) << "part " << contours[k].part;
    for (const double gap : check.uncut[k]) EXPECT_NEAR(gap, 1.0, 0.05) << "part " << contours[k].part;
    ++tabbed;
  }
  // 23 parts: six 118 x 34 plates share their whole outline with neighbours, and one 297.5 x 130
  // panel keeps only a 6-mm stretch of its own edges, too short for two tabs between the margins
  // kept from the junctions.
  EXPECT_EQ(outers, 23);
  EXPECT_EQ(enclosed, (std::set<int>{8, 9, 10, 14, 15, 16}));
  EXPECT_EQ(tabbed, 16);
  EXPECT_EQ(tabs["contours"], tabbed);
  EXPECT_EQ(tabs["tabs"], 2 * tabbed);
  EXPECT_EQ(tabs["contours_too_short"], outers - tabbed);
  EXPECT_EQ(report["pierces"], check.runs);
  std::filesystem::remove_all(dir);
}

// A row of four parts drawn one kerf apart: the common cuts run on the centre lines of the gaps.
TEST(CommonOptimize, KerfApartRow) {
  const auto dir = fresh_temp_dir("common-kerf");
  const double k = 0.2;
  DxfBuilder b;
  b.insunits(4);
  b.lwpolyline({Vertex{{0, 0}, 0}, Vertex{{1000, 0}, 0}, Vertex{{1000, 600}, 0}, Vertex{{0, 600}, 0}}, true, "SHEET");
  double perimeters = 0;
  for (int i = 0; i < 4; ++i) {
    const double x = 100 + i * (150 + k);
    b.lwpolyline({Vertex{{x, 100}, 0}, Vertex{{x + 150, 100}, 0}, Vertex{{x + 150, 190}, 0}, Vertex{{x, 190}, 0}}, true,
                 "PARTS");
    perimeters += 2 * (150 + 90);
  }
  const std::string dxf = (dir / "row.dxf").string();
  std::ofstream(dxf) << b.str();
  const auto check = optimize_and_check(dxf, dir, "--technique common --kerf 0.2", k / 2 + 0.005);
  EXPECT_EQ(check.runs, 1 + 3);
  // Three 90 mm centre lines instead of six edges; the outline crosses each gap twice.
  EXPECT_NEAR(check.boundary_cut_mm, perimeters - 3 * 90 + 6 * k, 0.05);
  std::filesystem::remove_all(dir);
}

// Two 30 x 50 parts side by side under a 61.5 x 20 one, all one kerf apart (tee15.dxf of an
// audit): at the T the stem's gap ends on the long part's edge. Before, the junction's centre lay
// off the through line, the long part's edge across the stem's mouth was cut as a loop narrower
// than the kerf, pierced 0.1 mm inside the long part (kerf 1.5: its kerf 0.85 mm into it; laser
// 0.15: 0.085 mm), and leads turned by 45° into a gap clipped a corner (0.22 mm). Re-read from
// the program: no pierce and no uncompensated cut comes nearer to any part than the common lines,
// half a kerf; every edge is still cut.
TEST(CommonOptimize, KerfApartTeeKeepsTheBeamOffTheParts) {
  const auto dir = fresh_temp_dir("common-kerf-tee");
  struct Case {
    double kerf;
    std::string options;
  };
  for (const Case& c : {Case{0.15, "--technique common"}, Case{0.15, "--technique auto"},
                        Case{1.5, "--technique common --dialect plasma-thc"}, Case{1.5, "--technique auto --dialect plasma-thc"}}) {
    SCOPED_TRACE(c.options + " --kerf " + std::to_string(c.kerf));
    const double k = c.kerf;
    DxfBuilder b;
    b.insunits(4);
    const auto rect = [&](double x, double y, double w, double h) {
      b.lwpolyline({Vertex{{x, y}, 0}, Vertex{{x + w, y}, 0}, Vertex{{x + w, y + h}, 0}, Vertex{{x, y + h}, 0}}, true, "PARTS");
    };
    rect(10, 10, 30, 50);
    rect(40 + k, 10, 30, 50);
    rect(10, 60 + k, 60 + k, 20);
    const std::string dxf = (dir / "tee.dxf").string();
    std::ofstream(dxf) << b.str();
    const auto rep = dir / "out.json";
    std::string program;
    const auto check = optimize_and_check(dxf, dir,
                                          c.options + " --kerf " + std::to_string(k) + " --threads 1 --time-limit 0 --work-limit 0.2 --report " +
                                              rep.string(),
                                          k / 2 + 0.005, &program);
    EXPECT_EQ(nlohmann::json::parse(read_text(rep)).at("chosen"), "common");
    EXPECT_GE(check.nearest_uncompensated_mm, k / 2 - 1e-6) << "line " << check.nearest_line << "\n" << program;
    // The outline, the through line and the stem: the stem's mouth is cut by the through line.
    EXPECT_EQ(check.runs, 3);
  }
  std::filesystem::remove_all(dir);
}

// Four parts round an oblique X (a horizontal gap crossed at 60 degrees), one kerf apart: the four
// edges round the crossing are each kerf / sin(60) long, 4.0 mm in all at kerf 1.5, and that loop,
// though the trails' kerf cuts every point of it, was entered: pierced 0.42 mm inside a part.
TEST(CommonOptimize, KerfApartObliqueCrossKeepsTheBeamOffTheParts) {
  const auto dir = fresh_temp_dir("common-kerf-x");
  for (const double k : {0.15, 1.5}) {
    SCOPED_TRACE("kerf " + std::to_string(k));
    const Vec2 c{50, 40};
    const double a = std::numbers::pi / 3;
    const Vec2 n1{0, 1}, n2{-std::sin(a), std::cos(a)};  // normals of the two gaps' centre lines
    // The sheet's 100 x 80 rectangle clipped to the side s of each line, half a kerf off it
    // (Sutherland-Hodgman against two half-planes).
    const auto piece = [&](double s1, double s2) {
      std::vector<Vec2> poly{{0, 0}, {100, 0}, {100, 80}, {0, 80}};
      for (const auto& [n, sgn] : {std::pair{n1, s1}, std::pair{n2, s2}}) {
        const auto f = [&](Vec2 p) { return sgn * ((p.x - c.x) * n.x + (p.y - c.y) * n.y) - k / 2; };
        std::vector<Vec2> out;
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const Vec2 p = poly[i], q = poly[(i + 1) % poly.size()];
          const double fp = f(p), fq = f(q);
          if (fp >= 0) out.push_back(p);
          if ((fp >= 0) != (fq >= 0)) out.push_back(p + (q - p) * (fp / (fp - fq)));
        }
        poly = out;
      }
      std::vector<Vertex> v;
      for (const Vec2& p : poly) v.push_back({p, 0});
      return v;
    };
    DxfBuilder b;
    b.insunits(4);
    for (const double s1 : {1.0, -1.0})
      for (const double s2 : {1.0, -1.0}) b.lwpolyline(piece(s1, s2), true, "PARTS");
    const std::string dxf = (dir / "x.dxf").string();
    std::ofstream(dxf) << b.str();
    std::string program;
    const auto check = optimize_and_check(
        dxf, dir, "--technique common --kerf " + std::to_string(k) + (k > 1 ? " --dialect plasma-thc" : "") +
                      " --threads 1 --time-limit 0 --work-limit 0.2",
        k / 2 + 0.005, &program);
    EXPECT_GE(check.nearest_uncompensated_mm, k / 2 - 0.01 * k - 1e-6) << "line " << check.nearest_line << "\n" << program;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cutroute::test
