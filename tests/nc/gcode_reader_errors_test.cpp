// Broken programs: one defect per file in tests/data/nc/bad/, each with its exact line and message.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include <cutroute/nc/gcode_reader.hpp>

#include "support/paths.hpp"

namespace cutroute::nc {
namespace {

struct BadCase {
  const char* file;
  long line;
  const char* message_part;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.file; }

class BrokenProgram : public ::testing::TestWithParam<BadCase> {};

TEST_P(BrokenProgram, ErrorNamesFileLineAndDefect) {
  const auto& c = GetParam();
  const std::string path = test::test_data(std::string("nc/bad/") + c.file);
  auto r = read_gcode_file(path, ReadOptions{});
  ASSERT_FALSE(r.ok()) << c.file;
  EXPECT_EQ(r.error().severity, Severity::error);
  EXPECT_EQ(r.error().file, path);
  ASSERT_TRUE(r.error().line.has_value());
  EXPECT_EQ(*r.error().line, c.line) << format(r.error());
  EXPECT_NE(r.error().message.find(c.message_part), std::string::npos) << format(r.error());
}

INSTANTIATE_TEST_SUITE_P(
    Files, BrokenProgram,
    ::testing::Values(BadCase{"malformed_number_two_dots.nc", 4, "malformed number after X"},
                      BadCase{"malformed_number_sign_only.nc", 4, "malformed number after Y"},
                      BadCase{"missing_number.nc", 4, "word Y has no number"},
                      BadCase{"decimal_comma.nc", 4, "malformed number after X"},
                      BadCase{"exponent_number.nc", 3, "malformed number after X"},
                      BadCase{"arc_radius_mismatch.nc", 4, "arc end is not on its circle"},
                      BadCase{"arc_radius_too_small.nc", 4, "shorter than half the chord"},
                      BadCase{"arc_without_centre.nc", 4, "without I/J or R"},
                      BadCase{"no_program_end.nc", 6, "no program end"},
                      BadCase{"unclosed_comment.nc", 2, "not closed"},
                      BadCase{"nested_comment.nc", 2, "comment opened inside a comment (column 10)"},
                      BadCase{"plane_g18.nc", 1, "only the XY plane"},
                      BadCase{"axis_without_motion_mode.nc", 2, "without a motion mode"},
                      BadCase{"duplicate_word.nc", 3, "appears twice"},
                      BadCase{"parameter_expression.nc", 2, "unsupported character '#'"},
                      BadCase{"dwell_without_p.nc", 4, "G4 dwell without P"}),
    [](const ::testing::TestParamInfo<BadCase>& p) {
      std::string n = p.param.file;
      n = n.substr(0, n.find('.'));
      return n;
    });

// An I/J arc whose end is off its circle is refused where LinuxCNC refuses it (beyond 2·0.01·√2 mm
// and 0.1 % of the start radius; in G20 2·0.001·√2 in), warned beyond the reader's own 0.01 mm /
// 0.002 in. The limits were found by bisection with rs274 2.9: radius 10 mm accepted up to
// 0.02828 mm, 100 mm up to 0.1000 mm, 1 in up to 0.002828 in, 10 in up to 0.01000 in.
TEST(BrokenProgramInline, ArcRadiusToleranceIsTheControllers) {
  const auto arc = [](const char* units, const char* r, const char* end_x) {
    return std::string(units) + "\nG0 X" + r + "\nM3\nG2 X-" + end_x + " Y0 I-" + r + " J0 F100\nM30\n";
  };
  const auto codes = [](const ProgramStats& s) {
    std::vector<std::string> c;
    for (const auto& w : s.warnings) c.push_back(w.code);
    return c;
  };
  const std::vector<std::string> off{"gcode.arc_off_circle"};
  // 0.005 mm off the circle: read without a word (tol::kGcodeArcRadiusMm = 0.01 mm).
  auto s = read_gcode(arc("G21", "10", "10.005"), "a.nc", ReadOptions{});
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(s->warnings.empty());
  // 0.02 and 0.028 mm at radius 10: LinuxCNC runs them (as a spiral), so they are read, and said.
  for (const char* e : {"10.02", "10.028"}) {
    s = read_gcode(arc("G21", "10", e), "a.nc", ReadOptions{});
    ASSERT_TRUE(s.ok()) << e;
    EXPECT_EQ(codes(*s), off) << e;
    EXPECT_EQ(s->warnings[0].line, 4);
  }
  // 0.029 mm at radius 10 (0.29 %): refused, as LinuxCNC does.
  auto bad = read_gcode(arc("G21", "10", "10.029"), "a.nc", ReadOptions{});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("LinuxCNC"), std::string::npos) << bad.error().message;
  // At radius 100 the relative limit rules: 0.099 mm run, 0.101 mm refused.
  EXPECT_TRUE(read_gcode(arc("G21", "100", "100.099"), "a.nc", ReadOptions{}).ok());
  EXPECT_FALSE(read_gcode(arc("G21", "100", "100.101"), "a.nc", ReadOptions{}).ok());
  // Inch programs: 0.0015 in (0.038 mm) is rounding of 0.001 in output, silent; 0.0025 in is run
  // and said; 0.003 in is refused; at 10 in 0.0099 in is run.
  s = read_gcode(arc("G20", "1", "1.0015"), "a.nc", ReadOptions{});
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(s->warnings.empty());
  s = read_gcode(arc("G20", "1", "1.0025"), "a.nc", ReadOptions{});
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(codes(*s), off);
  EXPECT_FALSE(read_gcode(arc("G20", "1", "1.003"), "a.nc", ReadOptions{}).ok());
  EXPECT_TRUE(read_gcode(arc("G20", "10", "10.0099"), "a.nc", ReadOptions{}).ok());
  EXPECT_FALSE(read_gcode(arc("G20", "10", "10.0102"), "a.nc", ReadOptions{}).ok());
  // The spiral is measured at its mean radius: 10.01 mm over half a turn.
  s = read_gcode(arc("G21", "10", "10.02"), "a.nc", ReadOptions{});
  ASSERT_TRUE(s.ok());
  EXPECT_NEAR(s->cut_length_mm, 10.01 * std::numbers::pi, 1e-9);
}

TEST(BrokenProgramInline, AbsurdCoordinatesAndEmptyInput) {
  EXPECT_FALSE(read_gcode("G0 X1e3\nM30\n", "a.nc", ReadOptions{}).ok());
  auto far = read_gcode("G0 X2000000\nM30\n", "a.nc", ReadOptions{});
  ASSERT_FALSE(far.ok());
  EXPECT_EQ(*far.error().line, 1);
  auto empty = read_gcode("", "empty.nc", ReadOptions{});
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().message.find("no program end"), std::string::npos);
  EXPECT_FALSE(read_gcode("G1 X1 F-5\nM30\n", "a.nc", ReadOptions{}).ok());
  EXPECT_FALSE(read_gcode("G0 X0\nG2 X0 Y0 R5\nM30\n", "a.nc", ReadOptions{}).ok());  // R full circle
  EXPECT_FALSE(read_gcode("G0 X0\nG2 X5 I0 J0\nM30\n", "a.nc", ReadOptions{}).ok());  // zero radius
  EXPECT_FALSE(read_gcode("G90.1\nG0 X5\nG2 X-5 I0\nM30\n", "a.nc", ReadOptions{}).ok());
  EXPECT_FALSE(read_gcode("G0 X5\nG2 X-5 R5 I-5\nM30\n", "a.nc", ReadOptions{}).ok());
  const std::string binary("G0 X1\n\x01\x02\xff\nM30\n", 15);
  auto bin = read_gcode(binary, "bin.nc", ReadOptions{});
  ASSERT_FALSE(bin.ok());
  EXPECT_EQ(*bin.error().line, 2);
}

