// G-code reader on hand-written programs whose lengths, pierces and frames were worked out by
// hand (the expected values are written next to each program in tests/data/nc/).
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <cutroute/nc/frames.hpp>
#include <cutroute/nc/gcode_reader.hpp>

#include "support/paths.hpp"

namespace cutroute::nc {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLenTol = 1e-9;  // [mm] hand values are exact up to rounding of the arithmetic

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

ProgramStats read_ok(const std::string& rel, const ReadOptions& opt = {}) {
  auto r = read_gcode_file(test::test_data("nc/" + rel), opt);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : format(r.error()));
  return r.ok() ? *r : ProgramStats{};
}

TEST(GcodeReader, AbsoluteMillimetreRectangle) {
  const auto s = read_ok("square_abs_mm.nc");
  EXPECT_NEAR(s.cut_length_mm, 300.0, kLenTol);
  EXPECT_NEAR(s.rapid_length_mm, 2.0 * std::sqrt(200.0), kLenTol);
  EXPECT_EQ(s.pierces, 1u);
  EXPECT_EQ(s.frames, 10u);  // N10..N100; '%', the O line and comments are not frames
  EXPECT_EQ(s.cut_moves, 4u);
  EXPECT_NEAR(s.cut_time_at_feed_s, 300.0 / 6000.0 * 60.0, 1e-12);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(GcodeReader, IncrementalInchRectangle) {
  const auto s = read_ok("square_inc_inch.nc");
  EXPECT_NEAR(s.cut_length_mm, 12.0 * 25.4, kLenTol);
  EXPECT_NEAR(s.rapid_length_mm, 2.0 * std::sqrt(2.0) * 25.4, kLenTol);
  EXPECT_EQ(s.pierces, 1u);
  EXPECT_EQ(s.frames, 10u);
  EXPECT_TRUE(s.inch);
  EXPECT_NEAR(s.cut_time_at_feed_s, 12.0 / 240.0 * 60.0, 1e-12);  // F240 in/min
}

TEST(GcodeReader, IncrementalCentreArcsAreExact) {
  const auto s = read_ok("arcs_ij.nc");
  // full circle r 10 + half circle r 10 + quarter circle r 10
  EXPECT_NEAR(s.cut_length_mm, 20.0 * kPi + 10.0 * kPi + 5.0 * kPi, kLenTol);
  EXPECT_NEAR(s.rapid_length_mm, 10.0 + 40.0 + std::sqrt(500.0), kLenTol);
  EXPECT_EQ(s.pierces, 2u);  // M3 ... M5, M4 ... M5
  EXPECT_EQ(s.frames, 12u);
  EXPECT_EQ(s.arc_moves, 3u);
}

TEST(GcodeReader, AbsoluteCentreArcsMatchIncremental) {
  const auto a = read_ok("arcs_absolute_centre.nc");
  const auto b = read_ok("arcs_ij.nc");
  EXPECT_NEAR(a.cut_length_mm, b.cut_length_mm, kLenTol);
  EXPECT_NEAR(a.rapid_length_mm, b.rapid_length_mm, kLenTol);
  EXPECT_EQ(a.pierces, b.pierces);
  EXPECT_EQ(a.frames, 13u);  // one block more: G91.1
}

TEST(GcodeReader, RadiusArcsTakeTheSignIntoAccount) {
  const auto s = read_ok("arcs_r.nc");
  EXPECT_NEAR(s.cut_length_mm, 5.0 * kPi + 15.0 * kPi, kLenTol);  // quarter (R+) + three quarters (R-)
  EXPECT_NEAR(s.rapid_length_mm, 20.0, kLenTol);
  EXPECT_EQ(s.frames, 8u);
}

TEST(GcodeReader, DwellCommentsLowerCaseCrlf) {
  const auto s = read_ok("dwell_comments_crlf.nc");
  EXPECT_NEAR(s.cut_length_mm, 35.0, kLenTol);
  EXPECT_NEAR(s.rapid_length_mm, 0.0, kLenTol);
  EXPECT_EQ(s.pierces, 1u);
  EXPECT_EQ(s.dwells, 2u);
  EXPECT_NEAR(s.dwell_s, 1.75, 1e-12);
  // Only the dwell between the beam-on and the first cut is the pierce's.
  EXPECT_EQ(s.pierce_dwells, 1u);
  EXPECT_NEAR(s.pierce_dwell_s, 0.5, 1e-12);
  EXPECT_EQ(s.frames, 9u);  // the N5-only line is not a frame
}

TEST(GcodeReader, SeveralDwellsAtOnePierceCountOncePerPierce) {
  auto r = read_gcode("G0 X0 Y0\nM3\nG4 P0.25\nG4 P0.5\nG1 X5\nG4 P2\nM5\nG0 X10\nM3\nG1 X20\nM5\nM30\n",
                      "p.nc", ReadOptions{});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->pierces, 2u);
  EXPECT_EQ(r->pierce_dwells, 1u);  // the second pierce has no dwell; the dwell after G1 is no pierce's
  EXPECT_NEAR(r->pierce_dwell_s, 0.75, 1e-12);
  EXPECT_NEAR(r->dwell_s, 2.75, 1e-12);
}

