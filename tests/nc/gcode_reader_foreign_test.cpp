// G-code reader on blocks a controller refuses though they can be measured, and on foreign
// conventions (GRBL's S0 laser power, Fanuc's G70/G71 units). Whether LinuxCNC refuses a block was
// checked with its interpreter (rs274 -g, LinuxCNC 2.9); the lengths are worked out by hand.
#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <vector>

#include <cutroute/nc/gcode_reader.hpp>

namespace cutroute::nc {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLenTol = 1e-9;  // [mm]

ProgramStats read_ok(const std::string& text, ReadOptions opt = {}) {
  auto r = read_gcode(text, "p.nc", opt);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : format(r.error()));
  return r.ok() ? *r : ProgramStats{};
}

std::vector<std::string> codes(const ProgramStats& s) {
  std::vector<std::string> c;
  for (const auto& w : s.warnings) c.push_back(w.code);
  return c;
}

// Found auditing `estimate`: an R arc 0.005 mm too short for its chord was read without a word
// (within the reader's 0.01 mm), though LinuxCNC refuses anything more than 0.00005 in (0.00127 mm)
// short: "Arc radius too small to reach end point". rs274: R4.9988 and R0.49996 accepted, R4.9986,
// R4.995, R4.989, R0.49994, R0.4985, R0.4979 refused.
TEST(GcodeReaderRefused, RadiusArcsTooShortForTheControllerAreWarned) {
  const auto mm = [](const char* r) {
    return std::string("G21 G90\nG0 X0 Y0\nM3\nG2 X10 Y0 R") + r + " F100\nM5\nM30\n";
  };
  const auto inch = [](const char* r) {
    return std::string("G20 G90\nG0 X0 Y0\nM3\nG2 X1 Y0 R") + r + " F4\nM5\nM30\n";
  };
  for (const char* r : {"4.995", "4.9986"}) {
    const auto s = read_ok(mm(r));
    ASSERT_EQ(s.warnings.size(), 1u) << r;
    EXPECT_EQ(s.warnings[0].code, "gcode.arc_radius_short");
    EXPECT_EQ(s.warnings[0].line, 4);
    EXPECT_NE(s.warnings[0].message.find("too small to reach end point"), std::string::npos)
        << s.warnings[0].message;
    EXPECT_NEAR(s.cut_length_mm, 5.0 * kPi, kLenTol);  // read as the half circle on the chord
  }
  EXPECT_TRUE(read_ok(mm("4.9988")).warnings.empty());
  EXPECT_FALSE(read_gcode(mm("4.989"), "p.nc", ReadOptions{}).ok());  // beyond the reader's 0.01 mm: an error
  // Inch programs: the same 0.00005 in, not 0.00005 mm.
  for (const char* r : {"0.49994", "0.4985"}) {
    const auto s = read_ok(inch(r));
    EXPECT_EQ(codes(s), std::vector<std::string>{"gcode.arc_radius_short"}) << r;
    EXPECT_NEAR(s.cut_length_mm, 12.7 * kPi, kLenTol);
  }
  EXPECT_TRUE(read_ok(inch("0.49996")).warnings.empty());
  EXPECT_FALSE(read_gcode(inch("0.4979"), "p.nc", ReadOptions{}).ok());  // beyond the reader's 0.002 in
}

// Found auditing `estimate`: "G0 G1 X20" was read as G1 without a word; LinuxCNC refuses it ("Two
// G-codes used from same modal group"), as it does G91 G90, G90.1 G91.1, G20 G21 and G1 G1, but
// accepts G0 G80 (the Fanuc safety line G17 G40 G49 G80 G90 G0 too).
TEST(GcodeReaderRefused, TwoCodesOfAMeasuredModalGroupAreWarned) {
  const auto s = read_ok(
      "G21 G90\n"                 // 1
      "G0 X0 Y0\n"                // 2
      "M3\n"                      // 3
      "G0 G1 X20 F100\n"          // 4 refused: read as G1, a 20 mm cut
      "G91 G90 X30\n"             // 5 refused: read as G90, 10 mm
      "G90.1 G91.1\n"             // 6 refused
      "G20 G21\n"                 // 7 refused: read in mm
      "G0 G80 X40\n"              // 8 accepted: a 10 mm rapid
      "G17 G40 G49 G80 G90 G0\n"  // 9 accepted
      "G1 G1 X50\n"               // 10 refused: 10 mm
      "M5\nM30\n");
  std::vector<long> lines;
  for (const auto& w : s.warnings)
    if (w.code == "gcode.same_modal_group") lines.push_back(w.line.value_or(0));
  EXPECT_EQ(lines, (std::vector<long>{4, 5, 6, 7, 10}));
  ASSERT_EQ(s.warnings.size(), 6u);  // and the rapid with the beam on (line 8)
  EXPECT_EQ(s.warnings[4].code, "gcode.beam_on_rapid");
  EXPECT_NE(s.warnings[0].message.find("G0 and G1 in one block"), std::string::npos) << s.warnings[0].message;
  EXPECT_NE(s.warnings[0].message.find("read with the last, G1"), std::string::npos) << s.warnings[0].message;
  EXPECT_NEAR(s.cut_length_mm, 40.0, kLenTol);  // G20 G21 left millimetres
  EXPECT_NEAR(s.rapid_length_mm, 10.0, kLenTol);
}

