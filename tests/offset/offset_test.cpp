// Tests of the kerf offset against closed-form areas and lengths, exact corner points, a
// brute-force grid of the offset region, and distances recomputed here from the source.
#include <cutroute/geometry/offset.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace cutroute::geometry {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- Independent geometry of bulge contours (written for the tests, not shared with offset.cpp)

struct Arc {
  bool line = true;
  Vec2 a, b, c;
  double r = 0, theta = 0;  // signed sweep [rad]
};

Arc seg(const Contour& c, std::size_t i) {
  const std::size_t n = c.vertices.size();
  Arc s;
  s.a = c.vertices[i].p;
  s.b = c.vertices[(i + 1) % n].p;
  const double k = c.vertices[i].bulge;
  if (std::abs(k) < 1e-12) return s;
  s.line = false;
  s.theta = 4 * std::atan(k);
  const double chord = distance(s.a, s.b);
  s.r = chord / (2 * std::sin(std::abs(s.theta) / 2));
  const Vec2 left = perp((s.b - s.a) / chord);
  s.c = (s.a + s.b) / 2.0 + left * (chord / 2 / std::tan(s.theta / 2));
  return s;
}

std::size_t seg_count(const Contour& c) {
  return c.closed ? c.vertices.size() : (c.vertices.empty() ? 0 : c.vertices.size() - 1);
}

Vec2 point_on(const Arc& s, double t) {
  if (s.line) return s.a + (s.b - s.a) * t;
  const double a0 = std::atan2(s.a.y - s.c.y, s.a.x - s.c.x) + s.theta * t;
  return s.c + Vec2{std::cos(a0), std::sin(a0)} * s.r;
}

double dist_to(const Arc& s, Vec2 p) {
  if (s.line) {
    const Vec2 d = s.b - s.a;
    const double t = std::clamp(dot(p - s.a, d) / dot(d, d), 0.0, 1.0);
    return distance(p, s.a + d * t);
  }
  double ang = std::atan2(p.y - s.c.y, p.x - s.c.x) - std::atan2(s.a.y - s.c.y, s.a.x - s.c.x);
  if (s.theta < 0) ang = -ang;
  while (ang < 0) ang += 2 * kPi;
  while (ang >= 2 * kPi) ang -= 2 * kPi;
  if (ang <= std::abs(s.theta)) return std::abs(distance(p, s.c) - s.r);
  return std::min(distance(p, s.a), distance(p, s.b));
}

double dist_to(const Contour& c, Vec2 p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < seg_count(c); ++i) best = std::min(best, dist_to(seg(c, i), p));
  return best;
}

double area(const Contour& c) {
  double a = 0;
  for (std::size_t i = 0; i < seg_count(c); ++i) {
    const Arc s = seg(c, i);
    a += cross(s.a, s.b) / 2;
    if (!s.line) a += s.r * s.r / 2 * (s.theta - std::sin(s.theta));
  }
  return a;
}

double perimeter(const Contour& c) {
  double l = 0;
  for (std::size_t i = 0; i < seg_count(c); ++i) {
    const Arc s = seg(c, i);
    l += s.line ? distance(s.a, s.b) : s.r * std::abs(s.theta);
  }
  return l;
}

std::vector<Vec2> polygon(const Contour& c, int per_arc) {
  std::vector<Vec2> pts;
  for (std::size_t i = 0; i < seg_count(c); ++i) {
    const Arc s = seg(c, i);
    const int steps = s.line ? 1 : per_arc;
    for (int k = 0; k < steps; ++k) pts.push_back(point_on(s, static_cast<double>(k) / steps));
  }
  return pts;
}

bool inside(const std::vector<Vec2>& poly, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 a = poly[i], b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// No two non-adjacent edges of the finely flattened contour cross.
bool is_simple(const Contour& c) {
  const std::vector<Vec2> p = polygon(c, 64);
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      if (segments_cross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return false;
    }
  return true;
}

double shortest_segment(const Contour& c) {
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < seg_count(c); ++i) {
    const Arc s = seg(c, i);
    m = std::min(m, s.line ? distance(s.a, s.b) : s.r * std::abs(s.theta));
  }
  return m;
}

bool all_finite(const Contour& c) {
  for (const Vertex& v : c.vertices)
    if (!std::isfinite(v.p.x) || !std::isfinite(v.p.y) || !std::isfinite(v.bulge)) return false;
  return true;
}

// Every vertex and `steps` points on every segment of `result` are |d| from `source`.
void expect_at_offset(const Contour& result, const Contour& source, double d, double tol = 1e-9, int steps = 16) {
  for (std::size_t i = 0; i < seg_count(result); ++i) {
    const Arc s = seg(result, i);
    for (int k = 0; k <= steps; ++k) {
      const Vec2 p = point_on(s, static_cast<double>(k) / steps);
      ASSERT_NEAR(dist_to(source, p), std::abs(d), tol) << "segment " << i << " sample " << k << " at (" << p.x
                                                         << ", " << p.y << ")";
    }
  }
}