TEST(GcodeReader, DwellInMillisecondsDialect) {
  ReadOptions opt;
  opt.dialect = *builtin_dialect("fanuc-ms");
  auto r = read_gcode("G4 P500\nG4 P1250\nM30\n", "ms.nc", opt);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->dwell_s, 1.75, 1e-12);
}

TEST(GcodeReader, BeamOffFeedAndRapidWithBeamOn) {
  const auto s = read_ok("beam_off_feed.nc");
  EXPECT_NEAR(s.cut_length_mm, 60.0, kLenTol);
  EXPECT_NEAR(s.rapid_length_mm, 40.0 + std::hypot(90.0, 80.0), kLenTol);
  EXPECT_NEAR(s.feed_off_length_mm, 50.0, kLenTol);
  EXPECT_NEAR(s.feed_off_time_s, 5.0, 1e-12);  // 50 mm at F600
  EXPECT_EQ(s.pierces, 2u);                    // M3, then a re-pierce after the G0 with the beam on
  EXPECT_EQ(s.beam_on_rapids, 1u);
  EXPECT_EQ(s.frames, 10u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].line, 7);
}

// GRBL laser programs switch the beam on once at the top (M4 S0: dynamic power, off during G0)
// and rapid to the first cut: that rapid moves the pierce counted at M4, it does not add one. Each
// later G0 between cuts is a new pierce, as the controller fires again at the next G1.
TEST(GcodeReader, RapidBeforeTheFirstCutMovesThePierce) {
  auto r = read_gcode("G21 G90\nM4 S0\nG0 X10 Y10\nG1 X20 Y10 F1000 S1000\nG1 X20 Y20\nG0 X50 Y50\nG1 X60 Y50 S1000\n"
                      "G1 X60 Y60\nM5\nG0 X0 Y0\nM2\n",
                      "grbl.nc", ReadOptions{});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->pierces, 2u);
  EXPECT_EQ(r->beam_on_rapids, 2u);
  EXPECT_NEAR(r->cut_length_mm, 40.0, kLenTol);
  ASSERT_EQ(r->warnings.size(), 1u);
  EXPECT_EQ(r->warnings[0].line, 6);  // the rapid between the cuts, not the one to the first
}

TEST(GcodeReader, CutterCompensationAndUnknownWordsAreWarnings) {
  const auto s = read_ok("cutter_comp_misc.nc");
  EXPECT_NEAR(s.cut_length_mm, 400.0, kLenTol);  // programmed path, no compensation applied
  EXPECT_NEAR(s.rapid_length_mm, 0.0, kLenTol);  // the G12 block did not move
  EXPECT_EQ(s.pierces, 1u);
  EXPECT_EQ(s.frames, 15u);
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_EQ(s.warnings[0].line, 8);
  EXPECT_NE(s.warnings[0].message.find("A15"), std::string::npos);
  EXPECT_EQ(s.warnings[1].line, 14);
  EXPECT_NE(s.warnings[1].message.find("G12"), std::string::npos);
}

