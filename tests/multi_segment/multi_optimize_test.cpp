// `cutroute optimize` with multi-segment cutting: the written program re-parsed (every contour
// covered by its pieces, holes first, leads in scrap), the GSCCP choice, options and their errors.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include <cutroute/core/number_format.hpp>
#include <cutroute/io/nest_loader.hpp>

#include "frame_nest.hpp"
#include "optimize/optimize_run.hpp"
#include "support/program_check.hpp"

namespace cutroute::test {
namespace {

namespace fs = std::filesystem;

std::string write_frame(const fs::path& dir) {
  const auto dxf = (dir / "frame.dxf").string();
  std::ofstream(dxf) << frame_nest_dxf();
  return dxf;
}

// `cutroute demo`: the paper-like sheet, 21 contours.
std::string write_demo(const fs::path& dir) {
  const auto dxf = (dir / "demo.dxf").string();
  EXPECT_EQ(run_command(cli_path() + " demo " + dxf).exit_code, 0);
  return dxf;
}

// The cut contour index (nest order, sheet left out) of the frame: the longest one.
std::size_t frame_index(const std::string& dxf) {
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  std::size_t k = 0, best = 0;
  double longest = 0;
  for (const auto& c : loaded->nest.contours) {
    if (c.role == model::ContourRole::sheet) continue;
    if (geometry::length(c.source.contour) > longest) {
      longest = geometry::length(c.source.contour);
      best = k;
    }
    ++k;
  }
  return best;
}

const nlohmann::json* alternative(const nlohmann::json& report, const std::string& name) {
  for (const auto& a : report["alternatives"])
    if (a["name"] == name) return &a;
  return nullptr;
}

// The frame between the start and the far parts: in two pieces the head cuts its length both
// ways instead of crossing it twice by rapid. Chosen by the objective, and the program is sound.
TEST(MultiOptimize, LongFrameIsCutInTwoPiecesWhenThatIsFaster) {
  const auto dir = temp_dir("multi-win");
  const auto dxf = write_frame(dir);
  const auto svg = (dir / "out.svg").string();
  const OptRun run = optimize(dxf, dir, "--multi-segment --svg " + svg);
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  EXPECT_EQ(run.report["technique"], "auto");
  ASSERT_EQ(run.report["chosen"], "multi");
  const auto* multi = alternative(run.report, "multi");
  ASSERT_NE(multi, nullptr);
  for (const auto& a : run.report["alternatives"])
    if (a["available"] == true && a["name"] != "multi") {
      EXPECT_LT((*multi)["objective"].get<double>(), a["objective"].get<double>()) << a;
    }
  EXPECT_EQ((*multi)["basic_segments"], 7);

  ProgramCheck check;
  expect_admissible(dxf, run, 0.0, &check);
  const std::size_t frame = frame_index(dxf);
  EXPECT_EQ(check.split_contours, 1);
  ASSERT_GT(check.runs_per_contour.size(), frame);
  EXPECT_EQ(check.runs_per_contour[frame], 2);
  EXPECT_EQ(check.runs, 7);
  expect_rs274_accepts(dir / "out.ngc");

  // Cut whole instead, the same nest needs over a metre more rapid travel (recomputed from both
  // programs) and more time.
  const auto std_dir = dir / "standard";
  fs::create_directories(std_dir);
  const OptRun whole = optimize(dxf, std_dir, "--technique standard");
  ASSERT_EQ(whole.cmd.exit_code, 0) << whole.cmd.err;
  ProgramCheck whole_check;
  expect_admissible(dxf, whole, 0.0, &whole_check);
  EXPECT_GT(whole_check.rapid_length, check.rapid_length + 1000.0);
  EXPECT_EQ(whole_check.runs + 1, check.runs);
  EXPECT_GT(whole.report["t_cut_s"].get<double>(), run.report["t_cut_s"].get<double>());

  // The report's sequence and the program's comments name the pieces; the picture draws them.
  int pieces = 0;
  for (const auto& e : run.report["sequence"]) {
    if (!e.contains("pieces")) continue;
    EXPECT_EQ(e["pieces"], nlohmann::json::array({"contour_part"}));
    EXPECT_EQ(e["contour"].get<std::size_t>(), frame + 1);
    ++pieces;
  }
  EXPECT_EQ(pieces, 2);
  EXPECT_NE(run.program.find("piece 1 of 2"), std::string::npos);
  EXPECT_NE(run.program.find("piece 2 of 2"), std::string::npos);
  const std::string picture = read_text(svg);
  int drawn = 0;
  for (auto at = picture.find("class=\"piece\""); at != std::string::npos; at = picture.find("class=\"piece\"", at + 1)) ++drawn;
  EXPECT_EQ(drawn, 2);
  fs::remove_all(dir);
}

// Without --multi-segment, `auto` compares standard, chain and common only, as before.
TEST(MultiOptimize, AutoLeavesMultiOutUnlessAsked) {
  const auto dir = temp_dir("multi-default");
  const auto dxf = write_frame(dir);
  const OptRun run = optimize(dxf, dir);
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  EXPECT_EQ(alternative(run.report, "multi"), nullptr);
  EXPECT_NE(run.report["chosen"], "multi");
  ProgramCheck check;
  expect_admissible(dxf, run, 0.0, &check);
  EXPECT_EQ(check.split_contours, 0);
  fs::remove_all(dir);
}

// On the demo sheet the extra pierces cost more than the rapids they save: multi loses.
TEST(MultiOptimize, DemoSheetKeepsWholeContours) {
  const auto dir = temp_dir("multi-demo");
  const auto dxf = write_demo(dir);
  const OptRun run = optimize(dxf, dir, "--multi-segment");
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  const auto* multi = alternative(run.report, "multi");
  ASSERT_NE(multi, nullptr);
  ASSERT_EQ((*multi)["available"], true) << *multi;
  EXPECT_NE(run.report["chosen"], "multi");
  EXPECT_GT((*multi)["objective"].get<double>(), run.report["t_cut_s"].get<double>());
  EXPECT_GT((*multi)["pierces"].get<int>(), run.report["pierces"].get<int>());
  expect_admissible(dxf, run);
  fs::remove_all(dir);
}

// Asked for explicitly, the demo sheet is cut with its long contours in pieces: every contour
// covered once by its pieces, holes and inner parts before any piece, leads in scrap. The same
// with the order rules, which price pieces like whole contours (two pieces of one contour are
// "close" for heat); their search never worsens the route's price under them.
TEST(MultiOptimize, DemoSheetInPiecesIsAdmissible) {
  for (const std::string rules : {"", "--heat-distance 30 --sheet-clamp bottom --avoid-tip-up"}) {
    const auto dir = temp_dir("multi-demo-forced");
    const auto dxf = write_demo(dir);
    const OptRun run = optimize(dxf, dir, "--technique multi " + rules);
    ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
    EXPECT_EQ(run.report["chosen"], "multi");
    ProgramCheck check;
    expect_admissible(dxf, run, 0.0, &check);
    EXPECT_GE(check.split_contours, 1);
    if (rules.empty()) {
      EXPECT_EQ(check.probe.pierces, 21 + check.split_contours);
      expect_rs274_accepts(dir / "out.ngc");
    } else {
      const auto& r = run.report["rules"];
      EXPECT_EQ(r["active"], nlohmann::json::array({"heat", "tip_up", "sheet_rigidity"}));
      EXPECT_LE(r["search"]["final_s"].get<double>(), r["search"]["solver_route_s"].get<double>() + 1e-9);
    }
    fs::remove_all(dir);
  }
}

// Three pieces per split contour (--multi-pieces 3).
TEST(MultiOptimize, FrameInThreePieces) {
  const auto dir = temp_dir("multi-three");
  const auto dxf = write_frame(dir);
  const OptRun run = optimize(dxf, dir, "--technique multi --multi-pieces 3");
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  ProgramCheck check;
  expect_admissible(dxf, run, 0.0, &check);
  EXPECT_EQ(check.runs_per_contour[frame_index(dxf)], 3);
  EXPECT_NE(run.program.find("piece 3 of 3"), std::string::npos);
  fs::remove_all(dir);
}

// Controller compensation follows each piece's direction: scrap is outside the frame, so a piece
// running counter-clockwise (the frame's centre on its left) has G42, clockwise G41.
TEST(MultiOptimize, KerfSideFollowsThePieceDirection) {
  const auto dir = temp_dir("multi-kerf");
  const auto dxf = write_frame(dir);
  const OptRun run = optimize(dxf, dir, "--technique multi");
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  std::vector<std::string> lines;
  {
    std::istringstream in(run.program);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  const auto& r = kFrameNest[0];
  const double cx = r.x + r.w / 2, cy = r.y + r.h / 2;
  const auto probe = probe_gcode(run.program);
  int judged = 0;
  for (const auto& m : probe.moves) {
    // A long cut along a long edge of the frame: the frame's pieces.
    if (m.rapid || !m.beam_on || m.arc != 0 || m.length < 1000) continue;
    const double turn = (m.x1 - m.x0) * (cy - m.y0) - (m.y1 - m.y0) * (cx - m.x0);
    std::string side;
    for (int i = m.line - 1; i-- > 0 && side.empty();) {
      if (lines[static_cast<std::size_t>(i)].find("G41") != std::string::npos) side = "G41";
      if (lines[static_cast<std::size_t>(i)].find("G42") != std::string::npos) side = "G42";
    }
    EXPECT_EQ(side, turn > 0 ? "G42" : "G41") << "line " << m.line;
    ++judged;
  }
  EXPECT_EQ(judged, 2);
  fs::remove_all(dir);
}

// --kerf-mode cam: the pieces are stretches of the offset toolpath; together they cover it.
TEST(MultiOptimize, CamKerfPiecesCoverTheOffsetContour) {
  const auto dir = temp_dir("multi-cam");
  const auto dxf = write_frame(dir);
  const OptRun run = optimize(dxf, dir, "--technique multi --kerf-mode cam --kerf 0.3 --dialect " + fine_dialect(dir));
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  ProgramCheck check;
  expect_admissible(dxf, run, 0.15, &check);
  EXPECT_EQ(check.runs_per_contour[frame_index(dxf)], 2);
  EXPECT_EQ(run.program.find("G41"), std::string::npos);
  EXPECT_EQ(run.program.find("G42"), std::string::npos);
  fs::remove_all(dir);
}

// --objective cost (eq. 3, F = L_off C_off + L_on C_on + N_pt C_pt): the price of a pierce decides.
// Cheap pierces: the frame in pieces wins; dear ones: it loses. F recomputed from the programs.
TEST(MultiOptimize, CostObjectiveDecidesByThePiercePrice) {
  const auto dir = temp_dir("multi-cost");
  const auto dxf = write_frame(dir);
  for (const double c_pt : {0.01, 5.0}) {
    SCOPED_TRACE("C_pt " + format_fixed(c_pt, 2));
    auto machine = nlohmann::json::parse(read_text(test_data("../../data/machines/bystar3015.json")));
    machine["speed_table"] = fs::absolute(test_data("../../data/materials/bystar3015.json")).string();
    machine["costs"] = {{"unit", "EUR"}, {"c_on_per_m", 0.5}, {"c_off_per_m", 0.5}, {"c_pt", c_pt}};
    const auto profile = dir / "machine.json";
    std::ofstream(profile) << machine.dump(2);
    const OptRun run = optimize(dxf, dir, "--multi-segment --objective cost --machine " + profile.string());
    ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
    ProgramCheck check;
    expect_admissible(dxf, run, 0.0, &check);
    const double f = check.rapid_length / 1000 * 0.5 + check.cut_length / 1000 * 0.5 + check.probe.pierces * c_pt;
    EXPECT_NEAR(run.report["cost"].get<double>(), f, 1e-9 * f);
    const auto* multi = alternative(run.report, "multi");
    ASSERT_NE(multi, nullptr);
    const double f_multi = (*multi)["rapid_length_mm"].get<double>() / 1000 * 0.5 +
                           (*multi)["cut_length_mm"].get<double>() / 1000 * 0.5 + (*multi)["pierces"].get<double>() * c_pt;
    EXPECT_NEAR((*multi)["objective"].get<double>(), f_multi, 1e-9 * f_multi);
    EXPECT_EQ(run.report["chosen"] == "multi", c_pt < 1) << run.report["alternatives"];
  }
  fs::remove_all(dir);
}

TEST(MultiOptimize, SameSeedSameBytes) {
  const auto dir = temp_dir("multi-det");
  const auto dxf = write_frame(dir);
  const std::string args = "--seed 7 --threads 2 --time-limit 0.5 --multi-segment";
  const std::string first = reproducible_outputs(dxf, (dir / "run0").string(), args);
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first, reproducible_outputs(dxf, (dir / "run1").string(), args));
  EXPECT_NE(first.find("piece 2 of 2"), std::string::npos);
  fs::remove_all(dir);
}

// Micro-joints on split contours: each part keeps its N gaps, spread over its pieces at least
// max(w, 1 mm) + w/2 from where the pieces meet (a gap at a junction would be cut by the other
// piece's start), and the frame is held: cut in 2 pieces + 2 gaps = 4 runs, every other outer
// contour in 3. The program re-parsed: each contour covered but for its gaps, holes first, leads
// in scrap; LinuxCNC accepts it with the kerf as its tool.
TEST(MultiOptimize, TabsAreSpreadOverThePiecesAwayFromTheirJunctions) {
  const auto dir = temp_dir("multi-tabs");
  const auto dxf = write_frame(dir);
  const double w = 1.5;
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  ASSERT_TRUE(loaded.ok());
  const std::size_t frame = frame_index(dxf);
  const geometry::Contour& f = loaded->nest.contours[model::ContourId(static_cast<std::int32_t>(frame))].source.contour;
  // With one tab the spread puts it where the first piece's usable length ends: at the second
  // piece's margin, the closest a gap may come to a junction.
  for (const int tabs : {2, 1}) {
    const OptRun run = optimize(dxf, dir, "--technique multi --tab-width 1.5 --tabs " + std::to_string(tabs));
    ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
    EXPECT_EQ(run.report["rules"]["tabs"]["tabs"], 5 * tabs);  // 5 outer contours (the frame, 4 parts)
    ProgramCheckOptions opt;
    opt.clearance_mm = 1.0;
    opt.tabs = tabs;
    opt.tab_width_mm = w;
    opt.max_runs_per_contour = 2;
    const auto check = check_program(loaded->nest, run.program, opt);
    for (const auto& e : check.failures) ADD_FAILURE() << tabs << ": " << e;
    ASSERT_GT(check.runs_per_contour.size(), frame);
    EXPECT_EQ(check.runs_per_contour[frame], 2 + tabs);
    EXPECT_EQ(check.split_contours, 1);
    // The frame's pieces start at its split points, two opposite corners. Every place where the
    // beam goes off and on again on the frame's edge is a gap end, at least max(w, 1 mm) from both
    // (straight distance: the nearest lie on the same edge).
    const auto probe = probe_gcode(run.program);
    std::vector<geometry::Vec2> ends;
    bool on = false;
    geometry::Vec2 last{};
    for (const auto& m : probe.moves) {
      const geometry::Vec2 a{m.x0, m.y0}, b{m.x1, m.y1};
      if (m.beam_on && !m.rapid) {
        if (!on && geometry::distance(f, a) < 1e-3) ends.push_back(a);
        on = true;
        last = b;
      } else if (m.rapid) {
        if (on && geometry::distance(f, last) < 1e-3) ends.push_back(last);
        on = false;
      }
    }
    const std::vector<geometry::Vec2> splits = {{50, 100}, {1550, 180}};
    int gap_ends = 0;
    for (const auto& e : ends) {
      const double d = std::min(geometry::distance(e, splits[0]), geometry::distance(e, splits[1]));
      if (d < 1e-3) continue;  // a piece's own start or end
      ++gap_ends;
      EXPECT_GE(d, std::max(w, 1.0) - 1e-3) << tabs << ": " << e.x << ", " << e.y;
    }
    EXPECT_EQ(gap_ends, 2 * tabs) << "each gap ended and resumed on the frame";
    expect_rs274_accepts(dir / "out.ngc");
  }
  fs::remove_all(dir);
}

// Refused with a clear message: part rigidity (one lead-in per contour) with multi, a nest without a
// contour long enough, option values out of range.
TEST(MultiOptimize, BadCombinationsAreRefused) {
  const auto dir = temp_dir("multi-bad");
  const auto dxf = write_frame(dir);
  const auto prog = (dir / "p.ngc").string();
  const std::string base = cli_path() + " optimize " + dxf + " -o " + prog + " --quiet --time-limit 0.2 ";
  auto r = run_command(base + "--multi-segment --part-rigidity");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not with --multi-segment"), std::string::npos) << r.err;
  r = run_command(base + "--technique chain --multi-segment");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not with --technique chain"), std::string::npos) << r.err;
  r = run_command(base + "--technique multi --multi-min-span 2000");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("multi-segment cutting not available"), std::string::npos) << r.err;
  // With auto the missing alternative is listed, not an error.
  const OptRun listed = optimize(dxf, dir, "--multi-segment --multi-min-span 2000");
  ASSERT_EQ(listed.cmd.exit_code, 0) << listed.cmd.err;
  const auto* multi = alternative(listed.report, "multi");
  ASSERT_NE(multi, nullptr);
  EXPECT_EQ((*multi)["available"], false);
  for (const char* bad : {"--multi-pieces 1", "--multi-pieces 9", "--multi-min-span -1", "--technique ecp"}) {
    r = run_command(base + bad);
    EXPECT_EQ(r.exit_code, 1) << bad;
  }
  EXPECT_FALSE(fs::exists(prog));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cutroute::test

namespace cutroute::test {
namespace {

// Every drawing of ../shared/data/dxf cut with --technique multi (half a second of solver time):
// where some contour is long enough the program cuts it in pieces that cover it, holes first,
// leads in scrap; where none is, the refusal says so (exit 2).
class CorpusMulti : public ::testing::TestWithParam<std::string> {};

TEST_P(CorpusMulti, ProgramIsAdmissibleOrNotAvailable) {
  const std::string dxf = shared("data/dxf/" + GetParam() + ".dxf");
  const auto dir = temp_dir(GetParam() + "-multi");
  const OptRun run = optimize(dxf, dir, "--allow-crossing --technique multi", sanitized() ? "2" : "0.5");
  if (run.cmd.exit_code == 2) {
    EXPECT_NE(run.cmd.err.find("multi-segment cutting not available"), std::string::npos) << run.cmd.err;
  } else {
    ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
    ProgramCheck check;
    expect_admissible(dxf, run, 0.0, &check);
    EXPECT_GE(check.split_contours, 1);
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(AllFiles, CorpusMulti, ::testing::ValuesIn(corpus()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

}  // namespace
}  // namespace cutroute::test
