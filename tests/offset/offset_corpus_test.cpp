// Kerf offset on the real contours of the shared DXF corpus: invariants recomputed from the
// outputs (every result point |d| from its source, outward grows, inward shrinks, no NaN).
#include <cutroute/geometry/offset.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace cutroute::geometry {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Closed LWPOLYLINEs (with bulges) and CIRCLEs of an ASCII DXF, read with a minimal group-code
// scanner written for this test only (independent of the project's DXF reader). Block
// definitions are read like entities; each contour is checked on its own.
std::vector<Contour> read_closed_contours(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::pair<int, std::string>> pairs;
  std::string code, value;
  while (std::getline(in, code) && std::getline(in, value)) {
    auto trim = [](std::string& s) {
      s.erase(0, s.find_first_not_of(" \t\r"));
      s.erase(s.find_last_not_of(" \t\r") + 1);
    };
    trim(code);
    trim(value);
    try {
      pairs.emplace_back(std::stoi(code), value);
    } catch (...) {
      return {};
    }
  }
  std::vector<Contour> out;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (pairs[i].first != 0) continue;
    const std::string& type = pairs[i].second;
    if (type != "LWPOLYLINE" && type != "CIRCLE") continue;
    Contour c;
    c.closed = true;
    bool closed_flag = false;
    double cx = 0, cy = 0, r = 0;
    std::size_t j = i + 1;
    for (; j < pairs.size() && pairs[j].first != 0; ++j) {
      const int g = pairs[j].first;
      const double v = (g == 10 || g == 20 || g == 40 || g == 42 || g == 70) ? std::stod(pairs[j].second) : 0.0;
      if (type == "CIRCLE") {
        if (g == 10) cx = v;
        if (g == 20) cy = v;
        if (g == 40) r = v;
      } else {
        if (g == 70) closed_flag = (static_cast<int>(v) & 1) != 0;
        if (g == 10) c.vertices.push_back({{v, 0.0}, 0.0});
        if (g == 20 && !c.vertices.empty()) c.vertices.back().p.y = v;
        if (g == 42 && !c.vertices.empty()) c.vertices.back().bulge = v;
      }
    }
    i = j - 1;
    if (type == "CIRCLE") {
      if (r > 0) out.push_back(Contour{{{{cx + r, cy}, 1.0}, {{cx - r, cy}, 1.0}}, true});
      continue;
    }
    if (c.vertices.size() >= 2 && !closed_flag) {
      // Open polylines whose ends meet are closed contours too.
      if (std::hypot(c.vertices.front().p.x - c.vertices.back().p.x, c.vertices.front().p.y - c.vertices.back().p.y) >
          1e-9)
        continue;
      c.vertices.pop_back();
    }
    if (c.vertices.size() >= 2) out.push_back(std::move(c));
  }
  return out;
}

// Independent bulge geometry (as in offset_test.cpp).
struct Arc {
  bool line = true;
  Vec2 a, b, c;
  double r = 0, theta = 0;
};

Arc seg(const Contour& c, std::size_t i) {
  const std::size_t n = c.vertices.size();
  Arc s;
  s.a = c.vertices[i].p;
  s.b = c.vertices[(i + 1) % n].p;
  const double k = c.vertices[i].bulge;
  const double chord = distance(s.a, s.b);
  if (std::abs(k) < 1e-12 || chord == 0) return s;
  s.line = false;
  s.theta = 4 * std::atan(k);
  s.r = chord / (2 * std::sin(std::abs(s.theta) / 2));
  s.c = (s.a + s.b) / 2.0 + perp((s.b - s.a) / chord) * (chord / 2 / std::tan(s.theta / 2));
  return s;
}

Vec2 point_on(const Arc& s, double t) {
  if (s.line) return s.a + (s.b - s.a) * t;
  const double a0 = std::atan2(s.a.y - s.c.y, s.a.x - s.c.x) + s.theta * t;
  return s.c + Vec2{std::cos(a0), std::sin(a0)} * s.r;
}

double dist_to(const Arc& s, Vec2 p) {
  if (s.line) {
    const Vec2 d = s.b - s.a;
    const double l2 = dot(d, d);
    const double t = l2 > 0 ? std::clamp(dot(p - s.a, d) / l2, 0.0, 1.0) : 0.0;
    return distance(p, s.a + d * t);
  }
  double ang = std::atan2(p.y - s.c.y, p.x - s.c.x) - std::atan2(s.a.y - s.c.y, s.a.x - s.c.x);
  if (s.theta < 0) ang = -ang;
  ang = std::fmod(std::fmod(ang, 2 * kPi) + 2 * kPi, 2 * kPi);
  if (ang <= std::abs(s.theta)) return std::abs(distance(p, s.c) - s.r);
  return std::min(distance(p, s.a), distance(p, s.b));
}