// Found by fuzzing: two dwells of 10^78 s summed to infinity, and a denormal feed made a cut last
// forever; both reported a total of "inf" (JSON null) with exit 0.
TEST(BrokenProgramInline, DwellsAndFeedsThatOverflowTheTotals) {
  const std::string huge = "G4 P" + std::string(79, '9') + "\n";
  auto dwell = read_gcode("G21\nG0 X1\nM3\n" + huge + huge + "G1 X10 F1000\nM5\nM30\n", "d.nc", ReadOptions{});
  ASSERT_FALSE(dwell.ok());
  EXPECT_EQ(*dwell.error().line, 4);
  EXPECT_NE(dwell.error().message.find("number after P beyond +-1e9"), std::string::npos) << format(dwell.error());
  auto feed = read_gcode("G21\nG0 X1\nM3\nG1 X10 F0." + std::string(320, '0') + "1\nM5\nM30\n", "f.nc", ReadOptions{});
  ASSERT_FALSE(feed.ok());
  EXPECT_EQ(*feed.error().line, 4);
  EXPECT_NE(feed.error().message.find("below 0.001 per minute"), std::string::npos) << format(feed.error());
  // The largest values still read give finite totals.
  auto big = read_gcode("G21\nG0 X1\nM3\nG4 P999999999\nG1 X10 F0.001\nM5\nM30\n", "b.nc", ReadOptions{});
  ASSERT_TRUE(big.ok()) << format(big.error());
}