TEST(GcodeReader, BeamCodesComeFromTheDialect) {
  ReadOptions m7;
  m7.dialect = *builtin_dialect("rs274-m7m9");
  const auto a = read_ok("m7m9_beam.nc", m7);
  EXPECT_NEAR(a.cut_length_mm, 50.0, kLenTol);
  EXPECT_NEAR(a.rapid_length_mm, 20.0, kLenTol);
  EXPECT_EQ(a.pierces, 2u);
  EXPECT_EQ(a.beam_on_rapids, 0u);
  EXPECT_EQ(a.frames, 13u);
  // The default dialect reads M3 as beam on and M7/M9 as assist gas: the beam stays on through
  // both rapids, so the second cut is a re-pierce and the rapids are beam-on rapids.
  const auto b = read_ok("m7m9_beam.nc");
  EXPECT_NEAR(b.cut_length_mm, 50.0, kLenTol);
  EXPECT_EQ(b.pierces, 2u);
  EXPECT_EQ(b.beam_on_rapids, 2u);
}

TEST(GcodeReader, CustomDialectRejectsContradictions) {
  EXPECT_FALSE(make_dialect("x", {3}, {3}, DwellUnit::seconds, "dialect").ok());
  EXPECT_FALSE(make_dialect("x", {30}, {5}, DwellUnit::seconds, "dialect").ok());
  EXPECT_FALSE(make_dialect("x", {}, {5}, DwellUnit::seconds, "dialect").ok());
  EXPECT_TRUE(make_dialect("x", {10}, {11}, DwellUnit::seconds, "dialect").ok());
  EXPECT_FALSE(builtin_dialect("heidenhain").ok());
}

TEST(GcodeReader, LineEndingsGiveIdenticalResults) {
  const std::string lf = slurp(test::test_data("nc/arcs_ij.nc"));
  std::string crlf;
  std::string cr;
  for (char c : lf) {
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    cr += c == '\n' ? '\r' : c;
  }
  const ReadOptions opt;
  for (const auto& text : {lf, crlf, cr}) {
    auto r = read_gcode(text, "x.nc", opt);
    ASSERT_TRUE(r.ok());
    EXPECT_NEAR(r->cut_length_mm, 35.0 * kPi, kLenTol);
    EXPECT_EQ(r->frames, 12u);
    EXPECT_EQ(r->pierces, 2u);
  }
}

TEST(GcodeReader, ModalMotionAndNumberForms) {
  const ReadOptions opt;
  auto r = read_gcode("G21 G90 M3\nG1 X+10. Y.0 F1000\nX-10\nY10.\nM5\nG0 X0 Y0\nM30\n", "forms.nc", opt);
  ASSERT_TRUE(r.ok()) << format(r.error());
  EXPECT_NEAR(r->cut_length_mm, 10.0 + 20.0 + 10.0, kLenTol);
  EXPECT_NEAR(r->rapid_length_mm, std::hypot(10.0, 10.0), kLenTol);
}

TEST(GcodeReader, FullCircleWithoutEndWordsAndHalfCircleByR) {
  const ReadOptions opt;
  auto r = read_gcode("G21 G90\nG0 X5 Y0\nM3\nG2 I-5\nG3 X-5 Y0 R5\nM5\nM30\n", "c.nc", opt);
  ASSERT_TRUE(r.ok()) << format(r.error());
  EXPECT_NEAR(r->cut_length_mm, 10.0 * kPi + 5.0 * kPi, kLenTol);
}

