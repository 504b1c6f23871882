// The G-code writer: exact text for formatting rules, meaning checked by re-parsing (tests/support).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <cutroute/core/version.hpp>
#include <cutroute/nc/gcode_reader.hpp>
#include <cutroute/nc/gcode_writer.hpp>

#include "support/gcode_probe.hpp"
#include "support/paths.hpp"

namespace cutroute::nc {
namespace {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

const double kPi = std::numbers::pi;

// A 100 x 50 rectangle cut clockwise from (0,0) after a 5 mm straight lead-in from (-5,0).
Toolpath square_path() {
  Toolpath tp;
  tp.start = {0, 0};
  tp.end = {0, 0};
  tp.pierce_time_s = 0.5;
  CutSegment s;
  s.pierce = {-5, 0};
  s.feed_mm_min = 6000;
  s.label = "part 1 outer";
  s.pieces.push_back({Contour{{Vertex{{-5, 0}, 0}, Vertex{{0, 0}, 0}}, false}, PieceRole::lead_in, -1});
  s.pieces.push_back({Contour{{Vertex{{0, 0}, 0}, Vertex{{0, 50}, 0}, Vertex{{100, 50}, 0}, Vertex{{100, 0}, 0},
                               Vertex{{0, 0}, 0}},
                              false},
                      PieceRole::contour, 0});
  tp.segments.push_back(s);
  return tp;
}

// A full circle of radius r around c, as two half arcs, cut counter-clockwise from its left point.
Toolpath circle_path(Vec2 c, double r) {
  Toolpath tp;
  tp.pierce_time_s = 0.2;
  CutSegment s;
  s.pierce = {c.x - r, c.y};
  s.feed_mm_min = 3000;
  s.pieces.push_back({Contour{{Vertex{{c.x - r, c.y}, 1}, Vertex{{c.x + r, c.y}, 1}, Vertex{{c.x - r, c.y}, 0}}, false},
                      PieceRole::contour, 0});
  tp.segments.push_back(s);
  return tp;
}

TEST(GcodeWriter, ExactTextOfASimpleProgram) {
  const auto w = write_gcode(square_path(), PostDialect{}, GcodeWriteOptions{"square", true});
  EXPECT_EQ(w.text,
            "(square)\n"
            "G21\n"
            "G17 G90 G40 G94\n"
            "(part 1 outer)\n"
            "G0 X-5 Y0\n"
            "M3 S1\n"
            "G4 P0.5\n"
            "G1 X0 Y0 F6000\n"
            "G1 X0 Y50\n"
            "G1 X100 Y50\n"
            "G1 X100 Y0\n"
            "G1 X0 Y0\n"
            "M5\n"
            "M30\n");  // the head already stands at the park point: no zero-length rapid
  EXPECT_EQ(w.pierces, 1u);
  EXPECT_DOUBLE_EQ(w.cut_length_mm, 305.0);
  EXPECT_DOUBLE_EQ(w.rapid_length_mm, 5.0);
}

// Comments carry file names and labels: parentheses would end or nest the comment, and many
// controllers alarm on bytes outside ASCII, so each non-ASCII character is one '?' (a stray
// non-UTF-8 byte too) and control codes are spaces. The program is ASCII throughout.
TEST(GcodeWriter, CommentsAreAsciiWithoutParentheses) {
  Toolpath tp = square_path();
  tp.segments[0].label = "part 1 outer \xC3\xA9\xE2\x82\xAC\xF0\x9F\x94\xA9 \xE9\tx";
  const auto w = write_gcode(tp, PostDialect{}, GcodeWriteOptions{"cutroute Blech_gro\xC3\x9F (2).dxf", true});
  EXPECT_EQ(w.text.substr(0, w.text.find('\n')), "(cutroute Blech_gro?  2 .dxf)");
  EXPECT_NE(w.text.find("\n(part 1 outer ??? ? x)\n"), std::string::npos) << w.text;
  for (const char c : w.text) EXPECT_LT(static_cast<unsigned char>(c), 0x80);
}

TEST(GcodeWriter, HalfArcsBecomeG3WithIncrementalCentre) {
  const auto w = write_gcode(circle_path({10, 20}, 5), PostDialect{}, GcodeWriteOptions{});
  EXPECT_NE(w.text.find("G3 X15 Y20 I5 J0 F3000\n"), std::string::npos) << w.text;
  EXPECT_NE(w.text.find("G3 X5 Y20 I-5 J0\n"), std::string::npos) << w.text;
  EXPECT_NEAR(w.cut_length_mm, 2 * kPi * 5, 1e-9);
}

TEST(GcodeWriter, ReparsedProgramHasTheMeasuredLengths) {
  for (auto arc : {ArcFormat::ij, ArcFormat::r}) {
    PostDialect d;
    d.arc_format = arc;
    Toolpath tp = circle_path({123.4567, -89.0123}, 17.77777);
    tp.segments.push_back(square_path().segments.front());
    const auto w = write_gcode(tp, d, GcodeWriteOptions{});
    const auto probe = test::probe_gcode(w.text);
    ASSERT_TRUE(probe.errors.empty());
    EXPECT_EQ(probe.pierces, 2);
    EXPECT_FALSE(probe.cut_with_beam_off);
    EXPECT_TRUE(probe.ended);
    EXPECT_NEAR(probe.cut_length, w.cut_length_mm, 1e-9);
    EXPECT_NEAR(probe.rapid_length, w.rapid_length_mm, 1e-6);
    // Quantised to 1 µm: the circle's length is kept to the resolution.
    EXPECT_NEAR(w.cut_length_mm, 2 * kPi * 17.77777 + 305, 0.01);
    EXPECT_LT(probe.max_arc_radius_error, 0.002);
  }
}

// Found by fuzzing: an edge of bulge 1e-8 was written "G2 ... J2500000000", and slightly jittered
// spline arcs had centres beyond 1e6 mm; controllers and our own reader refuse such words. Arcs of
// radius above 100 m are written as chords within the output resolution.
TEST(GcodeWriter, NearlyStraightArcsBecomeChordsTheReaderAccepts) {
  const double c = 3000, radius = 2.0e5;
  const double b = std::tan(std::asin(c / 2 / radius) / 2);  // bulge of that radius over that chord
  Toolpath tp;
  tp.pierce_time_s = 0.2;
  CutSegment s;
  s.pierce = {0, 0};
  s.feed_mm_min = 3000;
  s.pieces.push_back({Contour{{Vertex{{0, 0}, 1e-8}, Vertex{{10, 0}, b}, Vertex{{10 + c, 0}, 0}}, false}, PieceRole::contour, 0});
  tp.segments.push_back(s);
  const auto w = write_gcode(tp, PostDialect{}, GcodeWriteOptions{});
  EXPECT_EQ(w.text.find("\nG2 "), std::string::npos) << w.text;
  EXPECT_EQ(w.text.find("\nG3 "), std::string::npos) << w.text;
  const auto read = read_gcode(w.text, "flat.nc", ReadOptions{});
  ASSERT_TRUE(read.ok()) << format(read.error());
  const auto probe = test::probe_gcode(w.text);
  ASSERT_TRUE(probe.errors.empty());
  const Vec2 centre{10 + c / 2, std::sqrt(radius * radius - c * c / 4)};  // b > 0: counter-clockwise, centre to the left
  int chords = 0;
  for (const auto& m : probe.moves) {
    if (m.rapid || m.x0 < 10 - 1e-9) continue;
    ++chords;
    // Every chord end on the circle, every chord's middle within 1 µm (plus rounding) of it.
    EXPECT_NEAR(std::hypot(m.x1 - centre.x, m.y1 - centre.y), radius, 1e-3);
    EXPECT_NEAR(std::hypot((m.x0 + m.x1) / 2 - centre.x, (m.y0 + m.y1) / 2 - centre.y), radius, 2e-3);
  }
  EXPECT_GT(chords, 20);
  EXPECT_NEAR(w.cut_length_mm, 10 + 2 * radius * std::asin(c / 2 / radius), 0.01);
}

TEST(GcodeWriter, RFormatSplitsArcsAbove150Degrees) {
  PostDialect d;
  d.arc_format = ArcFormat::r;
  const auto w = write_gcode(circle_path({0, 0}, 10), d, GcodeWriteOptions{});
  const auto probe = test::probe_gcode(w.text);
  int arcs = 0;
  for (const auto& m : probe.moves) arcs += m.arc != 0;
  EXPECT_EQ(arcs, 4);  // each half circle split in two quarter arcs
  EXPECT_EQ(w.text.find(" R-"), std::string::npos);
  EXPECT_NEAR(probe.cut_length, 2 * kPi * 10, 1e-3);
}

TEST(GcodeWriter, NeverWritesNegativeZeroAndRoundsToResolution) {
  Toolpath tp = square_path();
  tp.start = {50, 50};
  tp.segments[0].pierce = {-0.0001, 1e-7};
  tp.segments[0].pieces[0].path.vertices[0].p = {-0.0001, 1e-7};
  const auto w = write_gcode(tp, PostDialect{}, GcodeWriteOptions{});
  EXPECT_EQ(w.text.find("-0 "), std::string::npos);
  EXPECT_EQ(w.text.find("-0\n"), std::string::npos);
  EXPECT_NE(w.text.find("G0 X0 Y0\n"), std::string::npos) << w.text;
}

TEST(GcodeWriter, InchDialectConvertsCoordinatesAndFeed) {
  PostDialect d;
  d.units = "in";
  d.decimals = 4;
  d.feed_decimals = 1;
  const auto w = write_gcode(square_path(), d, GcodeWriteOptions{});
  EXPECT_NE(w.text.find("G20\n"), std::string::npos);
  EXPECT_NE(w.text.find("G1 X0 Y1.9685\n"), std::string::npos) << w.text;  // 50 mm
  EXPECT_NE(w.text.find("F236.2\n"), std::string::npos) << w.text;          // 6000 mm/min
  const auto probe = test::probe_gcode(w.text);
  EXPECT_NEAR(probe.cut_length, 305.0, 0.01);
}

// The placeholders are filled in header and footer lines too (the job's feed, its pierce time),
// in the dialect's units: a literal "F{feed}" was a block no controller reads.
TEST(GcodeWriter, HeaderAndFooterPlaceholdersAreFilled) {
  PostDialect d;
  d.header = {"G17 G90 G40 G94", "F{feed}"};
  d.footer = {"(pierce {pierce_s} s)"};
  auto w = write_gcode(square_path(), d, GcodeWriteOptions{});
  EXPECT_NE(w.text.find("\nF6000\n"), std::string::npos) << w.text;
  EXPECT_NE(w.text.find("(pierce 0.5 s)\nM30\n"), std::string::npos) << w.text;
  EXPECT_EQ(w.text.find('{'), std::string::npos) << w.text;
  d.units = "in";
  d.decimals = 4;
  d.feed_decimals = 1;
  w = write_gcode(square_path(), d, GcodeWriteOptions{});
  EXPECT_NE(w.text.find("\nF236.2\n"), std::string::npos) << w.text;
}

// A dialect writing 2 or 1 decimals: every arc it writes is one the reader accepts (end on the
// circle within 0.01 mm), and the program's length stays within the grid of the exact one. At 2
// decimals the rounded centre lay up to 0.014 mm nearer one end (8 of the 27 corpus programs
// refused); at 1 decimal arcs go as chords.
TEST(GcodeWriter, CoarseDialectsWriteArcsTheReaderAccepts) {
  std::srand(11);
  auto u = [] { return static_cast<double>(std::rand()) / RAND_MAX; };
  Toolpath tp;
  tp.pierce_time_s = 0.2;
  double exact = 0;
  for (int i = 0; i < 300; ++i) {
    CutSegment seg;
    const Vec2 a{1000 * u(), 1000 * u()};
    const double angle = 6.283185307179586 * u(), chord = 0.5 + 80 * u(), bulge = (u() < 0.5 ? -1 : 1) * (0.05 + 1.5 * u());
    const Vec2 b = a + Vec2{chord * std::cos(angle), chord * std::sin(angle)};
    seg.pierce = a;
    seg.feed_mm_min = 3000;
    const Contour c{{Vertex{a, bulge}, Vertex{b, 0}}, false};
    exact += geometry::length(c);
    seg.pieces.push_back({c, PieceRole::contour, 0});
    tp.segments.push_back(seg);
  }
  for (const int decimals : {2, 1}) {
    PostDialect d;
    d.decimals = decimals;
    const auto w = write_gcode(tp, d, GcodeWriteOptions{});
    const auto r = read_gcode(w.text, "coarse.nc", ReadOptions{});
    ASSERT_TRUE(r.ok()) << decimals << ": " << format(r.error());
    EXPECT_NEAR(r->cut_length_mm, exact, exact * (decimals == 2 ? 1e-4 : 1e-3)) << decimals;
    EXPECT_NEAR(r->cut_length_mm, w.cut_length_mm, 1e-6 * exact) << decimals;
  }
}

TEST(GcodeWriter, LineNumbersThcAndKerfCodesFromTheDialect) {
  auto d = find_post_dialect("plasma-thc");
  ASSERT_TRUE(d.ok()) << format(d.error());
  Toolpath tp = square_path();
  tp.segments[0].kerf = KerfSide::left;
  tp.segments[0].pieces.push_back({Contour{{Vertex{{0, 0}, 0}, Vertex{{-3, -3}, 0}}, false}, PieceRole::lead_out, -1});
  const auto w = write_gcode(tp, *d, GcodeWriteOptions{});
  EXPECT_EQ(w.text.find("N10 G21\n"), 0u) << w.text;
  // Under G41 no digital output may be switched (LinuxCNC): THC around the compensated block.
  auto on = w.text.find("M65 P0"), off = w.text.find("M64 P0");
  const auto g41 = w.text.find("G41"), g40 = w.text.find("G40");
  ASSERT_NE(on, std::string::npos);
  ASSERT_NE(off, std::string::npos);
  EXPECT_LT(on, g41);
  EXPECT_GT(off, g40);
  // Without compensation: THC released after the lead-in and held again before the lead-out.
  tp.segments[0].kerf = KerfSide::none;
  const auto w2 = write_gcode(tp, *d, GcodeWriteOptions{});
  on = w2.text.find("M65 P0");
  off = w2.text.find("M64 P0");
  const auto first_contour_move = w2.text.find("X0 Y50");
  EXPECT_LT(w2.text.find("G1 X0 Y0"), on);
  EXPECT_LT(on, first_contour_move);
  EXPECT_GT(off, first_contour_move);
  EXPECT_LT(off, w2.text.find("X-3 Y-3"));
}

TEST(PostDialect, ErrorsNameTheField) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto write = [&](const std::string& name, const std::string& text) {
    const auto p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  };
  auto r = load_post_dialect(write("d1.json", R"({"decimals": "three"})"));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("'decimals'"), std::string::npos);
  r = load_post_dialect(write("d2.json", R"({"arc_fromat": "r"})"));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("unknown dialect field 'arc_fromat'"), std::string::npos);
  r = load_post_dialect(write("d3.json", R"({"arc_format": "xy"})"));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("'arc_format'"), std::string::npos);
  // Found by fuzzing: 2147483640 + step overflowed int, 2147483648 wrapped to N-2147483648.
  r = load_post_dialect(write("d5.json", R"({"line_numbers": true, "line_number_start": 2147483648})"));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("'line_number_start' is out of range"), std::string::npos) << r.error().message;
  r = load_post_dialect(write("d6.json", R"({"line_numbers": true, "line_number_start": 2147483640})"));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("'line_number_start' must be 0..99999999"), std::string::npos) << r.error().message;
  r = load_post_dialect(write("d4.json", "{ not json"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().file, (dir / "d4.json").string());
  r = find_post_dialect("no-such-dialect");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("generic"), std::string::npos);
  for (const char* name : {"d1.json", "d2.json", "d3.json", "d4.json", "d5.json", "d6.json"}) std::filesystem::remove(dir / name);
}