// Brute force: area of {p : p inside `source` or within |d| of it} (outward) or
// {p inside and at least |d| from its boundary} (inward), on a grid of step h.
double grid_area(const Contour& source, double d, bool outward, double h) {
  const std::vector<Vec2> poly = polygon(source, 128);
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  for (Vec2 p : poly) {
    xmin = std::min(xmin, p.x); xmax = std::max(xmax, p.x);
    ymin = std::min(ymin, p.y); ymax = std::max(ymax, p.y);
  }
  const double m = std::abs(d) + h;
  double count = 0;
  for (double y = ymin - m + h / 2; y < ymax + m; y += h)
    for (double x = xmin - m + h / 2; x < xmax + m; x += h) {
      const Vec2 p{x, y};
      const bool in = inside(poly, p);
      const double dist = dist_to(source, p);
      if (outward ? (in || dist <= std::abs(d)) : (in && dist >= std::abs(d))) count += 1;
    }
  return count * h * h;
}

Contour rect(double x0, double y0, double x1, double y1) {
  return Contour{{{{x0, y0}, 0}, {{x1, y0}, 0}, {{x1, y1}, 0}, {{x0, y1}, 0}}, true};
}

Contour circle(Vec2 c, double r) { return Contour{{{{c.x + r, c.y}, 1.0}, {{c.x - r, c.y}, 1.0}}, true}; }

Contour reverse(const Contour& c) {
  Contour r;
  r.closed = c.closed;
  const std::size_t n = c.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = n - 1 - i;  // vertex k, arriving from segment k (k-1 -> k)
    const std::size_t prev = (k + n - 1) % n;
    r.vertices.push_back({c.vertices[k].p, -c.vertices[prev].bulge});
  }
  return r;
}

// Rounded rectangle [0,w]x[0,h], corner radius rho, counter-clockwise.
Contour rounded_rect(double w, double h, double rho) {
  const double k = std::tan(kPi / 8);  // quarter arc
  return Contour{{{{rho, 0}, 0},
                  {{w - rho, 0}, k},
                  {{w, rho}, 0},
                  {{w, h - rho}, k},
                  {{w - rho, h}, 0},
                  {{rho, h}, k},
                  {{0, h - rho}, 0},
                  {{0, rho}, k}},
                 true};
}

Contour l_shape() {
  return Contour{{{{0, 0}, 0}, {{20, 0}, 0}, {{20, 10}, 0}, {{10, 10}, 0}, {{10, 20}, 0}, {{0, 20}, 0}}, true};
}

bool has_vertex(const Contour& c, Vec2 p, double tol) {
  return std::any_of(c.vertices.begin(), c.vertices.end(), [&](const Vertex& v) { return distance(v.p, p) <= tol; });
}

// ---- Tests

TEST(OffsetContour, SquareOutwardIsRoundedSquare) {
  const double a = 10, d = 1.5;
  const Contour sq = rect(0, 0, a, a);  // counter-clockwise: outward is to the right
  const OffsetResult r = offset_contour(sq, -d);
  ASSERT_EQ(r.contours.size(), 1u);
  EXPECT_FALSE(r.collapsed);
  EXPECT_FALSE(r.self_intersection_removed);
  const Contour& o = r.contours[0];
  EXPECT_TRUE(o.closed);
  EXPECT_EQ(o.vertices.size(), 8u);
  EXPECT_NEAR(area(o), a * a + 4 * a * d + kPi * d * d, 1e-9);
  EXPECT_NEAR(perimeter(o), 4 * a + 2 * kPi * d, 1e-9);
  int arcs = 0;
  for (const Vertex& v : o.vertices)
    if (v.bulge != 0) {
      ++arcs;
      EXPECT_NEAR(v.bulge, std::tan(kPi / 8), 1e-12);  // quarter arcs, counter-clockwise
    }
  EXPECT_EQ(arcs, 4);
  expect_at_offset(o, sq, d);
}

TEST(OffsetContour, SquareInwardIsSmallerSharpSquare) {
  const double a = 10, d = 1.5;
  const Contour sq = rect(0, 0, a, a);
  const OffsetResult r = offset_contour(sq, d);
  ASSERT_EQ(r.contours.size(), 1u);
  EXPECT_FALSE(r.self_intersection_removed);
  const Contour& o = r.contours[0];
  ASSERT_EQ(o.vertices.size(), 4u);
  for (const Vertex& v : o.vertices) EXPECT_EQ(v.bulge, 0.0);
  for (Vec2 p : {Vec2{d, d}, Vec2{a - d, d}, Vec2{a - d, a - d}, Vec2{d, a - d}}) EXPECT_TRUE(has_vertex(o, p, 1e-12));
  EXPECT_NEAR(area(o), (a - 2 * d) * (a - 2 * d), 1e-9);
  expect_at_offset(o, sq, d);
}