// Found auditing `estimate`: 400 digits (beyond a double) said "malformed number", 20 digits
// "beyond +-1e9"; both are too large. 400 digits of a tiny fraction are zero.
TEST(BrokenProgramInline, HundredsOfDigitsAreBeyondTheRangeAsTwentyAre) {
  auto digits400 = read_gcode("G0 X" + std::string(400, '9') + "\nM30\n", "x.nc", ReadOptions{});
  ASSERT_FALSE(digits400.ok());
  EXPECT_NE(digits400.error().message.find("number after X beyond +-1e9 (column 4)"), std::string::npos)
      << format(digits400.error());
  auto tiny = read_gcode("G0 X0." + std::string(400, '0') + "1 Y5\nM30\n", "t.nc", ReadOptions{});
  ASSERT_TRUE(tiny.ok()) << format(tiny.error());
  EXPECT_NEAR(tiny->rapid_length_mm, 5.0, 1e-12);
}

// A drawing where a program was meant is named as such.
TEST(BrokenProgramInline, ADrawingIsNotAProgram) {
  auto r = read_gcode("  0\nSECTION\n  2\nHEADER\n  0\nENDSEC\n  0\nEOF\n", "d.nc", ReadOptions{});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(*r.error().line, 1);
  EXPECT_NE(r.error().message.find("not a G-code program: it looks like a DXF drawing"), std::string::npos) << r.error().message;
}

TEST(BrokenProgramInline, MissingFile) {
  auto r = read_gcode_file(test::test_data("nc/does_not_exist.nc"), ReadOptions{});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("cannot open"), std::string::npos);
  auto dir = read_gcode_file(test::test_data("nc"), ReadOptions{});
  ASSERT_FALSE(dir.ok());
  EXPECT_NE(dir.error().message.find("is a directory"), std::string::npos) << format(dir.error());
}

// Found by fuzzing (session 39).
TEST(BrokenProgramInline, MessagesShowTheByteAndTheValueAsGiven) {
  // The byte in hex (ESC read '\x27', an apostrophe, when its decimal value followed the \x).
  auto esc = read_gcode("G0 X1\nG1 X2 \x1b Y1\nM30\n", "e.nc", ReadOptions{});
  ASSERT_FALSE(esc.ok());
  EXPECT_NE(esc.error().message.find("unsupported character '\\x1B'"), std::string::npos) << format(esc.error());
  auto ff = read_gcode("G0 X1\n\xff\nM30\n", "f.nc", ReadOptions{});
  ASSERT_FALSE(ff.ok());
  EXPECT_NE(ff.error().message.find("'\\xFF'"), std::string::npos) << format(ff.error());
  // All digits of a coordinate beyond the range (six read "1e+06 mm is beyond ... ±1e+06 mm").
  auto far = read_gcode("G0 X1000000.0001\nM30\n", "x.nc", ReadOptions{});
  ASSERT_FALSE(far.ok());
  EXPECT_NE(far.error().message.find("X 1000000.0001 mm"), std::string::npos) << format(far.error());
}