TEST(PostDialect, ShippedDialectsLoad) {
  for (const char* name : {"generic", "plasma-thc"}) {
    auto d = find_post_dialect(name);
    ASSERT_TRUE(d.ok()) << format(d.error());
    EXPECT_EQ(d->name, name);
  }
}

// LinuxCNC's own interpreter must accept every program we write (installed by
// scripts/install-deps; the test says so and stops when it is missing).
// Spline fits leave arcs of a micrometre or two at cusps; LinuxCNC refuses arcs below its 0.005 mm
// tolerance ("zero-radius arc"), so they are written as chords within the resolution.
TEST(GcodeWriter, MicrometreArcsBecomeChords) {
  Toolpath tp = square_path();
  // A half circle of radius 1.5 um between (0, 0) and (0, 0.003), then on up the edge.
  tp.segments[0].pieces[1].path = Contour{{Vertex{{0, 0}, 1.0}, Vertex{{0, 0.003}, 0}, Vertex{{0, 50}, 0}}, false};
  auto d = find_post_dialect("generic");
  ASSERT_TRUE(d.ok());
  const auto w = write_gcode(tp, *d, GcodeWriteOptions{});
  EXPECT_EQ(w.text.find("\nG2 "), std::string::npos) << w.text;
  EXPECT_EQ(w.text.find("\nG3 "), std::string::npos) << w.text;
  EXPECT_NE(w.text.find("G1 X0 Y50"), std::string::npos) << w.text;
  // A 0.05 mm arc stays an arc.
  tp.segments[0].pieces[1].path = Contour{{Vertex{{0, 0}, 1.0}, Vertex{{0, 0.1}, 0}, Vertex{{0, 50}, 0}}, false};
  EXPECT_NE(write_gcode(tp, *d, GcodeWriteOptions{}).text.find("G3 X0 Y0.1 I0 J0.05"), std::string::npos);
  if (std::system("command -v rs274 >/dev/null 2>&1") != 0) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const auto path = std::filesystem::temp_directory_path() / "cutroute-rs274-micro-arc.ngc";
  std::ofstream(path) << w.text;
  const auto r = test::run_rs274(path.string());
  EXPECT_EQ(r.exit_code, 0) << r.err << "\n" << w.text;
  std::filesystem::remove(path);
}

