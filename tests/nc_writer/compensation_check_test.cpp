// compensation_hazards() against LinuxCNC's interpreter: each small program is written with the
// generic dialect and run through rs274 with a tool of the kerf; the interpreter refuses it
// exactly when the check says the controller's offset cannot follow the path.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <cutroute/nc/compensation_check.hpp>
#include <cutroute/nc/gcode_writer.hpp>
#include <cutroute/nc/post_dialect.hpp>

#include "support/paths.hpp"

namespace cutroute::nc {
namespace {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

constexpr double kKerf = 0.2;  // tool radius 0.1 mm

// One compensated cut (G41: the tool left of the path) along `loop`, after a straight lead-in
// from `pierce` to its first point.
Toolpath cut(const Contour& loop, Vec2 pierce) {
  Toolpath tp;
  tp.pierce_time_s = 0.3;
  CutSegment s;
  s.pierce = pierce;
  s.kerf = KerfSide::left;
  s.feed_mm_min = 3000;
  s.label = "cut";
  s.pieces.push_back({Contour{{Vertex{pierce, 0}, Vertex{loop.vertices.front().p, 0}}, false}, PieceRole::lead_in, -1});
  s.pieces.push_back({loop, PieceRole::contour, 0});
  tp.segments.push_back(s);
  return tp;
}

// A 20 mm square from (0, 0), counter-clockwise (the tool, on the left, inside it: a hole), with
// `corner` in place of its corner (20, 20); closed back to (0, 0).
Contour hole(std::vector<Vertex> corner) {
  Contour c{{Vertex{{0, 0}, 0}, Vertex{{20, 0}, 0}}, false};
  for (const auto& v : corner) c.vertices.push_back(v);
  c.vertices.push_back({{0, 20}, 0});
  c.vertices.push_back({{0, 0}, 0});
  return c;
}

// A round hole of radius `radius` around (10, 10), counter-clockwise from (10 + radius, 10) in two
// half circles.
Contour round_hole(double radius) {
  return Contour{{Vertex{{10 + radius, 10}, 1.0}, Vertex{{10 - radius, 10}, 1.0}, Vertex{{10 + radius, 10}, 0}}, false};
}

bool refused_by_linuxcnc(const Toolpath& tp, const PostDialect& d) {
  const auto path = std::filesystem::temp_directory_path() / ("cutroute-comp-check-" + std::to_string(::getpid()) + ".ngc");
  std::ofstream(path) << write_gcode(tp, d, GcodeWriteOptions{}).text;
  const auto r = test::run_rs274(path.string(), kKerf);
  std::filesystem::remove(path);
  return r.exit_code != 0;
}

bool refused_by_linuxcnc(const Toolpath& tp, const char* dialect = "generic") {
  auto d = find_post_dialect(dialect);
  EXPECT_TRUE(d.ok());
  return refused_by_linuxcnc(tp, *d);
}

TEST(CompensationCheck, AgreesWithLinuxCncOnDetailsFinerThanTheKerf) {
  struct Case {
    const char* what;
    Toolpath path;
    bool at_risk;
  };
  const Vec2 inside{10, 3};
  // A quarter arc from (20, 20 - f) to (20 - f, 20) rounding the corner, bulge tan(90°/4).
  auto fillet = [](double f, double sign) {
    return std::vector<Vertex>{{{20, 20 - f}, sign * std::tan(std::numbers::pi / 8)}, {{20 - f, 20}, 0}};
  };
  const Case cases[] = {
      {"square hole", cut(hole({{{20, 20}, 0}}), inside), false},
      {"a 0.05 mm chamfer at an inside corner", cut(hole({{{20, 19.965}, 0}, {{19.965, 20}, 0}}), inside), true},
      {"a 1 mm chamfer at an inside corner", cut(hole({{{20, 19.3}, 0}, {{19.3, 20}, 0}}), inside), false},
      {"an inside fillet of radius 0.05 mm", cut(hole(fillet(0.05, 1)), inside), true},
      {"an inside fillet of radius 0.5 mm", cut(hole(fillet(0.5, 1)), inside), false},
      {"a lead-in of 0.05 mm", cut(hole({{{20, 20}, 0}}), {0.035, 0.035}), true},
      // A straight lead from the centre of a round hole: the offset lead (0.1 mm beside the centre
      // line) must cross the offset circle (radius R - 0.1), which it misses when R < 0.2 mm.
      {"a hole of radius 0.15 mm entered from its centre", cut(round_hole(0.15), {10, 10}), true},
      {"a hole of radius 0.5 mm entered from its centre", cut(round_hole(0.5), {10, 10}), false},
      // A drawing's micrometre steps, nearly straight (turns of 0.9°), along y = 0.0005: the program
      // rounds them to (10, 0) (10.001, 0.001) (10.003, 0), a 45° inside corner on a 1.4-um move.
      {"micrometre steps the program's rounding turns into a zig-zag",
       cut(Contour{{Vertex{{0, 0}, 0}, Vertex{{10, 0.00049}, 0}, Vertex{{10.0013, 0.00051}, 0}, Vertex{{10.0026, 0.00049}, 0},
                    Vertex{{20, 0}, 0}, Vertex{{20, 20}, 0}, Vertex{{0, 20}, 0}, Vertex{{0, 0}, 0}},
                   false},
           inside),
       true},
      {"the same steps on the grid, in a straight line",
       cut(Contour{{Vertex{{0, 0}, 0}, Vertex{{10, 0}, 0}, Vertex{{10.001, 0}, 0}, Vertex{{10.003, 0}, 0}, Vertex{{20, 0}, 0},
                    Vertex{{20, 20}, 0}, Vertex{{0, 20}, 0}, Vertex{{0, 0}, 0}},
                   false},
           inside),
       false},
  };
  for (const auto& c : cases) {
    const CompensationHazards h = compensation_hazards(c.path, kKerf / 2, true);
    EXPECT_EQ(h.compensated, 1) << c.what;
    EXPECT_EQ(h.at.size(), c.at_risk ? 1u : 0u) << c.what;
    if (c.at_risk) {
      EXPECT_EQ(h.at, std::vector<std::size_t>{0}) << c.what;  // the segment labelled "cut"
    }
    if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
      EXPECT_EQ(refused_by_linuxcnc(c.path), c.at_risk) << c.what;
    }
  }
  // Outside the part (the same square cut clockwise: the tool outside), a tight corner arc is no
  // obstacle: the offset goes round it.
  Contour outer = geometry::reversed(hole(fillet(0.05, 1)));
  const Toolpath convex = cut(outer, {-3, 0});
  EXPECT_TRUE(compensation_hazards(convex, kKerf / 2, true).at.empty());
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    EXPECT_FALSE(refused_by_linuxcnc(convex));
  }
  // Without compensation nothing is checked.
  Toolpath plain = cut(hole(fillet(0.05, 1)), inside);
  plain.segments[0].kerf = KerfSide::none;
  EXPECT_EQ(compensation_hazards(plain, kKerf / 2, true).compensated, 0);
}