// Found auditing `estimate`: G70 was "unknown word G70 ignored", not saying that a Fanuc-style
// program meaning inches by it is read in millimetres, 25.4 times too short. LinuxCNC refuses both
// G70 and G71 here (lathe cycles: "G7x.x requires a Q word"). The unit is not guessed.
TEST(GcodeReaderForeign, G70AndG71SayWhichUnitTheProgramIsReadIn) {
  auto s = read_ok("G70\nG0 X1\nM3\nG1 X2 F10\nM5\nM30\n");
  ASSERT_EQ(codes(s), std::vector<std::string>{"gcode.fanuc_units"});
  EXPECT_EQ(s.warnings[0].line, 1);
  EXPECT_NE(s.warnings[0].message.find("read in millimetres"), std::string::npos) << s.warnings[0].message;
  EXPECT_NE(s.warnings[0].message.find("25.4 times too short"), std::string::npos) << s.warnings[0].message;
  EXPECT_NE(s.warnings[0].message.find("write G20 for G70"), std::string::npos) << s.warnings[0].message;
  EXPECT_NEAR(s.cut_length_mm, 1.0, kLenTol);  // millimetres, as the warning says
  s = read_ok("G71\nG0 X1\nM3\nG1 X2 F10\nM5\nM30\n");
  ASSERT_EQ(codes(s), std::vector<std::string>{"gcode.fanuc_units"});
  EXPECT_NE(s.warnings[0].message.find("as that control would"), std::string::npos) << s.warnings[0].message;
  s = read_ok("G20\nG71\nG0 X1\nM3\nG1 X2 F10\nM5\nM30\n");
  ASSERT_EQ(codes(s), std::vector<std::string>{"gcode.fanuc_units"});
  EXPECT_NE(s.warnings[0].message.find("25.4 times too long"), std::string::npos) << s.warnings[0].message;
  EXPECT_NEAR(s.cut_length_mm, 25.4, kLenTol);
}

// Found auditing `estimate`: a GRBL laser program (LightBurn: M4 once at the top, power by S on
// each G1) travels between cuts with "G1 ... S0", at which the laser does not fire; those moves
// were counted as cutting. They are beam-off travel at feed, and the cut after them a new pierce.
TEST(GcodeReaderForeign, GrblFeedMovesAtS0AreTravelNotCutting) {
  const std::string lightburn =
      "G00 G17 G40 G21 G54\n"  // 1
      "G90\n"                  // 2
      "M4\n"                   // 3
      "M8\n"                   // 4
      "G0 X10 Y10\n"           // 5
      "G1 X20 Y10S800F1000\n"  // 6 cut 10
      "G1 X20 Y20\n"           // 7 cut 10
      "G1 X30 Y20 S0\n"        // 8 travel 10 at F1000
      "G1 X40 Y20 S800\n"      // 9 a new pierce, cut 10
      "G1 X40 Y30\n"           // 10 cut 10
      "M9\nG1 S0\nM5\nM2\n";
  std::vector<Move> moves;
  ReadOptions opt;
  opt.moves = &moves;
  const auto s = read_ok(lightburn, opt);
  EXPECT_NEAR(s.cut_length_mm, 40.0, kLenTol);
  EXPECT_NEAR(s.feed_off_length_mm, 10.0, kLenTol);
  EXPECT_NEAR(s.feed_off_time_s, 0.6, 1e-12);
  EXPECT_EQ(s.pierces, 2u);
  EXPECT_EQ(s.cut_moves, 4u);
  ASSERT_EQ(codes(s), std::vector<std::string>{"gcode.zero_power"});
  EXPECT_EQ(s.warnings[0].line, 8);
  ASSERT_EQ(moves.size(), 6u);
  EXPECT_FALSE(moves[3].beam_on);
  EXPECT_TRUE(moves[4].beam_on);
  EXPECT_TRUE(moves[4].pierce);
  // S0 before any power above 0 is a torch post's placeholder ("M3 S0"), not zero power: read as
  // cutting, as without S words; after S500 it is zero power again.
  const auto first = read_ok("G21 G90\nM3 S0\nG1 X10 F1000\nG1 X20 S500\nG1 X30 S0\nM5\nM2\n");
  EXPECT_NEAR(first.cut_length_mm, 20.0, kLenTol);
  EXPECT_NEAR(first.feed_off_length_mm, 10.0, kLenTol);
  EXPECT_EQ(first.pierces, 1u);
  EXPECT_EQ(codes(first), std::vector<std::string>{"gcode.zero_power"});
  const auto torch = read_ok("G21 G90\nG0 X5\nM3 S0\nG1 X10 F1000\nG1 X20\nM5\nG0 X30\nM3 S0\nG1 X40\nM5\nM2\n");
  EXPECT_NEAR(torch.cut_length_mm, 25.0, kLenTol);
  EXPECT_EQ(torch.pierces, 2u);
  EXPECT_TRUE(torch.warnings.empty());
}

}  // namespace
}  // namespace cutroute::nc
