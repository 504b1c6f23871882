// `cutroute optimize --kerf-mode cam`: the written program re-parsed, every cut point measured
// against the drawn contours (independently of the offset code), and the kerf diagnostics.
// One pierce per contour is asserted below: these runs ask for the standard technique (chains are
// checked with cam kerf in the corpus test).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <tuple>

#include <cutroute/core/number_format.hpp>
#include <cutroute/io/nest_loader.hpp>
#include <cutroute/model/cut_job.hpp>
#include <cutroute/model/kerf_neighbours.hpp>
#include <cutroute/model/kerf_offset.hpp>

#include "optimize_run.hpp"
#include "support/dxf_builder.hpp"

namespace cutroute::test {
namespace {

namespace fs = std::filesystem;
using geometry::Vec2;
using geometry::Vertex;

const double kQuarter = std::tan(std::numbers::pi / 8);  // bulge of a 90° arc

// Rounded rectangle, counter-clockwise, corner radius r.
std::vector<Vertex> rounded_rect(double x0, double y0, double x1, double y1, double r) {
  return {{{x0 + r, y0}, 0},       {{x1 - r, y0}, kQuarter}, {{x1, y0 + r}, 0},       {{x1, y1 - r}, kQuarter},
          {{x1 - r, y1}, 0},       {{x0 + r, y1}, kQuarter}, {{x0, y1 - r}, 0},       {{x0, y0 + r}, kQuarter}};
}

// Obround slot from (x0, y) to (x1, y), width w.
std::vector<Vertex> slot(double x0, double x1, double y, double w) {
  const double h = w / 2;
  return {{{x0, y - h}, 0}, {{x1, y - h}, 1}, {{x1, y + h}, 0}, {{x0, y + h}, 1}};
}

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

// Parts with arcs, lines, concave corners, holes of several shapes and a part inside a hole.
std::string generated_nest() {
  DxfBuilder b;
  b.insunits(4);
  b.lwpolyline(rounded_rect(0, 0, 60, 40, 5), true);            // part 1 outer
  b.circle({15, 20}, 6);                                         // hole: circle
  b.lwpolyline(slot(34, 50, 20, 6), true);                       // hole: slot
  b.lwpolyline({{{80, 0}, 0}, {{120, 0}, 0}, {{120, 15}, 0}, {{95, 15}, 0}, {{95, 40}, 0}, {{80, 40}, 0}}, true);  // L
  b.lwpolyline({{{0, 60}, 0}, {{60, 60}, 0}, {{60, 120}, 0}, {{0, 120}, 0}}, true);  // frame
  b.lwpolyline({{{10, 70}, 0}, {{50, 70}, 0}, {{50, 110}, 0}, {{10, 110}, 0}}, true);  // its window
  b.circle({30, 90}, 8);                                         // a part inside the window
  b.circle({30, 90}, 3);                                         // with a hole
  b.lwpolyline(rounded_rect(80, 60, 120, 100, 12), true);        // big corner radii
  return b.str();
}

// Does the drawn contour have an arc the offset must keep (radius well above the kerf)?
bool has_real_arc(const geometry::Contour& c, double kerf) {
  for (std::size_t i = 0; i < geometry::segment_count(c); ++i) {
    const auto s = geometry::segment(c, i);
    if (s.is_arc() && s.radius() > 2 * kerf && s.length() > 2 * kerf) return true;
  }
  return false;
}

// Every contour cut once at kerf/2 on its scrap side, arcs as G2/G3, no controller compensation.
// `on_contour_mm`: 1 µm with the 4-decimal dialect (fine_dialect), more with 3 decimals.
void expect_cam_program(const std::string& dxf, const OptRun& run, double kerf, double on_contour_mm = 1e-3) {
  ProgramCheck check;
  expect_admissible(dxf, run, kerf / 2, &check, on_contour_mm);
  EXPECT_EQ(run.program.find("G41"), std::string::npos);
  EXPECT_EQ(run.program.find("G42"), std::string::npos);
  EXPECT_EQ(run.report["kerf_mode"], "cam");
  EXPECT_DOUBLE_EQ(run.report["kerf_mm"].get<double>(), kerf);
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  ASSERT_TRUE(loaded.ok());
  std::size_t k = 0;
  for (const auto& c : loaded->nest.contours) {
    if (c.role == model::ContourRole::sheet) continue;
    if (k < check.arc_moves.size() && has_real_arc(c.source.contour, kerf)) {
      EXPECT_GT(check.arc_moves[k], 0) << dxf << ": contour " << k + 1 << " has arcs but is cut in chords";
    }
    ++k;
  }
  // The report's sequence names the drawn contours, each once.
  std::set<int> named;
  for (const auto& e : run.report["sequence"]) named.insert(e["contour"].get<int>());
  EXPECT_EQ(named.size(), run.report["sequence"].size());
  EXPECT_EQ(named.size(), k);
}

TEST(KerfCam, GeneratedNestIsCutAtHalfTheKerfWithArcs) {
  const auto dir = temp_dir("cam-gen");
  const auto dxf = (dir / "gen.dxf").string();
  write(dxf, generated_nest());
  const std::string fine = fine_dialect(dir);
  for (double kerf : {0.3, 1.0}) {
    SCOPED_TRACE("kerf " + format_fixed(kerf, 2));
    OptRun run = optimize(dxf, dir, "--technique standard --kerf-mode cam --dialect " + fine + " --kerf " + format_fixed(kerf, 2));
    ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
    expect_cam_program(dxf, run, kerf);
    EXPECT_EQ(run.report["pierces"], 9);
    // The shipped generic dialect (1 µm): end points and arc centres (I, J) are each rounded by
    // up to 0.7 µm, so a point on an arc may be 2.5 µm off.
    run = optimize(dxf, dir, "--technique standard --kerf-mode cam --kerf " + format_fixed(kerf, 2));
    ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
    expect_cam_program(dxf, run, kerf, 2.5e-3);
    expect_rs274_accepts(dir / "out.ngc");
  }
  fs::remove_all(dir);
}

// The same nest in controller mode: the drawn contours with G41/G42; in cam mode the outer
// contours grow by 2π · kerf/2 (plain convex outlines) and the holes shrink by as much.
TEST(KerfCam, CutLengthChangesByTheOffsetOfConvexOutlines) {
  const auto dir = temp_dir("cam-len");
  const auto dxf = (dir / "one.dxf").string();
  DxfBuilder b;
  b.insunits(4);
  b.lwpolyline(rounded_rect(0, 0, 60, 40, 5), true);
  b.circle({20, 20}, 6);
  write(dxf, b.str());
  const double kerf = 0.3;  // within what the profile's leads (lead-out 0.5 mm) serve under compensation
  const std::string common = "--kerf " + format_fixed(kerf, 2);
  const OptRun ctl = optimize(dxf, dir, common + " --technique standard --kerf-mode controller");
  ASSERT_EQ(ctl.cmd.exit_code, 0) << ctl.cmd.err;
  EXPECT_NE(ctl.program.find("G41"), std::string::npos);
  const ProbeResult pc = probe_gcode(ctl.program);
  const OptRun cam = optimize(dxf, dir, common + " --technique standard --kerf-mode cam --dialect " + fine_dialect(dir));
  ASSERT_EQ(cam.cmd.exit_code, 0) << cam.cmd.err;
  expect_cam_program(dxf, cam, kerf);
  // Contour lengths: drawn outer 2·(50 + 30) + 2π·5, hole 2π·6; offsets: outer + 2π·0.15, hole - 2π·0.15.
  const ProbeResult pm = probe_gcode(cam.program);
  const double leads_ctl = pc.cut_length - (2 * 80 + 2 * std::numbers::pi * 5 + 2 * std::numbers::pi * 6);
  const double leads_cam = pm.cut_length - (2 * 80 + 2 * std::numbers::pi * 5.15 + 2 * std::numbers::pi * 5.85);
  EXPECT_NEAR(leads_ctl, leads_cam, 0.01);  // the same lead shapes around an offset contour
  fs::remove_all(dir);
}

TEST(KerfCam, DemoSheetSameOptionsSameBytes) {
  const auto dir = temp_dir("cam-det");
  const auto dxf = (dir / "demo.dxf").string();
  ASSERT_EQ(run_command(cli_path() + " demo " + dxf).exit_code, 0);
  const OptRun first = optimize(dxf, dir, "--technique standard --kerf-mode cam --seed 3 --threads 2 --dialect " + fine_dialect(dir));
  ASSERT_EQ(first.cmd.exit_code, 0) << first.cmd.err;
  expect_cam_program(dxf, first, first.report["kerf_mm"].get<double>());
  const std::string args = "--seed 7 --threads 2 --technique standard --kerf-mode cam";
  const std::string once = reproducible_outputs(dxf, (dir / "run0").string(), args);
  ASSERT_FALSE(once.empty());
  EXPECT_EQ(once, reproducible_outputs(dxf, (dir / "run1").string(), args));
  EXPECT_NE(once.find("cam (toolpath drawn offset by kerf/2)"), std::string::npos);  // the page says so
  fs::remove_all(dir);
}

// A 0.2 mm hole under a 0.3 mm kerf: the beam would burn it bigger than drawn. Refused, naming it.
TEST(KerfCam, HoleSmallerThanTheKerfIsAnInputError) {
  const auto dir = temp_dir("cam-small");
  const auto dxf = (dir / "small.dxf").string();
  DxfBuilder b;
  b.insunits(4);
  b.lwpolyline({{{0, 0}, 0}, {{20, 0}, 0}, {{20, 20}, 0}, {{0, 20}, 0}}, true);
  b.circle({10, 10}, 0.1);
  b.circle({5, 5}, 1.0);
  write(dxf, b.str());
  const auto prog = dir / "p.ngc";
  auto r = run_command(cli_path() + " optimize " + dxf + " -o " + prog.string() + " --quiet --kerf 0.3 --technique standard --kerf-mode cam");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("hole 2 (part 1) is too small for the kerf (0.3 mm)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(prog));
  // Controller mode leaves the offset to the machine and says nothing: the program is written.
  r = run_command(cli_path() + " optimize " + dxf + " -o " + prog.string() + " --quiet --kerf 0.3");
  EXPECT_EQ(r.exit_code, 0) << r.err;

  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  ASSERT_TRUE(loaded.ok());
  const auto kerf = model::offset_for_kerf(loaded->nest, 0.3);
  ASSERT_EQ(kerf.diagnostics.size(), 1u);
  EXPECT_EQ(kerf.diagnostics[0].code, "kerf.collapsed");
  EXPECT_EQ(kerf.diagnostics[0].severity, Severity::error);
  // Under a 0.15 mm kerf the 0.2 mm hole is cut: a toolpath of radius 0.025 mm.
  EXPECT_TRUE(model::offset_for_kerf(loaded->nest, 0.15).diagnostics.empty());
  fs::remove_all(dir);
}

// A part in a hole 0.2 mm from its edge all round, under a 0.3 mm kerf: the hole's toolpath shrinks
// and the part's grows past it, so the two never meet and the pair passed; each cut took 0.1 mm
// from the other (found by an audit: square and round rings). 0.4 mm apart is fine.
TEST(KerfCam, APartInAHoleCloserThanTheKerfAllRoundIsAnOverlap) {
  const auto dir = temp_dir("cam-ring");
  for (const double gap : {0.2, 0.4}) {
    for (const bool round : {false, true}) {
      const auto dxf = (dir / "ring.dxf").string();
      DxfBuilder b;
      b.insunits(4);
      if (round) {
        b.circle({50, 50}, 40).circle({50, 50}, 20).circle({50, 50}, 20 - gap);
      } else {
        b.lwpolyline({{{0, 0}, 0}, {{100, 0}, 0}, {{100, 100}, 0}, {{0, 100}, 0}}, true);
        b.lwpolyline({{{10, 10}, 0}, {{90, 10}, 0}, {{90, 90}, 0}, {{10, 90}, 0}}, true);
        const double a = 10 + gap, z = 90 - gap;
        b.lwpolyline({{{a, a}, 0}, {{z, a}, 0}, {{z, z}, 0}, {{a, z}, 0}}, true);
      }
      write(dxf, b.str());
      auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
      ASSERT_TRUE(loaded.ok());
      const auto kerf = model::offset_for_kerf(loaded->nest, 0.3);
      std::size_t overlaps = 0;
      for (const auto& d : kerf.diagnostics) {
        overlaps += d.code == "kerf.overlap" && d.severity == Severity::error;
        if (d.code == "kerf.overlap") {
          EXPECT_NE(d.message.find("pass each other"), std::string::npos) << d.message;
        }
      }
      EXPECT_EQ(overlaps, gap < 0.3 ? 1u : 0u) << "gap " << gap << (round ? " round" : " square");
    }
  }
  fs::remove_all(dir);
}

// With the controller's compensation (the default) parts less than a kerf apart were cut without a
// word: side by side 0.2 mm under a 0.3 mm kerf, or a part in a hole 0.2 mm from its edge. Exactly
// a kerf apart loses nothing; touching is the nest's own diagnostic (nest.kerf_loss).
TEST(KerfController, PartsCloserThanTheKerfAreSaid) {
  const auto dir = temp_dir("ctl-close");
  const auto dxf = (dir / "close.dxf").string();
  const auto square = [](DxfBuilder& b, double x0, double y0, double x1, double y1) {
    b.lwpolyline({{{x0, y0}, 0}, {{x1, y0}, 0}, {{x1, y1}, 0}, {{x0, y1}, 0}}, true);
  };
  for (const auto& [gap, ring, pairs] :
       {std::tuple{0.2, false, 1u}, std::tuple{0.2, true, 1u}, std::tuple{0.3, false, 0u}, std::tuple{0.0, false, 0u}}) {
    DxfBuilder b;
    b.insunits(4);
    square(b, 0, 0, 40, 40);
    if (ring) {
      square(b, 5, 5, 35, 35);
      square(b, 5 + gap, 5 + gap, 35 - gap, 35 - gap);
    } else {
      square(b, 40 + gap, 0, 80, 40);
    }
    write(dxf, b.str());
    auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
    ASSERT_TRUE(loaded.ok());
    const auto close = model::closer_than_kerf(loaded->nest, 0.3, 1e-6);
    EXPECT_EQ(close.pairs, pairs) << gap << (ring ? " ring" : " side");
    if (pairs == 0 || ring) continue;
    EXPECT_NEAR(close.near.x, 40, 1e-9);
    auto r = optimize(dxf, dir, "--kerf 0.3 --technique standard");
    ASSERT_EQ(r.cmd.exit_code, 0) << r.cmd.err;
    EXPECT_NE(r.cmd.err.find("1 pair(s) of contours lie closer than the kerf (0.3 mm) without touching"), std::string::npos)
        << r.cmd.err;
    int said = 0;
    for (const auto& d : r.report["diagnostics"]) said += d.value("code", "") == "nest.closer_than_kerf";
    EXPECT_EQ(said, 1);
  }
  fs::remove_all(dir);
}

// Parts 0.2 mm apart under a 0.3 mm kerf: cutting one cuts into the other.
TEST(KerfCam, PartsCloserThanTheKerfAreRefusedUnlessAllowed) {
  const auto dir = temp_dir("cam-close");
  const auto dxf = (dir / "close.dxf").string();
  DxfBuilder b;
  b.insunits(4);
  b.lwpolyline({{{0, 0}, 0}, {{20, 0}, 0}, {{20, 20}, 0}, {{0, 20}, 0}}, true);
  b.lwpolyline({{{20.2, 0}, 0}, {{40, 0}, 0}, {{40, 20}, 0}, {{20.2, 20}, 0}}, true);
  b.lwpolyline({{{0, 30}, 0}, {{20, 30}, 0}, {{20, 50}, 0}, {{0, 50}, 0}}, true);
  b.lwpolyline({{{20.4, 30}, 0}, {{40, 30}, 0}, {{40, 50}, 0}, {{20.4, 50}, 0}}, true);  // 0.4 apart: fine
  write(dxf, b.str());
  auto r = optimize(dxf, dir, "--kerf 0.3 --technique standard --kerf-mode cam");
  EXPECT_EQ(r.cmd.exit_code, 2);
  EXPECT_NE(r.cmd.err.find("the toolpaths of contour 1 (part 1) and contour 2 (part 2) meet"), std::string::npos) << r.cmd.err;
  EXPECT_NE(r.cmd.err.find("--allow-kerf-overlap"), std::string::npos) << r.cmd.err;
  EXPECT_EQ(r.cmd.err.find("more kerf errors"), std::string::npos) << r.cmd.err;  // the 0.4 mm pair is fine

  r = optimize(dxf, dir, "--kerf 0.3 --technique standard --kerf-mode cam --allow-kerf-overlap --dialect " + fine_dialect(dir));
  ASSERT_EQ(r.cmd.exit_code, 0) << r.cmd.err;
  int overlaps = 0;
  for (const auto& d : r.report["diagnostics"]) overlaps += d.value("code", "") == "kerf.overlap";
  EXPECT_EQ(overlaps, 1);
  expect_cam_program(dxf, r, 0.3);
  fs::remove_all(dir);
}

// The same in an inch drawing: the place was named in mm (25.4 times off for anyone looking at
// the drawing), as every message's was before positions followed the drawing's unit.
TEST(KerfCam, AnInchDrawingsOverlapIsNamedInInches) {
  const auto dir = temp_dir("cam-close-inch");
  const auto dxf = (dir / "close.dxf").string();
  DxfBuilder b;
  b.insunits(1);
  b.lwpolyline({{{0, 0}, 0}, {{1, 0}, 0}, {{1, 1}, 0}, {{0, 1}, 0}}, true);
  b.lwpolyline({{{1.008, 0}, 0}, {{2, 0}, 0}, {{2, 1}, 0}, {{1.008, 1}, 0}}, true);  // 0.2 mm apart
  write(dxf, b.str());
  const auto r = optimize(dxf, dir, "--kerf 0.3 --technique standard --kerf-mode cam");
  EXPECT_EQ(r.cmd.exit_code, 2);
  EXPECT_NE(r.cmd.err.find("meet near (1.004, "), std::string::npos) << r.cmd.err;
  EXPECT_NE(r.cmd.err.find(") in: the contours are closer than the kerf"), std::string::npos) << r.cmd.err;
  fs::remove_all(dir);
}

// Two holes that touch at a point, as in d2g_DRAAK: a square hole's corner and the tip of a 4°
// wedge. The wedge's toolpath stops 2.15 mm short of its tip (kerf/2 / sin 2°), so a lead into
// the square's corner keeps the clearance from every toolpath and still passes 0.25 mm from the
// wedge's drawn tip. With the drawing given (what `optimize --kerf-mode cam` does), every entry
// the planner admits keeps clearance - kerf/2 from the other drawn contours, measured here
// point by point; without it, the corner entry is admitted (the case this guards).
TEST(KerfCam, LeadsKeepClearOfDrawnTipsTheToolpathCannotReach) {
  const auto dir = temp_dir("cam-tip");
  const auto dxf = (dir / "tip.dxf").string();
  DxfBuilder b;
  b.insunits(4);
  b.lwpolyline({{{-30, -30}, 0}, {{30, -30}, 0}, {{30, 30}, 0}, {{-30, 30}, 0}}, true);  // part
  b.lwpolyline({{{-10, -10}, 0}, {{0, -10}, 0}, {{0, 0}, 0}, {{-10, 0}, 0}}, true);      // square hole
  const double half = 2.0 * std::numbers::pi / 180, len = 15;
  const double a0 = std::numbers::pi / 4 - half, a1 = std::numbers::pi / 4 + half;
  b.lwpolyline({{{0, 0}, 0}, {{len * std::cos(a0), len * std::sin(a0)}, 0}, {{len * std::cos(a1), len * std::sin(a1)}, 0}}, true);
  write(dxf, b.str());
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  ASSERT_TRUE(loaded.ok());
  const model::Nest& drawn = loaded->nest;
  const double kerf = 0.15;
  const auto offset = model::offset_for_kerf(drawn, kerf);
  for (const auto& d : offset.diagnostics) ASSERT_NE(d.severity, Severity::error) << d.message;
  // Which contour is the square hole, which the wedge.
  model::ContourId square, wedge;
  for (std::size_t i = 0; i < drawn.contours.size(); ++i) {
    const model::ContourId id(static_cast<std::int32_t>(i));
    if (drawn.contours[id].role != model::ContourRole::hole) continue;
    (drawn.contours[id].area_mm2 > 50 ? square : wedge) = id;
  }
  ASSERT_TRUE(square.valid() && wedge.valid());

  model::EntryOptions eo;
  eo.kerf_mm = kerf;
  eo.lead.in_length_mm = 2;
  eo.lead.in_arc_radius_mm = 1;
  eo.free_direction = true;
  const double need = kerf + 1.0 - kerf / 2;  // default clearance (kerf + 1 mm) less the offset
  // The closest any lead-in or pierce of an admitted entry of the square comes to the drawn wedge.
  auto closest_to_wedge = [&](const model::EntryPlanner& planner) {
    double closest = 1e9;
    const auto& w = drawn.contours[wedge].source.contour;
    auto measure = [&](const model::EntryCandidate& e) {
      closest = std::min(closest, geometry::closest_point(w, e.pierce).distance);
      const double l = geometry::length(e.lead_in);
      for (int k = 0; k <= 50; ++k)
        closest = std::min(closest, geometry::closest_point(w, geometry::point_at_length(e.lead_in, l * k / 50)).distance);
    };
    Diagnostics diags;
    for (const auto& e : planner.candidates(square, diags)) measure(e);
    const double total = planner.contour_length(square);
    for (int k = 0; k < 4000; ++k)
      for (bool cw : {false, true})
        if (auto e = planner.entry_at(square, total * k / 4000, cw)) measure(*e);
    return closest;
  };
  const model::EntryPlanner toolpaths_only(offset.nest, eo);
  EXPECT_LT(closest_to_wedge(toolpaths_only), 0.3);  // entries next to the corner: 0.24 mm from the tip
  eo.drawn = &drawn;
  const model::EntryPlanner with_drawing(offset.nest, eo);
  EXPECT_GE(closest_to_wedge(with_drawing), need - 1e-6);
  fs::remove_all(dir);
}

// The checker can fail: the drawn contours (controller mode) are not a cam cut, nor is a cam cut
// with the wrong kerf, nor the cam cut read as if it were on the drawing.
TEST(KerfCam, CheckerRejectsCutsAtTheWrongDistance) {
  const auto dir = temp_dir("cam-neg");
  const auto dxf = (dir / "gen.dxf").string();
  write(dxf, generated_nest());
  const std::string fine = fine_dialect(dir);
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  ASSERT_TRUE(loaded.ok());
  ProgramCheckOptions opt;
  opt.on_contour_mm = 1e-3;
  const OptRun ctl = optimize(dxf, dir, "--kerf 0.3 --technique standard --kerf-mode controller --dialect " + fine);
  ASSERT_EQ(ctl.cmd.exit_code, 0) << ctl.cmd.err;
  opt.kerf_offset_mm = 0.15;
  EXPECT_FALSE(check_program(loaded->nest, ctl.program, opt).failures.empty());
  const OptRun cam = optimize(dxf, dir, "--kerf 0.3 --technique standard --kerf-mode cam --dialect " + fine);
  ASSERT_EQ(cam.cmd.exit_code, 0) << cam.cmd.err;
  EXPECT_TRUE(check_program(loaded->nest, cam.program, opt).failures.empty());
  opt.kerf_offset_mm = 0.148;  // 2 µm off
  EXPECT_FALSE(check_program(loaded->nest, cam.program, opt).failures.empty());
  opt.kerf_offset_mm = 0.0;
  opt.on_contour_mm = 0.005;
  EXPECT_FALSE(check_program(loaded->nest, cam.program, opt).failures.empty());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cutroute::test