// A 50 mm square cut clockwise (the tool outside) with a tab that ends 0.05 mm before the corner
// (0, 50): the piece after it begins with a 0.05 mm move. Where the compensation stays on over the
// tab (generic) that move is no entry and the corner is convex: nothing to refuse. Where it is
// switched on again (plasma-thc), the 0.05 mm move is the entry move, shorter than the tool radius.
TEST(CompensationCheck, APieceAfterATabIsNoEntryWhileTheCompensationHolds) {
  Toolpath tp = cut(Contour{{Vertex{{0, 0}, 0}, Vertex{{0, 48.95}, 0}}, false}, {-3, 0});
  CutSegment after;
  after.kerf = KerfSide::left;
  after.after_tab = true;
  after.feed_mm_min = 3000;
  after.label = "cut after tab 1";
  after.pierce = {0, 49.95};
  after.pieces.push_back(
      {Contour{{Vertex{{0, 49.95}, 0}, Vertex{{0, 50}, 0}, Vertex{{50, 50}, 0}, Vertex{{50, 0}, 0}, Vertex{{0, 0}, 0}}, false},
       PieceRole::contour, 0});
  tp.segments.push_back(after);
  const auto held = compensation_hazards(tp, kKerf / 2, true);
  EXPECT_EQ(held.compensated, 1);
  EXPECT_TRUE(held.at.empty());
  const auto switched = compensation_hazards(tp, kKerf / 2, false);
  EXPECT_EQ(switched.compensated, 2);
  EXPECT_EQ(switched.at, std::vector<std::size_t>{1});  // the segment "cut after tab 1"
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    EXPECT_FALSE(refused_by_linuxcnc(tp, "generic"));
    EXPECT_TRUE(refused_by_linuxcnc(tp, "plasma-thc"));
  }
}

