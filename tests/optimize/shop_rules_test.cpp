// Shop rules end to end: each rule checked on the re-parsed program of a generated nest, and shown
// to be violated by the same nest without the rule (so the check can fail).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include <cutroute/io/nest_loader.hpp>

#include "support/dxf_builder.hpp"
#include "support/files.hpp"
#include "support/paths.hpp"
#include "support/program_check.hpp"

namespace cutroute::test {
namespace {

namespace fs = std::filesystem;
using geometry::Vec2;

fs::path temp_dir(const std::string& name) { return fresh_temp_dir("rules", name); }

struct Rect {
  double x0, y0, x1, y1;  // [mm]
  Vec2 centre() const { return {(x0 + x1) / 2, (y0 + y1) / 2}; }
  bool strictly_inside(Vec2 p, double eps) const { return p.x > x0 + eps && p.x < x1 - eps && p.y > y0 + eps && p.y < y1 - eps; }
  double boundary_distance(Vec2 p) const {
    const bool in = p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1;
    if (in) return std::min({p.x - x0, x1 - p.x, p.y - y0, y1 - p.y});
    const double dx = std::max({0.0, x0 - p.x, p.x - x1}), dy = std::max({0.0, y0 - p.y, p.y - y1});
    return std::hypot(dx, dy);
  }
};

double gap(const Rect& a, const Rect& b) {
  const double dx = std::max({0.0, a.x0 - b.x1, b.x0 - a.x1}), dy = std::max({0.0, a.y0 - b.y1, b.y0 - a.y1});
  return std::hypot(dx, dy);
}

// A sheet (layer "sheet") with the given rectangular parts.
std::string write_nest(const fs::path& dir, const std::vector<Rect>& parts, double w, double h) {
  DxfBuilder b;
  b.insunits(4);
  b.lwpolyline({{{0, 0}}, {{w, 0}}, {{w, h}}, {{0, h}}}, true, "sheet");
  for (const auto& r : parts) b.lwpolyline({{{r.x0, r.y0}}, {{r.x1, r.y0}}, {{r.x1, r.y1}}, {{r.x0, r.y1}}}, true, "0");
  const auto path = (dir / "nest.dxf").string();
  std::ofstream(path) << b.str();
  return path;
}

struct Run {
  std::vector<const ProbeMove*> moves;  // beam-on moves
  int part = -1;                        // the rectangle most of its moves lie on
  Vec2 first_on_contour{};              // where the cut of the contour itself begins
  Vec2 end{};                           // last point with the beam on
};

struct Program {
  std::string text;
  nlohmann::json report;
  ProbeResult probe;
  std::vector<Run> runs;
  std::vector<std::pair<const ProbeMove*, int>> rapids;  // each G0 move and the number of runs before it
};

// Runs of the re-parsed program, each given the rectangle it cuts (independently of the route data).
Program parse(const std::string& text, const std::vector<Rect>& parts) {
  Program p;
  p.text = text;
  p.probe = probe_gcode(text);
  bool beam = false;
  for (const auto& m : p.probe.moves) {
    if (m.rapid) {
      beam = false;
      p.rapids.emplace_back(&m, static_cast<int>(p.runs.size()));
      continue;
    }
    if (!m.beam_on) continue;
    if (!beam) p.runs.emplace_back();
    beam = true;
    p.runs.back().moves.push_back(&m);
  }
  for (auto& r : p.runs) {
    std::vector<int> votes(parts.size(), 0);
    for (const auto* m : r.moves)
      for (std::size_t k = 0; k < parts.size(); ++k) {
        Vec2 a{m->x0, m->y0}, b{m->x1, m->y1};
        if (parts[k].boundary_distance(a) < 0.01 && parts[k].boundary_distance(b) < 0.01) ++votes[k];
      }
    r.part = static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    for (const auto* m : r.moves) {
      if (parts[static_cast<std::size_t>(r.part)].boundary_distance({m->x0, m->y0}) < 0.01 &&
          parts[static_cast<std::size_t>(r.part)].boundary_distance({m->x1, m->y1}) < 0.01) {
        r.first_on_contour = {m->x0, m->y0};
        break;
      }
    }
    r.end = {r.moves.back()->x1, r.moves.back()->y1};
  }
  return p;
}

Program optimize(const std::string& dxf, const fs::path& dir, const std::string& extra, const std::vector<Rect>& parts,
                 const std::string& technique = "standard") {
  const auto prog = dir / "out.ngc", rep = dir / "out.json";
  fs::remove(prog);
  const auto r = run_command(cli_path() + " optimize " + dxf + " -o " + prog.string() + " --report " + rep.string() +
                             " --svg " + (dir / "out.svg").string() + " --quiet --time-limit 2 --threads 1 --technique " +
                             technique + " " + extra);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  if (r.exit_code != 0) return {};
  Program p = parse(read_text(prog), parts);
  p.report = nlohmann::json::parse(read_text(rep));
  return p;
}

// `moved_start`: the program was made for a start point other than (0, 0), where the probe begins,
// so its first rapid differs from the report's.
ProgramCheck expect_admissible(const std::string& dxf, const Program& p, int tabs = 0, double tab_width = 0, bool moved_start = false) {
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  if (!loaded.ok()) {
    ADD_FAILURE() << dxf << ": " << loaded.error().message;
    return {};
  }
  ProgramCheckOptions opt;
  opt.clearance_mm = 1.0;
  opt.tabs = tabs;
  opt.tab_width_mm = tab_width;
  const auto check = check_program(loaded->nest, p.text, opt);
  for (const auto& f : check.failures) ADD_FAILURE() << f;
  EXPECT_EQ(p.report["pierces"].get<int>(), check.probe.pierces);
  EXPECT_NEAR(p.report["cut_length_mm"].get<double>(), check.cut_length, 1e-6 * check.cut_length + 1e-6);
  if (!moved_start) {
    EXPECT_NEAR(p.report["rapid_length_mm"].get<double>(), check.rapid_length, 1e-6 * check.rapid_length + 1e-6);
  }
  EXPECT_EQ(p.report["frames"].get<int>(), check.probe.frames);
  return check;
}

// ---------------------------------------------------------------------------------------------
// Heat: six 40 mm squares in a row, 5 mm apart. With D = 20 mm only non-neighbours may follow each
// other; such orders exist (e.g. 1 3 5 2 4 6), and the shortest route (1 2 3 4 5 6) breaks it.

std::vector<Rect> row_of_squares(int n, double side, double gap_mm, double y0) {
  std::vector<Rect> v;
  for (int i = 0; i < n; ++i) {
    const double x = 20 + i * (side + gap_mm);
    v.push_back({x, y0, x + side, y0 + side});
  }
  return v;
}

int closest_consecutive(const Program& p, const std::vector<Rect>& parts, double d) {
  int close = 0;
  for (std::size_t i = 1; i < p.runs.size(); ++i)
    close += gap(parts[static_cast<std::size_t>(p.runs[i - 1].part)], parts[static_cast<std::size_t>(p.runs[i].part)]) < d;
  return close;
}

TEST(ShopRules, HeatKeepsConsecutiveCutsApart) {
  const auto dir = temp_dir("heat");
  const auto parts = row_of_squares(6, 40, 5, 30);
  const auto dxf = write_nest(dir, parts, 320, 100);
  const Program plain = optimize(dxf, dir, "", parts);
  ASSERT_EQ(plain.runs.size(), 6u);
  EXPECT_GT(closest_consecutive(plain, parts, 20), 0) << "the nest must tempt the solver into neighbours";
  EXPECT_FALSE(plain.report.contains("rules"));

  const Program heat = optimize(dxf, dir, "--heat-distance 20", parts);
  ASSERT_EQ(heat.runs.size(), 6u);
  expect_admissible(dxf, heat);
  EXPECT_EQ(closest_consecutive(heat, parts, 20), 0);
  const auto& rules = heat.report["rules"];
  EXPECT_EQ(rules["active"], nlohmann::json::array({"heat"}));
  EXPECT_EQ(rules["route"]["heat"]["consecutive_closer_than_d"], 0);
  EXPECT_GT(rules["search"]["solver_route"]["heat"]["consecutive_closer_than_d"].get<int>(), 0);
  // Heat costs rapid length: the program is longer than the shortest one.
  EXPECT_GT(heat.report["rapid_length_mm"].get<double>(), plain.report["rapid_length_mm"].get<double>());
  fs::remove_all(dir);
}

TEST(ShopRules, HeatMemoryLooksFurtherBack) {
  // Nine 20 mm squares in a row 5 mm apart, D = 20 mm (neighbours are 5 mm apart, the next but one
  // 30 mm), memory 2: a cut should not be next to either of the last two cuts. Such orders exist (e.g. 1 4 7 2 5 8 3 6 9).
  const auto dir = temp_dir("heatmem");
  const auto parts = row_of_squares(9, 20, 5, 30);
  const auto dxf = write_nest(dir, parts, 260, 100);
  const Program p = optimize(dxf, dir, "--heat-distance 20 --heat-memory 2", parts);
  ASSERT_EQ(p.runs.size(), 9u);
  expect_admissible(dxf, p);
  for (std::size_t i = 1; i < p.runs.size(); ++i)
    for (std::size_t k = 1; k <= 2 && k <= i; ++k)
      EXPECT_GE(gap(parts[static_cast<std::size_t>(p.runs[i - k].part)], parts[static_cast<std::size_t>(p.runs[i].part)]), 20)
          << "runs " << i - k << " and " << i;
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Tip-up: squares on the diagonal through the start point (0, 0), the machine's park position:
// the way back (and every step back) passes over parts already cut free unless it goes around.

int rapids_over_freed(const Program& p, const std::vector<Rect>& parts) {
  int over = 0;
  for (const auto& [m, runs_before] : p.rapids) {
    std::vector<char> freed(parts.size(), 0);
    for (int r = 0; r < runs_before; ++r) freed[static_cast<std::size_t>(p.runs[static_cast<std::size_t>(r)].part)] = 1;
    bool hit = false;
    for (std::size_t k = 0; k < parts.size() && !hit; ++k) {
      if (!freed[k]) continue;
      for (int s = 0; s <= 200 && !hit; ++s) {
        Vec2 q;
        probe_point(*m, s / 200.0, q.x, q.y);
        hit = parts[k].strictly_inside(q, 0.01);
      }
    }
    over += hit;
  }
  return over;
}

TEST(ShopRules, TipUpRapidsGoAroundFreedParts) {
  const auto dir = temp_dir("tipup");
  std::vector<Rect> parts;
  for (int i = 0; i < 5; ++i) parts.push_back({15.0 + i * 50, 15.0 + i * 50, 45.0 + i * 50, 45.0 + i * 50});
  for (int i = 0; i < 4; ++i) parts.push_back({65.0 + i * 50, 15.0 + i * 50, 95.0 + i * 50, 45.0 + i * 50});
  const auto dxf = write_nest(dir, parts, 280, 280);
  const Program plain = optimize(dxf, dir, "", parts);
  EXPECT_GT(rapids_over_freed(plain, parts), 0) << "the nest must make straight rapids pass over freed parts";

  const Program tip = optimize(dxf, dir, "--avoid-tip-up", parts);
  expect_admissible(dxf, tip);
  EXPECT_EQ(rapids_over_freed(tip, parts), 0);
  const auto& rules = tip.report["rules"];
  EXPECT_EQ(rules["tip_up_program"]["unavoidable"], 0);
  EXPECT_EQ(rules["tip_up_program"]["unavoidable_left_at_time_limit"], 0);  // 9 parts: done well within the limit
  // Detours are written as extra G0 moves: at least one more per detour than one rapid per run + park.
  const int detours = rules["tip_up_program"]["detours"].get<int>();
  EXPECT_GT(detours, 0);
  EXPECT_GE(static_cast<int>(tip.rapids.size()), static_cast<int>(tip.runs.size()) + 1 + detours);
  EXPECT_EQ(rules["tip_up_program"]["rapids_over_freed_parts"].get<int>(), detours);
  // The picture draws the detours too: one dashed rapid line per G0 move of the program.
  const std::string svg = read_text(dir / "out.svg");
  std::size_t dashed = 0;
  for (auto at = svg.find("stroke-dasharray=\"5 4\""); at != std::string::npos; at = svg.find("stroke-dasharray=\"5 4\"", at + 1)) ++dashed;
  EXPECT_EQ(dashed, tip.rapids.size());
  fs::remove_all(dir);
}

// The straight moves between runs (end of one run's cut, lead-out included, to the next run's
// pierce) that pass over a part cut by an earlier run: what the program's rapids would be without
// detour waypoints, measured on the re-parsed program.
int straight_transitions_over_freed(const Program& p, const std::vector<Rect>& parts) {
  int over = 0;
  std::vector<char> freed(parts.size(), 0);
  for (std::size_t i = 1; i < p.runs.size(); ++i) {
    freed[static_cast<std::size_t>(p.runs[i - 1].part)] = 1;
    const Vec2 a = p.runs[i - 1].end;
    const Vec2 b{p.runs[i].moves.front()->x0, p.runs[i].moves.front()->y0};
    bool hit = false;
    for (std::size_t k = 0; k < parts.size() && !hit; ++k)
      for (int t = 0; t <= 400 && freed[k] && !hit; ++t) hit = parts[k].strictly_inside(a + (b - a) * (t / 400.0), 0.01);
    over += hit;
  }
  return over;
}

// The entry refinement slides pierce points along their contours to shorten rapids; with tip-up it
// must not bring back the rapids over freed parts that the order avoided. A 6 x 6 grid of 20-mm
// squares at a 30-mm pitch: the route leaves no rapid over a freed part, and before the refinement
// priced them, sliding the entries made 2 of the program's rapids cross a freed square (detoured).
TEST(ShopRules, TipUpEntryRefinementKeepsRapidsOffFreedParts) {
  const auto dir = temp_dir("tipup_refine");
  std::vector<Rect> parts;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) parts.push_back({10.0 + i * 30, 10.0 + j * 30, 30.0 + i * 30, 30.0 + j * 30});
  const auto dxf = write_nest(dir, parts, 190, 190);
  const Program tip = optimize(dxf, dir, "--avoid-tip-up", parts);
  expect_admissible(dxf, tip);
  const auto& rules = tip.report["rules"];
  ASSERT_EQ(rules["route"]["tip_up"]["straight_rapids_over_freed_parts"].get<int>(), 0);
  EXPECT_EQ(straight_transitions_over_freed(tip, parts), 0);
  EXPECT_EQ(rules["tip_up_program"]["rapids_over_freed_parts"].get<int>(), 0);
  EXPECT_EQ(static_cast<int>(tip.rapids.size()), static_cast<int>(tip.runs.size()) + 1);  // no detour waypoints
  EXPECT_EQ(rapids_over_freed(tip, parts), 0);
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Part rigidity: every outer contour entered at a corner, the corner nearest the parts cut after it.

bool at_corner(const Rect& r, Vec2 p) {
  for (Vec2 c : {Vec2{r.x0, r.y0}, Vec2{r.x1, r.y0}, Vec2{r.x1, r.y1}, Vec2{r.x0, r.y1}})
    if (geometry::distance(c, p) < 0.01) return true;
  return false;
}

TEST(ShopRules, PartRigidityEntersAtTheCornerTowardUncutMaterial) {
  const auto dir = temp_dir("rigid");
  // Long bars stacked above the start point (150, 0) at their middle: the shortest rapids enter
  // them in the middle of their long edges, far from any corner.
  std::vector<Rect> parts;
  for (int i = 0; i < 4; ++i) parts.push_back({30, 20.0 + i * 40, 270, 40.0 + i * 40});
  const auto dxf = write_nest(dir, parts, 300, 190);
  const Program plain = optimize(dxf, dir, "--start 150,0", parts);
  int plain_off = 0;
  for (const auto& r : plain.runs) plain_off += !at_corner(parts[static_cast<std::size_t>(r.part)], r.first_on_contour);
  EXPECT_GT(plain_off, 0) << "without the rule some entries must lie along edges";

  const Program rigid = optimize(dxf, dir, "--start 150,0 --part-rigidity", parts);
  expect_admissible(dxf, rigid, 0, 0, true);
  ASSERT_EQ(rigid.runs.size(), parts.size());
  for (std::size_t i = 0; i < rigid.runs.size(); ++i) {
    const Rect& r = parts[static_cast<std::size_t>(rigid.runs[i].part)];
    const Vec2 entry = rigid.runs[i].first_on_contour;
    EXPECT_TRUE(at_corner(r, entry)) << "run " << i << " enters at (" << entry.x << ", " << entry.y << ")";
    // The cut ends at its entry: the corner nearest the centre of the parts cut later (sheet centre last).
    Vec2 target{150, 95};  // the sheet's centre
    if (i + 1 < rigid.runs.size()) {
      Vec2 sum{0, 0};
      for (std::size_t k = i + 1; k < rigid.runs.size(); ++k) sum = sum + parts[static_cast<std::size_t>(rigid.runs[k].part)].centre();
      target = sum / static_cast<double>(rigid.runs.size() - i - 1);
    }
    double best = 1e18;
    for (Vec2 c : {Vec2{r.x0, r.y0}, Vec2{r.x1, r.y0}, Vec2{r.x1, r.y1}, Vec2{r.x0, r.y1}}) best = std::min(best, geometry::distance(c, target));
    EXPECT_NEAR(geometry::distance(entry, target), best, 1e-3) << "run " << i;
  }
  EXPECT_EQ(rigid.report["rules"]["part_rigidity"]["outer_contours_entered_at_a_corner"], static_cast<int>(parts.size()));
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Sheet rigidity: a 4 x 3 grid, start at the bottom left. Clamped on the right, the order must
// sweep right to left (column never increasing); clamped at the top, top to bottom.

std::vector<Rect> grid(int cols, int rows) {
  std::vector<Rect> v;
  for (int c = 0; c < cols; ++c)
    for (int r = 0; r < rows; ++r) v.push_back({20.0 + c * 60, 20.0 + r * 60, 60.0 + c * 60, 60.0 + r * 60});
  return v;
}

bool monotone(const Program& p, const std::vector<Rect>& parts, bool by_x, bool decreasing) {
  for (std::size_t i = 1; i < p.runs.size(); ++i) {
    const Vec2 a = parts[static_cast<std::size_t>(p.runs[i - 1].part)].centre(), b = parts[static_cast<std::size_t>(p.runs[i].part)].centre();
    const double da = by_x ? a.x : a.y, db = by_x ? b.x : b.y;
    if (decreasing ? db > da + 1e-9 : db < da - 1e-9) return false;
  }
  return true;
}

TEST(ShopRules, SheetRigiditySweepsAwayFromTheClamp) {
  const auto dir = temp_dir("sheet");
  const auto parts = grid(4, 3);
  const auto dxf = write_nest(dir, parts, 280, 220);
  const Program plain = optimize(dxf, dir, "", parts);
  EXPECT_FALSE(monotone(plain, parts, true, true)) << "the shortest route must not already sweep right to left";
  EXPECT_FALSE(monotone(plain, parts, false, true));

  const Program right = optimize(dxf, dir, "--sheet-clamp right", parts);
  expect_admissible(dxf, right);
  ASSERT_EQ(right.runs.size(), parts.size());
  EXPECT_TRUE(monotone(right, parts, true, true));
  EXPECT_EQ(right.report["rules"]["route"]["sheet"]["steps_behind_front"], 0);

  const Program top = optimize(dxf, dir, "--sheet-clamp top", parts);
  ASSERT_EQ(top.runs.size(), parts.size());
  EXPECT_TRUE(monotone(top, parts, false, true));
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Micro-joints: N gaps of width w per outer contour, beam off over each.

double perimeter(const Rect& r) { return 2 * (r.x1 - r.x0 + r.y1 - r.y0); }
// Arc length of a boundary point, clockwise from the lower left corner (the direction outer contours are cut).
double perimeter_at(const Rect& r, Vec2 p) {
  const double w = r.x1 - r.x0, h = r.y1 - r.y0;
  if (std::abs(p.x - r.x0) < 0.01) return p.y - r.y0;
  if (std::abs(p.y - r.y1) < 0.01) return h + (p.x - r.x0);
  if (std::abs(p.x - r.x1) < 0.01) return h + w + (r.y1 - p.y);
  return 2 * h + w + (r.x1 - p.x);
}

TEST(ShopRules, TabsLeaveNGapsOfWidthW) {
  const auto dir = temp_dir("tabs");
  const auto parts = grid(3, 2);
  const auto dxf = write_nest(dir, parts, 220, 160);
  const int n = 3;
  const double w = 1.5;
  const Program p = optimize(dxf, dir, "--tabs 3 --tab-width 1.5", parts);
  expect_admissible(dxf, p, n, w);
  ASSERT_EQ(p.runs.size(), parts.size() * (n + 1));
  EXPECT_EQ(p.report["pierces"].get<std::size_t>(), parts.size() * (n + 1));
  // Per part: N + 1 consecutive runs; the head moves over each gap (beam off) from the end of one
  // run to the start of the next, a straight gap of w along the edge; the cut length on the part
  // is its perimeter less N w.
  for (std::size_t i = 0; i < p.runs.size(); i += n + 1) {
    const int part = p.runs[i].part;
    const Rect& r = parts[static_cast<std::size_t>(part)];
    double on = 0;
    for (std::size_t k = i; k < i + n + 1; ++k) {
      ASSERT_EQ(p.runs[k].part, part) << "run " << k;
      for (const auto* m : p.runs[k].moves)
        if (r.boundary_distance({m->x0, m->y0}) < 0.01 && r.boundary_distance({m->x1, m->y1}) < 0.01) on += m->length;
      if (k > i) {
        const Vec2 from = p.runs[k - 1].end, to{p.runs[k].moves.front()->x0, p.runs[k].moves.front()->y0};
        // The gap's width along the contour (a gap may turn round a corner).
        const double along = std::fmod(perimeter_at(r, to) - perimeter_at(r, from) + 2 * perimeter(r), perimeter(r));
        EXPECT_NEAR(along, w, 2e-3) << "gap before run " << k;
        EXPECT_LT(r.boundary_distance(from), 0.01);
        EXPECT_LT(r.boundary_distance(to), 0.01);
      }
    }
    EXPECT_NEAR(on, 2 * (r.x1 - r.x0 + r.y1 - r.y0) - n * w, 0.02) << "part " << part;
  }
  EXPECT_EQ(p.report["rules"]["tabs"]["tabs"], static_cast<int>(parts.size()) * n);
  // Controller compensation (the default) stays on over the gaps: one G41 per part, and LinuxCNC,
  // with the kerf as its tool, accepts the program.
  std::size_t g41 = 0;
  for (auto at = p.text.find("\nG41\n"); at != std::string::npos; at = p.text.find("\nG41\n", at + 1)) ++g41;
  EXPECT_EQ(g41, parts.size());
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    const auto rs = run_rs274((dir / "out.ngc").string(), p.report["kerf_mm"].get<double>());
    EXPECT_EQ(rs.exit_code, 0) << rs.out;
  }
  // The picture shows every piece: one group per cutting segment (+ the park rapid).
  const std::string svg = read_text(dir / "out.svg");
  std::size_t groups = 0;
  for (auto at = svg.find("class=\"seg\""); at != std::string::npos; at = svg.find("class=\"seg\"", at + 1)) ++groups;
  EXPECT_EQ(groups, p.runs.size() + 1);
  // Without tabs the same checker rejects the tabbed program: the check can fail.
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  ASSERT_TRUE(loaded.ok());
  EXPECT_FALSE(check_program(loaded->nest, p.text, ProgramCheckOptions{}).failures.empty());
  fs::remove_all(dir);
}

// The tool centre's path while the beam is on, as LinuxCNC's interpreter computes it with the kerf
// loaded as the tool (G41/G42 applied): the closest it comes to a part's edge, and how many of its
// samples lie inside a part. From the interpreter's canonical commands alone.
struct KerfReach {
  double closest = 1e300;  // [mm]
  int inside = 0;
};

std::vector<double> canon_args(const std::string& line, const std::string& call) {
  std::vector<double> v;
  const auto at = line.find(call + "(");
  if (at == std::string::npos) return v;
  std::stringstream in(line.substr(at + call.size() + 1));
  for (std::string field; std::getline(in, field, ',');) v.push_back(std::atof(field.c_str()));
  return v;
}

KerfReach kerf_reach(const std::string& canon, const std::vector<Rect>& parts) {
  KerfReach k;
  Vec2 at{0, 0};
  bool beam = false;
  auto sample = [&](Vec2 q) {
    for (const Rect& r : parts) {
      k.closest = std::min(k.closest, r.boundary_distance(q));
      k.inside += r.strictly_inside(q, 0.0);
    }
  };
  std::stringstream in(canon);
  for (std::string line; std::getline(in, line);) {
    if (line.find("START_SPINDLE_CLOCKWISE") != std::string::npos) {
      beam = true;
      sample(at);  // the pierce
    } else if (line.find("STOP_SPINDLE_TURNING") != std::string::npos) {
      beam = false;
    } else if (const auto t = canon_args(line, "STRAIGHT_TRAVERSE"); t.size() >= 2) {
      at = {t[0], t[1]};
    } else if (const auto f = canon_args(line, "STRAIGHT_FEED"); f.size() >= 2) {
      const Vec2 to{f[0], f[1]};
      for (int i = 1; i <= 50 && beam; ++i) sample(at + (to - at) * (i / 50.0));
      at = to;
    } else if (const auto a = canon_args(line, "ARC_FEED"); a.size() >= 5) {
      const Vec2 to{a[0], a[1]}, c{a[2], a[3]};
      const double a0 = std::atan2(at.y - c.y, at.x - c.x), a1 = std::atan2(to.y - c.y, to.x - c.x);
      const double turn = 2 * std::numbers::pi, rad = std::hypot(at.x - c.x, at.y - c.y);
      double sweep = a[4] > 0 ? std::fmod(a1 - a0 + 2 * turn, turn) : -std::fmod(a0 - a1 + 2 * turn, turn);
      if (std::abs(sweep) < 1e-12) sweep = a[4] > 0 ? turn : -turn;
      for (int i = 1; i <= 50 && beam; ++i) {
        const double u = a0 + sweep * i / 50.0;
        sample({c.x + rad * std::cos(u), c.y + rad * std::sin(u)});
      }
      at = to;
    }
  }
  return k;
}

// After a tab a plasma program (torch-height codes: compensation off over the gap) resumes with a
// straight lead-in from scrap: the compensation's entry move then starts off the part, and the
// pierce leaves no mark on its edge. Pierced on the contour, the torch starts on the part's edge.
TEST(ShopRules, TabsOnPlasmaResumeWithALeadInNotOnThePartsEdge) {
  const auto dir = temp_dir("tab_leads");
  const auto parts = grid(3, 2);
  const auto dxf = write_nest(dir, parts, 220, 160);
  const double kerf = 1.5;
  const std::string plasma = "--dialect plasma-thc --kerf 1.5 --tabs 2 --tab-width 3 ";
  const Program led = optimize(dxf, dir, plasma, parts);
  const auto& tabs = led.report["rules"]["tabs"];
  EXPECT_TRUE(tabs["lead_in_after_tab"].get<bool>());
  EXPECT_EQ(tabs["lead_ins"], static_cast<int>(parts.size()) * 2);
  EXPECT_EQ(tabs["resumed_on_path"], 0);
  ASSERT_EQ(led.runs.size(), parts.size() * 3);
  const std::string led_text = led.text;
  for (const auto& r : led.runs) {  // every pierce in scrap, more than half a kerf off the parts
    const Vec2 pierce{r.moves.front()->x0, r.moves.front()->y0};
    for (const Rect& part : parts) EXPECT_GT(part.boundary_distance(pierce), kerf / 2) << pierce.x << " " << pierce.y;
  }
  const Program on_path = optimize(dxf, dir, plasma + "--tab-lead-in off", parts);
  EXPECT_EQ(on_path.report["rules"]["tabs"]["lead_ins"], 0);
  EXPECT_EQ(on_path.report["rules"]["tabs"]["resumed_on_path"], static_cast<int>(parts.size()) * 2);
  EXPECT_LT(on_path.report["t_cut_s"].get<double>(), led.report["t_cut_s"].get<double>()) << "the leads cost time";
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    const auto prog = dir / "check.ngc";
    std::ofstream(prog) << led_text;
    const auto rs = run_rs274(prog.string(), kerf);
    ASSERT_EQ(rs.exit_code, 0) << rs.out;
    const KerfReach k = kerf_reach(rs.out, parts);
    EXPECT_EQ(k.inside, 0);
    EXPECT_GT(k.closest, kerf / 2 - 2e-3) << "the kerf reaches into a part";
    std::ofstream(prog) << on_path.text;
    const auto rs_off = run_rs274(prog.string(), kerf);
    ASSERT_EQ(rs_off.exit_code, 0) << rs_off.out;
    EXPECT_LT(kerf_reach(rs_off.out, parts).closest, 0.01) << "pierced on the contour, the torch starts on the part's edge";
  }
  // A laser dialect keeps compensation on over the gap and pierces on the path unless asked.
  const Program laser = optimize(dxf, dir, "--tabs 2 --tab-width 3", parts);
  EXPECT_FALSE(laser.report["rules"]["tabs"]["lead_in_after_tab"].get<bool>());
  EXPECT_EQ(laser.text, optimize(dxf, dir, "--tabs 2 --tab-width 3 --tab-lead-in off", parts).text);
  const Program laser_led = optimize(dxf, dir, "--tabs 2 --tab-width 3 --tab-lead-in on", parts);
  EXPECT_EQ(laser_led.report["rules"]["tabs"]["lead_ins"], static_cast<int>(parts.size()) * 2);
  expect_admissible(dxf, laser_led, 2, 3.0);
  // A tab no wider than the kerf would be cut away: refused.
  const auto narrow = run_command(cli_path() + " optimize " + dxf + " -o " + (dir / "x.ngc").string() +
                                  " --quiet --kerf 1.5 --tabs 2 --tab-width 1.5");
  EXPECT_EQ(narrow.exit_code, 2);
  EXPECT_NE(narrow.err.find("not wider than the kerf"), std::string::npos) << narrow.err;
  EXPECT_FALSE(fs::exists(dir / "x.ngc"));
  fs::remove_all(dir);
}

TEST(ShopRules, OffMeansOffAndAllRulesTogetherStayAdmissibleAndDeterministic) {
  const auto dir = temp_dir("all");
  const auto parts = grid(3, 3);
  const auto dxf = write_nest(dir, parts, 220, 220);
  // Rules given at their "off" values change nothing, byte for byte.
  const Program plain = optimize(dxf, dir, "", parts);
  const Program off = optimize(dxf, dir, "--heat-distance 0 --tabs 0 --heat-weight 99 --sheet-weight 3", parts);
  EXPECT_EQ(plain.text, off.text);
  EXPECT_FALSE(off.report.contains("rules"));
  // Everything at once: admissible with the tabs, the same bytes twice.
  const std::string all = "--heat-distance 15 --heat-memory 2 --part-rigidity --sheet-clamp bottom --tabs 2 --tab-width 2";
  const Program a = optimize(dxf, dir, all, parts);
  expect_admissible(dxf, a, 2, 2.0);
  EXPECT_TRUE(monotone(a, parts, false, false));  // clamped at the bottom: rows bottom to top
  const Program b = optimize(dxf, dir, all, parts);
  EXPECT_EQ(a.text, b.text);
  EXPECT_EQ(a.report["rules"]["active"], nlohmann::json::array({"heat", "part_rigidity", "sheet_rigidity", "tabs"}));
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// The order rules with the other techniques: a segment is every part it cuts (a chain's parts).

// The parts each run of the program cuts along (a chain's run cuts several), from the re-parsed
// moves alone.
std::vector<std::vector<int>> parts_of_runs(const Program& p, const std::vector<Rect>& parts) {
  std::vector<std::vector<int>> out;
  for (const auto& r : p.runs) {
    std::vector<int> on;
    for (std::size_t k = 0; k < parts.size(); ++k)
      for (const auto* m : r.moves)
        if (parts[k].boundary_distance({m->x0, m->y0}) < 0.01 && parts[k].boundary_distance({m->x1, m->y1}) < 0.01 && m->length > 1) {
          on.push_back(static_cast<int>(k));
          break;
        }
    out.push_back(on);
  }
  return out;
}

// Consecutive runs with parts closer than d.
int close_consecutive_runs(const std::vector<std::vector<int>>& runs, const std::vector<Rect>& parts, double d) {
  int close = 0;
  for (std::size_t i = 1; i < runs.size(); ++i) {
    bool near = false;
    for (int a : runs[i - 1])
      for (int b : runs[i]) near = near || gap(parts[static_cast<std::size_t>(a)], parts[static_cast<std::size_t>(b)]) < d;
    close += near;
  }
  return close;
}

// Four pairs of 40 mm squares in a row: the squares of a pair 5 mm apart (chain cutting joins
// them), the pairs 30 mm apart. With D = 40 only pairs that are not neighbours may follow each
// other (e.g. 2 4 1 3); the shortest chain route (1 2 3 4) breaks it.
std::vector<Rect> pairs_in_a_row(double y0) {
  std::vector<Rect> v;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 2; ++k) {
      const double x = 20 + i * 115 + k * 45;
      v.push_back({x, y0, x + 40, y0 + 40});
    }
  return v;
}

TEST(ShopRules, HeatKeepsChainsApart) {
  const auto dir = temp_dir("heat_chain");
  const auto parts = pairs_in_a_row(30);
  const auto dxf = write_nest(dir, parts, 500, 100);
  const Program plain = optimize(dxf, dir, "", parts, "chain");
  ASSERT_EQ(plain.runs.size(), 4u) << "chain cutting must join each pair";
  EXPECT_GT(close_consecutive_runs(parts_of_runs(plain, parts), parts, 40), 0) << "the nest must tempt the route into neighbours";

  const Program heat = optimize(dxf, dir, "--heat-distance 40", parts, "chain");
  ASSERT_EQ(heat.runs.size(), 4u);
  const auto runs = parts_of_runs(heat, parts);
  for (const auto& r : runs) EXPECT_EQ(r.size(), 2u) << "each run cuts one pair";
  EXPECT_EQ(close_consecutive_runs(runs, parts, 40), 0);
  EXPECT_EQ(heat.report["chosen"], "chain");
  EXPECT_EQ(heat.report["rules"]["route"]["heat"]["consecutive_closer_than_d"], 0);
  EXPECT_GT(heat.report["rules"]["search"]["solver_route"]["heat"]["consecutive_closer_than_d"].get<int>(), 0);
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  ASSERT_TRUE(loaded.ok());
  const auto check = check_program(loaded->nest, heat.text, ProgramCheckOptions{});
  for (const auto& f : check.failures) ADD_FAILURE() << f;
  EXPECT_EQ(check.bridges, 4);
  fs::remove_all(dir);
}

TEST(ShopRules, SheetRigiditySweepsChainsAwayFromTheClamp) {
  // Three rows of the pairs above; clamped at the top, the chains must go row by row downwards.
  const auto dir = temp_dir("sheet_chain");
  std::vector<Rect> parts;
  for (double y : {20.0, 100.0, 180.0})
    for (const Rect& r : pairs_in_a_row(y)) parts.push_back(r);
  const auto dxf = write_nest(dir, parts, 500, 240);
  auto row_order_down = [&](const Program& p) {
    double last = 1e18;
    for (const auto& run : parts_of_runs(p, parts))
      for (int k : run) {
        const double y = parts[static_cast<std::size_t>(k)].centre().y;
        if (y > last + 1e-9) return false;
        last = std::min(last, y);
      }
    return true;
  };
  const Program plain = optimize(dxf, dir, "", parts, "chain");
  ASSERT_EQ(plain.runs.size(), 12u);
  EXPECT_FALSE(row_order_down(plain)) << "the shortest route must not already sweep downwards";
  const Program top = optimize(dxf, dir, "--sheet-clamp top", parts, "chain");
  ASSERT_EQ(top.runs.size(), 12u);
  EXPECT_TRUE(row_order_down(top));
  EXPECT_EQ(top.report["rules"]["route"]["sheet"]["steps_behind_front"], 0);
  fs::remove_all(dir);
}

// A chain is measured against the sweep front by its part nearest the clamp and moves the front
// to its farthest part. Clamped left: a chain of two squares at x = 100 and 145 and a lone square,
// in two rows. With the lone square at x = 140 the chain goes first (then 5 mm back to 140; the
// square first would leave the chain's 100 40 mm behind); with it at x = 105 the square goes first
// (5 mm back against 40). A chain priced by its farthest part only gets the first case wrong (the
// square first is then free), by its nearest part only the second (the chain first is then free).
TEST(ShopRules, SheetRigidityMeasuresAChainByItsNearestPartAndMovesTheFrontToItsFarthest) {
  const auto dir = temp_dir("sheet_chain_ends");
  for (const auto& [lone_x, chain_y, lone_y, chain_goes_first] : {std::tuple{140.0, 130.0, 50.0, true}, std::tuple{105.0, 50.0, 130.0, false}}) {
    SCOPED_TRACE("lone square at x = " + std::to_string(lone_x));
    const std::vector<Rect> parts = {{80, chain_y - 20, 120, chain_y + 20},
                                     {125, chain_y - 20, 165, chain_y + 20},
                                     {lone_x - 20, lone_y - 20, lone_x + 20, lone_y + 20}};
    const auto dxf = write_nest(dir, parts, 250, 200);
    auto chain_first = [&](const Program& p) {
      const auto runs = parts_of_runs(p, parts);
      EXPECT_EQ(runs.size(), 2u);
      return !runs.empty() && runs.front().size() == 2;
    };
    const Program left = optimize(dxf, dir, "--sheet-clamp left --sheet-weight 2", parts, "chain");
    EXPECT_EQ(chain_first(left), chain_goes_first);
  }
  fs::remove_all(dir);
}

TEST(ShopRules, TipUpRapidsGoAroundFreedChains) {
  // Pairs of squares on the diagonal through the park position (0, 0): the way back passes over
  // the chains already cut unless it goes around them.
  const auto dir = temp_dir("tipup_chain");
  std::vector<Rect> parts;
  for (int i = 0; i < 4; ++i) {
    const double o = 15.0 + i * 70;
    parts.push_back({o, o, o + 25, o + 25});
    parts.push_back({o + 30, o, o + 55, o + 25});
  }
  const auto dxf = write_nest(dir, parts, 320, 320);
  auto over = [&](const Program& p) {
    const auto runs = parts_of_runs(p, parts);
    int n = 0;
    for (const auto& [m, runs_before] : p.rapids) {
      std::vector<char> freed(parts.size(), 0);
      for (int r = 0; r < runs_before; ++r)
        for (int k : runs[static_cast<std::size_t>(r)]) freed[static_cast<std::size_t>(k)] = 1;
      bool hit = false;
      for (std::size_t k = 0; k < parts.size() && !hit; ++k)
        for (int s = 0; s <= 200 && freed[k] && !hit; ++s) {
          Vec2 q;
          probe_point(*m, s / 200.0, q.x, q.y);
          hit = parts[k].strictly_inside(q, 0.01);
        }
      n += hit;
    }
    return n;
  };
  const Program plain = optimize(dxf, dir, "", parts, "chain");
  ASSERT_EQ(plain.runs.size(), 4u);
  EXPECT_GT(over(plain), 0) << "the nest must make straight rapids pass over freed parts";
  const Program tip = optimize(dxf, dir, "--avoid-tip-up", parts, "chain");
  ASSERT_EQ(tip.runs.size(), 4u);
  EXPECT_EQ(over(tip), 0);
  EXPECT_EQ(tip.report["rules"]["tip_up_program"]["unavoidable"], 0);
  fs::remove_all(dir);
}

// Micro-joints with chain cutting: each chained part's loop gets its gaps; the bridge still leaves
// from where the loop ends and the compensation holds over the gaps and the bridge.
TEST(ShopRules, TabsWorkWithChains) {
  const auto dir = temp_dir("tabs_chain");
  const auto parts = pairs_in_a_row(30);
  const auto dxf = write_nest(dir, parts, 500, 100);
  const int n = 2;
  const double w = 1.5;
  const Program p = optimize(dxf, dir, "--tabs 2 --tab-width 1.5", parts, "chain");
  EXPECT_EQ(p.report["chosen"], "chain");
  // 4 chains of 2 parts, each part in n + 1 runs: 4 pierces + one after each gap.
  ASSERT_EQ(p.runs.size(), 4u + parts.size() * n);
  EXPECT_EQ(p.report["pierces"].get<std::size_t>(), p.runs.size());
  EXPECT_EQ(p.report["rules"]["tabs"]["tabs"], static_cast<int>(parts.size()) * n);
  EXPECT_EQ(p.report["rules"]["tabs"]["contours"], static_cast<int>(parts.size()));
  EXPECT_EQ(expect_admissible(dxf, p, n, w).bridges, 4);
  // The runs of a chain: the first part's n + 1 runs, the bridge in its last one, then the second
  // part's; every gap of a part lies between two of its own runs.
  const auto runs = parts_of_runs(p, parts);
  for (std::size_t i = 0; i < runs.size(); i += 2 * n + 1) {
    ASSERT_LE(i + 2 * n + 1, runs.size());
    ASSERT_EQ(runs[i].size(), 1u) << "run " << i;
    const int a = runs[i].front();
    for (std::size_t k = i; k < i + n; ++k) EXPECT_EQ(runs[k], std::vector<int>{a}) << "run " << k;
    ASSERT_EQ(runs[i + n].size(), 2u) << "run " << i + n << " ends the first part and crosses the bridge";
    const int b = runs[i + n][0] == a ? runs[i + n][1] : runs[i + n][0];
    for (std::size_t k = i + n + 1; k < i + 2 * n + 1; ++k) EXPECT_EQ(runs[k], std::vector<int>{b}) << "run " << k;
  }
  // One G41 per chain, and LinuxCNC with the kerf as its tool accepts the program.
  std::size_t g41 = 0;
  for (auto at = p.text.find("\nG41\n"); at != std::string::npos; at = p.text.find("\nG41\n", at + 1)) ++g41;
  EXPECT_EQ(g41, 4u);
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    const auto rs = run_rs274((dir / "out.ngc").string(), p.report["kerf_mm"].get<double>());
    EXPECT_EQ(rs.exit_code, 0) << rs.out;
  }
  // `auto` with tabs weighs standard and chain (and common lines, which these parts, 5 mm apart,
  // do not have).
  const Program a = optimize(dxf, dir, "--tabs 2 --tab-width 1.5", parts, "auto");
  std::vector<std::string> built;
  for (const auto& alt : a.report["alternatives"]) {
    if (alt["available"].get<bool>()) {
      built.push_back(alt["name"]);
    } else if (alt["name"] == "common") {
      EXPECT_NE(alt["reason"].get<std::string>().find("no two parts share an edge"), std::string::npos) << alt;
    }
  }
  EXPECT_EQ(built, (std::vector<std::string>{"standard", "chain"}));
  fs::remove_all(dir);
}

TEST(ShopRules, AutoComparesTechniquesByTimePlusTheRulesPrice) {
  const auto dir = temp_dir("heat_auto");
  const auto parts = pairs_in_a_row(30);
  const auto dxf = write_nest(dir, parts, 500, 100);
  for (const char* rule : {"--heat-distance 40", "--heat-distance 60 --heat-weight 1", "--sheet-clamp right --sheet-weight 1"}) {
    const Program p = optimize(dxf, dir, rule, parts, "auto");
    const auto& alts = p.report["alternatives"];
    double best = 1e300;
    std::string best_name;
    int available = 0;
    for (const auto& a : alts) {
      if (!a["available"].get<bool>()) continue;
      ++available;
      ASSERT_TRUE(a.contains("rules_penalty")) << rule;
      const double v = a["objective"].get<double>() + a["rules_penalty"].get<double>();
      if (v < best - 1e-9) best = v, best_name = a["name"].get<std::string>();
    }
    EXPECT_GE(available, 2) << rule << ": standard and chain are both built";
    EXPECT_EQ(p.report["chosen"], best_name) << rule;
  }
  fs::remove_all(dir);
}

TEST(ShopRules, BadRuleOptionsAreUsageErrors) {
  const auto dir = temp_dir("bad");
  const auto dxf = write_nest(dir, grid(2, 1), 160, 100);
  for (const char* bad : {"--sheet-clamp middle", "--tabs -1", "--heat-distance -3", "--tab-width 0", "--heat-memory 0",
                          "--tabs 2 --tab-lead-in sometimes"}) {
    const auto r = run_command(cli_path() + " optimize " + dxf + " -o " + (dir / "x.ngc").string() + " --quiet " + bad);
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_FALSE(fs::exists(dir / "x.ngc"));
  }
  // Part rigidity chooses each outer contour's entry: a technique that enters contours otherwise,
  // asked for, is refused with the reason.
  for (const auto& [bad, why] : std::vector<std::pair<std::string, std::string>>{
           {"--part-rigidity --technique chain", "--part-rigidity works with --technique standard only, not chain"},
           {"--part-rigidity --heat-distance 5 --technique multi", "--part-rigidity works with --technique standard only, not multi"}}) {
    const auto r = run_command(cli_path() + " optimize " + dxf + " -o " + (dir / "x.ngc").string() + " --quiet " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.ngc"));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cutroute::test