TEST(OffsetContour, CircleStaysTwoExactHalfArcs) {
  const Vec2 c{3, -4};
  const double r0 = 5;
  for (double d : {1.25, -1.25}) {
    const OffsetResult r = offset_contour(circle(c, r0), d);
    ASSERT_EQ(r.contours.size(), 1u);
    const Contour& o = r.contours[0];
    ASSERT_EQ(o.vertices.size(), 2u);
    for (const Vertex& v : o.vertices) {
      EXPECT_NEAR(v.bulge, 1.0, 1e-12);
      EXPECT_NEAR(distance(v.p, c), r0 - d, 1e-12);
    }
    EXPECT_NEAR(area(o), kPi * (r0 - d) * (r0 - d), 1e-9);
  }
  // Clockwise circle: left is outward.
  const OffsetResult cw = offset_contour(reverse(circle(c, r0)), 1.25);
  ASSERT_EQ(cw.contours.size(), 1u);
  for (const Vertex& v : cw.contours[0].vertices) {
    EXPECT_NEAR(v.bulge, -1.0, 1e-12);
    EXPECT_NEAR(distance(v.p, c), r0 + 1.25, 1e-12);
  }
}

TEST(OffsetContour, ClockwiseInputOffsetsLeftOutward) {
  const double a = 10, d = 1;
  const Contour cw = reverse(rect(0, 0, a, a));
  ASSERT_LT(area(cw), 0);
  const OffsetResult out = offset_contour(cw, d);
  ASSERT_EQ(out.contours.size(), 1u);
  EXPECT_NEAR(area(out.contours[0]), -(a * a + 4 * a * d + kPi * d * d), 1e-9);
  expect_at_offset(out.contours[0], cw, d);
  const OffsetResult in = offset_contour(cw, -d);
  ASSERT_EQ(in.contours.size(), 1u);
  EXPECT_NEAR(area(in.contours[0]), -(a - 2 * d) * (a - 2 * d), 1e-9);
}

TEST(OffsetContour, RoundedRectangleKeepsArcsAndSharpensWhenRadiusCollapses) {
  const double w = 30, h = 20, rho = 3;
  const Contour rr = rounded_rect(w, h, rho);
  auto rr_area = [](double ww, double hh, double rr_) { return ww * hh - (4 - kPi) * rr_ * rr_; };
  ASSERT_NEAR(area(rr), rr_area(w, h, rho), 1e-9);
  // Outward: radius rho + d.
  const OffsetResult out = offset_contour(rr, -2);
  ASSERT_EQ(out.contours.size(), 1u);
  EXPECT_NEAR(area(out.contours[0]), rr_area(w + 4, h + 4, rho + 2), 1e-9);
  EXPECT_EQ(out.contours[0].vertices.size(), 8u);
  expect_at_offset(out.contours[0], rr, 2);
  // Inward, d < rho: radius rho - d.
  const OffsetResult in = offset_contour(rr, 2);
  ASSERT_EQ(in.contours.size(), 1u);
  EXPECT_NEAR(area(in.contours[0]), rr_area(w - 4, h - 4, rho - 2), 1e-9);
  expect_at_offset(in.contours[0], rr, 2);
  // Inward, d > rho: the corner arcs collapse, the lines meet in sharp corners.
  const OffsetResult sharp = offset_contour(rr, 4);
  ASSERT_EQ(sharp.contours.size(), 1u);
  EXPECT_EQ(sharp.contours[0].vertices.size(), 4u);
  EXPECT_NEAR(area(sharp.contours[0]), (w - 8) * (h - 8), 1e-9);
  EXPECT_TRUE(has_vertex(sharp.contours[0], {4, 4}, 1e-12));
}

TEST(OffsetContour, LShapeConcaveCornerIsTrimmedExactly) {
  const Contour l = l_shape();
  const double d = 2;
  const OffsetResult out = offset_contour(l, -d);
  ASSERT_EQ(out.contours.size(), 1u);
  const Contour& o = out.contours[0];
  EXPECT_TRUE(has_vertex(o, {12, 12}, 1e-12));  // the two shifted edges meet here
  // 5 convex corners give quarter arcs, the concave one a d x d overlap of the edge strips.
  EXPECT_NEAR(area(o), 300 + 80 * d - d * d + 5 * kPi * d * d / 4, 1e-9);
  EXPECT_NEAR(perimeter(o), 80 - 2 * d + 5 * kPi * d / 2, 1e-9);
  expect_at_offset(o, l, d);

  // Inward by 1: the concave corner becomes a concave quarter arc around (10, 10).
  const OffsetResult in = offset_contour(l, 1);
  ASSERT_EQ(in.contours.size(), 1u);
  EXPECT_NEAR(area(in.contours[0]), 225 - kPi / 4, 1e-9);
  EXPECT_NEAR(perimeter(in.contours[0]), 70 + kPi / 2, 1e-9);
  EXPECT_TRUE(has_vertex(in.contours[0], {1, 1}, 1e-12));
  EXPECT_TRUE(has_vertex(in.contours[0], {19, 9}, 1e-12));
  expect_at_offset(in.contours[0], l, 1);
}

