// Reader tests on drawings generated here: every entity and variant, transforms, units, layers.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include <cutroute/core/random.hpp>
#include <cutroute/io/dxf.hpp>

#include "contour_math.hpp"
#include "support/dxf_builder.hpp"

namespace cutroute::test {
namespace {

using geometry::Vertex;
constexpr double kPi = std::numbers::pi;

io::DxfDrawing read(const std::string& text, const io::DxfOptions& opt = {}) {
  auto r = io::read_dxf_string(text, "test.dxf", opt);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : format(r.error()));
  if (!r.ok()) return {};
  return std::move(r).value();
}

void expect_point(Vec2 p, Vec2 q, double tol = 1e-9) {
  EXPECT_NEAR(p.x, q.x, tol);
  EXPECT_NEAR(p.y, q.y, tol);
}

// 1-based line of the "0" group code before the n-th (0-based) line equal to `s` in `text`.
long line_of(const std::string& text, const std::string& s, int nth = 0) {
  long line = 1;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = text.find('\n', pos);
    const std::string l = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    if (l == s && nth-- == 0) return line - 1;
    if (end == std::string::npos) break;
    pos = end + 1;
    ++line;
  }
  return -1;
}

TEST(DxfReader, LineArcCircle) {
  DxfBuilder b;
  b.insunits(4).line({0, 0}, {10, 5}).arc({5, 5}, 10, 0, 90).circle({-3, 4}, 2.5);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 3u);
  const auto& line = d.entities[0];
  EXPECT_EQ(line.type, "LINE");
  EXPECT_FALSE(line.path.closed);
  ASSERT_EQ(line.path.vertices.size(), 2u);
  EXPECT_EQ(line.path.vertices[0].p, (Vec2{0, 0}));
  EXPECT_EQ(line.path.vertices[1].p, (Vec2{10, 5}));

  const auto& arc = d.entities[1];
  EXPECT_EQ(arc.type, "ARC");
  ASSERT_EQ(arc.path.vertices.size(), 2u);
  expect_point(arc.path.vertices[0].p, {15, 5});
  expect_point(arc.path.vertices[1].p, {5, 15});
  EXPECT_NEAR(arc.path.vertices[0].bulge, std::tan(kPi / 8), 1e-12);  // 90° counter-clockwise
  EXPECT_NEAR(path_length(arc.path), 10 * kPi / 2, 1e-9);

  const auto& circle = d.entities[2];
  EXPECT_EQ(circle.type, "CIRCLE");
  EXPECT_TRUE(circle.path.closed);
  ASSERT_EQ(circle.path.vertices.size(), 2u);
  EXPECT_EQ(circle.path.vertices[0].bulge, 1.0);
  EXPECT_EQ(circle.path.vertices[1].bulge, 1.0);
  EXPECT_NEAR(path_length(circle.path), 2 * kPi * 2.5, 1e-9);
  EXPECT_NEAR(path_area(circle.path), kPi * 2.5 * 2.5, 1e-9);
  EXPECT_EQ(d.entity_counts.at("LINE"), 1u);
  EXPECT_EQ(d.entity_counts.at("ARC"), 1u);
  EXPECT_EQ(d.entity_counts.at("CIRCLE"), 1u);
  EXPECT_TRUE(d.skipped.empty());
}

TEST(DxfReader, ArcAcrossZeroDegreesAndFullArc) {
  DxfBuilder b;
  b.arc({0, 0}, 1, 350, 10).arc({0, 0}, 2, 0, 360);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 2u);
  EXPECT_NEAR(path_length(d.entities[0].path), 2 * kPi * 20 / 360, 1e-12);
  EXPECT_GT(d.entities[0].path.vertices[0].bulge, 0);
  // An ARC from 0 to 360 degrees is a full circle.
  EXPECT_TRUE(d.entities[1].path.closed);
  EXPECT_NEAR(path_length(d.entities[1].path), 4 * kPi, 1e-12);
}

// Angles count modulo 360, as in AutoCAD: an end more than a turn past the start is not a full
// circle (found by a hand-written DXF audit: -30..390 was read as a circle).
TEST(DxfReader, ArcAnglesCountModuloAFullTurn) {
  DxfBuilder b;
  b.arc({0, 0}, 10, -30, 390).arc({0, 0}, 10, 10, 400).arc({0, 0}, 1, 0, 720).arc({0, 0}, 1, 90, -270);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 4u);
  EXPECT_FALSE(d.entities[0].path.closed);
  EXPECT_NEAR(path_length(d.entities[0].path), 10 * kPi / 3, 1e-12);  // 330..30
  EXPECT_NEAR(dist(d.entities[0].path.vertices.front().p, {10 * std::cos(-kPi / 6), 10 * std::sin(-kPi / 6)}), 0, 1e-12);
  EXPECT_FALSE(d.entities[1].path.closed);
  EXPECT_NEAR(path_length(d.entities[1].path), 10 * kPi / 6, 1e-12);  // 10..40
  for (std::size_t k : {2u, 3u}) {  // whole turns apart: a full circle
    EXPECT_TRUE(d.entities[k].path.closed) << k;
    EXPECT_NEAR(path_length(d.entities[k].path), 2 * kPi, 1e-12) << k;
  }
}

// A 40 x 20 rectangle with its top-right corner rounded by r = 5 (counter-clockwise).
std::vector<Vertex> rounded_rect() {
  const double b = std::tan(kPi / 8);
  return {{{0, 0}, 0}, {{40, 0}, 0}, {{40, 15}, b}, {{35, 20}, 0}, {{0, 20}, 0}};
}
constexpr double kRoundedRectLength = 40 + 15 + 35 + 20 + 2 * kPi * 5 / 4;
const double kRoundedRectArea = 40 * 20 - 25 + kPi * 25 / 4;