TEST(GcodeReader, FramesAgreeWithTheSharedDefinition) {
  for (const auto& entry : std::filesystem::directory_iterator(test::test_data("nc"))) {
    if (entry.path().extension() != ".nc") continue;
    const std::string text = slurp(entry.path().string());
    ReadOptions opt;
    auto r = read_gcode(text, entry.path().string(), opt);
    ASSERT_TRUE(r.ok()) << entry.path();
    EXPECT_EQ(r->frames, count_frames(text)) << entry.path();
  }
  for (const auto& entry : std::filesystem::directory_iterator(test::test_data("nc/dxf2gcode"))) {
    const std::string text = slurp(entry.path().string());
    auto r = read_gcode(text, entry.path().string(), ReadOptions{});
    ASSERT_TRUE(r.ok()) << entry.path();
    EXPECT_EQ(r->frames, count_frames(text)) << entry.path();
  }
}

TEST(GcodeReader, BlocksAfterTheEndAreIgnoredWithAWarning) {
  auto r = read_gcode("M3\nG1 X10 F100\nM30\nG1 X20\n", "after.nc", ReadOptions{});
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->cut_length_mm, 10.0, kLenTol);
  EXPECT_EQ(r->frames, 3u);
  ASSERT_EQ(r->warnings.size(), 1u);
  EXPECT_EQ(r->warnings[0].line, 3);
}

TEST(GcodeReader, WarningsAreCapped) {
  std::string text;
  for (int i = 0; i < 80; ++i) text += "G1 A1\n";
  text += "M30\n";
  ReadOptions opt;
  opt.max_warnings = 10;
  auto r = read_gcode(text, "many.nc", opt);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->warnings.size(), 10u);
  EXPECT_EQ(r->suppressed_warnings, 70u);
}

// Found auditing `estimate`: its warnings had no code, where every other warning of the tool has
// one (dxf.truncated, chain.duplicate ...): a JSON reader could only tell them apart by their text.
TEST(GcodeReader, EveryWarningCarriesItsCode) {
  const std::string text =
      "G21 G90\n"           // 1
      "G0 X10 Y0 A5\n"      // 2 gcode.unknown_word
      "N-5 G1 X11\n"        // 3 gcode.line_number, gcode.no_feed (before any F)
      "M3 M5\n"             // 4 gcode.beam_on_and_off
      "M3\n"                // 5
      "G4 P200\n"           // 6 gcode.dwell_unit
      "G1 X20 I5 F100\n"    // 7 gcode.arc_word_on_line
      "G0 X30\n"            // 8 gcode.beam_on_rapid
      "G1 X40\n"            // 9
      "M5 M64\n"            // 10 gcode.unknown_m_code
      "G28\n"               // 11 gcode.travel_not_counted
      "G12 X1\n"            // 12 gcode.unknown_word
      "M30\n"               // 13 gcode.after_end
      "G0 X0\n";
  auto r = read_gcode(text, "codes.nc", ReadOptions{});
  ASSERT_TRUE(r.ok()) << r.error().message;
  const std::vector<std::pair<long, std::string>> expected = {
      {2, "gcode.unknown_word"},     {3, "gcode.line_number"},   {3, "gcode.no_feed"},
      {4, "gcode.beam_on_and_off"},  {6, "gcode.dwell_unit"},    {7, "gcode.arc_word_on_line"},
      {8, "gcode.beam_on_rapid"},    {10, "gcode.unknown_m_code"}, {11, "gcode.travel_not_counted"},
      {12, "gcode.unknown_word"},    {13, "gcode.after_end"}};
  ASSERT_EQ(r->warnings.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(r->warnings[i].line, expected[i].first) << i << ": " << r->warnings[i].message;
    EXPECT_EQ(r->warnings[i].code, expected[i].second) << i << ": " << r->warnings[i].message;
  }
  // The end-of-program summary and the Fanuc-dialect dwell block have theirs too.
  r = read_gcode("M7\nG1 X5 F100\nM9\nM30\n", "m7.nc", ReadOptions{});
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->warnings.size(), 1u);
  EXPECT_EQ(r->warnings[0].code, "gcode.never_cut");
  ReadOptions fanuc;
  fanuc.dialect = *builtin_dialect("fanuc-ms");
  r = read_gcode("G4 P500 Y5\nM30\n", "dwell.nc", fanuc);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->warnings.size(), 1u);
  EXPECT_EQ(r->warnings[0].code, "gcode.dwell_axis_words");
}