// A convex shape of arcs and corners: the outward offset obeys Steiner's formula exactly.
TEST(OffsetContour, ConvexArcShapeFollowsSteinerFormula) {
  const Contour s{{{{0, 0}, 0.2}, {{10, 0}, 0.35}, {{12, 8}, 0.1}, {{4, 11}, 0.25}, {{-2, 6}, 0.0}}, true};
  ASSERT_GT(area(s), 0);
  for (double d : {0.1, 1.0, 3.0}) {
    const OffsetResult r = offset_contour(s, -d);
    ASSERT_EQ(r.contours.size(), 1u);
    EXPECT_NEAR(area(r.contours[0]), area(s) + perimeter(s) * d + kPi * d * d, 1e-8);
    EXPECT_NEAR(perimeter(r.contours[0]), perimeter(s) + 2 * kPi * d, 1e-9);
    expect_at_offset(r.contours[0], s, d);
    EXPECT_TRUE(is_simple(r.contours[0]));
  }
}

// Concave and convex arcs, checked against a brute-force grid of the offset region.
TEST(OffsetContour, ArcRichShapeMatchesGridArea) {
  const Contour s{{{{0, 0}, -0.3}, {{10, 0}, 0.4}, {{12, 8}, -0.25}, {{4, 11}, 0.5}, {{-2, 6}, 0.15}}, true};
  ASSERT_GT(area(s), 0);
  for (double d : {0.8, -0.8}) {
    const OffsetResult r = offset_contour(s, d);
    ASSERT_EQ(r.contours.size(), 1u) << d;
    const Contour& o = r.contours[0];
    expect_at_offset(o, s, d);
    EXPECT_TRUE(is_simple(o));
    const double h = 0.04;
    const double grid = grid_area(s, d, d < 0, h);
    EXPECT_NEAR(area(o), grid, perimeter(o) * h) << d;
  }
}

TEST(OffsetContour, SmallHoleCollapses) {
  // A counter-clockwise hole: the scrap is its inside, to the left.
  const OffsetResult c = offset_contour(circle({5, 5}, 0.4), 0.5);
  EXPECT_TRUE(c.collapsed);
  EXPECT_TRUE(c.contours.empty());
  const OffsetResult sq = offset_contour(rect(0, 0, 1, 1), 0.6);  // shifted edges cross over
  EXPECT_TRUE(sq.collapsed);
  EXPECT_TRUE(sq.self_intersection_removed);  // the inverted square was dropped
  EXPECT_TRUE(sq.contours.empty());
  const OffsetResult far = offset_contour(rect(0, 0, 1, 1), 3);  // shifted edges miss each other
  EXPECT_TRUE(far.collapsed);
  const OffsetResult ok = offset_contour(rect(0, 0, 1, 1), 0.4);
  ASSERT_EQ(ok.contours.size(), 1u);
  EXPECT_NEAR(area(ok.contours[0]), 0.04, 1e-12);
}

// A notch 1 mm wide is closed by an outward offset of 1 mm: the loop inside it is removed.
TEST(OffsetContour, ThinSlotLoopIsRemoved) {
  const Contour part{{{{0, 0}, 0},
                      {{20, 0}, 0},
                      {{20, 20}, 0},
                      {{10.5, 20}, 0},
                      {{10.5, 10}, 0},
                      {{9.5, 10}, 0},
                      {{9.5, 20}, 0},
                      {{0, 20}, 0}},
                     true};
  const double d = 1;
  const OffsetResult r = offset_contour(part, -d);
  EXPECT_TRUE(r.self_intersection_removed);
  ASSERT_EQ(r.contours.size(), 1u);
  const Contour& o = r.contours[0];
  EXPECT_TRUE(is_simple(o));
  EXPECT_GT(area(o), 0);
  expect_at_offset(o, part, d);
  // The two corner arcs of the notch's mouth meet on its axis, sqrt(1 - 0.5²) above the top.
  EXPECT_TRUE(has_vertex(o, {10, 20 + std::sqrt(0.75)}, 1e-9));
  const double h = 0.04;
  EXPECT_NEAR(area(o), grid_area(part, d, true, h), perimeter(o) * h);
}

// A dumbbell hole whose neck is narrower than 2d splits into two loops.
TEST(OffsetContour, DumbbellHoleSplitsIntoTwoLoops) {
  // Two circles of radius 4 (centres 0 and 12) joined by a neck 2 mm wide, counter-clockwise.
  const double r = 4, y = 1;
  const double x = std::sqrt(r * r - y * y);
  auto bulge = [](double sweep) { return std::tan(sweep / 4); };
  const double big = 2 * kPi - 2 * std::asin(y / r);
  const Contour hole{{{{x, -y}, 0},
                      {{12 - x, -y}, bulge(big)},
                      {{12 - x, y}, 0},
                      {{x, y}, bulge(big)}},
                     true};
  ASSERT_GT(area(hole), 0);
  const double d = 1.5;
  const OffsetResult res = offset_contour(hole, d);
  EXPECT_TRUE(res.self_intersection_removed);
  ASSERT_EQ(res.contours.size(), 2u);
  double total = 0;
  for (const Contour& o : res.contours) {
    expect_at_offset(o, hole, d);
    EXPECT_TRUE(is_simple(o));
    EXPECT_GT(area(o), 0);
    total += area(o);
  }
  const double h = 0.04;
  EXPECT_NEAR(total, grid_area(hole, d, false, h), 2 * kPi * 2.5 * 2 * h);
}