TEST(DxfReader, LwpolylineWithBulgesAndClosedFlag) {
  DxfBuilder b;
  b.lwpolyline(rounded_rect(), true, "cut").lwpolyline(rounded_rect(), false, "cut");
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 2u);
  EXPECT_TRUE(d.entities[0].path.closed);
  EXPECT_EQ(d.entities[0].path.vertices, rounded_rect());
  EXPECT_NEAR(path_length(d.entities[0].path), kRoundedRectLength, 1e-9);
  EXPECT_NEAR(path_area(d.entities[0].path), kRoundedRectArea, 1e-9);
  EXPECT_FALSE(d.entities[1].path.closed);
  EXPECT_NEAR(path_length(d.entities[1].path), kRoundedRectLength - 20, 1e-9);
  EXPECT_EQ(d.entities[0].layer, "cut");
}

TEST(DxfReader, R12PolylineEqualsLwpolyline) {
  DxfBuilder b;
  b.polyline(rounded_rect(), true).lwpolyline(rounded_rect(), true);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 2u);
  EXPECT_EQ(d.entities[0].type, "POLYLINE");
  EXPECT_EQ(d.entities[0].path, d.entities[1].path);
  EXPECT_EQ(d.entity_counts.at("POLYLINE"), 1u);
  EXPECT_EQ(d.entity_counts.count("VERTEX"), 0u);
}

TEST(DxfReader, ExtrusionMinusZMirrorsArcCircleAndPolyline) {
  DxfBuilder b;
  b.arc({10, 0}, 10, 0, 90, "0", -1).circle({10, 5}, 3, "0", -1).lwpolyline(rounded_rect(), true, "0", -1);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 3u);
  // OCS (x, y) is WCS (-x, y): the arc runs from (-20, 0) to (-10, 10), clockwise.
  const auto& arc = d.entities[0].path;
  expect_point(arc.vertices[0].p, {-20, 0});
  expect_point(arc.vertices[1].p, {-10, 10});
  EXPECT_NEAR(arc.vertices[0].bulge, -std::tan(kPi / 8), 1e-12);
  const auto& circle = d.entities[1].path;
  EXPECT_EQ(circle.vertices[0].bulge, -1.0);
  EXPECT_NEAR(path_area(circle), -kPi * 9, 1e-9);
  Vec2 centre = (circle.vertices[0].p + circle.vertices[1].p) * 0.5;
  expect_point(centre, {-10, 5});
  const auto& poly = d.entities[2].path;
  EXPECT_NEAR(path_area(poly), -kRoundedRectArea, 1e-9);
  EXPECT_NEAR(path_length(poly), kRoundedRectLength, 1e-9);
  expect_point(poly.vertices[1].p, {-40, 0});
}

TEST(DxfReader, CircleAsTwoHalfArcs) {
  DxfBuilder b;
  b.arc({7, 7}, 4, 0, 180).arc({7, 7}, 4, 180, 360);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 2u);
  const auto& a = d.entities[0].path;
  const auto& c = d.entities[1].path;
  EXPECT_NEAR(a.vertices[0].bulge, 1.0, 1e-12);
  EXPECT_NEAR(c.vertices[0].bulge, 1.0, 1e-12);
  expect_point(a.vertices[1].p, c.vertices[0].p, 1e-12);
  expect_point(c.vertices[1].p, a.vertices[0].p, 1e-12);
  EXPECT_NEAR(path_length(a) + path_length(c), 8 * kPi, 1e-12);
}

// p' = at + R(rot) * (scale * (p - base))
Vec2 place(Vec2 p, Vec2 base, Vec2 at, double sx, double sy, double rot_deg) {
  const double r = rot_deg * kPi / 180;
  const Vec2 q{(p.x - base.x) * sx, (p.y - base.y) * sy};
  return {at.x + q.x * std::cos(r) - q.y * std::sin(r), at.y + q.x * std::sin(r) + q.y * std::cos(r)};
}

TEST(DxfReader, RotatedScaledInsertWithBasePoint) {
  DxfBuilder b;
  b.begin_block("PART", {2, 3}).lwpolyline(rounded_rect(), true).arc({2, 3}, 1, 0, 90).end_block();
  b.insert("PART", {100, 50}, 2, 2, 90, "nest");
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 2u);
  const auto& poly = d.entities[0].path;
  const auto src = rounded_rect();
  for (std::size_t i = 0; i < src.size(); ++i) {
    expect_point(poly.vertices[i].p, place(src[i].p, {2, 3}, {100, 50}, 2, 2, 90));
    EXPECT_NEAR(poly.vertices[i].bulge, src[i].bulge, 1e-12);
  }
  EXPECT_NEAR(path_area(poly), 4 * kRoundedRectArea, 1e-6);
  expect_point(d.entities[1].path.vertices[0].p, place({3, 3}, {2, 3}, {100, 50}, 2, 2, 90));
  EXPECT_EQ(d.entities[0].block, "PART");
  EXPECT_EQ(d.entities[0].layer, "nest");  // layer 0 inside the block inherits the INSERT's
  EXPECT_EQ(d.entity_counts.at("INSERT"), 1u);
  EXPECT_EQ(d.entity_counts.at("LWPOLYLINE"), 1u);
}

TEST(DxfReader, MirroredInsertFlipsBulges) {
  DxfBuilder b;
  b.begin_block("P").lwpolyline(rounded_rect(), true).circle({5, 5}, 2).end_block();
  b.insert("P", {0, 0}, -1, 1, 0).insert("P", {0, 0}, 1, -1, 30);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 4u);
  for (int k : {0, 2}) {
    const auto& poly = d.entities[static_cast<std::size_t>(k)].path;
    EXPECT_NEAR(path_area(poly), -kRoundedRectArea, 1e-9);
    EXPECT_NEAR(path_length(poly), kRoundedRectLength, 1e-9);
    EXPECT_NEAR(poly.vertices[2].bulge, -std::tan(kPi / 8), 1e-12);
  }
  expect_point(d.entities[0].path.vertices[1].p, {-40, 0});
  expect_point(d.entities[2].path.vertices[3].p, place({35, 20}, {}, {}, 1, -1, 30));
  EXPECT_EQ(d.entities[1].path.vertices[0].bulge, -1.0);
}

