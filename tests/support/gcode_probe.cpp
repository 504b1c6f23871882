#include "support/gcode_probe.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

namespace cutroute::test {

ProbeResult probe_gcode(const std::string& program) {
  ProbeResult r;
  std::istringstream in(program);
  std::string raw;
  int lineno = 0;
  double x = 0, y = 0, scale = 1;
  bool beam = false;
  bool compensated = false;  // G41/G42 until G40
  int motion = 0;  // 0,1,2,3
  const double pi = std::acos(-1.0);
  while (std::getline(in, raw)) {
    ++lineno;
    std::string s;
    bool in_paren = false;
    for (char c : raw) {
      if (c == '(') in_paren = true;
      else if (c == ')') in_paren = false;
      else if (c == ';' && !in_paren) break;
      else if (!in_paren && !std::isspace(static_cast<unsigned char>(c))) s += static_cast<char>(std::toupper(c));
    }
    if (s.empty() || s == "%") continue;
    ++r.frames;
    std::map<char, double> w;
    std::vector<int> gs, ms;
    for (std::size_t i = 0; i < s.size();) {
      const char letter = s[i++];
      // Plain decimal only (strtod would read "0X1" as hexadecimal once blanks are removed).
      std::size_t j = i;
      if (j < s.size() && (s[j] == '-' || s[j] == '+')) ++j;
      const std::size_t digits_from = j;
      while (j < s.size() && (std::isdigit(static_cast<unsigned char>(s[j])) || s[j] == '.')) ++j;
      if (j == digits_from) {
        r.errors.push_back("line " + std::to_string(lineno) + ": bad word");
        break;
      }
      const double v = std::stod(s.substr(i, j - i));
      i = j;
      if (letter == 'G') gs.push_back(static_cast<int>(std::lround(v * 10)));
      else if (letter == 'M') ms.push_back(static_cast<int>(std::lround(v)));
      else w[letter] = v;
    }
    for (int g : gs) {
      if (g == 0 || g == 10 || g == 20 || g == 30) motion = g / 10;
      if (g == 200) scale = 25.4;
      if (g == 210) scale = 1;
      if (g == 410 || g == 420) compensated = true;
      if (g == 400) compensated = false;
    }
    for (int m : ms) {
      if ((m == 3 || m == 4) && !beam) {
        beam = true;
        ++r.pierces;
      }
      if (m == 5) beam = false;
      if (m == 2 || m == 30) r.ended = true;
    }
    if (!w.count('X') && !w.count('Y')) continue;
    ProbeMove m;
    m.line = lineno;
    m.x0 = x;
    m.y0 = y;
    m.x1 = w.count('X') ? w['X'] * scale : x;
    m.y1 = w.count('Y') ? w['Y'] * scale : y;
    m.rapid = motion == 0;
    m.beam_on = beam;
    m.compensated = compensated;
    if (motion == 2 || motion == 3) {
      m.arc = motion == 3 ? 1 : -1;
      if (w.count('R')) {
        const double rr = w['R'] * scale;
        const double dx = m.x1 - x, dy = m.y1 - y, c = std::hypot(dx, dy);
        const double h = std::sqrt(std::max(0.0, rr * rr - c * c / 4));
        // Centre left of the chord for CCW small arcs (R > 0), right for CW; negative R flips.
        double side = (m.arc > 0 ? 1 : -1) * (rr > 0 ? 1 : -1);
        m.cx = (x + m.x1) / 2 - side * dy / c * h;
        m.cy = (y + m.y1) / 2 + side * dx / c * h;
      } else {
        m.cx = x + (w.count('I') ? w['I'] * scale : 0);
        m.cy = y + (w.count('J') ? w['J'] * scale : 0);
      }
      const double r0 = std::hypot(x - m.cx, y - m.cy), r1 = std::hypot(m.x1 - m.cx, m.y1 - m.cy);
      r.max_arc_radius_error = std::max(r.max_arc_radius_error, std::abs(r0 - r1));
      double a0 = std::atan2(y - m.cy, x - m.cx), a1 = std::atan2(m.y1 - m.cy, m.x1 - m.cx);
      double sweep = a1 - a0;
      if (m.arc > 0) {
        while (sweep <= 1e-12) sweep += 2 * pi;
      } else {
        while (sweep >= -1e-12) sweep -= 2 * pi;
      }
      m.length = std::abs(sweep) * (r0 + r1) / 2;
    } else {
      m.length = std::hypot(m.x1 - x, m.y1 - y);
    }
    if (m.rapid) {
      r.rapid_length += m.length;
    } else if (beam) {
      r.cut_length += m.length;
    } else {
      r.cut_with_beam_off = true;
    }
    r.moves.push_back(m);
    x = m.x1;
    y = m.y1;
  }
  return r;
}

void probe_point(const ProbeMove& m, double t, double& x, double& y) {
  if (m.arc == 0) {
    x = m.x0 + (m.x1 - m.x0) * t;
    y = m.y0 + (m.y1 - m.y0) * t;
    return;
  }
  const double pi = std::acos(-1.0);
  const double r = std::hypot(m.x0 - m.cx, m.y0 - m.cy);
  double a0 = std::atan2(m.y0 - m.cy, m.x0 - m.cx), a1 = std::atan2(m.y1 - m.cy, m.x1 - m.cx);
  double sweep = a1 - a0;
  if (m.arc > 0) {
    while (sweep <= 1e-12) sweep += 2 * pi;
  } else {
    while (sweep >= -1e-12) sweep -= 2 * pi;
  }
  x = m.cx + r * std::cos(a0 + sweep * t);
  y = m.cy + r * std::sin(a0 + sweep * t);
}

double probe_distance(const ProbeMove& m, double x, double y) {
  if (m.arc == 0) {
    const double dx = m.x1 - m.x0, dy = m.y1 - m.y0, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((x - m.x0) * dx + (y - m.y0) * dy) / l2, 0.0, 1.0) : 0.0;
    return std::hypot(x - (m.x0 + dx * t), y - (m.y0 + dy * t));
  }
  const double two_pi = 2 * std::acos(-1.0);
  const double r = std::hypot(m.x0 - m.cx, m.y0 - m.cy);
  const auto ang = [&](double px, double py) { return std::atan2(py - m.cy, px - m.cx); };
  const auto wrap = [&](double a) {
    a = std::fmod(a, two_pi);
    return a < 0 ? a + two_pi : a;
  };
  double sweep = wrap(m.arc > 0 ? ang(m.x1, m.y1) - ang(m.x0, m.y0) : ang(m.x0, m.y0) - ang(m.x1, m.y1));
  if (sweep < 1e-12) sweep = two_pi;  // full circle
  const double at = wrap(m.arc > 0 ? ang(x, y) - ang(m.x0, m.y0) : ang(m.x0, m.y0) - ang(x, y));
  if (at <= sweep) return std::abs(std::hypot(x - m.cx, y - m.cy) - r);
  return std::min(std::hypot(x - m.x0, y - m.y0), std::hypot(x - m.x1, y - m.y1));
}

}  // namespace cutroute::test
