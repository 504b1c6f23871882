// xml_escape(): any text becomes well-formed XML character data in UTF-8; arcs keep their shape in SVG paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <cutroute/core/text.hpp>
#include <cutroute/io/svg.hpp>

namespace cutroute::io {
namespace {

TEST(SvgText, MarkupControlCodesAndLegacyBytesAreMadeSafe) {
  // Markup escaped; tab, LF and CR kept; other control codes (an ESC from a file name) replaced,
  // since XML 1.0 allows them in no form; a Windows-1252 byte read as such.
  EXPECT_EQ(xml_escape("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&apos;");
  EXPECT_EQ(xml_escape("x\x1B[31m\t\x7F\ny\r"), "x?[31m\t?\ny\r");
  EXPECT_EQ(xml_escape("Gravír"), "Gravír");
  EXPECT_EQ(xml_escape("Grav\xEDr"), "Gravír");
  for (int c = 0; c < 0x100; ++c) EXPECT_TRUE(is_utf8(xml_escape(std::string(1, static_cast<char>(c))))) << c;
}

// A near half circle (a slot end) is drawn as the arc it is: its bulge off the chord (as SVG
// computes it from the written radius and the written end points) within 1 µm of the exact one.
// With the radius rounded to the µm apart from the end points, SVG drew the short arc 0.11 mm off.
TEST(SvgPath, NearHalfCirclesKeepTheirShape) {
  const geometry::Box world{0, 0, 100, 100};
  const SvgDocument svg(world, 1.0, 1000);
  for (const double bulge : {1.0 - 1e-6, 1.0, 1.0 + 1e-6, 0.999}) {
    for (const double x1 : {59.99963, 60.00041, 59.9996}) {
      const geometry::Contour arc{{{{20.0002, 30.0004}, bulge}, {{20.0002 + x1, 30.0004}, 0.0}}, false};
      const std::string d = svg.path_data(arc);
      double ax, ay, r1, r2, rot, large, sweep, bx, by;
      ASSERT_EQ(std::sscanf(d.c_str(), "M%lf %lfA%lf %lf %lf %lf %lf %lf %lf", &ax, &ay, &r1, &r2, &rot, &large, &sweep, &bx, &by), 9) << d;
      const double c = std::hypot(bx - ax, by - ay);
      const double r = std::max(r1, c / 2);  // SVG scales a radius too small for the chord up to it
      // Height of the arc's middle over its chord, as drawn and as drawn exactly.
      const double h = std::sqrt(std::max(0.0, r * r - c * c / 4));
      const double drawn = large > 0.5 ? r + h : r - h;
      const double theta = 4 * std::atan(std::abs(bulge));
      const double exact = x1 / 2 * std::tan(theta / 4);  // sagitta = c/2 · tan(θ/4)
      EXPECT_NEAR(drawn, exact, 1e-3) << "bulge " << bulge << " chord " << x1 << ": " << d;
    }
  }
}

}  // namespace
}  // namespace cutroute::io
