// The generated drawings committed under tests/data/dxf/ (for CLI and end-to-end tests): each is
// rebuilt here with DxfBuilder and must equal its file (CUTROUTE_REGENERATE=1 rewrites them), and
// each reads with the properties it was made for.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <cutroute/core/random.hpp>
#include <cutroute/io/dxf.hpp>

#include "contour_math.hpp"
#include "support/dxf_builder.hpp"
#include "support/paths.hpp"

namespace cutroute::test {
namespace {

using geometry::Vertex;
constexpr double kPi = std::numbers::pi;

// A plate with a rounded corner, a round hole and a slot (two half arcs and two lines).
void plate(DxfBuilder& b, double k, const std::string& layer) {
  const double bu = std::tan(kPi / 8);
  b.lwpolyline({{{0, 0}, 0}, {{k * 60, 0}, 0}, {{k * 60, k * 30}, bu}, {{k * 50, k * 40}, 0}, {{0, k * 40}, 0}}, true,
               layer);
  b.circle({k * 15, k * 20}, k * 6, layer);
  b.line({k * 30, k * 10}, {k * 45, k * 10}, layer).arc({k * 45, k * 15}, k * 5, 270, 90, layer);
  b.line({k * 45, k * 20}, {k * 30, k * 20}, layer).arc({k * 30, k * 15}, k * 5, 90, 270, layer);
}

DxfBuilder twin(double k, int insunits) {
  DxfBuilder b;
  b.insunits(insunits);
  plate(b, k, "cut");
  b.ellipse({k * 80, k * 20}, {k * 10, k * 4}, 0.5, 0, 2 * kPi, "cut");
  b.spline(3, {0, 0, 0, 0, 1, 1, 1, 1}, {{k * 70, k * 40}, {k * 80, k * 55}, {k * 95, k * 30}, {k * 100, k * 45}}, {}, 8,
           "mark");
  return b;
}

DxfBuilder inserts() {
  DxfBuilder b;
  b.insunits(4);
  b.begin_block("PLATE");
  plate(b, 1.0, "0");
  b.end_block();
  b.begin_block("PAIR", {5, 5}).insert("PLATE", {5, 5}).insert("PLATE", {75, 5}, -1, 1, 0, "0", 1, 1, 0, 0).end_block();
  b.insert("PLATE", {0, 0}, 1, 1, 0, "cut");
  b.insert("PLATE", {200, 0}, 1, 1, 90, "cut");
  b.insert("PLATE", {300, 0}, -1, 1, 0, "cut");   // mirrored
  b.insert("PLATE", {300, 100}, 1, -1, 30, "cut");  // mirrored and rotated
  b.insert("PAIR", {0, 200}, 1, 1, 0, "cut");     // nested
  b.insert("PLATE", {0, 400}, 1, 1, 0, "cut", 3, 2, 70, 50);  // MINSERT 3 x 2
  return b;
}

DxfBuilder extrusion() {
  DxfBuilder b;
  b.insunits(4);
  // The same plate drawn with extrusion (0,0,-1): mirrored about the Y axis.
  const double bu = std::tan(kPi / 8);
  b.lwpolyline({{{0, 0}, 0}, {{60, 0}, 0}, {{60, 30}, bu}, {{50, 40}, 0}, {{0, 40}, 0}}, true, "cut", -1);
  b.circle({15, 20}, 6, "cut", -1);
  b.arc({45, 15}, 5, 270, 90, "cut", -1).arc({30, 15}, 5, 90, 270, "cut", -1);
  b.line({-30, 10}, {-45, 10}, "cut").line({-45, 20}, {-30, 20}, "cut");
  return b;
}

DxfBuilder shuffled() {
  // 50 slots 30 x 10 whose 4 entities come in random order and direction.
  struct E {
    bool arc;
    Vec2 a, b;
    double a1, a2;
  };
  std::vector<E> es;
  for (int i = 0; i < 50; ++i) {
    const double x = (i % 10) * 50.0, y = (i / 10) * 30.0;
    es.push_back({false, {x, y}, {x + 30, y}, 0, 0});
    es.push_back({true, {x + 30, y + 5}, {}, 270, 90});
    es.push_back({false, {x + 30, y + 10}, {x, y + 10}, 0, 0});
    es.push_back({true, {x, y + 5}, {}, 90, 270});
  }
  Rng rng(2026);
  rng.shuffle(es.begin(), es.end());
  DxfBuilder b;
  b.insunits(4);
  for (const E& e : es) {
    if (e.arc) b.arc(e.a, 5, e.a1, e.a2, "cut");
    else if (rng.chance(0.5)) b.line(e.b, e.a, "cut");
    else b.line(e.a, e.b, "cut");
  }
  b.text({0, -10}, "50 slots", "notes");
  return b;
}

struct Generated {
  const char* file;
  std::function<std::string()> make;
};

const Generated kGenerated[] = {
    {"twin_inch.dxf", [] { return twin(1.0, 1).str(); }},
    {"twin_mm.dxf", [] { return twin(25.4, 4).str(); }},
    {"inserts_mirrored_rotated_nested.dxf", [] { return inserts().str(); }},
    {"extrusion_minus_z.dxf", [] { return extrusion().str(); }},
    {"slots_random_order.dxf", [] { return shuffled().str(); }},
    {"slots_random_order_crlf.dxf", [] { return shuffled().str_crlf(); }},
    {"slots_random_order_cr.dxf", [] { return shuffled().str_cr(); }},
};

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

TEST(DxfGenerated, FilesAreCurrent) {
  const char* env = std::getenv("CUTROUTE_REGENERATE");
  const bool regenerate = env != nullptr && std::string(env) == "1";
  for (const auto& g : kGenerated) {
    const std::string path = test_data(std::string("dxf/") + g.file);
    const std::string want = g.make();
    if (regenerate) {
      std::ofstream(path, std::ios::binary) << want;
    }
    EXPECT_EQ(slurp(path), want) << g.file << " is stale: rerun with CUTROUTE_REGENERATE=1";
  }
}

io::DxfDrawing read_file(const std::string& name) {
  auto r = io::read_dxf(test_data("dxf/" + name), {});
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : format(r.error()));
  if (!r.ok()) return {};
  return std::move(r).value();
}

double total_length(const io::DxfDrawing& d) {
  double l = 0;
  for (const auto& e : d.entities) l += path_length(e.path);
  return l;
}

const double kPlateLength = 60 + 30 + 50 + 40 + 2 * kPi * 10 / 4 + 2 * kPi * 6 + 30 + 2 * kPi * 5;
const double kPlateArea = 60 * 40 - 100 + kPi * 100 / 4;

TEST(DxfGenerated, TwinsReadAlike) {
  const auto in = read_file("twin_inch.dxf");
  const auto mm = read_file("twin_mm.dxf");
  ASSERT_EQ(in.entities.size(), mm.entities.size());
  for (std::size_t i = 0; i < in.entities.size(); ++i) {
    ASSERT_EQ(in.entities[i].path.vertices.size(), mm.entities[i].path.vertices.size());
    for (std::size_t k = 0; k < in.entities[i].path.vertices.size(); ++k) {
      EXPECT_NEAR(dist(in.entities[i].path.vertices[k].p, mm.entities[i].path.vertices[k].p), 0, 1e-9);
    }
  }
  EXPECT_NEAR(total_length(in), total_length(mm), 1e-9);
  EXPECT_EQ(in.units_in_file, "in");
}

TEST(DxfGenerated, InsertsKeepAreaAndLength) {
  const auto d = read_file("inserts_mirrored_rotated_nested.dxf");
  // 4 single plates + 2 in PAIR + 6 in the MINSERT, 6 curves each.
  ASSERT_EQ(d.entities.size(), 12u * 6u);
  EXPECT_NEAR(total_length(d), 12 * kPlateLength, 1e-6);
  int mirrored = 0;
  for (const auto& e : d.entities) {
    EXPECT_EQ(e.layer, "cut");  // layer 0 inside the blocks inherits the INSERT's
    if (e.type == "LWPOLYLINE") {
      EXPECT_NEAR(std::abs(path_area(e.path)), kPlateArea, 1e-6);
      mirrored += path_area(e.path) < 0;
    }
  }
  EXPECT_EQ(mirrored, 3);  // sx = -1, sy = -1, and the mirrored plate inside PAIR
}

TEST(DxfGenerated, ExtrusionMinusZIsTheMirroredPlate) {
  const auto d = read_file("extrusion_minus_z.dxf");
  EXPECT_NEAR(total_length(d), kPlateLength, 1e-9);
  const auto& poly = d.entities[0].path;
  EXPECT_NEAR(path_area(poly), -kPlateArea, 1e-9);
  // The slot's arcs (OCS) meet its lines (WCS, drawn at negative x).
  EXPECT_NEAR(dist(d.entities[2].path.vertices[0].p, {-45, 10}), 0, 1e-9);
  EXPECT_NEAR(dist(d.entities[3].path.vertices[0].p, {-30, 20}), 0, 1e-9);
}

TEST(DxfGenerated, LineEndingVariantsReadTheSame) {
  const auto lf = read_file("slots_random_order.dxf");
  EXPECT_EQ(lf.entities.size(), 200u);
  EXPECT_NEAR(total_length(lf), 50 * (60 + 10 * kPi), 1e-6);
  for (const char* f : {"slots_random_order_crlf.dxf", "slots_random_order_cr.dxf"}) {
    const auto d = read_file(f);
    ASSERT_EQ(d.entities.size(), lf.entities.size());
    for (std::size_t i = 0; i < d.entities.size(); ++i) {
      EXPECT_EQ(d.entities[i].path, lf.entities[i].path);
      EXPECT_EQ(d.entities[i].line, lf.entities[i].line);
    }
    EXPECT_EQ(d.skipped.at("TEXT"), 1u);
  }
}

}  // namespace
}  // namespace cutroute::test