// Programs from other CAM systems: what changes the quote is read, or refused, or warned of; never
// silently left out. Expected values by hand.
bool warned(const ProgramStats& s, const std::string& text, long line) {
  for (const auto& w : s.warnings)
    if (w.message.find(text) != std::string::npos && w.line == line) return true;
  return false;
}

TEST(GcodeReaderForeign, ABeamNeverSwitchedOnIsWarnedWithTheDialectThatReadsIt) {
  const std::string m7 = "G21 G90\nG0 X10 Y0\nM07\nG1 X20 F1000\nY10\nM09\nG0 X0 Y0\nM30\n";
  auto r = read_gcode(m7, "m7.nc", ReadOptions{});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->pierces, 0u);
  EXPECT_NEAR(r->feed_off_length_mm, 20.0, kLenTol);
  EXPECT_TRUE(warned(*r, "no cutting: the beam is never switched on", 4)) << (r->warnings.empty() ? "" : r->warnings[0].message);
  EXPECT_TRUE(warned(*r, "it uses M7 (line 3), which --dialect rs274-m7m9 reads as beam on", 4));
  ReadOptions opt;
  opt.dialect = *builtin_dialect("rs274-m7m9");
  r = read_gcode(m7, "m7.nc", opt);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->cut_length_mm, 20.0, kLenTol);
  EXPECT_TRUE(r->warnings.empty());
  // No beam code at all: the warning, without a dialect to suggest.
  r = read_gcode("G0 X1\nG1 X5 F100\nM30\n", "none.nc", ReadOptions{});
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->warnings.size(), 1u);
  EXPECT_EQ(r->warnings[0].message.find("it uses"), std::string::npos);
}

TEST(GcodeReaderForeign, SubprogramsAndOWordsAreRefusedAtTheirLine) {
  auto r = read_gcode("O0001\nG0 X10\nM98 P1000\nM30\nO1000\nM3\nG1 X20 F100\nM5\nM99\n", "sub.nc", ReadOptions{});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(*r.error().line, 3);
  EXPECT_NE(r.error().message.find("M98 subprogram call"), std::string::npos) << r.error().message;
  r = read_gcode("G0 X0\nM99\n", "ret.nc", ReadOptions{});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("M99"), std::string::npos);
  r = read_gcode("G21\no100 sub\nG1 X10 F100\no100 endsub\nM30\n", "o.nc", ReadOptions{});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(*r.error().line, 2);
  EXPECT_NE(r.error().message.find("o-word o100 sub"), std::string::npos) << r.error().message;
}

// Found auditing `estimate`: G92 was an unknown word, so the absolute move after it was measured
// from the old origin: a step-and-repeat program's rapid to each next copy had a wrong length
// (here 10 mm for 20, as LinuxCNC moves it).
TEST(GcodeReaderForeign, G92MovesTheOriginOfLaterAbsoluteCoordinates) {
  auto r = read_gcode("G21 G90\nG0 X10 Y0\nG92 X0 Y0\nM3\nG1 X20 F100\nM5\nG0 X0 Y0\nM30\n", "g92.nc", ReadOptions{});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->warnings.empty()) << r->warnings[0].message;
  EXPECT_NEAR(r->cut_length_mm, 20.0, kLenTol);
  EXPECT_NEAR(r->rapid_length_mm, 10.0 + 20.0, kLenTol);
  // Two copies of a 10 mm lead and a G90.1 centred circle, the origin moved to X100 mm (inches) for
  // the second; G92.1 cancels the offset, so the last rapid goes to the machine's X0 Y50.
  const std::string copy = "G0 X0 Y0\nM3\nG1 X0.3937008 F10\nG2 X0.3937008 Y0 I0.5905512 J0\nM5\n";
  r = read_gcode("G20 G90 G90.1\n" + copy + "G0 X3.937008\nG92 X0\n" + copy + "G92.1\nG0 X0 Y1.968504\nM30\n", "copies.nc",
                 ReadOptions{});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->pierces, 2u);
  EXPECT_NEAR(r->cut_length_mm, 2 * (10.0 + 2 * kPi * 5.0), 1e-5);  // the inch words round to 0.3 um
  EXPECT_NEAR(r->rapid_length_mm, 90.0 + std::hypot(110.0, 50.0), 1e-5);
  r = read_gcode("G92\nM30\n", "bare.nc", ReadOptions{});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(*r.error().line, 1);
}