// The rectangle of square_path() with two tabs: one in the middle of the first edge, one round the
// corner (0, 50); the pieces after them resume on the contour. With compensation the generic
// dialect keeps G41 on over both gaps (one G41 .. G40 for the contour) and its rapid follows the
// gap's corner; plasma-thc, whose THC outputs LinuxCNC refuses under G41, switches it per piece.
Toolpath tabbed_square() {
  Toolpath tp = square_path();
  CutSegment first = tp.segments.front();
  first.kerf = KerfSide::left;
  first.pieces[1].path = Contour{{Vertex{{0, 0}, 0}, Vertex{{0, 24}, 0}}, false};
  CutSegment second;
  second.kerf = KerfSide::left;
  second.feed_mm_min = first.feed_mm_min;
  second.after_tab = true;
  second.pierce = {0, 26};
  second.pieces.push_back({Contour{{Vertex{{0, 26}, 0}, Vertex{{0, 49}, 0}}, false}, PieceRole::contour, 0});
  CutSegment third = second;
  third.pierce = {1, 50};
  third.rapid_via = {{0, 50}};
  third.pieces[0].path = Contour{{Vertex{{1, 50}, 0}, Vertex{{100, 50}, 0}, Vertex{{100, 0}, 0}, Vertex{{0, 0}, 0}}, false};
  tp.segments = {first, second, third};
  return tp;
}