// A UTF-8 byte order mark (Windows editors) is skipped; a feed move at F0 or before any F is read
// (the estimate prices cuts at V_on*(n)) with a warning at its line: the controller would refuse it.
TEST(BrokenProgramInline, ByteOrderMarkAndFeedMovesWithoutAFeed) {
  const auto dir = std::filesystem::temp_directory_path() / ("cutroute-bom-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto bom = dir / "bom.nc";
  std::ofstream(bom, std::ios::binary) << "\xEF\xBB\xBFG21\nG0 X1\nM3\nG1 X10 F1000\nM5\nM30\n";
  auto r = read_gcode_file(bom.string(), ReadOptions{});
  ASSERT_TRUE(r.ok()) << format(r.error());
  EXPECT_NEAR(r->cut_length_mm, 9.0, 1e-12);
  EXPECT_TRUE(r->warnings.empty());
  std::filesystem::remove_all(dir);
  for (const char* program : {"G21\nG0 X1\nM3\nG1 X10 F0\nM5\nM30\n", "G21\nG0 X1\nM3\nG1 X10\nM5\nM30\n"}) {
    auto z = read_gcode(program, "z.nc", ReadOptions{});
    ASSERT_TRUE(z.ok()) << format(z.error());
    EXPECT_NEAR(z->cut_length_no_feed_mm, 9.0, 1e-12);
    ASSERT_EQ(z->warnings.size(), 1u) << program;
    EXPECT_EQ(z->warnings[0].line, 4);
    EXPECT_NE(z->warnings[0].message.find("zero feed rate"), std::string::npos) << z->warnings[0].message;
  }
}

// Found by fuzzing (session 39): blocks LinuxCNC refuses were read without a word.
TEST(BrokenProgramInline, BlocksTheControllerRefusesAreWarnedAtTheirLine) {
  auto r = read_gcode("G21\nG0 X1\nM3 M5\nM3\nG1 X10 I5 F1000\nG1 X20 R3\nM5\nM30\n", "w.nc", ReadOptions{});
  ASSERT_TRUE(r.ok()) << format(r.error());
  ASSERT_EQ(r->warnings.size(), 3u);
  EXPECT_EQ(r->warnings[0].line, 3);
  EXPECT_NE(r->warnings[0].message.find("switched on and off in one block"), std::string::npos) << r->warnings[0].message;
  EXPECT_EQ(r->warnings[1].line, 5);
  EXPECT_NE(r->warnings[1].message.find("word I on a straight move"), std::string::npos) << r->warnings[1].message;
  EXPECT_EQ(r->warnings[2].line, 6);
  EXPECT_NE(r->warnings[2].message.find("word R on a straight move"), std::string::npos) << r->warnings[2].message;
  EXPECT_NEAR(r->cut_length_mm, 19.0, 1e-12);  // read in order: M3 M5 leaves the beam off
}

// Found by fuzzing (session 39): negative and fractional sequence numbers passed without a word.
TEST(BrokenProgramInline, LineNumbersTheControllerRefusesAreWarned) {
  auto r = read_gcode("N10 G21\nN-5 G0 X1\nN2.5 M3\nN0 G1 X10 F1000\nN30 M5\nM30\n", "n.nc", ReadOptions{});
  ASSERT_TRUE(r.ok()) << format(r.error());
  ASSERT_EQ(r->warnings.size(), 2u);
  EXPECT_EQ(r->warnings[0].line, 2);
  EXPECT_NE(r->warnings[0].message.find("line number N-5 is not a whole number >= 0"), std::string::npos) << r->warnings[0].message;
  EXPECT_EQ(r->warnings[1].line, 3);
  EXPECT_NE(r->warnings[1].message.find("line number N2.5"), std::string::npos) << r->warnings[1].message;
  EXPECT_NEAR(r->cut_length_mm, 9.0, 1e-12);
}

}  // namespace
}  // namespace cutroute::nc