// A point of the circle about c through p, turned by `turn` [rad] about c.
Vec2 turned(Vec2 c, Vec2 p, double turn) {
  const Vec2 v = p - c;
  return c + Vec2{v.x * std::cos(turn) - v.y * std::sin(turn), v.x * std::sin(turn) + v.y * std::cos(turn)};
}

// A line of 0.07 mm between two inside corners with arcs (the tool left): the arc before it turns
// into it by 60 degrees, the arc after it by 30. Each corner alone leaves the line long enough
// (its offset crosses the arc's 0.058 and 0.027 mm from the line's ends), both together do not,
// and LinuxCNC refuses the line once its end is moved back behind its start. At 0.1 mm it fits.
TEST(CompensationCheck, ALineLosesItsLengthAtBothOfItsCornersWithArcs) {
  for (const double length : {0.07, 0.1}) {
    const double radius = 5, sweep = std::numbers::pi / 6;
    const Vec2 p0{0, 0}, p1{0, -length};
    // Clockwise into p0, heading 150 degrees below the x axis; counter-clockwise out of p1, 60 below.
    const Vec2 c0 = p0 + Vec2{-0.5, std::sqrt(3.0) / 2} * radius;
    const Vec2 c1 = p1 + Vec2{std::sqrt(3.0) / 2, 0.5} * radius;
    const Vec2 start = turned(c0, p0, sweep);
    const double bulge = std::tan(sweep / 4);
    const Vec2 heading = geometry::perp(c0 - start) / radius;  // clockwise at the start
    const Toolpath tp = cut(Contour{{Vertex{start, -bulge}, Vertex{p0, 0}, Vertex{p1, bulge}, Vertex{turned(c1, p1, sweep), 0}}, false},
                            start - heading * 3);
    const bool fits = length > 0.08;
    EXPECT_EQ(compensation_hazards(tp, kKerf / 2, true).at.size(), fits ? 0u : 1u) << length;
    if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
      EXPECT_EQ(refused_by_linuxcnc(tp), !fits) << length;
    }
  }
}

// A line up to (1.02, 0.999) in and an arc on about (1, 1) to (1.001, 1.02), both ends 0.020025 in
// from the centre: the arc turns 0.05 rad from the line, under LinuxCNC's corner threshold, so the
// controller takes the tool on from where the line's offset ended, 0.012 rad before the arc's own
// offset start, and the arc, which ends at the G40, sweeps that much more than written. In a G20
// program the controller allows 0.001 rad and refuses it; the same path in millimetres (0.0254)
// passes.
TEST(CompensationCheck, AnArcTakenOnAtANearlyStraightJointMaySweepNoMoreThanWritten) {
  auto inches = [](double x, double y) { return Vec2{x * 25.4, y * 25.4}; };
  const Vec2 c = inches(1, 1), a = inches(1.02, 0.999), b = inches(1.001, 1.02);
  const double sweep = std::atan2(b.y - c.y, b.x - c.x) - std::atan2(a.y - c.y, a.x - c.x);
  const Toolpath tp = cut(Contour{{Vertex{inches(1.02, 0.959), 0}, Vertex{a, std::tan(sweep / 4)}, Vertex{b, 0}}, false},
                          inches(1, 0.93));
  auto generic = find_post_dialect("generic");
  ASSERT_TRUE(generic.ok());
  PostDialect inch = *generic;
  inch.name = "inch";
  inch.units = "in";
  EXPECT_EQ(compensation_hazards(tp, kKerf / 2, true, inch).at, std::vector<std::size_t>{0});
  EXPECT_TRUE(compensation_hazards(tp, kKerf / 2, true, *generic).at.empty());
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    EXPECT_TRUE(refused_by_linuxcnc(tp, inch));
    EXPECT_FALSE(refused_by_linuxcnc(tp, *generic));
  }
}