TEST(OffsetContour, OffsetBackRestoresConvexShapes) {
  const Contour sq = rect(-3, 2, 17, 9);
  const OffsetResult out = offset_contour(sq, -1.5);
  ASSERT_EQ(out.contours.size(), 1u);
  const OffsetResult back = offset_contour(out.contours[0], 1.5);
  ASSERT_EQ(back.contours.size(), 1u);
  ASSERT_EQ(back.contours[0].vertices.size(), 4u);
  for (const Vertex& v : sq.vertices) EXPECT_TRUE(has_vertex(back.contours[0], v.p, 1e-9));
  EXPECT_NEAR(area(back.contours[0]), area(sq), 1e-9);

  const Contour s{{{{0, 0}, 0.2}, {{10, 0}, 0.35}, {{12, 8}, 0.1}, {{4, 11}, 0.25}, {{-2, 6}, 0.0}}, true};
  const OffsetResult o2 = offset_contour(s, -2);
  ASSERT_EQ(o2.contours.size(), 1u);
  const OffsetResult b2 = offset_contour(o2.contours[0], 2);
  ASSERT_EQ(b2.contours.size(), 1u);
  EXPECT_NEAR(area(b2.contours[0]), area(s), 1e-8);
  EXPECT_NEAR(perimeter(b2.contours[0]), perimeter(s), 1e-8);
  expect_at_offset(b2.contours[0], o2.contours[0], 2);
  for (const Vertex& v : s.vertices) EXPECT_TRUE(has_vertex(b2.contours[0], v.p, 1e-8));
}

TEST(OffsetContour, TranslationAndRotationInvariant) {
  const Contour s{{{{0, 0}, -0.3}, {{10, 0}, 0.4}, {{12, 8}, -0.25}, {{4, 11}, 0.5}, {{-2, 6}, 0.15}}, true};
  const double ang = 0.6458, cs = std::cos(ang), sn = std::sin(ang);
  const Vec2 shift{1234.5, -678.25};
  auto move = [&](Vec2 p) { return Vec2{cs * p.x - sn * p.y, sn * p.x + cs * p.y} + shift; };
  Contour t = s;
  for (Vertex& v : t.vertices) v.p = move(v.p);
  for (double d : {0.7, -0.7}) {
    const OffsetResult a = offset_contour(s, d);
    const OffsetResult b = offset_contour(t, d);
    ASSERT_EQ(a.contours.size(), 1u);
    ASSERT_EQ(b.contours.size(), 1u);
    ASSERT_EQ(a.contours[0].vertices.size(), b.contours[0].vertices.size());
    EXPECT_NEAR(area(a.contours[0]), area(b.contours[0]), 1e-8);
    EXPECT_NEAR(perimeter(a.contours[0]), perimeter(b.contours[0]), 1e-9);
    for (std::size_t i = 0; i < a.contours[0].vertices.size(); ++i) {
      EXPECT_NEAR(distance(move(a.contours[0].vertices[i].p), b.contours[0].vertices[i].p), 0.0, 1e-9);
      EXPECT_NEAR(a.contours[0].vertices[i].bulge, b.contours[0].vertices[i].bulge, 1e-9);
    }
  }
}

TEST(OffsetContour, DegenerateInputGivesNoNaN) {
  // Duplicate points and zero-length segments: same result as without them.
  const Contour dup{
      {{{0, 0}, 0}, {{0, 0}, 0}, {{10, 0}, 0.5}, {{10, 0}, 0}, {{10, 10}, 0}, {{0, 10}, 0}, {{0, 10}, 0}}, true};
  const OffsetResult a = offset_contour(dup, -1);
  const OffsetResult b = offset_contour(rect(0, 0, 10, 10), -1);
  ASSERT_EQ(a.contours.size(), 1u);
  ASSERT_EQ(b.contours.size(), 1u);
  EXPECT_TRUE(all_finite(a.contours[0]));
  EXPECT_NEAR(area(a.contours[0]), area(b.contours[0]), 1e-9);
  EXPECT_EQ(a.contours[0].vertices.size(), b.contours[0].vertices.size());

  // A huge bulge (almost a full circle through two close points) stays finite.
  const Contour huge{{{{0, 0}, 1e12}, {{1, 0}, 0.0}}, true};
  for (double d : {0.5, -0.5}) {
    const OffsetResult r = offset_contour(huge, d);
    for (const Contour& c : r.contours) EXPECT_TRUE(all_finite(c));
  }
  // Everything at one point; a single vertex; an empty contour; NaN coordinates; NaN distance.
  const Contour point{{{{1, 1}, 0}, {{1, 1}, 0.7}, {{1, 1}, 0}}, true};
  EXPECT_TRUE(offset_contour(point, 1).collapsed);
  EXPECT_TRUE(offset_contour(Contour{{{{1, 1}, 0.5}}, true}, 1).collapsed);
  EXPECT_TRUE(offset_contour(Contour{{}, true}, 1).collapsed);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(offset_contour(Contour{{{{0, 0}, 0}, {{nan, 0}, 0}, {{1, 1}, 0}}, true}, 1).collapsed);
  EXPECT_TRUE(offset_contour(rect(0, 0, 1, 1), nan).collapsed);
  // A zero-area back-and-forth "closed" contour.
  EXPECT_TRUE(offset_contour(Contour{{{{0, 0}, 0}, {{5, 0}, 0}}, true}, 1).collapsed);
  // Zero offset returns the contour itself.
  const OffsetResult zero = offset_contour(rect(0, 0, 2, 3), 0);
  ASSERT_EQ(zero.contours.size(), 1u);
  EXPECT_EQ(zero.contours[0], rect(0, 0, 2, 3));
}

