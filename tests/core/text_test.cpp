// to_utf8(): strings from drawings in a legacy code page come out as UTF-8, valid UTF-8 unchanged.
#include <gtest/gtest.h>

#include <cutroute/core/text.hpp>

namespace cutroute {
namespace {

TEST(Text, ValidUtf8IsKept) {
  for (const char* s : {"", "LAYER_1", "Gravír", "Durchbrüche", "€ 100", "\xF0\x9F\x94\xA9"}) {
    EXPECT_TRUE(is_utf8(s)) << s;
    EXPECT_EQ(to_utf8(s), s);
  }
}

TEST(Text, MalformedUtf8IsRecognised) {
  // A Latin-1 byte, a cut-off sequence, an overlong '/', a surrogate, a code point above U+10FFFF.
  for (const char* s : {"Grav\xEDr", "\xC3", "\xC0\xAF", "\xED\xA0\x80", "\xF4\x90\x80\x80"}) EXPECT_FALSE(is_utf8(s)) << s;
}

TEST(Text, LegacyCodePagesAreConverted) {
  // Windows-1252: AutoCAD's default code page; 0x80 is the euro sign there (not in Latin-1).
  EXPECT_EQ(to_utf8("Grav\xEDr"), "Gravír");
  EXPECT_EQ(to_utf8("\x80 10"), "€ 10");
  EXPECT_EQ(to_utf8("Durchbr\xFC" "che"), "Durchbrüche");
  // Windows-1251 (ANSI_1251): Cyrillic.
  EXPECT_EQ(to_utf8("\xD0\xE0\xE7\xEC\xE5\xF0", "CP1251"), "Размер");
  // A byte Windows-1252 leaves undefined, and an unknown charset: U+FFFD for what cannot be read.
  EXPECT_EQ(to_utf8("a\x81" "b"), "a\xEF\xBF\xBD" "b");
  EXPECT_EQ(to_utf8("a\xE9" "b", "NO-SUCH-CHARSET"), "a\xEF\xBF\xBD" "b");
  for (int b = 0x80; b < 0x100; ++b) EXPECT_TRUE(is_utf8(to_utf8(std::string(1, static_cast<char>(b))))) << b;
}

}  // namespace
}  // namespace cutroute