TEST(DxfReader, NonUniformScaleTurnsCircleIntoEllipse) {
  DxfBuilder b;
  b.begin_block("C").circle({0, 0}, 10).end_block();
  b.insert("C", {50, 50}, 2, 1, 30);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 1u);
  const auto& c = d.entities[0].path;
  EXPECT_TRUE(c.closed);
  EXPECT_GT(c.vertices.size(), 4u);
  const double r = 30 * kPi / 180;
  auto ellipse = [&](double t) {
    const Vec2 q{20 * std::cos(t), 10 * std::sin(t)};
    return Vec2{50 + q.x * std::cos(r) - q.y * std::sin(r), 50 + q.x * std::sin(r) + q.y * std::cos(r)};
  };
  EXPECT_LE(deviation(c, ellipse, 0, 2 * kPi), 0.01 + 1e-6);
  EXPECT_NEAR(path_area(c), kPi * 20 * 10, 0.01 * 2 * kPi * 20);
}

TEST(DxfReader, NestedBlocksInheritLayersAndKeepTopHandle) {
  DxfBuilder b;
  b.begin_block("INNER", {1, 0}).line({1, 0}, {2, 0}).line({1, 0}, {1, 1}, "own").end_block();
  b.begin_block("OUTER").insert("INNER", {10, 0}, 1, 1, 90).insert("INNER", {20, 0}, 1, 1, 0, "mid").end_block();
  b.insert("OUTER", {100, 0}, 1, 1, 0, "top");
  const std::string text = b.str();
  const auto d = read(text);
  ASSERT_EQ(d.entities.size(), 4u);
  // INNER's layer-0 line: via an INSERT on layer 0 it inherits "top"; via "mid" it is "mid".
  EXPECT_EQ(d.entities[0].layer, "top");
  EXPECT_EQ(d.entities[1].layer, "own");
  EXPECT_EQ(d.entities[2].layer, "mid");
  EXPECT_EQ(d.entities[3].layer, "own");
  expect_point(d.entities[0].path.vertices[1].p, {110, 1});
  expect_point(d.entities[2].path.vertices[1].p, {121, 0});
  const long top_line = line_of(text, "INSERT", 2);
  for (const auto& e : d.entities) {
    EXPECT_EQ(e.line, top_line);
    EXPECT_EQ(e.block, "INNER");
  }
  EXPECT_EQ(d.entities[0].source_line, line_of(text, "LINE", 0));
  EXPECT_EQ(d.entity_counts.at("INSERT"), 3u);
  EXPECT_EQ(d.entity_counts.at("LINE"), 4u);
}

TEST(DxfReader, MinsertRowsAndColumns) {
  DxfBuilder b;
  b.begin_block("SQ").lwpolyline({{{0, 0}, 0}, {{5, 0}, 0}, {{5, 5}, 0}, {{0, 5}, 0}}, true).end_block();
  b.insert("SQ", {0, 0}, 1, 1, 90, "0", 3, 2, 10, 20);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 6u);
  // Cells are spaced along the rotated axes: column c, row r sits at R(90) (10 c, 20 r).
  std::vector<Vec2> firsts;
  for (const auto& e : d.entities) firsts.push_back(e.path.vertices[0].p);
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 3; ++c) {
      const Vec2 want = place({10.0 * c, 20.0 * r}, {}, {}, 1, 1, 90);
      EXPECT_TRUE(std::any_of(firsts.begin(), firsts.end(), [&](Vec2 p) { return dist(p, want) < 1e-9; }))
          << "cell " << r << "," << c;
    }
  }
  EXPECT_EQ(d.entity_counts.at("LWPOLYLINE"), 6u);
}

TEST(DxfReader, InsertWithExtrusionMinusZIsMirrored) {
  DxfBuilder b;
  b.begin_block("P").lwpolyline(rounded_rect(), true).end_block();
  b.insert("P", {5, 0}, 1, 1, 0, "0", 1, 1, 0, 0, -1);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 1u);
  expect_point(d.entities[0].path.vertices[1].p, {-45, 0});
  EXPECT_NEAR(path_area(d.entities[0].path), -kRoundedRectArea, 1e-9);
}

TEST(DxfReader, UndefinedBlockIsAWarning) {
  DxfBuilder b;
  b.insert("NOPE", {0, 0}).line({0, 0}, {1, 1});
  const auto d = read(b.str());
  EXPECT_EQ(d.entities.size(), 1u);
  ASSERT_FALSE(d.diagnostics.empty());
  EXPECT_EQ(d.diagnostics[0].message, "INSERT of undefined block 'NOPE' skipped");
  EXPECT_EQ(d.diagnostics[0].severity, Severity::warning);
}

// The same drawing in inches and, multiplied by 25.4, in millimetres.
DxfBuilder twin(double k, int insunits) {
  DxfBuilder b;
  b.insunits(insunits);
  b.begin_block("B", {k * 1, k * 2}).arc({k * 1, k * 2}, k * 3, 10, 250).end_block();
  b.line({0, 0}, {k * 4, k * 0.5})
      .arc({k * 2, k * 2}, k * 1.25, 30, 300)
      .circle({k * -1, k * 3}, k * 0.75)
      .lwpolyline({{{0, 0}, 0.3}, {{k * 2, 0}, 0}, {{k * 2, k * 1}, -0.5}}, true)
      .ellipse({k * 5, k * 5}, {k * 2, k * 1}, 0.4, 0.5, 4.0)
      .spline(3, {0, 0, 0, 0, 1, 1, 1, 1}, {{0, 0}, {k * 1, k * 2}, {k * 3, k * 2}, {k * 4, 0}}, {}, 8)
      .insert("B", {k * 10, k * 10}, 1.5, 1.5, 45);
  return b;
}

