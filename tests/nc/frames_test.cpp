// The frame definition (nc/frames.hpp) on single lines and whole programs.
#include <gtest/gtest.h>

#include <cutroute/nc/frames.hpp>

namespace cutroute::nc {
namespace {

TEST(Frames, WordsMakeAFrameCommentsBlanksAndTapeMarksDoNot) {
  EXPECT_TRUE(is_frame("G1 X10 Y20"));
  EXPECT_TRUE(is_frame("M5"));
  EXPECT_TRUE(is_frame("F6000"));
  EXPECT_TRUE(is_frame("S6000"));
  EXPECT_TRUE(is_frame("N10 G0 X0"));
  EXPECT_TRUE(is_frame("/M3"));
  EXPECT_TRUE(is_frame("g1x1y2 ; compact"));
  EXPECT_FALSE(is_frame(""));
  EXPECT_FALSE(is_frame("   \t"));
  EXPECT_FALSE(is_frame("(a comment)"));
  EXPECT_FALSE(is_frame("; a comment"));
  EXPECT_FALSE(is_frame("%"));
  EXPECT_FALSE(is_frame("% G1 X5"));
  EXPECT_FALSE(is_frame("N20"));
  EXPECT_FALSE(is_frame("O1000 (program number)"));
  EXPECT_FALSE(is_frame("G1 X1.2.3"));  // malformed: the reader reports it as an error
}

TEST(Frames, ProgramEnd) {
  EXPECT_TRUE(ends_program("M30"));
  EXPECT_TRUE(ends_program("N100 M2 (end)"));
  EXPECT_FALSE(ends_program("(M30)"));
  EXPECT_FALSE(ends_program("M3"));
}

// The example of docs/FRAMES.md: 7 frames.
TEST(Frames, DocumentedExample) {
  const char* program =
      "%\n"
      "O0001 (one square hole)\n"
      "N10 G21 G90\n"
      "\n"
      "N20 G0 X10 Y10 ; rapid to the pierce point\n"
      "N30 M3\n"
      "N40 G1 X20 F6000\n"
      "N45\n"
      "N50 G1 Y20\n"
      "N60 M5\n"
      "N70 M30\n"
      "%\n"
      "G0 X0 Y0 (after the end: not a frame)\n";
  EXPECT_EQ(count_frames(program), 7u);
}

TEST(Frames, LineEndingsDoNotChangeTheCount) {
  const std::string lf = "G21\nG0 X1\n\n(c)\nM3\nG1 X2\nM5\nM30\n";
  std::string crlf;
  std::string cr;
  for (char c : lf) {
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    cr += c == '\n' ? '\r' : c;
  }
  EXPECT_EQ(count_frames(lf), 6u);
  EXPECT_EQ(count_frames(crlf), 6u);
  EXPECT_EQ(count_frames(cr), 6u);
  EXPECT_EQ(count_frames("G21\nM30"), 2u);  // no newline at the end
}

}  // namespace
}  // namespace cutroute::nc