TEST(GcodeReaderForeign, ArcTurnCountsAddFullCircles) {
  // LinuxCNC: P is the number of turns. A full circle of radius 10 three times, then a quarter
  // circle plus one more turn.
  auto r = read_gcode("G0 X10 Y0\nM3\nG2 X10 Y0 I-10 J0 P3 F1000\nG3 X0 Y10 I-10 P2\nM5\nM30\n", "p.nc", ReadOptions{});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(r->cut_length_mm, 3 * 20 * kPi + (0.25 + 1) * 20 * kPi, 1e-9);
  EXPECT_EQ(r->arc_moves, 2u);
  for (const char* p : {"P0", "P1.5", "P-2"}) {
    auto bad = read_gcode(std::string("G0 X10\nM3\nG2 X10 Y0 I-10 ") + p + " F100\nM30\n", "bad.nc", ReadOptions{});
    ASSERT_FALSE(bad.ok()) << p;
    EXPECT_EQ(*bad.error().line, 3) << p;
    EXPECT_NE(bad.error().message.find("arc turn count"), std::string::npos) << bad.error().message;
  }
}

TEST(GcodeReaderForeign, DwellsInEitherUnitAndAxisWordsInTheDwellBlock) {
  // Seconds read as a Fanuc program's milliseconds: counted as written, and warned of once.
  auto r = read_gcode("G0 X1\nM3\nG4 P500\nG1 X5 F100\nG4 P300\nM5\nM30\n", "f.nc", ReadOptions{});
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->dwell_s, 800.0, 1e-12);
  EXPECT_TRUE(warned(*r, "--dialect fanuc-ms", 3));
  EXPECT_EQ(r->warnings.size(), 1u);
  // Fanuc: G4 X is seconds, P milliseconds; no motion in the dwell block.
  ReadOptions fanuc;
  fanuc.dialect = *builtin_dialect("fanuc-ms");
  r = read_gcode("G0 X10\nM3\nG4 P500\nG1 X20 F1000\nG4 X1.5\nG4 X0.25\nM5\nM30\n", "x.nc", fanuc);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(r->dwell_s, 2.25, 1e-12);
  EXPECT_NEAR(r->cut_length_mm, 10.0, kLenTol);
  EXPECT_TRUE(r->warnings.empty());
  r = read_gcode("G0 X10\nG4 X1.5\nM30\n", "x.nc", ReadOptions{});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("--dialect fanuc-ms"), std::string::npos) << r.error().message;
  // RS274/NGC: the dwell, then the block's motion in the modal (or the block's own) motion mode.
  r = read_gcode("G21 G90\nG0 X10 Y0\nM3\nG1 X20 F1000\nG4 P1 G1 X30\nG4 P1 X40\nM5\nG0 X0 Y0\nM30\n", "g4.nc", ReadOptions{});
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->cut_length_mm, 30.0, kLenTol);
  EXPECT_NEAR(r->rapid_length_mm, 50.0, kLenTol);
  EXPECT_NEAR(r->dwell_s, 2.0, 1e-12);
  EXPECT_TRUE(r->warnings.empty());
}