TEST(DxfReader, InchFileGivesTheContoursOfItsMillimetreTwin) {
  const auto in = read(twin(1.0, 1).str());
  const auto mm = read(twin(25.4, 4).str());
  EXPECT_EQ(in.units_in_file, "in");
  EXPECT_EQ(in.units_source, "$INSUNITS");
  EXPECT_EQ(in.mm_per_unit, 25.4);
  EXPECT_EQ(mm.units_in_file, "mm");
  ASSERT_EQ(in.entities.size(), mm.entities.size());
  for (std::size_t i = 0; i < in.entities.size(); ++i) {
    const auto& a = in.entities[i].path;
    const auto& b = mm.entities[i].path;
    EXPECT_EQ(a.closed, b.closed);
    // Curves are fitted after unit scaling, so the inch file's SPLINE/ELLIPSE get the same
    // arcs as the mm twin; all coordinates agree to rounding (a few ulps of 25.4 x).
    ASSERT_EQ(a.vertices.size(), b.vertices.size()) << in.entities[i].type;
    for (std::size_t k = 0; k < a.vertices.size(); ++k) {
      expect_point(a.vertices[k].p, b.vertices[k].p, 1e-9);
      EXPECT_NEAR(a.vertices[k].bulge, b.vertices[k].bulge, 1e-9);
    }
  }
}

TEST(DxfReader, UnitsRules) {
  struct Case {
    std::optional<int> insunits, measurement;
    std::optional<std::string> option;
    std::string units_in_file, source;
    double mm;
  };
  const Case cases[] = {
      {4, {}, {}, "mm", "$INSUNITS", 1.0},
      {5, {}, {}, "cm", "$INSUNITS", 10.0},
      {6, {}, {}, "m", "$INSUNITS", 1000.0},
      {1, 1, {}, "in", "$INSUNITS", 25.4},
      {2, {}, {}, "ft", "$INSUNITS", 304.8},
      {0, 0, {}, "unitless", "$INSUNITS", 1.0},  // $INSUNITS 0 says unitless: mm, $MEASUREMENT unused
      {{}, 0, {}, "in", "$MEASUREMENT", 25.4},   // no $INSUNITS: $MEASUREMENT decides
      {{}, 1, {}, "mm", "$MEASUREMENT", 1.0},
      {0, {}, {}, "unitless", "$INSUNITS", 1.0},
      {{}, {}, {}, "unitless", "default", 1.0},
      {1, {}, "mm", "in", "option", 1.0},        // the option overrides the scale only
      {{}, {}, "ft", "unitless", "option", 304.8},
  };
  for (const auto& c : cases) {
    DxfBuilder b;
    if (c.insunits) b.insunits(*c.insunits);
    if (c.measurement) b.measurement(*c.measurement);
    b.line({0, 0}, {1, 0});
    io::DxfOptions opt;
    opt.units = c.option;
    const auto d = read(b.str(), opt);
    EXPECT_EQ(d.units_in_file, c.units_in_file);
    EXPECT_EQ(d.units_source, c.source);
    EXPECT_EQ(d.mm_per_unit, c.mm);
    ASSERT_EQ(d.entities.size(), 1u);
    EXPECT_EQ(d.entities[0].path.vertices[1].p.x, c.mm);
  }
  io::DxfOptions bad;
  bad.units = "furlong";
  auto r = io::read_dxf_string(DxfBuilder().line({0, 0}, {1, 0}).str(), "x.dxf", bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "unknown units 'furlong' (use mm, cm, m, in or ft)");
}

TEST(DxfReader, LayerFilters) {
  DxfBuilder b;
  b.line({0, 0}, {1, 0}, "Cut").line({0, 1}, {1, 1}, "Gravír").circle({5, 5}, 1, "sheet").text({0, 0}, "x", "Cut");
  io::DxfOptions keep;
  keep.layers = {"cut", "SHEET"};
  auto d = read(b.str(), keep);
  ASSERT_EQ(d.entities.size(), 2u);
  EXPECT_EQ(d.entities[0].layer, "Cut");
  EXPECT_EQ(d.entities[1].layer, "sheet");
  EXPECT_EQ(d.entity_counts.at("TEXT"), 1u);
  io::DxfOptions drop;
  drop.ignore_layers = {"Gravír"};
  d = read(b.str(), drop);
  ASSERT_EQ(d.entities.size(), 2u);
  EXPECT_EQ(d.entity_counts.count("LINE"), 1u);
  EXPECT_EQ(d.entity_counts.at("LINE"), 1u);
}