std::size_t count_blocks(const std::string& text, const std::string& block) {
  std::size_t n = 0;
  for (auto at = text.find("\n" + block + "\n"); at != std::string::npos; at = text.find("\n" + block + "\n", at + 1)) ++n;
  return n;
}

TEST(GcodeWriter, CompensationStaysOnOverTabs) {
  auto generic = find_post_dialect("generic");
  auto plasma = find_post_dialect("plasma-thc");
  ASSERT_TRUE(generic.ok() && plasma.ok());
  const Toolpath tp = tabbed_square();
  const auto g = write_gcode(tp, *generic, GcodeWriteOptions{});
  EXPECT_EQ(count_blocks(g.text, "G41"), 1u) << g.text;
  EXPECT_EQ(count_blocks(g.text, "G40"), 1u) << g.text;  // the header's G40 shares its line
  EXPECT_EQ(g.pierces, 3u);
  EXPECT_NE(g.text.find("M5\nG0 X0 Y50\nG0 X1 Y50\nM3"), std::string::npos) << g.text;
  const auto p = write_gcode(tp, *plasma, GcodeWriteOptions{});
  std::size_t g41 = 0;
  for (auto at = p.text.find(" G41\n"); at != std::string::npos; at = p.text.find(" G41\n", at + 1)) ++g41;
  EXPECT_EQ(g41, 3u) << p.text;
  // Under a tool of 0.2 mm the interpreter offsets the path and checks it for gouges: the held
  // compensation passes; switched on again on the contour after a tab it would enter on a cut.
  if (std::system("command -v rs274 >/dev/null 2>&1") != 0) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const auto path = std::filesystem::temp_directory_path() / "cutroute-rs274-tabs.ngc";
  // Where the interpreter puts the tool on the left edge (x = 0, cut upwards, tool on its left):
  // the end points of the moves there, x of each.
  auto left_edge_xs = [](const std::string& canon) {
    std::vector<double> xs;
    std::istringstream in(canon);
    for (std::string line; std::getline(in, line);) {
      const auto at = line.find("STRAIGHT_");
      if (at == std::string::npos) continue;
      double x = 0, y = 0;
      if (std::sscanf(line.c_str() + line.find('(', at) + 1, "%lf, %lf", &x, &y) != 2) continue;
      if (y > 1 && y < 49.5 && std::abs(x) < 1) xs.push_back(x);
    }
    return xs;
  };
  for (const auto* w : {&g, &p}) {
    std::ofstream(path) << w->text;
    const auto r = test::run_rs274(path.string(), 0.2);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err << "\n" << w->text;
    const auto xs = left_edge_xs(r.out);
    ASSERT_GE(xs.size(), 3u) << r.out;  // before the tab, over the gap, after it
    const bool on_offset = std::all_of(xs.begin(), xs.end(), [](double x) { return std::abs(x + 0.1) < 1e-3; });
    // Held (generic): the whole edge on the offset path. Switched on again on the contour
    // (plasma-thc): the gap's rapid ends on the contour and the entry move slants from there.
    EXPECT_EQ(on_offset, w == &g) << r.out;
  }
  std::filesystem::remove(path);
}

TEST(GcodeWriter, LinuxCncInterpreterAcceptsOurPrograms) {
  if (std::system("command -v rs274 >/dev/null 2>&1") != 0) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  for (const char* name : {"generic", "plasma-thc"}) {
    auto d = find_post_dialect(name);
    ASSERT_TRUE(d.ok());
    Toolpath tp = circle_path({50, 50}, 20);
    tp.segments.push_back(square_path().segments.front());
    tp.segments.back().kerf = KerfSide::left;
    const auto w = write_gcode(tp, *d, GcodeWriteOptions{"rs274 check"});
    const auto path = std::filesystem::temp_directory_path() / (std::string("cutroute-rs274-") + name + ".ngc");
    std::ofstream(path) << w.text;
    const auto r = test::run_rs274(path.string());
    EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.out << r.err << "\n" << w.text;
    std::filesystem::remove(path);
  }
}

}  // namespace
}  // namespace cutroute::nc
