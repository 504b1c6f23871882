// reader_dialect(): a program written with a post-processor dialect reads back with the reader
// dialect derived from it, without warnings and with the writer's measures.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <cutroute/nc/gcode_reader.hpp>
#include <cutroute/nc/gcode_writer.hpp>
#include <cutroute/nc/post_dialect.hpp>

namespace cutroute::nc {
namespace {

using geometry::Contour;
using geometry::Vertex;

// A Ø40 circle (two half arcs) and a 100 x 50 rectangle with a straight lead-in and a lead-out:
// the THC is released after each lead-in and held again before each lead-out.
Toolpath two_contours() {
  Toolpath tp;
  tp.pierce_time_s = 0.5;
  CutSegment circle;
  circle.pierce = {30, 50};
  circle.feed_mm_min = 3000;
  circle.pieces.push_back(
      {Contour{{Vertex{{30, 50}, 0}, Vertex{{35, 50}, 0}}, false}, PieceRole::lead_in, -1});
  circle.pieces.push_back({Contour{{Vertex{{35, 50}, 1}, Vertex{{75, 50}, 1}, Vertex{{35, 50}, 0}}, false},
                           PieceRole::contour, 0});
  tp.segments.push_back(circle);
  CutSegment square;
  square.pierce = {195, 0};
  square.feed_mm_min = 6000;
  square.pieces.push_back(
      {Contour{{Vertex{{195, 0}, 0}, Vertex{{200, 0}, 0}}, false}, PieceRole::lead_in, -1});
  square.pieces.push_back({Contour{{Vertex{{200, 0}, 0}, Vertex{{200, 50}, 0}, Vertex{{300, 50}, 0},
                                    Vertex{{300, 0}, 0}, Vertex{{200, 0}, 0}},
                                   false},
                           PieceRole::contour, 1});
  square.pieces.push_back(
      {Contour{{Vertex{{200, 0}, 0}, Vertex{{203, -3}, 0}}, false}, PieceRole::lead_out, -1});
  tp.segments.push_back(square);
  return tp;
}

bool has_warning(const ProgramStats& s, const std::string& text) {
  for (const auto& w : s.warnings)
    if (w.message.find(text) != std::string::npos) return true;
  return false;
}

TEST(ReaderDialect, OurPlasmaProgramReadsBackWithoutWarnings) {
  const auto post = find_post_dialect("plasma-thc");
  ASSERT_TRUE(post.ok()) << format(post.error());
  const auto w = write_gcode(two_contours(), *post, GcodeWriteOptions{"plasma"});
  ASSERT_NE(w.text.find("M64 P0"), std::string::npos) << w.text;
  ASSERT_NE(w.text.find("M65 P0"), std::string::npos) << w.text;

  const auto dialect = reader_dialect(*post);
  ASSERT_TRUE(dialect.ok()) << format(dialect.error());
  ReadOptions ro;
  ro.dialect = *dialect;
  const auto stats = read_gcode(w.text, "plasma.ngc", ro);
  ASSERT_TRUE(stats.ok()) << format(stats.error());
  for (const auto& d : stats->warnings) ADD_FAILURE() << format(d);
  EXPECT_EQ(stats->suppressed_warnings, 0u);
  EXPECT_EQ(stats->pierces, w.pierces);
  EXPECT_EQ(stats->pierces, 2u);
  EXPECT_NEAR(stats->cut_length_mm, w.cut_length_mm, 1e-6);
  EXPECT_NEAR(stats->rapid_length_mm, w.rapid_length_mm, 1e-6);
  EXPECT_EQ(stats->beam_on_rapids, 0u);
  EXPECT_DOUBLE_EQ(stats->feed_off_length_mm, 0.0);
  // G4 P{pierce_s} is in seconds: each pierce dwells 0.5 s, and that dwell is the pierce.
  EXPECT_EQ(stats->pierce_dwells, 2u);
  EXPECT_NEAR(stats->pierce_dwell_s, 1.0, 1e-12);

  // The plain rs274 reader dialect does not know the THC outputs: the same program warns (this
  // is what the derived dialect is for) and still measures the same.
  const auto plain = read_gcode(w.text, "plasma.ngc", ReadOptions{});
  ASSERT_TRUE(plain.ok()) << format(plain.error());
  EXPECT_TRUE(has_warning(*plain, "unknown word M64 ignored"));
  EXPECT_TRUE(has_warning(*plain, "unknown word M65 ignored"));
  EXPECT_NEAR(plain->cut_length_mm, stats->cut_length_mm, 1e-12);
}

TEST(ReaderDialect, ShippedDialectsDerive) {
  auto generic = find_post_dialect("generic");
  ASSERT_TRUE(generic.ok());
  auto g = reader_dialect(*generic);
  ASSERT_TRUE(g.ok()) << format(g.error());
  EXPECT_EQ(g->name, "generic");
  EXPECT_EQ(g->beam_on, std::vector<int>{3});
  EXPECT_EQ(g->beam_off, std::vector<int>{5});
  EXPECT_TRUE(g->inert.empty());  // M30 ends the program: a fixed meaning, not inert
  auto plasma = find_post_dialect("plasma-thc");
  ASSERT_TRUE(plasma.ok());
  auto p = reader_dialect(*plasma);
  ASSERT_TRUE(p.ok()) << format(p.error());
  EXPECT_EQ(p->beam_on, std::vector<int>{3});
  EXPECT_EQ(p->beam_off, std::vector<int>{5});
  EXPECT_EQ(p->inert, (std::vector<int>{64, 65}));
  EXPECT_EQ(p->dwell_p_unit, DwellUnit::seconds);
}

TEST(ReaderDialect, CodesOfAHandWrittenDialect) {
  PostDialect post;
  post.name = "coolant-laser";
  post.header = {"G17 G90 G40 G94", "M52 P1 (gas valve; M99 in a comment is no code)"};
  post.beam_on = {"M7"};
  post.pierce = {"G4 P{pierce_s}"};
  post.beam_off = {"M9"};
  post.thc_on = {"M62 P1"};
  post.thc_off = {"M63 P1"};
  post.footer = {"M63 P1", "M5"};  // M5 is not a beam code here: inert
  post.program_end = "M30";
  const auto d = reader_dialect(post);
  ASSERT_TRUE(d.ok()) << format(d.error());
  EXPECT_EQ(d->name, "coolant-laser");
  EXPECT_EQ(d->beam_on, std::vector<int>{7});
  EXPECT_EQ(d->beam_off, std::vector<int>{9});
  EXPECT_EQ(d->inert, (std::vector<int>{5, 52, 62, 63}));
  EXPECT_EQ(d->dwell_p_unit, DwellUnit::seconds);
  EXPECT_TRUE(d->switches_on(7));
  EXPECT_FALSE(d->switches_on(3));
  EXPECT_TRUE(d->is_inert(62));
  EXPECT_FALSE(d->is_inert(30));

  // Several M words on one beam line all switch: "M8 M7" (gas, then beam) both turn it on.
  post.beam_on = {"M8 M7"};
  post.beam_off = {"M9", "M10"};
  const auto two = reader_dialect(post);
  ASSERT_TRUE(two.ok()) << format(two.error());
  EXPECT_EQ(two->beam_on, (std::vector<int>{7, 8}));
  EXPECT_EQ(two->beam_off, (std::vector<int>{9, 10}));
}

TEST(ReaderDialect, ErrorsNameTheFileAndTheField) {
  const auto path = std::filesystem::temp_directory_path() / "cutroute-reader-dialect.json";
  const auto derive = [&](const std::string& json) {
    std::ofstream(path) << json;
    auto post = load_post_dialect(path.string());
    return post ? reader_dialect(*post) : Result<Dialect>(post.error());
  };
  auto r = derive(R"({"beam_on": ["G4 P0"]})");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().file, path.string());
  EXPECT_NE(r.error().message.find("'beam_on' writes no M code"), std::string::npos) << r.error().message;
  r = derive(R"({"beam_on": ["M3"], "beam_off": ["M30"]})");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("'beam_off' writes M30, which has a fixed meaning"), std::string::npos)
      << r.error().message;
  r = derive(R"({"beam_on": ["M3"], "beam_off": ["M5 M3"]})");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("'beam_on' and 'beam_off' both write M3"), std::string::npos)
      << r.error().message;
  r = derive(R"({"thc_on": ["M65 P{output}"]})");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().file, path.string());
  EXPECT_NE(r.error().message.find("field 'thc_on': line 'M65 P{output}' is no G-code block"), std::string::npos)
      << r.error().message;
  r = derive(R"({"header": ["M62.5"]})");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("field 'header'"), std::string::npos) << r.error().message;

  // Each line the writer cannot rely on is refused when the file is read, naming the field.
  const std::pair<const char*, const char*> refused[] = {
      {R"({"units": "in", "header": ["G21 G17"]})", "field 'header': line 'G21 G17' switches to millimetres (G21)"},
      {R"({"header": ["G20"]})", "switches to inches (G20) where the dialect's units are mm"},
      {R"({"footer": ["G91"]})", "field 'footer': line 'G91' switches to incremental coordinates"},
      {R"({"header": ["G90.1"]})", "makes arc centres absolute (G90.1)"},
      {R"({"header": ["G41"]})", "switches cutter compensation on, which only 'kerf_left' and 'kerf_right' may"},
      {R"({"beam_on": ["M3 S1 G1 X0"]})", "field 'beam_on': line 'M3 S1 G1 X0' moves the head in the plane"},
      {R"({"pierce": ["G4 Y{pierce_s}"]})", "field 'pierce': line 'G4 Y{pierce_s}' moves the head"},
      {R"({"kerf_left": ""})", "'kerf_left' must write G41"},
      {R"({"kerf_right": "M3 S1"})", "'kerf_right' must write G42"},
      {R"({"kerf_off": "G49"})", "'kerf_off' must write G40"},
      {R"({"program_end": "G0 X0"})", "'program_end' must write M2 or M30"},
      {R"({"header": ["G17\nG90"]})", "field 'header': a line holds printable ASCII only"},
      {"{\"header\": [\"(F\xC3\xBC" "r)\"]}", "field 'header': a line holds printable ASCII only"},
      {R"({"pierce": ["G4 P{pierce_s}", "G4 P{pierce_ms}"]})", "G4 P{pierce_s} (seconds) beside {pierce_ms}"},
      {R"({"decimals": 3, "decimals": 4})", "dialect field 'decimals' appears twice"},
  };
  for (const auto& [json, message] : refused) {
    r = derive(json);
    ASSERT_FALSE(r.ok()) << json;
    EXPECT_EQ(r.error().file, path.string());
    EXPECT_NE(r.error().message.find(message), std::string::npos) << json << ": " << r.error().message;
  }
  r = derive(R"({"header": [")" + std::string(201, 'G') + R"("]})");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("longer than 200 characters"), std::string::npos) << r.error().message;
  // Accepted: a tab between words, a torch Z move with the beam, a park move in the footer, and
  // Fanuc-style dwells (G4 X seconds, or {pierce_ms}), which make the reader count G4 P in ms.
  for (const char* json : {R"({"header": ["G17\tG90"], "beam_on": ["M3 S1 G0 Z1"], "footer": ["G0 X0 Y1200"]})",
                           R"({"pierce": ["G04 X{pierce_s}"]})", R"({"pierce": ["G4 P{pierce_ms}"]})"}) {
    r = derive(json);
    ASSERT_TRUE(r.ok()) << json << ": " << r.error().message;
    EXPECT_EQ(r->dwell_p_unit, std::string(json).find("pierce") != std::string::npos ? DwellUnit::milliseconds : DwellUnit::seconds)
        << json;
  }
  std::filesystem::remove(path);
  // A dialect file that is not there is said so, not taken for an unknown name.
  const auto missing = find_post_dialect("no/such/dialect.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("dialect file 'no/such/dialect.json' not found"), std::string::npos) << missing.error().message;

  PostDialect in_code;
  in_code.name = "mine";
  in_code.beam_on = {};
  r = reader_dialect(in_code);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("dialect 'mine': "), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace cutroute::nc