TEST(GcodeReaderForeign, PercentEndsBlanksInNumbersAndFanucProgramNumbers) {
  // Between two '%' lines no M2/M30 is needed (LinuxCNC); blanks inside a number are ignored
  // (RS274/NGC); ":1000" is a Fanuc program number.
  auto r = read_gcode("%\n:1000\nG21 G90\nG0 X 1 0\nM3\nG1 X 2 0.5 F1000\nM5\n%\nG1 X500\n", "pct.nc", ReadOptions{});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(r->cut_length_mm, 10.5, kLenTol);
  EXPECT_NEAR(r->rapid_length_mm, 10.0, kLenTol);
  EXPECT_EQ(r->lines, 8u);
  EXPECT_EQ(r->frames, 5u);  // the ':' line is a program number like an O line: no frame
  // Without the opening '%' a closing one ends nothing.
  EXPECT_FALSE(read_gcode("G0 X1\nM3\nG1 X2 F100\n%\n", "open.nc", ReadOptions{}).ok());
}

TEST(GcodeReaderForeign, HomeMovesAndEachMissingFeedAreWarned) {
  auto r = read_gcode("G0 X10\nG28\nG53 G0 X0\nM3\nG1 X20\nG1 X30 F0\nM5\nM30\n", "h.nc", ReadOptions{});
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(warned(*r, "G28 (return to a home position) is not followed: its travel is not counted", 2));
  EXPECT_TRUE(warned(*r, "G53 (a move in machine coordinates) is not followed", 3));
  EXPECT_TRUE(warned(*r, "feed move before any F word", 5));
  EXPECT_TRUE(warned(*r, "feed move at F0", 6));
  EXPECT_NEAR(r->rapid_length_mm, 10.0, kLenTol);
}

}  // namespace
}  // namespace cutroute::nc

namespace cutroute::nc {
namespace {

TEST(GcodeReaderMoves, RecordedMovesCarryTangentsRadiiAndPierces) {
  std::vector<Move> moves;
  ReadOptions opt;
  opt.moves = &moves;
  // A rapid, a pierce, a line east, a ccw quarter arc turning north, an R-form cw arc, a rapid
  // with the beam on, a re-pierced line.
  auto r = read_gcode(
      "G21 G90\nG0 X10 Y0\nM3\nG0 Z1\nG1 X20 Y0 F600\nG3 X30 Y10 I0 J10\nG2 X40 Y20 R10\nG0 X50 Y20\nG1 X60 "
      "Y20\nM5\nM30\n",
      "m.nc", opt);
  ASSERT_TRUE(r.ok()) << format(r.error());
  ASSERT_EQ(moves.size(), 6u);
  const double pi = std::numbers::pi;
  EXPECT_EQ(moves[0].kind, Move::Kind::rapid);
  EXPECT_FALSE(moves[0].beam_on);
  EXPECT_EQ(moves[1].kind, Move::Kind::line);
  EXPECT_TRUE(moves[1].pierce);  // the Z-only block between M3 and the cut does not consume it
  EXPECT_NEAR(moves[1].start_dir_rad, 0.0, 1e-12);
  EXPECT_NEAR(moves[1].feed_mm_min, 600.0, 0.0);
  EXPECT_EQ(moves[2].kind, Move::Kind::arc_ccw);
  EXPECT_FALSE(moves[2].pierce);
  EXPECT_NEAR(moves[2].radius_mm, 10.0, 1e-12);
  EXPECT_NEAR(std::remainder(moves[2].start_dir_rad - 0.0, 2 * pi), 0.0, 1e-12);   // tangent east
  EXPECT_NEAR(std::remainder(moves[2].end_dir_rad - pi / 2, 2 * pi), 0.0, 1e-12);  // tangent north
  EXPECT_NEAR(moves[2].length_mm, 5.0 * pi, 1e-12);
  // cw minor arc from (30,10) to (40,20), R 10: centre (40,10), from north-going to east-going
  EXPECT_EQ(moves[3].kind, Move::Kind::arc_cw);
  EXPECT_NEAR(std::remainder(moves[3].start_dir_rad - pi / 2, 2 * pi), 0.0, 1e-12);
  EXPECT_NEAR(std::remainder(moves[3].end_dir_rad - 0.0, 2 * pi), 0.0, 1e-12);
  EXPECT_EQ(moves[4].kind, Move::Kind::rapid);
  EXPECT_TRUE(moves[5].pierce);  // re-pierce after the beam-on rapid
  EXPECT_EQ(moves[5].line, 9u);
  EXPECT_EQ(r->pierces, 2u);
}

}  // namespace
}  // namespace cutroute::nc

