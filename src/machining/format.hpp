// Private number formatting for machining messages and reports: shortest round-trip or fixed digits.
#pragma once

#include <charconv>
#include <cmath>
#include <string>

#include <cutroute/core/number_format.hpp>

namespace cutroute::machining {

// Shortest text that reads back to the same double (std::to_chars, no locale).
inline std::string fmt_exact(double v) { return format_shortest(v); }

// At most `sig` significant digits, general notation: for messages.
inline std::string fmt(double v, int sig = 6) {
  if (!std::isfinite(v)) return fmt_exact(v);
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, sig);
  return std::string(buf, r.ptr);
}

// Fixed number of decimals: for CSV and SVG coordinates.
inline std::string fmt_fixed(double v, int decimals) {
  if (!std::isfinite(v)) return fmt_exact(v);
  if (v == 0.0) v = 0.0;  // never print -0
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  std::string s(buf, r.ptr);
  if (s.size() > 1 && s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

}  // namespace cutroute::machining
