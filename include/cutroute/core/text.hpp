// Text from input files as UTF-8: strings written in a legacy code page converted, stray bytes replaced.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace cutroute {

// Is `s` well-formed UTF-8 (pure ASCII is)? Overlong forms, surrogates and code points above
// U+10FFFF are not.
bool is_utf8(std::string_view s);

// `bytes` as UTF-8 for reports, pictures and messages (JSON and XML need it): returned unchanged
// when it already is UTF-8; else read in `charset` (an iconv name such as "CP1252", the Windows
// code page AutoCAD writes Western European drawings in) through glibc's iconv, and each byte it
// cannot convert (or every byte, when iconv lacks the charset) becomes U+FFFD.
std::string to_utf8(std::string_view bytes, const char* charset = "CP1252");

// The parts with `separator` between them ("a, b, c" for a list in a message).
std::string join(const std::vector<std::string>& parts, std::string_view separator);

}  // namespace cutroute