namespace cutroute::nc {
namespace {

// Rewrites a program: X and I multiplied by fx, Y and J by fy; with swap_arcs G2 <-> G3 (a
// mirror reverses the turning sense). Comments are left alone.
std::string transform(const std::string& text, double fx, double fy, bool swap_arcs) {
  std::string out;
  std::size_t i = 0;
  int depth = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ';' && depth == 0) {  // comment to the end of the line
      while (i < text.size() && text[i] != '\n') out += text[i++];
      continue;
    }
    if (c == '(') ++depth;
    if (c == ')') --depth;
    const char u = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    const bool axis = depth == 0 && (u == 'X' || u == 'Y' || u == 'I' || u == 'J');
    if (depth == 0 && u == 'G' && swap_arcs) {
      std::size_t j = i + 1;
      while (j < text.size() && text[j] == ' ') ++j;
      if (j < text.size() && (text[j] == '2' || text[j] == '3') &&
          (j + 1 >= text.size() ||
           !(std::isdigit(static_cast<unsigned char>(text[j + 1])) || text[j + 1] == '.'))) {
        out += 'G';
        out += text[j] == '2' ? '3' : '2';
        i = j + 1;
        continue;
      }
    }
    if (!axis) {
      out += c;
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < text.size() && text[j] == ' ') ++j;
    std::size_t k = j;
    while (k < text.size() && (std::isdigit(static_cast<unsigned char>(text[k])) || text[k] == '.' ||
                               text[k] == '-' || text[k] == '+'))
      ++k;
    const double v = std::stod(text.substr(j, k - j));
    const double f = (u == 'X' || u == 'I') ? fx : fy;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%c%.6f", u, v * f);
    out += buf;
    i = k;
  }
  return out;
}

// STYLE.md #14: the same programs rotated by 180° and mirrored keep lengths, pierces and frames.
TEST(GcodeReaderTransforms, RotatedAndMirroredProgramsKeepTheirTotals) {
  for (const char* rel :
       {"dxf2gcode/d2g_ATT00079.ngc", "dxf2gcode/deepnestsharp_part_6.ngc",
        "dxf2gcode/openscad_ellipse-arc-rot.ngc", "arcs_ij.nc", "arcs_r.nc", "square_inc_inch.nc"}) {
    SCOPED_TRACE(rel);
    const std::string text = slurp(test::test_data(std::string("nc/") + rel));
    auto base = read_gcode(text, rel, ReadOptions{});
    ASSERT_TRUE(base.ok());
    const struct {
      double fx, fy;
      bool swap;
    } cases[] = {{-1, -1, false}, {-1, 1, true}, {1, -1, true}};
    for (const auto& c : cases) {
      const std::string t = transform(text, c.fx, c.fy, c.swap);
      ASSERT_NE(t, text);
      auto r = read_gcode(t, rel, ReadOptions{});
      ASSERT_TRUE(r.ok()) << format(r.error());
      EXPECT_NEAR(r->cut_length_mm, base->cut_length_mm, 1e-9 * std::max(1.0, base->cut_length_mm));
      EXPECT_NEAR(r->rapid_length_mm, base->rapid_length_mm, 1e-9 * std::max(1.0, base->rapid_length_mm));
      EXPECT_EQ(r->pierces, base->pierces);
      EXPECT_EQ(r->frames, base->frames);
    }
  }
}

}  // namespace
}  // namespace cutroute::nc