// A filter naming no layer of the drawing is said, with the drawing's layers: an error when nothing
// would be left (--layers), else a warning.
TEST(DxfReader, LayerFiltersNamingNoLayerOfTheDrawing) {
  DxfBuilder b;
  b.line({0, 0}, {1, 0}, "Cut").line({0, 1}, {1, 1}, "Gravír").circle({5, 5}, 1, "sheet").text({0, 0}, "x", "Cut");
  const auto all = read(b.str());
  EXPECT_EQ(all.layers, (std::map<std::string, std::size_t>{{"Cut", 2}, {"Gravír", 1}, {"sheet", 1}}));
  io::DxfOptions none;
  none.layers = {"Nope"};
  auto r = io::read_dxf_string(b.str(), "x.dxf", none);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message,
            "no layer given with --layers is in the drawing ('Nope'); its layers, with their entities: Cut (2), Gravír (1), sheet (1)");
  io::DxfOptions some;
  some.layers = {"cut", "Nope"};
  const auto d = read(b.str(), some);
  EXPECT_EQ(d.entities.size(), 1u);
  auto warned = [](const io::DxfDrawing& x, const std::string& text) {
    for (const auto& w : x.diagnostics)
      if (w.message.find(text) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(warned(d, "layer 'Nope' (--layers) is not in the drawing; its layers: Cut (2)"));
  io::DxfOptions ignore;
  ignore.ignore_layers = {"Engrave"};
  EXPECT_TRUE(warned(read(b.str(), ignore), "layer 'Engrave' (--ignore-layers) is not in the drawing"));
  EXPECT_FALSE(warned(read(b.str(), io::DxfOptions{}), "is not in the drawing"));
}

// Drawings before AutoCAD 2007 store names in their code page ($DWGCODEPAGE, Windows-1252 when
// absent), AutoCAD 2000-2004 characters outside it as \U+XXXX; reports and pictures get UTF-8.
TEST(DxfReader, NamesInTheDrawingsCodePageComeOutAsUtf8) {
  DxfBuilder b;
  b.begin_block("Fl\xFC" "gel").line({0, 0}, {1, 0}).end_block();
  b.line({0, 0}, {1, 0}, "Grav\xEDr").line({0, 1}, {1, 1}, "Durchbr\\U+00FCche").line({0, 2}, {1, 2}, "Gravír");
  b.insert("Fl\xFC" "gel", {5, 5}, 1, 1, 0, "Teile");
  auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 4u);
  EXPECT_EQ(d.entities[0].layer, "Gravír");
  EXPECT_EQ(d.entities[1].layer, "Durchbrüche");
  EXPECT_EQ(d.entities[2].layer, "Gravír");
  EXPECT_EQ(d.entities[3].layer, "Teile");
  EXPECT_EQ(d.entities[3].block, "Flügel");
  io::DxfOptions drop;
  drop.ignore_layers = {"gravír"};
  EXPECT_EQ(read(b.str(), drop).entities.size(), 2u);
  // The code page the header names.
  DxfBuilder cyr;
  cyr.codepage("ANSI_1251").line({0, 0}, {1, 0}, "\xD0\xE0\xE7\xEC\xE5\xF0");
  d = read(cyr.str());
  ASSERT_EQ(d.entities.size(), 1u);
  EXPECT_EQ(d.entities[0].layer, "Размер");
  // A message quoting a value from such a file is UTF-8 too, and still names the line.
  DxfBuilder bad;
  bad.raw(0, "LINE").raw(8, "0").raw(10, "3.5\xFF").raw(20, "0").raw(11, "1").raw(21, "0");
  auto r = io::read_dxf_string(bad.str(), "x.dxf", {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "group code 10: '3.5ÿ' is not a number");
  EXPECT_TRUE(r.error().line.has_value());
}

TEST(DxfReader, NonCurveEntitiesAreCountedAndSkipped) {
  DxfBuilder b;
  b.line({0, 0}, {1, 0}).text({0, 0}, "label").mtext({1, 1}, "more").point({2, 2});
  b.raw(0, "HATCH").raw(8, "0").raw(2, "SOLID").raw(70, "1").raw(91, "0");
  b.raw(0, "DIMENSION").raw(8, "0").raw(70, "0").raw(10, "0").raw(20, "0");
  b.raw(0, "3DSOLID").raw(8, "0");
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 1u);
  for (const char* t : {"TEXT", "MTEXT", "POINT", "HATCH", "DIMENSION", "3DSOLID"}) {
    EXPECT_EQ(d.entity_counts.at(t), 1u) << t;
    EXPECT_EQ(d.skipped.at(t), 1u) << t;
  }
  EXPECT_EQ(d.skipped.count("LINE"), 0u);
  const bool warned = std::any_of(d.diagnostics.begin(), d.diagnostics.end(),
                                  [](const Diagnostic& x) { return x.message == "1 TEXT entity skipped (not cut)"; });
  EXPECT_TRUE(warned);
}

TEST(DxfReader, LineNumbersAndHandles) {
  DxfBuilder b;
  b.text({0, 0}, "a").line({0, 0}, {1, 0}).circle({0, 0}, 1).lwpolyline(rounded_rect(), true);
  b.polyline(rounded_rect(), false).spline(3, {0, 0, 0, 0, 1, 1, 1, 1}, {{0, 0}, {1, 1}, {2, 1}, {3, 0}}, {}, 8);
  b.ellipse({0, 0}, {3, 0}, 0.5, 0, 2 * kPi).arc({0, 0}, 1, 0, 45);
  const std::string text = b.str();
  const auto d = read(text);
  const char* types[] = {"LINE", "CIRCLE", "LWPOLYLINE", "POLYLINE", "SPLINE", "ELLIPSE", "ARC"};
  const char* handles[] = {"101", "102", "103", "104", "10B", "10C", "10D"};
  ASSERT_EQ(d.entities.size(), 7u);
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(d.entities[i].type, types[i]);
    EXPECT_EQ(d.entities[i].line, line_of(text, types[i])) << types[i];
    EXPECT_EQ(d.entities[i].handle, handles[i]) << types[i];
    EXPECT_EQ(d.entities[i].source_line, d.entities[i].line);
  }
}

TEST(DxfReader, LfCrlfAndCrLineEndingsReadTheSame) {
  DxfBuilder b;
  b.insunits(4).begin_block("B").arc({0, 0}, 2, 0, 270).end_block();
  b.line({0, 0}, {1, 0}).lwpolyline(rounded_rect(), true).insert("B", {3, 3}, 1, 1, 20).text({0, 0}, "t");
  const auto lf = read(b.str());
  for (const std::string& text : {b.str_crlf(), b.str_cr()}) {
    const auto d = read(text);
    ASSERT_EQ(d.entities.size(), lf.entities.size());
    for (std::size_t i = 0; i < d.entities.size(); ++i) {
      EXPECT_EQ(d.entities[i].path, lf.entities[i].path);
      EXPECT_EQ(d.entities[i].line, lf.entities[i].line);
      EXPECT_EQ(d.entities[i].handle, lf.entities[i].handle);
    }
    EXPECT_EQ(d.entity_counts, lf.entity_counts);
    EXPECT_EQ(d.units_in_file, "mm");
  }
}