// A path that turns straight back, as a bridge retraced between two holes does: a counter-
// clockwise arc of radius R1 into P1, then back from P1 along a clockwise arc of radius R2 < R1
// tangent to it there (both centres on the same side). With the tool left of the path, LinuxCNC
// reads the turn as a concave corner whichever way rounding tips it, since the tool runs outside
// the second arc, and takes the crossing of the two offsets that its arc-to-arc rule names, not
// the nearer one; where that crossing lies past the first arc's end, the first arc sweeps more
// than written and is refused. Mirrored (clockwise, then counter-clockwise: the tool inside the
// second arc) the corner is convex and the tool goes round it. The check read both by the nearer
// crossing and by the sign rounding gave the turn: it flagged 8 of these 12 arcs that LinuxCNC
// runs, and the slit at the end, and passed such a turn in d2g_DRAAK that LinuxCNC refused.
TEST(CompensationCheck, APathTurningStraightBackAlongAnArc) {
  struct Case {
    double r1, r2, sweep1, sweep2;
    double mirror;  // 1: counter-clockwise then clockwise; -1: the mirror image
    double tilt;    // the second arc's start turned by this much off straight back [rad]
    bool refused;   // by LinuxCNC 2.9 (rs274)
  };
  const Case cases[] = {
      {100, 80, 0.3, 0.4, 1, 0, false},      {100, 99.5, 0.3, 0.3, 1, 0, true},     {20, 5, 0.5, 1.0, 1, 0, false},
      {100, 80, 0.3, 0.4, 1, 0.02, false},   {100, 80, 0.3, 0.4, 1, -0.02, false},  {100, 99.5, 0.3, 0.3, 1, 0.02, true},
      {100, 99.5, 0.3, 0.3, 1, -0.02, false}, {20, 5, 0.5, 1.0, 1, 0.04, false},    {20, 5, 0.5, 1.0, 1, -0.04, false},
      {100, 80, 0.3, 0.4, -1, 0, false},     {20, 5, 0.5, 1.0, -1, 0, false},       {100, 80, 0.3, 0.4, -1, 0.02, false}};
  const bool have_rs274 = std::system("command -v rs274 >/dev/null 2>&1") == 0;
  for (const auto& c : cases) {
    const Vec2 p1{0, 0}, t{1, 0}, n = geometry::perp(t) * c.mirror;  // heading +x at P1, centres on n
    const Vec2 c1 = p1 + n * c.r1, c2 = p1 + turned({0, 0}, n, c.tilt) * c.r2;
    const Vec2 p0 = turned(c1, p1, -c.mirror * c.sweep1), p2 = turned(c2, p1, -c.mirror * c.sweep2);
    const double b1 = c.mirror * std::tan(c.sweep1 / 4), b2 = -c.mirror * std::tan(c.sweep2 / 4);
    const Vec2 heading = geometry::perp(c1 - p0) * (c.mirror / c.r1);
    const Toolpath tp = cut(Contour{{Vertex{p0, b1}, Vertex{p1, b2}, Vertex{p2, 0}}, false}, p0 - heading * 3);
    const std::string what = "R1 " + std::to_string(c.r1) + ", R2 " + std::to_string(c.r2) + ", mirror " +
                             std::to_string(c.mirror) + ", tilt " + std::to_string(c.tilt);
    EXPECT_EQ(compensation_hazards(tp, kKerf / 2, true).at.empty(), !c.refused) << what;
    if (have_rs274) {
      EXPECT_EQ(refused_by_linuxcnc(tp), c.refused) << what;
    }
  }
  // Between lines a turn straight back is convex to LinuxCNC, whichever way rounding tips it: the
  // tool goes round the end of a slit drawn out from a hole's corner and back.
  for (const double tilt : {0.0, 0.03, -0.03}) {
    const Vec2 tip{25, 25}, back = turned(tip, {20, 20}, tilt);
    const Toolpath tp = cut(hole({{{20, 20}, 0}, {tip, 0}, {back, 0}}), {10, 3});
    EXPECT_TRUE(compensation_hazards(tp, kKerf / 2, true).at.empty()) << tilt;
    if (have_rs274) {
      EXPECT_FALSE(refused_by_linuxcnc(tp)) << tilt;
    }
  }
}

}  // namespace
}  // namespace cutroute::nc