double area(const Contour& c) {
  double a = 0;
  for (std::size_t i = 0; i < c.vertices.size(); ++i) {
    const Arc s = seg(c, i);
    a += cross(s.a, s.b) / 2;
    if (!s.line) a += s.r * s.r / 2 * (s.theta - std::sin(s.theta));
  }
  return a;
}

struct Tally {
  std::size_t contours = 0, outward_loops = 0, inward_collapsed = 0, bad = 0;
  double worst_mm = 0;  // largest |distance - |d|| over all samples
};

void check(const Contour& src, double d, Tally& t) {
  const double src_area = area(src);
  if (std::abs(src_area) < 1e-6) return;
  const bool outward = (d > 0) != (src_area > 0);
  const OffsetResult r = offset_contour(src, d);
  double total = 0;
  for (const Contour& o : r.contours) {
    for (const Vertex& v : o.vertices)
      if (!std::isfinite(v.p.x) || !std::isfinite(v.p.y) || !std::isfinite(v.bulge)) ++t.bad;
    for (std::size_t i = 0; i < o.vertices.size(); ++i) {
      const Arc s = seg(o, i);
      for (double f : {0.0, 0.5}) {
        const Vec2 p = point_on(s, f);
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < src.vertices.size(); ++k) best = std::min(best, dist_to(seg(src, k), p));
        t.worst_mm = std::max(t.worst_mm, std::abs(best - std::abs(d)));
      }
    }
    total += area(o);
  }
  if (outward) {
    // An outward offset always leaves an outer loop bigger than the source.
    if (r.contours.empty() || std::abs(total) <= std::abs(src_area)) ++t.bad;
    t.outward_loops += r.contours.size();
  } else {
    if (std::abs(total) >= std::abs(src_area)) ++t.bad;
    if (r.collapsed) ++t.inward_collapsed;
  }
  ++t.contours;
}

TEST(OffsetCorpus, SharedDxfContoursKeepTheirDistance) {
  const std::string dir = std::string(CUTROUTE_SHARED_DIR) + "/data/dxf/";
  const char* files[] = {"vrs_Lv10_SHEET_001.dxf", "vrs_Lv10_SHEET_004.dxf", "d2g_AFluegel_Rippen.dxf",
                         "d2g_Fluegel_Rippen_sp2.dxf", "d2g_fraesen_test_02_2004.dxf", "d2g_DRAAK.dxf",
                         "d2g_Lueftergitter_R14.dxf"};
  Tally t;
  std::size_t read = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const char* f : files) {
    const std::vector<Contour> contours = read_closed_contours(dir + f);
    read += contours.size();
    for (const Contour& c : contours)
      for (double d : {0.1, -0.1, 1.0, -1.0}) check(c, d, t);
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_GT(read, 1000u) << "the shared corpus was not found under " << dir;
  EXPECT_EQ(t.bad, 0u);
  EXPECT_LT(t.worst_mm, 1e-6);
  std::cout << "[ corpus   ] " << read << " closed contours x 4 offsets: " << t.contours << " checked, "
            << t.outward_loops << " outward loops, " << t.inward_collapsed << " inward collapsed, worst distance error "
            << t.worst_mm << " mm, " << secs << " s (including checks)\n";
}

// Not a benchmark (no repetitions, shared machine): prints the time one nest's kerf offset
// takes, so a regression to quadratic behaviour on real contours shows in the log.
TEST(OffsetCorpus, TimeOfOneNest) {
  const std::vector<Contour> contours =
      read_closed_contours(std::string(CUTROUTE_SHARED_DIR) + "/data/dxf/vrs_Lv10_SHEET_001.dxf");
  ASSERT_GT(contours.size(), 700u);  // the issue counts about 786 contours on this sheet
  std::size_t vertices = 0, loops = 0;
  for (const Contour& c : contours) vertices += c.vertices.size();
  const auto start = std::chrono::steady_clock::now();
  for (double d : {0.1, -0.1})
    for (const Contour& c : contours) loops += offset_contour(c, d).contours.size();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GT(loops, contours.size());
  std::cout << "[ timing   ] vrs_Lv10_SHEET_001: " << contours.size() << " contours (" << vertices
            << " vertices) offset both ways by 0.1 mm in " << secs * 1e3 << " ms\n";
}

}  // namespace
}  // namespace cutroute::geometry
