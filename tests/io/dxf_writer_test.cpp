// write_dxf(): valid ASCII DXF that read_dxf reads back exactly.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include <cutroute/core/random.hpp>
#include <cutroute/io/dxf.hpp>
#include <cutroute/io/dxf_writer.hpp>

#include "contour_math.hpp"

namespace cutroute::test {
namespace {

using geometry::Vertex;

std::vector<io::DxfWriteEntity> sample_nest(Rng& rng) {
  std::vector<io::DxfWriteEntity> es;
  for (int i = 0; i < 40; ++i) {
    io::DxfWriteEntity e;
    const int n = 2 + static_cast<int>(rng.below(6));
    for (int k = 0; k < n; ++k) {
      const double bulge = rng.chance(0.4) ? (rng.uniform01() * 2 - 1) * 0.9 : 0.0;
      e.path.vertices.push_back({{rng.uniform01() * 3000 - 100, rng.uniform01() * 1500 + 1e-3}, bulge});
    }
    e.path.closed = rng.chance(0.7);
    if (!e.path.closed) e.path.vertices.back().bulge = 0;  // no segment leaves the last vertex
    e.layer = rng.chance(0.5) ? "cut" : "mark";
    es.push_back(std::move(e));
  }
  return es;
}

TEST(DxfWriter, RoundTripIsExactInMillimetres) {
  Rng rng(11);
  const auto es = sample_nest(rng);
  const std::string text = io::write_dxf(es, {});
  const auto r = io::read_dxf_string(text, "written.dxf", {});
  ASSERT_TRUE(r.ok()) << format(r.error());
  EXPECT_EQ(r->units_in_file, "mm");
  EXPECT_EQ(r->units_source, "$INSUNITS");
  ASSERT_EQ(r->entities.size(), es.size());
  for (std::size_t i = 0; i < es.size(); ++i) {
    EXPECT_EQ(r->entities[i].path, es[i].path) << i;
    EXPECT_EQ(r->entities[i].layer, es[i].layer);
    EXPECT_EQ(r->entities[i].type, "LWPOLYLINE");
    EXPECT_FALSE(r->entities[i].handle.empty());
  }
  EXPECT_TRUE(r->diagnostics.empty());
}

TEST(DxfWriter, FullCirclesBecomeCircles) {
  io::DxfWriteEntity ccw, cw;
  ccw.path = {{{{10, 5}, 1.0}, {{4, 5}, 1.0}}, true};
  cw.path = {{{{0, 0}, -1.0}, {{0, 8}, -1.0}}, true};
  const std::string text = io::write_dxf({ccw, cw}, {});
  EXPECT_NE(text.find("\nCIRCLE\n"), std::string::npos);
  EXPECT_EQ(text.find("LWPOLYLINE"), std::string::npos);
  const auto r = io::read_dxf_string(text, "c.dxf", {});
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->entities.size(), 2u);
  // Read back as the counter-clockwise circle starting at angle 0: same centre and radius.
  EXPECT_EQ(r->entities[0].path, (geometry::Contour{{{{10, 5}, 1.0}, {{4, 5}, 1.0}}, true}));
  EXPECT_EQ(r->entities[1].path, (geometry::Contour{{{{4, 4}, 1.0}, {{-4, 4}, 1.0}}, true}));
  EXPECT_EQ(r->entities[1].type, "CIRCLE");
  EXPECT_EQ(r->entities[1].layer, "0");
}

TEST(DxfWriter, InchOutputScalesBack) {
  Rng rng(5);
  const auto es = sample_nest(rng);
  io::DxfWriteOptions opt;
  opt.units = "in";
  const auto r = io::read_dxf_string(io::write_dxf(es, opt), "in.dxf", {});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->units_in_file, "in");
  ASSERT_EQ(r->entities.size(), es.size());
  for (std::size_t i = 0; i < es.size(); ++i) {
    const auto& a = r->entities[i].path.vertices;
    ASSERT_EQ(a.size(), es[i].path.vertices.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_NEAR(a[k].p.x, es[i].path.vertices[k].p.x, 1e-9);
      EXPECT_NEAR(a[k].p.y, es[i].path.vertices[k].p.y, 1e-9);
      EXPECT_EQ(a[k].bulge, es[i].path.vertices[k].bulge);
    }
  }
}

TEST(DxfWriter, OutputIsPlainAsciiDxf) {
  io::DxfWriteEntity e;
  e.path = {{{{0, 0}, 0}, {{-0.0, 1}, 0}}, false};
  e.layer = "a\nb";
  const std::string text = io::write_dxf({e}, {});
  EXPECT_EQ(text.rfind("0\nEOF\n"), text.size() - 6);
  EXPECT_EQ(text.find("-0\n"), std::string::npos);  // never "-0"
  EXPECT_NE(text.find("\na_b\n"), std::string::npos);
  for (unsigned char c : text) EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7f));
}

}  // namespace
}  // namespace cutroute::test
