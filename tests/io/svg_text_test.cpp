// xml_escape(): any text (file names, labels) becomes well-formed XML character data in UTF-8.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace cutroute::io