TEST(DxfReader, NoHeaderSectionAndCommentsRead) {
  DxfBuilder b;
  b.no_header().raw(999, "a comment between entities").line({0, 0}, {1, 0}).raw(999, "inside the LINE? no: after it");
  const std::string text = b.str();
  const auto d = read(text);
  ASSERT_EQ(d.entities.size(), 1u);
  EXPECT_EQ(d.units_in_file, "unitless");
  EXPECT_EQ(d.units_source, "default");
}

TEST(DxfReader, EntitiesInRandomOrderAndDirection) {
  // A 30 x 10 slot: two lines and two half circles, shuffled and some reversed.
  struct E {
    bool is_arc;
    Vec2 a, b;
    double a1, a2;
  };
  std::vector<E> es = {{false, {0, 0}, {30, 0}, 0, 0}, {true, {30, 5}, {}, 270, 90},
                       {false, {30, 10}, {0, 10}, 0, 0}, {true, {0, 5}, {}, 90, 270}};
  Rng rng(7);
  for (int round = 0; round < 5; ++round) {
    rng.shuffle(es.begin(), es.end());
    DxfBuilder b;
    for (const auto& e : es) {
      if (e.is_arc) b.arc(e.a, 5, e.a1, e.a2);
      else if (rng.chance(0.5)) b.line(e.b, e.a);
      else b.line(e.a, e.b);
    }
    const auto d = read(b.str());
    ASSERT_EQ(d.entities.size(), 4u);
    double total = 0;
    for (const auto& x : d.entities) total += path_length(x.path);
    EXPECT_NEAR(total, 60 + 10 * kPi, 1e-9);
  }
}

TEST(DxfReader, DropsRepeatedPolylineVertices) {
  DxfBuilder b;
  b.lwpolyline({{{0, 0}, 0}, {{0, 0}, 0}, {{10, 0}, 0.5}, {{10, 10}, 0}, {{0, 0}, 0}}, true);
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 1u);
  ASSERT_EQ(d.entities[0].path.vertices.size(), 3u);
  EXPECT_EQ(d.entities[0].path.vertices[1].bulge, 0.5);
}

TEST(DxfReader, ExpansionLimitsAreCheckedBeforeExpanding) {
  DxfBuilder b;
  b.begin_block("L").line({0, 0}, {1, 0}).line({0, 0}, {0, 1}).end_block();
  b.insert("L", {0, 0}, 1, 1, 0, "0", 4, 3, 2, 2);
  io::DxfOptions opt;
  opt.max_entities = 25;  // 24 LINEs and the INSERT itself
  const std::string text = b.str();
  auto ok = io::read_dxf_string(text, "x.dxf", opt);
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok->entities.size(), 24u);
  opt.max_entities = 24;
  auto r = io::read_dxf_string(text, "x.dxf", opt);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "INSERT expansion gives 25 entities, more than the limit of 24");
  EXPECT_EQ(r.error().line, line_of(text, "INSERT"));

  DxfBuilder deep;
  deep.begin_block("D0").line({0, 0}, {1, 0}).end_block();
  const char* names[] = {"D0", "D1", "D2", "D3", "D4", "D5"};
  for (int i = 1; i <= 5; ++i) deep.begin_block(names[i]).insert(names[i - 1], {1, 0}).end_block();
  deep.insert("D5", {0, 0});
  io::DxfOptions shallow;
  shallow.max_insert_depth = 4;
  auto rd = io::read_dxf_string(deep.str(), "x.dxf", shallow);
  ASSERT_FALSE(rd.ok());
  EXPECT_EQ(rd.error().message, "INSERT nesting deeper than 4 levels");
  shallow.max_insert_depth = 6;
  EXPECT_TRUE(io::read_dxf_string(deep.str(), "x.dxf", shallow).ok());
}

// Curves the CAD program hides (a layer turned off or frozen in the LAYER table, an entity marked
// invisible) are cut like the others, and said: a drawing that looks right on screen can hold
// construction lines or an old revision there. Layer names match without regard to case.
TEST(DxfReader, HiddenLayersAndInvisibleEntitiesAreCutAndSaid) {
  const std::string text =
      "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n70\n3\n"
      "0\nLAYER\n2\nOff\n70\n0\n62\n-7\n6\nCONTINUOUS\n"
      "0\nLAYER\n2\nFrozen\n70\n1\n62\n7\n6\nCONTINUOUS\n"
      "0\nLAYER\n2\nShown\n70\n0\n62\n7\n6\nCONTINUOUS\n"
      "0\nENDTAB\n0\nENDSEC\n"
      "0\nSECTION\n2\nENTITIES\n"
      "0\nCIRCLE\n8\nOff\n10\n0\n20\n0\n40\n5\n"
      "0\nCIRCLE\n8\nFROZEN\n10\n20\n20\n0\n40\n5\n"
      "0\nCIRCLE\n8\nFROZEN\n10\n40\n20\n0\n40\n5\n"
      "0\nCIRCLE\n8\nShown\n10\n60\n20\n0\n40\n5\n"
      "0\nCIRCLE\n8\nShown\n60\n1\n10\n80\n20\n0\n40\n5\n"
      "0\nENDSEC\n0\nEOF\n";
  auto r = io::read_dxf_string(text, "h.dxf", {});
  ASSERT_TRUE(r.ok()) << format(r.error());
  EXPECT_EQ(r->entities.size(), 5u);
  std::vector<std::string> said;
  for (const auto& d : r->diagnostics) {
    said.push_back(d.code + " " + d.layer);
    if (d.code == "dxf.hidden_layer" && d.layer == "Frozen") {
      EXPECT_NE(d.message.find("a layer frozen in the drawing"), std::string::npos) << d.message;
      EXPECT_NE(d.message.find("has 2 curve entities"), std::string::npos) << d.message;
      EXPECT_NE(d.message.find("--ignore-layers Frozen"), std::string::npos) << d.message;
    }
  }
  EXPECT_EQ(said, (std::vector<std::string>{"dxf.hidden_layer Off", "dxf.hidden_layer Frozen", "dxf.invisible "}));
  // Left out as the warning says, nothing hidden is read, and nothing is said.
  io::DxfOptions opt;
  opt.ignore_layers = {"Off", "Frozen"};
  auto kept = io::read_dxf_string(text, "h.dxf", opt);
  ASSERT_TRUE(kept.ok());
  EXPECT_EQ(kept->entities.size(), 2u);
  for (const auto& d : kept->diagnostics) EXPECT_NE(d.code, "dxf.hidden_layer") << d.message;
}