TEST(OffsetOpenPath, LineAndArcLeadIn) {
  // Line then a tangent counter-clockwise quarter arc of radius 2.
  const Contour lead{{{{0, 0}, 0}, {{5, 0}, std::tan(kPi / 8)}, {{7, 2}, 0}}, false};
  const double d = 0.5;
  const Contour o = offset_open_path(lead, d);
  EXPECT_FALSE(o.closed);
  ASSERT_EQ(o.vertices.size(), 3u);  // tangent join: no extra piece
  EXPECT_NEAR(distance(o.vertices[0].p, {0, 0.5}), 0, 1e-12);
  EXPECT_NEAR(distance(o.vertices[1].p, {5, 0.5}), 0, 1e-12);
  EXPECT_NEAR(distance(o.vertices[2].p, {6.5, 2}), 0, 1e-12);  // radius 2 - 0.5 around (5, 2)
  EXPECT_NEAR(perimeter(o), 5 + 1.5 * kPi / 2, 1e-12);
  expect_at_offset(o, lead, d);
}

TEST(OffsetOpenPath, CornersGetJoinArcsOrTrims) {
  // Right turn at (10, 0): offsetting left is the convex side (join arc), right the concave one.
  const Contour path{{{{0, 0}, 0}, {{10, 0}, 0}, {{10, -10}, 0}}, false};
  const Contour left = offset_open_path(path, 1);
  ASSERT_EQ(left.vertices.size(), 4u);
  EXPECT_NEAR(left.vertices[1].bulge, -std::tan(kPi / 8), 1e-12);
  EXPECT_NEAR(perimeter(left), 20 + kPi / 2, 1e-12);
  expect_at_offset(left, path, 1);
  const Contour right = offset_open_path(path, -1);
  ASSERT_EQ(right.vertices.size(), 3u);
  EXPECT_NEAR(distance(right.vertices[1].p, {9, -1}), 0, 1e-12);
  EXPECT_NEAR(distance(right.vertices[0].p, {0, -1}), 0, 1e-12);
  EXPECT_NEAR(distance(right.vertices[2].p, {9, -10}), 0, 1e-12);
  // A fillet tighter than the offset collapses: the neighbours meet in a sharp corner.
  const Contour fillet{{{{0, 0}, 0}, {{10, 0}, std::tan(kPi / 8)}, {{10.2, 0.2}, 0}, {{10.2, 10}, 0}}, false};
  const Contour sharp = offset_open_path(fillet, 0.5);
  ASSERT_EQ(sharp.vertices.size(), 3u);
  EXPECT_NEAR(distance(sharp.vertices[0].p, {0, 0.5}), 0, 1e-12);
  EXPECT_NEAR(distance(sharp.vertices[1].p, {9.7, 0.5}), 0, 1e-12);
  EXPECT_NEAR(distance(sharp.vertices[2].p, {9.7, 10}), 0, 1e-12);
  expect_at_offset(sharp, fillet, 0.5);
  // Degenerate open paths.
  EXPECT_TRUE(offset_open_path(Contour{{{{1, 1}, 0}}, false}, 1).vertices.empty());
  EXPECT_TRUE(offset_open_path(Contour{{{{1, 1}, 0}, {{1, 1}, 3}}, false}, 1).vertices.empty());
}

// ---- Random shapes against brute force

// Deterministic generator for the test shapes (splitmix64).
struct TestRng {
  unsigned long long state;
  double uniform(double lo, double hi) {
    unsigned long long z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return lo + (hi - lo) * static_cast<double>(z >> 11) / 9007199254740992.0;
  }
};

// Star-shaped polygon around the origin with random radii and bulges, counter-clockwise.
Contour random_star(TestRng& rng, int n, double max_bulge) {
  Contour c;
  c.closed = true;
  for (int i = 0; i < n; ++i) {
    const double ang = 2 * kPi * (i + rng.uniform(0.1, 0.9)) / n;
    const double r = rng.uniform(4, 10);
    c.vertices.push_back({{r * std::cos(ang), r * std::sin(ang)}, rng.uniform(-max_bulge, max_bulge)});
  }
  return c;
}

bool loops_cross(const Contour& a, const Contour& b) {
  const std::vector<Vec2> p = polygon(a, 64), q = polygon(b, 64);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < q.size(); ++j)
      if (segments_cross(p[i], p[(i + 1) % p.size()], q[j], q[(j + 1) % q.size()])) return true;
  return false;
}

