// Malformed files of tests/data/dxf/bad/ (one defect each): exact error message and line, no crash.
#include <map>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include <cutroute/core/random.hpp>
#include <cutroute/io/dxf.hpp>

#include "support/dxf_builder.hpp"
#include "support/paths.hpp"

namespace cutroute::test {
namespace {

struct BadCase {
  const char* file;
  long line;
  const char* message;
};

// Lines were read off the files (tests/data/dxf/bad/make_bad_files.py writes them).
const BadCase kBad[] = {
    {"empty.dxf", 1, "file is empty"},
    {"truncated_inside_entity.dxf", 55, "file is truncated inside the LINE entity starting at this line (no ENDSEC/EOF)"},
    {"non_numeric_coordinate.dxf", 68, "group code 11: 'abc' is not a number"},
    {"nan_coordinate.dxf", 70, "group code 21: 'nan' is not a finite number"},
    {"inf_coordinate.dxf", 62, "group code 10: 'inf' is not a finite number"},
    {"huge_coordinate_1e300.dxf", 68, "group code 11: coordinate 1e300 is out of range (more than 1e6 mm from the origin)"},
    {"unknown_section.dxf", 18, "unknown section 'FOOBAR'"},
    {"binary_garbage.dxf", 1, "binary data (byte 0x02) in a text DXF file"},
    {"insert_cycle_a_b_a.dxf", 101, "INSERT cycle: block 'A' -> 'B' -> 'A'"},
    {"insert_expansion_1e7_minsert.dxf", 259, "INSERT expansion gives 1e+07 entities, more than the limit of 2000000"},
    // 10^7 LINEs plus 1.1e7 INSERT cells: every expanded INSERT counts as an entity too.
    {"insert_expansion_1e7_nested.dxf", 1203, "INSERT expansion gives 2.11e+07 entities, more than the limit of 2000000"},
    {"group_code_not_integer.dxf", 67, "group code '1x' is not an integer"},
    {"group_code_without_value.dxf", 75, "group code 0 has no value: the file is truncated"},
    {"bulge_before_first_vertex.dxf", 55, "LWPOLYLINE has a bulge (group 42) before its first vertex"},
    {"vertex_count_mismatch.dxf", 55, "LWPOLYLINE declares 1000000000 vertices (group 90) but has 2"},
};

class DxfBadFile : public ::testing::TestWithParam<BadCase> {};

TEST_P(DxfBadFile, GivesItsErrorWithLine) {
  const BadCase& c = GetParam();
  const std::string path = test_data(std::string("dxf/bad/") + c.file);
  const auto r = io::read_dxf(path, {});
  ASSERT_FALSE(r.ok()) << c.file;
  EXPECT_EQ(r.error().severity, Severity::error);
  EXPECT_EQ(r.error().message, c.message);
  EXPECT_EQ(r.error().file, path);
  EXPECT_EQ(r.error().line, c.line);
}

INSTANTIATE_TEST_SUITE_P(Bad, DxfBadFile, ::testing::ValuesIn(kBad), [](const auto& param_info) {
  std::string n = param_info.param.file;
  for (char& ch : n) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return n;
});

TEST(DxfBad, HandlesOfTheOffendingInsertAreReported) {
  const auto r = io::read_dxf(test_data("dxf/bad/insert_cycle_a_b_a.dxf"), {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().handle, "301");
  EXPECT_EQ(format(r.error()), test_data("dxf/bad/insert_cycle_a_b_a.dxf") +
                                   ":101: error: INSERT cycle: block 'A' -> 'B' -> 'A' (entity 301)");
}

// Another kind of file where a drawing was meant (a G-code program, say) is named as such.
TEST(DxfBad, AProgramIsNotADrawing) {
  const auto r = io::read_dxf_string("(cutroute demo.dxf)\nG21\nG0 X1\nM30\n", "p.dxf", {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().line, 1);
  EXPECT_EQ(r.error().message, "not a DXF drawing: a text DXF starts with a group code (0) and SECTION, this file with '(cutroute demo.dxf)'");
}

TEST(DxfBad, MissingFile) {
  const auto r = io::read_dxf(test_data("dxf/bad/no_such_file.dxf"), {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "cannot open: No such file or directory");  // says why
}

// Every prefix of a valid file either reads or gives an error: never a crash or a hang (the
// sanitizer build runs this too).
TEST(DxfBad, EveryTruncationOfAFileIsHandled) {
  DxfBuilder b;
  b.insunits(4).begin_block("B").arc({0, 0}, 1, 0, 90).end_block();
  b.line({0, 0}, {1, 0}).lwpolyline({{{0, 0}, 0.5}, {{1, 0}, 0}, {{1, 1}, 0}}, true).insert("B", {1, 1});
  b.spline(3, {0, 0, 0, 0, 1, 1, 1, 1}, {{0, 0}, {1, 1}, {2, 1}, {3, 0}}, {}, 8).ellipse({0, 0}, {2, 0}, 0.5, 0, 1);
  const std::string text = b.str();
  int ok = 0, errors = 0;
  for (std::size_t n = 0; n < text.size(); n += 3) {
    const auto r = io::read_dxf_string(text.substr(0, n), "cut.dxf", {});
    if (r.ok()) ++ok;
    else ++errors;
  }
  EXPECT_GT(errors, 0);
  // Only cuts after the ENTITIES section's ENDSEC can read (the file then just lacks EOF).
  EXPECT_LE(ok, 4);
}

// EOF present or at least ENTITIES complete: a cut in a later section only warns.
TEST(DxfBad, TruncationAfterEntitiesIsAWarning) {
  DxfBuilder b;
  b.line({0, 0}, {1, 0});
  std::string text = b.str();
  text = text.substr(0, text.rfind("0\nEOF\n")) + "0\nSECTION\n2\nOBJECTS\n0\nDICTIONARY\n5\nC\n";
  const auto r = io::read_dxf_string(text, "cut.dxf", {});
  ASSERT_TRUE(r.ok()) << format(r.error());
  EXPECT_EQ(r->entities.size(), 1u);
  ASSERT_EQ(r->diagnostics.size(), 1u);
  EXPECT_EQ(r->diagnostics[0].message, "file is truncated after the ENTITIES section (in section OBJECTS)");
  EXPECT_EQ(r->diagnostics[0].severity, Severity::warning);
}

// dxflib reads lines into a 1024-byte buffer: numbers that long are refused up front.
TEST(DxfBad, OverlongNumberIsAnError) {
  DxfBuilder b;
  b.line({0, 0}, {1, 0});
  std::string text = b.str();
  const std::string lead = "10\n0\n20";
  text.replace(text.find(lead), lead.size(), "10\n" + std::string(1500, '0') + "\n20");
  const auto r = io::read_dxf_string(text, "long.dxf", {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "group code 10: number of more than 1000 characters");
}

// Found by fuzzing: in metres the limit (1e6 mm) is 1000 drawing units, and a message quoting
// 1481.35 against "1e6 mm" read as a contradiction.
TEST(DxfBad, OutOfRangeCoordinateInOtherUnitsSaysItsMillimetres) {
  DxfBuilder b;
  b.line({0, 0}, {1481.35, 0});
  io::DxfOptions metres;
  metres.units = "m";
  const auto r = io::read_dxf_string(b.str(), "m.dxf", metres);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "group code 11: coordinate 1481.35 (1481350 mm) is out of range (more than 1e6 mm from the origin)");
}

// Found by fuzzing: degree 0 gave "needs 5 knots, has 5", and -1 (read by dxflib as 2^32 - 1) was
// reported as degree 64. Degrees 31-64 passed the check, then the curve was skipped as "of zero
// length" (found auditing against ezdxf).
TEST(DxfBad, SplineDegreeOutOfRangeIsNamed) {
  for (const auto& [degree, shown] :
       {std::pair{"0", "0"}, std::pair{"-1", "-1"}, std::pair{"31", "31"}, std::pair{"65", "65"}}) {
    DxfBuilder b;
    b.spline(3, {0, 0, 0, 0, 1, 1, 1, 1}, {{0, 0}, {1, 1}, {2, 1}, {3, 0}}, {}, 8);
    std::string text = b.str();
    const std::string lead = "71\n3\n";
    ASSERT_NE(text.find(lead), std::string::npos);
    text.replace(text.find(lead), lead.size(), std::string("71\n") + degree + "\n");
    const auto r = io::read_dxf_string(text, "deg.dxf", {});
    ASSERT_FALSE(r.ok()) << degree;
    EXPECT_EQ(r.error().message, std::string("SPLINE of degree ") + shown + ": only degrees 1 to 30 are read");
  }
}

// Single-byte corruptions anywhere in a valid file never crash.
TEST(DxfBad, ByteFlipsAreHandled) {
  DxfBuilder b;
  b.insunits(1).line({0, 0}, {1, 0}).lwpolyline({{{0, 0}, 0.5}, {{1, 0}, 0}, {{1, 1}, 0}}, true);
  b.spline(2, {0, 0, 0, 1, 1, 1}, {{0, 0}, {1, 1}, {2, 0}}, {1, 0.7, 1}, 8);
  const std::string text = b.str();
  const char repl[] = {'\0', '9', '-', 'e', '\n', 'x', '.', ' '};
  for (std::size_t i = 0; i < text.size(); ++i) {
    for (char c : repl) {
      std::string t = text;
      t[i] = c;
      const auto r = io::read_dxf_string(t, "flip.dxf", {});
      if (!r.ok()) {
        EXPECT_FALSE(r.error().message.empty());
      }
    }
  }
}

// Line-level mutations of a drawing with every entity kind (deleted, duplicated, swapped or
// replaced lines): each read ends in a value or an error, never a crash (run under ASan/UBSan).
TEST(DxfBad, RandomLineMutationsAreHandled) {
  DxfBuilder b;
  b.insunits(4).begin_block("B", {1, 1}).arc({0, 0}, 1, 0, 90).circle({2, 2}, 1).end_block();
  b.line({0, 0}, {1, 0}).lwpolyline({{{0, 0}, 0.5}, {{1, 0}, 0}, {{1, 1}, 0}}, true).insert("B", {1, 1}, 2, 1, 30);
  b.polyline({{{0, 0}, 0.3}, {{4, 0}, 0}, {{4, 4}, 0}}, true).text({0, 0}, "t");
  b.spline(3, {0, 0, 0, 0, 1, 1, 1, 1}, {{0, 0}, {1, 1}, {2, 1}, {3, 0}}, {1, 2, 1, 1}, 8);
  b.spline_fit({{0, 0}, {1, 2}, {3, 1}}, 8).ellipse({0, 0}, {2, 0}, 0.5, 0, 1, "0", -1);
  b.insert("B", {5, 5}, 1, 1, 0, "0", 3, 2, 4, 4);
  std::vector<std::string> lines;
  {
    const std::string text = b.str();
    std::size_t pos = 0;
    while (pos < text.size()) {
      const std::size_t end = text.find('\n', pos);
      lines.push_back(text.substr(pos, end - pos));
      pos = end + 1;
    }
  }
  const char* values[] = {"0", "-1", "1e308", "99999999999", "SPLINE", "INSERT", "POLYLINE", "SEQEND", "42", "90",
                          "73", "B", "ENDSEC", "", "3.5", "-0.5"};
  Rng rng(99);
  int errors = 0;
  for (int round = 0; round < 3000; ++round) {
    std::vector<std::string> l = lines;
    const int edits = 1 + static_cast<int>(rng.below(3));
    for (int k = 0; k < edits; ++k) {
      const std::size_t i = rng.below(l.size());
      switch (rng.below(4)) {
        case 0: l.erase(l.begin() + static_cast<std::ptrdiff_t>(i)); break;
        case 1: l.insert(l.begin() + static_cast<std::ptrdiff_t>(i), l[i]); break;
        case 2: std::swap(l[i], l[rng.below(l.size())]); break;
        default: l[i] = values[rng.below(std::size(values))]; break;
      }
    }
    std::string t;
    for (const auto& x : l) t += x + "\n";
    const auto r = io::read_dxf_string(t, "mutant.dxf", {});
    if (!r.ok()) {
      ++errors;
      EXPECT_FALSE(r.error().message.empty());
    }
  }
  EXPECT_GT(errors, 100);
}

}  // namespace
}  // namespace cutroute::test

namespace cutroute::test {
namespace {

// Angles no drawing has (an ARC to 1e300 degrees, an ELLIPSE to parameter -1e7) are errors naming
// the entity's line, not an arc of fmod's choosing; a unit the drawing names but cutroute cannot
// read, and an entity it skips, are warnings with a code (summary.csv counts them by code).
TEST(DxfBad, AbsurdAnglesAndUnknownUnitsAreSaid) {
  {
    DxfBuilder b;
    b.arc({0, 0}, 5, 0, 1e300);
    const auto r = io::read_dxf_string(b.str(), "arc.dxf", {});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "ARC angle beyond ±1e6 degrees");
    EXPECT_TRUE(r.error().line.has_value());
  }
  {
    DxfBuilder b;
    b.begin_block("B").circle({5, 0}, 1).end_block().insert("B", {0, 0}, 1, 1, 1e300);
    const auto r = io::read_dxf_string(b.str(), "insert.dxf", {});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "INSERT rotation beyond ±1e6 degrees");
    EXPECT_TRUE(r.error().line.has_value());
  }
  {
    DxfBuilder b;
    b.ellipse({0, 0}, {2, 0}, 0.5, 0, -1e7);
    const auto r = io::read_dxf_string(b.str(), "ellipse.dxf", {});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "ELLIPSE parameter beyond ±1e6");
  }
  {
    DxfBuilder b;
    b.arc({0, 0}, 5, -30, 1e6);  // still a drawing's angle: 1e6 = 2777 turns + 280 degrees
    EXPECT_TRUE(io::read_dxf_string(b.str(), "ok.dxf", {}).ok());
  }
  DxfBuilder b;
  b.insunits(99).circle({0, 0}, 5).circle({20, 0}, -1);
  const auto r = io::read_dxf_string(b.str(), "units.dxf", {});
  ASSERT_TRUE(r.ok());
  std::map<std::string, int> codes;
  for (const auto& d : r->diagnostics) ++codes[d.code];
  EXPECT_EQ(codes["dxf.units_ignored"], 1);
  EXPECT_EQ(codes["dxf.entity_skipped"], 1);
  EXPECT_EQ(codes[""], 0);
  EXPECT_DOUBLE_EQ(r->mm_per_unit, 1.0);
}

}  // namespace
}  // namespace cutroute::test