// An entity in a tilted plane (extrusion (0.6, 0, 0.8)) at height 20 along its normal lies 12 mm
// sideways of the same entity at height 0; the height was dropped (ezdxf: x 4..12 for the circle).
// Worked by hand: the plane's axes are Ax = (0, 1, 0), Ay = (-0.8, 0, 0.6), so (x, y, 20) is seen
// from above at (12 - 0.8 y, x).
TEST(DxfReader, TiltedPlanesKeepTheirHeightAndAreSaid) {
  const std::string text =
      "0\nSECTION\n2\nENTITIES\n"
      "0\nCIRCLE\n8\n0\n10\n10\n20\n5\n30\n20\n40\n5\n210\n0.6\n220\n0\n230\n0.8\n"
      "0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n38\n20\n10\n100\n20\n0\n10\n110\n20\n0\n10\n110\n20\n10\n10\n100\n20\n10\n"
      "210\n0.6\n220\n0\n230\n0.8\n"
      "0\nCIRCLE\n8\n0\n10\n-50\n20\n0\n30\n35\n40\n5\n210\n0\n220\n0\n230\n-1\n"
      "0\nENDSEC\n0\nEOF\n";
  auto r = io::read_dxf_string(text, "t.dxf", {});
  ASSERT_TRUE(r.ok()) << format(r.error());
  ASSERT_EQ(r->entities.size(), 3u);
  const auto near = [](const geometry::Box& b, double x0, double y0, double x1, double y1) {
    return std::abs(b.xmin - x0) < 1e-6 && std::abs(b.ymin - y0) < 1e-6 && std::abs(b.xmax - x1) < 1e-6 &&
           std::abs(b.ymax - y1) < 1e-6;
  };
  const auto circle = geometry::bounding_box(r->entities[0].path);
  EXPECT_TRUE(near(circle, 4, 5, 12, 15)) << circle.xmin << " " << circle.ymin << " " << circle.xmax << " " << circle.ymax;
  const auto square = geometry::bounding_box(r->entities[1].path);
  EXPECT_TRUE(near(square, 4, 100, 12, 110)) << square.xmin << " " << square.ymin << " " << square.xmax << " " << square.ymax;
  // Upside down (0, 0, -1) the height moves nothing: x mirrored only.
  const auto flat = geometry::bounding_box(r->entities[2].path);
  EXPECT_TRUE(near(flat, 45, -5, 55, 5)) << flat.xmin << " " << flat.xmax;
  ASSERT_EQ(r->diagnostics.size(), 1u);
  EXPECT_EQ(r->diagnostics[0].code, "dxf.tilted_plane");
  EXPECT_EQ(*r->diagnostics[0].line, 5);
}

TEST(DxfReader, EntityLevelErrorsNameTheEntity) {
  struct Case {
    std::function<void(DxfBuilder&)> draw;
    std::string message;
  };
  const std::vector<Case> cases = {
      {[](DxfBuilder& b) { b.spline(3, {0, 0, 0, 0, 1, 1, 1}, {{0, 0}, {1, 1}, {2, 1}, {3, 0}}, {}, 8); },
       "SPLINE of degree 3 with 4 control points needs 8 knots, has 7"},
      {[](DxfBuilder& b) { b.spline(3, {0, 0, 0, 0, 1, 0.5, 1, 1}, {{0, 0}, {1, 1}, {2, 1}, {3, 0}}, {}, 8); },
       "SPLINE knots are not in increasing order"},
      {[](DxfBuilder& b) { b.spline(2, {0, 0, 0, 1, 1, 1}, {{0, 0}, {1, 1}, {2, 0}}, {1, 0, 1}, 8); },
       "SPLINE has a weight <= 0"},
      {[](DxfBuilder& b) { b.lwpolyline({{{0, 0}, 1e12}, {{1, 0}, 0}}, false); }, "LWPOLYLINE has an invalid bulge"},
      {[](DxfBuilder& b) { b.begin_block("B").line({0, 0}, {1e5, 0}).end_block().insert("B", {0, 0}, 100, 100); },
       "LINE lies more than 1e6 mm from the origin after INSERT and unit scaling"},
      {[](DxfBuilder& b) { b.ellipse({0, 0}, {10, 0}, 1e300, 0, 1); },
       "ELLIPSE lies more than 1e6 mm from the origin after INSERT and unit scaling"},
      {[](DxfBuilder& b) { b.spline(2, {0, 0, 0, 1, 1, 1}, {{0, 0}, {1, 1e5}, {2, 0}}, {1, 1e308, 1}, 8); },
       "SPLINE has no finite points (overflowing numbers)"},
      {[](DxfBuilder& b) {
         b.begin_block("C").circle({0, 0}, 1e5).end_block().insert("C", {0, 0}, 1e3, 1);
       },
       "CIRCLE lies more than 1e6 mm from the origin after INSERT and unit scaling"},
      // Both vertices of the circle are in range, its top (0, 1.4e6) is not.
      {[](DxfBuilder& b) { b.circle({0, 5e5}, 9e5); },
       "CIRCLE lies more than 1e6 mm from the origin after INSERT and unit scaling"},
      {[](DxfBuilder& b) { b.lwpolyline({{{0, 0}, 1e8}, {{10, 0}, 0}}, false); },
       "LWPOLYLINE lies more than 1e6 mm from the origin after INSERT and unit scaling"},
  };
  for (const auto& c : cases) {
    DxfBuilder b;
    b.line({0, 0}, {1, 1});
    c.draw(b);
    const std::string text = b.str();
    const auto r = io::read_dxf_string(text, "e.dxf", {});
    ASSERT_FALSE(r.ok()) << c.message;
    // Errors in a block's entity go on to name the entity in its block: "... (in block 'B' at line L, entity H,
    // inserted here)", the line and handle of the error being the INSERT's.
    const bool in_block = text.find("BLOCK\n") != std::string::npos && text.find("\nINSERT\n") != std::string::npos;
    if (in_block) {
      EXPECT_EQ(r.error().message.rfind(c.message + " (in block '", 0), 0u) << r.error().message;
      EXPECT_TRUE(r.error().message.ends_with(", inserted here)")) << r.error().message;
    } else {
      EXPECT_EQ(r.error().message, c.message);
    }
    EXPECT_TRUE(r.error().line.has_value());
    EXPECT_FALSE(r.error().handle.empty());
  }
}