TEST(OffsetContour, RandomStarShapesMatchBruteForce) {
  TestRng rng{20261121};
  int checked = 0;
  for (int shape = 0; shape < 30; ++shape) {
    const Contour src = random_star(rng, 5 + shape % 10, shape % 3 == 0 ? 0.0 : 0.35);
    if (!is_simple(src)) continue;
    // Per grid point: inside? and distance to the source, computed once per shape.
    const double h = 0.15, m = 3.2;
    const std::vector<Vec2> poly = polygon(src, 48);
    std::vector<char> in;
    std::vector<double> dist;
    for (double y = -10 - m + h / 2; y < 10 + m; y += h)
      for (double x = -10 - m + h / 2; x < 10 + m; x += h) {
        in.push_back(inside(poly, {x, y}) ? 1 : 0);
        dist.push_back(dist_to(src, {x, y}));
      }
    for (double d : {0.3, -0.3, 1.2, -1.2, 3.0, -3.0}) {
      SCOPED_TRACE(testing::Message() << "shape " << shape << " d " << d);
      const OffsetResult r = offset_contour(src, d);
      double total = 0, perim = 0;
      for (const Contour& o : r.contours) {
        ASSERT_TRUE(all_finite(o));
        EXPECT_GE(shortest_segment(o), 1e-6);
        expect_at_offset(o, src, d, 1e-7);
        EXPECT_TRUE(is_simple(o));
        EXPECT_GT(area(o), 0);
        total += area(o);
        perim += perimeter(o);
      }
      for (std::size_t i = 0; i < r.contours.size(); ++i)
        for (std::size_t j = i + 1; j < r.contours.size(); ++j)
          EXPECT_FALSE(loops_cross(r.contours[i], r.contours[j]));
      EXPECT_EQ(r.collapsed, r.contours.empty());
      double grid = 0;
      for (std::size_t k = 0; k < in.size(); ++k)
        if (d > 0 ? (in[k] && dist[k] >= d) : (in[k] || dist[k] <= -d)) grid += h * h;
      // Each boundary cell is off by at most h² / 2 (the perimeter of src bounds the offset's
      // for inward offsets; for outward ones the offset's own perimeter is used).
      EXPECT_NEAR(total, grid, std::max(perim, perimeter(src)) * h / 2 + 4 * h * h);
      ++checked;
    }
  }
  EXPECT_GE(checked, 120);
}

// Combs on an integer grid: teeth and gaps 1-3 mm wide, so that offsets by 0.5, 1 and 1.5 mm
// make walls coincide exactly (gaps of exactly 2|d|) or pass exactly through corners.
Contour random_comb(TestRng& rng, int teeth) {
  std::vector<Vec2> top;  // the toothed top edge, left to right
  double x = 0;
  for (int i = 0; i < teeth; ++i) {
    const double w = std::floor(rng.uniform(1, 4)), h = std::floor(rng.uniform(1, 6)), g = std::floor(rng.uniform(1, 4));
    top.push_back({x, 2});
    top.push_back({x, 2 + h});
    top.push_back({x + w, 2 + h});
    top.push_back({x + w, 2});
    x += w + g;
  }
  Contour c;
  c.closed = true;
  c.vertices.push_back({{x, 0}, 0});
  c.vertices.push_back({{x, 2}, 0});
  for (auto it = top.rbegin(); it != top.rend(); ++it) c.vertices.push_back({*it, 0});
  c.vertices.push_back({{-1, 2}, 0});
  c.vertices.push_back({{-1, 0}, 0});
  return c;
}

TEST(OffsetContour, RandomCombsWithExactCoincidencesMatchBruteForce) {
  TestRng rng{7};
  int checked = 0;
  for (int shape = 0; shape < 12; ++shape) {
    const Contour src = random_comb(rng, 2 + shape % 4);
    ASSERT_TRUE(is_simple(src));
    double xmax = 0;
    for (const Vertex& v : src.vertices) xmax = std::max(xmax, v.p.x);
    const double h = 0.1, m = 2;
    const std::vector<Vec2> poly = polygon(src, 1);
    std::vector<char> in;
    std::vector<double> dist;
    for (double y = -m + h / 2; y < 8 + m; y += h)
      for (double x = -1 - m + h / 2; x < xmax + m; x += h) {
        in.push_back(inside(poly, {x, y}) ? 1 : 0);
        dist.push_back(dist_to(src, {x, y}));
      }
    for (double d : {0.5, -0.5, 1.0, -1.0, 1.5, -1.5}) {
      SCOPED_TRACE(testing::Message() << "comb " << shape << " d " << d);
      const OffsetResult r = offset_contour(src, d);
      double total = 0, perim = 0;
      for (const Contour& o : r.contours) {
        ASSERT_TRUE(all_finite(o));
        EXPECT_GE(shortest_segment(o), 1e-6);
        expect_at_offset(o, src, d, 1e-7);
        EXPECT_TRUE(is_simple(o));
        EXPECT_GT(area(o), 0);
        total += area(o);
        perim += perimeter(o);
      }
      double grid = 0;
      for (std::size_t k = 0; k < in.size(); ++k)
        if (d > 0 ? (in[k] && dist[k] >= d) : (in[k] || dist[k] <= -d)) grid += h * h;
      EXPECT_NEAR(total, grid, std::max(perim, perimeter(src)) * h / 2 + 4 * h * h);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 72);
}

// Many short pieces (as from a spline converted to arcs) with waves of about the offset's size:
// whatever is trimmed or removed between the waves, the result keeps its distance.
TEST(OffsetContour, LargeWavyContourKeepsDistance) {
  TestRng rng{99};
  Contour c;
  c.closed = true;
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    const double ang = 2 * kPi * i / n, r = 100 + rng.uniform(0, 0.5);
    c.vertices.push_back({{r * std::cos(ang), r * std::sin(ang)}, i % 3 == 0 ? 0.1 : 0.0});
  }
  for (double d : {1.0, -1.0}) {
    SCOPED_TRACE(d);
    const OffsetResult r = offset_contour(c, d);
    ASSERT_EQ(r.contours.size(), 1u);
    expect_at_offset(r.contours[0], c, d, 1e-7, 2);
    // Between the circles of radius 100 - d and 100.5 - d (resp. 100 + |d|, 100.5 + |d|).
    const double lo = d > 0 ? 100 - d : 100 + std::abs(d), hi = lo + 0.5;
    EXPECT_GT(area(r.contours[0]), kPi * lo * lo);
    EXPECT_LT(area(r.contours[0]), kPi * hi * hi);
  }
}

