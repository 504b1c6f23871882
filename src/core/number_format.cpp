#include <cutroute/core/number_format.hpp>

#include <array>
#include <charconv>
#include <cmath>

namespace cutroute {

void append_fixed(std::string& out, double v, int decimals) {
  if (!std::isfinite(v)) {
    out += std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
    return;
  }
  std::array<char, 64> buf{};
  auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::fixed, decimals);
  if (ec != std::errc{}) {  // magnitude too large for the buffer: fall back to general format
    const auto general = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    out.append(buf.data(), general.ptr);
    return;
  }
  char* first = buf.data();
  if (decimals > 0) {
    while (end > first && end[-1] == '0') --end;
    if (end > first && end[-1] == '.') --end;
  }
  const std::string_view s(first, static_cast<std::size_t>(end - first));
  if (s == "-0" || s.empty()) {
    out += '0';
    return;
  }
  out.append(s);
}

std::string format_shortest(double v) {
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
  std::array<char, 64> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

std::string format_fixed(double v, int decimals) {
  std::string s;
  append_fixed(s, v, decimals);
  return s;
}

}  // namespace cutroute