TEST(DxfReader, DegenerateEntitiesAreWarnings) {
  DxfBuilder b;
  b.circle({0, 0}, 0).arc({0, 0}, -1, 0, 90).ellipse({0, 0}, {0, 0}, 0.5, 0, 1).line({0, 0}, {1, 0});
  const auto d = read(b.str());
  EXPECT_EQ(d.entities.size(), 1u);
  std::vector<std::string> messages;
  for (const auto& x : d.diagnostics) messages.push_back(x.message);
  EXPECT_EQ(messages, (std::vector<std::string>{"CIRCLE with radius <= 0 skipped", "ARC with radius <= 0 skipped",
                                                "degenerate ELLIPSE skipped"}));
  EXPECT_EQ(d.diagnostics[0].line, line_of(b.str(), "CIRCLE"));
}

TEST(DxfReader, DirectoryIsAnError) {
  const auto r = io::read_dxf("/", {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "is a directory, not a DXF file");
}

TEST(DxfReader, InsertAttributesAndPolylineVariants) {
  DxfBuilder b;
  b.begin_block("B").line({0, 0}, {1, 0}).end_block();
  // INSERT followed by its ATTRIBs and SEQEND (group 66 = 1).
  b.insert("B", {10, 0}).raw(66, "1");
  b.raw(0, "ATTRIB").raw(8, "0").raw(10, "0").raw(20, "0").raw(40, "1").raw(1, "value").raw(2, "TAG");
  b.raw(0, "SEQEND").raw(8, "0");
  // A 3D POLYLINE (flag 8): projected onto XY, no bulges.
  b.raw(0, "POLYLINE").raw(8, "0").raw(66, "1").raw(70, "8");
  b.raw(0, "VERTEX").raw(8, "0").raw(10, "0").raw(20, "0").raw(30, "5").raw(70, "32");
  b.raw(0, "VERTEX").raw(8, "0").raw(10, "3").raw(20, "4").raw(30, "-2").raw(70, "32");
  b.raw(0, "SEQEND").raw(8, "0");
  // A polyface mesh (flag 64): a surface, skipped.
  b.raw(0, "POLYLINE").raw(8, "0").raw(66, "1").raw(70, "64");
  b.raw(0, "VERTEX").raw(8, "0").raw(10, "0").raw(20, "0").raw(70, "192");
  b.raw(0, "SEQEND").raw(8, "0");
  // A spline-fit 2D POLYLINE (flag 4): the frame control points (vertex flag 16) are not on it.
  b.raw(0, "POLYLINE").raw(8, "0").raw(66, "1").raw(70, "4");
  b.raw(0, "VERTEX").raw(8, "0").raw(10, "0").raw(20, "0").raw(70, "16");
  b.raw(0, "VERTEX").raw(8, "0").raw(10, "0").raw(20, "1").raw(70, "8");
  b.raw(0, "VERTEX").raw(8, "0").raw(10, "5").raw(20, "9").raw(70, "16");
  b.raw(0, "VERTEX").raw(8, "0").raw(10, "2").raw(20, "2").raw(70, "8");
  b.raw(0, "SEQEND").raw(8, "0");
  b.line({0, 5}, {1, 5});
  const auto d = read(b.str());
  ASSERT_EQ(d.entities.size(), 4u);
  expect_point(d.entities[0].path.vertices[1].p, {11, 0});
  EXPECT_EQ(d.entities[1].path.vertices.size(), 2u);
  EXPECT_NEAR(path_length(d.entities[1].path), 5, 1e-12);
  ASSERT_EQ(d.entities[2].path.vertices.size(), 2u);
  expect_point(d.entities[2].path.vertices[0].p, {0, 1});
  expect_point(d.entities[2].path.vertices[1].p, {2, 2});
  EXPECT_EQ(d.entities[3].type, "LINE");
  EXPECT_EQ(d.entity_counts.at("POLYLINE"), 3u);
  EXPECT_EQ(d.skipped.at("POLYLINE"), 1u);
  EXPECT_EQ(d.entity_counts.count("ATTRIB"), 0u);
  EXPECT_EQ(d.entity_counts.at("INSERT"), 1u);
}

TEST(DxfReader, CurveToleranceIsValidated) {
  const std::string text = DxfBuilder().ellipse({0, 0}, {10, 0}, 0.5, 0, 1).str();
  for (double tol : {0.0, 1e-7, 101.0, std::nan("")}) {
    io::DxfOptions opt;
    opt.curve_tol_mm = tol;
    const auto r = io::read_dxf_string(text, "t.dxf", opt);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "curve tolerance must be between 1e-6 and 100 mm");
  }
  io::DxfOptions fine;
  fine.curve_tol_mm = 1e-6;
  const auto r = io::read_dxf_string(text, "t.dxf", fine);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r->diagnostics.empty());  // reached without exceeding the tolerance
}

}  // namespace
}  // namespace cutroute::test