TEST(OffsetContour, SelfIntersectingInputGivesFiniteOutput) {
  // A figure eight and a bow tie: not valid contours, but no crash and no NaN.
  const Contour eight{{{{0, 0}, 0.8}, {{10, 0}, -0.8}, {{20, 0}, 0.8}, {{10, 0}, -0.8}}, true};
  const Contour bow{{{{0, 0}, 0}, {{10, 10}, 0}, {{10, 0}, 0}, {{0, 10}, 0}}, true};
  for (const Contour* c : {&eight, &bow})
    for (double d : {0.5, -0.5, 3.0, -3.0})
      for (const Contour& o : offset_contour(*c, d).contours) EXPECT_TRUE(all_finite(o));
}

// A cavity whose mouth is narrower than 2d: the outward offset seals the mouth; the loop around
// the sealed cavity has the opposite orientation and is dropped, so the one loop left encloses
// the dilated part together with the cavity.
TEST(OffsetContour, SealedCavityLeavesOnlyTheOuterLoop) {
  const Contour part{{{{0, 0}, 0},
                      {{20, 0}, 0},
                      {{20, 20}, 0},
                      {{10.5, 20}, 0},
                      {{10.5, 15}, 0},
                      {{15, 15}, 0},
                      {{15, 5}, 0},
                      {{5, 5}, 0},
                      {{5, 15}, 0},
                      {{9.5, 15}, 0},
                      {{9.5, 20}, 0},
                      {{0, 20}, 0}},
                     true};
  ASSERT_TRUE(is_simple(part));
  const double d = 1;
  const OffsetResult r = offset_contour(part, -d);
  EXPECT_TRUE(r.self_intersection_removed);
  ASSERT_EQ(r.contours.size(), 1u);
  const Contour& o = r.contours[0];
  EXPECT_TRUE(is_simple(o));
  expect_at_offset(o, part, d);
  const double h = 0.04;
  const std::vector<Vec2> poly = polygon(part, 1);
  double grid = 0;
  for (double y = -2 + h / 2; y < 22; y += h)
    for (double x = -2 + h / 2; x < 22; x += h) {
      const bool cavity = x > 5 && x < 15 && y > 5 && y < 15;
      if (cavity || inside(poly, {x, y}) || dist_to(part, {x, y}) <= d) grid += h * h;
    }
  EXPECT_NEAR(area(o), grid, perimeter(o) * h);
}

// Offsets down to the join resolution stay exact; below it the source comes back unchanged.
TEST(OffsetContour, TinyOffsets) {
  const Contour l = l_shape();
  for (double d : {1e-9, 1e-7, 1e-6, 2e-6, 1e-5, 1e-4}) {
    for (double s : {1.0, -1.0}) {
      SCOPED_TRACE(d * s);
      const OffsetResult r = offset_contour(l, d * s);
      ASSERT_EQ(r.contours.size(), 1u);
      if (d <= 1e-6) {
        EXPECT_EQ(r.contours[0], l);
        continue;
      }
      expect_at_offset(r.contours[0], l, d, 1e-12);
      // Inward: the edge strips overlap by d² at the 5 convex corners and leave a quarter disc at
      // the concave one; outward: d² overlap at the concave corner, quarter discs at the convex.
      const double expected =
          s > 0 ? 300 - 80 * d + 5 * d * d - kPi * d * d / 4 : 300 + 80 * d - d * d + 5 * kPi * d * d / 4;
      EXPECT_NEAR(area(r.contours[0]), expected, 1e-9);
    }
  }
}

}  // namespace
}  // namespace cutroute::geometry
