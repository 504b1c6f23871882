// SPLINE and ELLIPSE conversion to arcs: curves of known shape, deviation measured here
// independently (dense sampling of the exact curve against the produced arcs, both ways).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include <cutroute/io/dxf.hpp>

#include "contour_math.hpp"
#include "support/dxf_builder.hpp"

namespace cutroute::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTol = 0.01;  // default curve tolerance [mm]

// expected: the code of the one warning the drawing must give (none when null).
io::DxfEntity read_one(const std::string& text, double tol = kTol, const char* expected = nullptr) {
  io::DxfOptions opt;
  opt.curve_tol_mm = tol;
  auto r = io::read_dxf_string(text, "curve.dxf", opt);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : format(r.error()));
  if (!r.ok() || r->entities.size() != 1) {
    ADD_FAILURE() << "expected one entity";
    return {};
  }
  std::size_t found = 0;
  for (const auto& d : r->diagnostics) {
    if (expected && d.code == expected) {
      ++found;
    } else {
      ADD_FAILURE() << format(d);
    }
  }
  if (expected) {
    EXPECT_EQ(found, 1u) << expected;
  }
  return r->entities[0];
}

// Cox–de Boor recursion, written plainly (independent of the reader's evaluation).
double basis(const std::vector<double>& U, int i, int p, double u) {
  if (p == 0) {
    const bool last = u == U.back() && U[static_cast<std::size_t>(i + 1)] == U.back() &&
                      U[static_cast<std::size_t>(i)] < U[static_cast<std::size_t>(i + 1)];
    return (U[static_cast<std::size_t>(i)] <= u && u < U[static_cast<std::size_t>(i + 1)]) || last ? 1.0 : 0.0;
  }
  double r = 0;
  const double d1 = U[static_cast<std::size_t>(i + p)] - U[static_cast<std::size_t>(i)];
  const double d2 = U[static_cast<std::size_t>(i + p + 1)] - U[static_cast<std::size_t>(i + 1)];
  if (d1 > 0) r += (u - U[static_cast<std::size_t>(i)]) / d1 * basis(U, i, p - 1, u);
  if (d2 > 0) r += (U[static_cast<std::size_t>(i + p + 1)] - u) / d2 * basis(U, i + 1, p - 1, u);
  return r;
}

Vec2 nurbs(const std::vector<double>& U, const std::vector<Vec2>& P, const std::vector<double>& W, int p, double u) {
  double x = 0, y = 0, w = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const double n = basis(U, static_cast<int>(i), p, u) * (W.empty() ? 1.0 : W[i]);
    x += n * P[i].x;
    y += n * P[i].y;
    w += n;
  }
  return {x / w, y / w};
}

TEST(DxfCurves, RationalQuarterCircleSplineIsExactArcs) {
  const double r = 25;
  const std::vector<double> U{0, 0, 0, 1, 1, 1};
  const std::vector<Vec2> P{{r, 0}, {r, r}, {0, r}};
  const std::vector<double> W{1, std::sqrt(0.5), 1};
  DxfBuilder b;
  b.spline(2, U, P, W, 8 | 4);
  const auto e = read_one(b.str());
  EXPECT_EQ(e.type, "SPLINE");
  EXPECT_NEAR(path_length(e.path), kPi * r / 2, 1e-6);
  for (const Vec2& q : sample(e.path, 16)) EXPECT_NEAR(std::hypot(q.x, q.y), r, 1e-6);
  EXPECT_EQ(e.path.vertices.front().p, (Vec2{r, 0}));
  EXPECT_LE(e.path.vertices.size(), 5u);  // a circle is fitted by arcs of itself
}

TEST(DxfCurves, ClosedRationalCircleSpline) {
  const double r = 10, w = std::sqrt(0.5);
  const std::vector<double> U{0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
  const std::vector<Vec2> P{{r, 0}, {r, r}, {0, r}, {-r, r}, {-r, 0}, {-r, -r}, {0, -r}, {r, -r}, {r, 0}};
  const std::vector<double> W{1, w, 1, w, 1, w, 1, w, 1};
  DxfBuilder b;
  b.spline(2, U, P, W, 1 | 4 | 8);
  const auto e = read_one(b.str());
  EXPECT_TRUE(e.path.closed);
  EXPECT_NEAR(path_length(e.path), 2 * kPi * r, 1e-6);
  EXPECT_NEAR(path_area(e.path), kPi * r * r, 1e-6);
}

TEST(DxfCurves, CubicBezierWithinTolerance) {
  const std::vector<double> U{0, 0, 0, 0, 1, 1, 1, 1};
  const std::vector<Vec2> P{{0, 0}, {10, 30}, {40, -20}, {50, 10}};
  DxfBuilder b;
  b.spline(3, U, P, {}, 8);
  auto f = [&](double t) {
    const double s = 1 - t;
    return Vec2{s * s * s * P[0].x + 3 * s * s * t * P[1].x + 3 * s * t * t * P[2].x + t * t * t * P[3].x,
                s * s * s * P[0].y + 3 * s * s * t * P[1].y + 3 * s * t * t * P[2].y + t * t * t * P[3].y};
  };
  const auto coarse = read_one(b.str(), kTol);
  EXPECT_LE(deviation(coarse.path, f, 0, 1), kTol);
  EXPECT_EQ(coarse.path.vertices.front().p, P.front());
  EXPECT_EQ(coarse.path.vertices.back().p, P.back());
  const auto fine = read_one(b.str(), 0.001);
  EXPECT_LE(deviation(fine.path, f, 0, 1), 0.001);
  EXPECT_GT(fine.path.vertices.size(), coarse.path.vertices.size());
  // Arcs, not a polyline: far fewer segments than chords would need (~sqrt(L / 8 tol) per bend).
  EXPECT_LT(coarse.path.vertices.size(), 40u);
}

TEST(DxfCurves, ClampedSplineWithInteriorKnots) {
  const std::vector<double> U{0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1};
  const std::vector<Vec2> P{{0, 0}, {20, 40}, {60, 45}, {80, 0}, {120, -30}, {150, 10}};
  DxfBuilder b;
  b.spline(3, U, P, {}, 8);
  const auto e = read_one(b.str());
  EXPECT_LE(deviation(e.path, [&](double u) { return nurbs(U, P, {}, 3, u); }, 0, 1), kTol);
}

TEST(DxfCurves, KnotOfFullMultiplicityKeepsTheCorner) {
  // Two Bézier pieces meeting at (50, 0) with different tangents (interior knot of multiplicity 3).
  const std::vector<double> U{0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2};
  const std::vector<Vec2> P{{0, 0}, {10, 20}, {40, 20}, {50, 0}, {60, 30}, {90, 30}, {100, 0}};
  DxfBuilder b;
  b.spline(3, U, P, {}, 8);
  const auto e = read_one(b.str());
  bool corner = false;
  for (const auto& v : e.path.vertices) corner = corner || dist(v.p, {50, 0}) < 1e-9;
  EXPECT_TRUE(corner);
  EXPECT_LE(deviation(e.path, [&](double u) { return nurbs(U, P, {}, 3, u); }, 0, 2), kTol);
}

TEST(DxfCurves, PeriodicSplineStoredWithoutWrappedPointsIsClosed) {
  // Uniform knots, 6 control points on a hexagon: the closed curve needs the first 3 control
  // points repeated at the end, which some writers leave out.
  std::vector<Vec2> P;
  for (int i = 0; i < 6; ++i) P.push_back({30 * std::cos(i * kPi / 3), 30 * std::sin(i * kPi / 3)});
  std::vector<double> U;
  for (int i = 0; i < 10; ++i) U.push_back(i);
  DxfBuilder b;
  b.spline(3, U, P, {}, 1 | 2 | 8);
  const auto e = read_one(b.str());
  EXPECT_TRUE(e.path.closed);
  std::vector<Vec2> Pw = P;
  for (int i = 0; i < 3; ++i) Pw.push_back(P[static_cast<std::size_t>(i)]);
  std::vector<double> Uw;
  for (int i = 0; i < 13; ++i) Uw.push_back(i);
  EXPECT_LE(deviation(e.path, [&](double u) { return nurbs(Uw, Pw, {}, 3, u); }, 3, 9), kTol);
}

TEST(DxfCurves, FitPointSplinePassesThroughItsPoints) {
  std::vector<Vec2> fit;
  for (int i = 0; i <= 8; ++i) fit.push_back({i * 10.0, 15 * std::sin(i * 0.7)});
  DxfBuilder b;
  b.spline_fit(fit, 8);
  // Its end tangents are not in the file: natural ends are taken, and said.
  const auto e = read_one(b.str(), kTol, "dxf.spline_fit_ends");
  EXPECT_FALSE(e.path.closed);
  const auto pts = sample(e.path, 200);
  for (const Vec2& f : fit) {
    double best = 1e9;
    for (const Vec2& q : pts) best = std::min(best, dist(q, f));
    EXPECT_LT(best, kTol) << f.x;
  }
  EXPECT_EQ(e.path.vertices.front().p, fit.front());
  EXPECT_EQ(e.path.vertices.back().p, fit.back());
}

// The curve through a block's fit points is the block's: a non-uniformly scaled INSERT scales that
// curve. Fitting the scaled points instead (chord lengths in other ratios) drew a curve 0.65 mm off
// under a 3 x 0.5 scale. Truth: the natural cubic through the points, chord-length parametrised,
// solved here by dense elimination, then mapped by the INSERT.
TEST(DxfCurves, FitPointSplineInANonUniformInsertIsTheBlocksCurveScaled) {
  const std::vector<Vec2> fit{{0, 0}, {10, 12}, {25, 3}, {32, 18}, {50, 10}, {60, 25}};
  DxfBuilder b;
  b.begin_block("S").spline_fit(fit, 8).end_block();
  b.insert("S", {100, 50}, 3, 0.5, 20);
  const auto e = read_one(b.str(), kTol, "dxf.spline_fit_ends");
  const std::size_t n = fit.size();
  std::vector<double> h(n - 1), t(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) t[i + 1] = t[i] + (h[i] = dist(fit[i], fit[i + 1]));
  // Second derivatives: M_0 = M_{n-1} = 0, h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} = 6 (slope_i - slope_{i-1}).
  std::vector<std::vector<double>> A(n, std::vector<double>(n + 2, 0.0));  // [A | rhs x | rhs y]
  A[0][0] = A[n - 1][n - 1] = 1;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    A[i][i - 1] = h[i - 1], A[i][i] = 2 * (h[i - 1] + h[i]), A[i][i + 1] = h[i];
    A[i][n] = 6 * ((fit[i + 1].x - fit[i].x) / h[i] - (fit[i].x - fit[i - 1].x) / h[i - 1]);
    A[i][n + 1] = 6 * ((fit[i + 1].y - fit[i].y) / h[i] - (fit[i].y - fit[i - 1].y) / h[i - 1]);
  }
  for (std::size_t c = 0; c < n; ++c)
    for (std::size_t r = 0; r < n; ++r)
      if (r != c && A[r][c] != 0) {
        const double f = A[r][c] / A[c][c];
        for (std::size_t k = 0; k < n + 2; ++k) A[r][k] -= f * A[c][k];
      }
  const double rot = 20 * kPi / 180;
  auto f = [&](double u) {
    std::size_t i = 0;
    while (i + 2 < n && u > t[i + 1]) ++i;
    const double a = t[i + 1] - u, bb = u - t[i], hh = h[i];
    auto coord = [&](double y0, double y1, std::size_t k) {
      const double m0 = A[i][k] / A[i][i], m1 = A[i + 1][k] / A[i + 1][i + 1];
      return m0 * a * a * a / (6 * hh) + m1 * bb * bb * bb / (6 * hh) + (y0 / hh - m0 * hh / 6) * a +
             (y1 / hh - m1 * hh / 6) * bb;
    };
    const Vec2 q{3 * coord(fit[i].x, fit[i + 1].x, n), 0.5 * coord(fit[i].y, fit[i + 1].y, n + 1)};
    return Vec2{100 + q.x * std::cos(rot) - q.y * std::sin(rot), 50 + q.x * std::sin(rot) + q.y * std::cos(rot)};
  };
  EXPECT_LE(deviation(e.path, f, 0, t.back()), kTol);
}

TEST(DxfCurves, DegreeOneSplineIsItsControlPolygon) {
  const std::vector<Vec2> P{{0, 0}, {10, 0}, {10, 10}, {20, 15}};
  DxfBuilder b;
  b.spline(1, {0, 0, 1, 2, 3, 3}, P, {}, 8);
  const auto e = read_one(b.str());
  ASSERT_EQ(e.path.vertices.size(), P.size());
  for (std::size_t i = 0; i < P.size(); ++i) {
    EXPECT_NEAR(dist(e.path.vertices[i].p, P[i]), 0, 1e-12);
    EXPECT_EQ(e.path.vertices[i].bulge, 0.0);
  }
}

Vec2 ellipse_point(Vec2 c, Vec2 major, double ratio, double ez, double t) {
  const Vec2 minor = ez > 0 ? Vec2{-major.y * ratio, major.x * ratio} : Vec2{major.y * ratio, -major.x * ratio};
  return {c.x + major.x * std::cos(t) + minor.x * std::sin(t), c.y + major.y * std::cos(t) + minor.y * std::sin(t)};
}

double numeric_length(const std::function<Vec2(double)>& f, double t0, double t1) {
  double l = 0;
  const int n = 100000;
  for (int k = 0; k < n; ++k) l += dist(f(t0 + (t1 - t0) * k / n), f(t0 + (t1 - t0) * (k + 1) / n));
  return l;
}

TEST(DxfCurves, FullRotatedEllipse) {
  const Vec2 c{100, -40}, major{30 * std::cos(0.4), 30 * std::sin(0.4)};
  DxfBuilder b;
  b.ellipse(c, major, 0.4, 0, 2 * kPi);
  const auto e = read_one(b.str());
  EXPECT_TRUE(e.path.closed);
  auto f = [&](double t) { return ellipse_point(c, major, 0.4, 1, t); };
  EXPECT_LE(deviation(e.path, f, 0, 2 * kPi), kTol);
  // Biarcs are tangent-continuous and cross the curve within each piece, so their length error
  // is second order in the 0.01 mm deviation: a few 1e-5 relative (measured 1.2e-5 here).
  const double exact = numeric_length(f, 0, 2 * kPi);
  EXPECT_NEAR(path_length(e.path), exact, 5e-5 * exact);
  EXPECT_NEAR(path_area(e.path), kPi * 30 * 12, kTol * numeric_length(f, 0, 2 * kPi));
  EXPECT_GT(path_area(e.path), 0);
}

TEST(DxfCurves, PartialEllipseUsesParametersNotAngles) {
  // With ratio 0.25 the parameter 1.0 rad is at polar angle atan(0.25 tan 1) = 0.37 rad.
  const Vec2 c{0, 0}, major{40, 0};
  DxfBuilder b;
  b.ellipse(c, major, 0.25, 1.0, 2.5);
  const auto e = read_one(b.str());
  EXPECT_FALSE(e.path.closed);
  EXPECT_NEAR(dist(e.path.vertices.front().p, ellipse_point(c, major, 0.25, 1, 1.0)), 0, 1e-9);
  EXPECT_NEAR(dist(e.path.vertices.back().p, ellipse_point(c, major, 0.25, 1, 2.5)), 0, 1e-9);
  EXPECT_LE(deviation(e.path, [&](double t) { return ellipse_point(c, major, 0.25, 1, t); }, 1.0, 2.5), kTol);
}

TEST(DxfCurves, EllipseParametersCountModuloAFullTurn) {
  // 0.5 .. 0.5 + 2π + 1 is the arc over 0.5 .. 1.5, not the full ellipse; 0 .. 4π is the full one.
  const Vec2 c{0, 0}, major{50, 0};
  DxfBuilder b;
  b.ellipse(c, major, 0.5, 0.5, 0.5 + 2 * kPi + 1);
  const auto e = read_one(b.str());
  EXPECT_FALSE(e.path.closed);
  EXPECT_NEAR(dist(e.path.vertices.front().p, ellipse_point(c, major, 0.5, 1, 0.5)), 0, 1e-9);
  EXPECT_NEAR(dist(e.path.vertices.back().p, ellipse_point(c, major, 0.5, 1, 1.5)), 0, 1e-9);
  EXPECT_LE(deviation(e.path, [&](double t) { return ellipse_point(c, major, 0.5, 1, t); }, 0.5, 1.5), kTol);
  DxfBuilder f;
  f.ellipse(c, major, 0.5, 0, 4 * kPi);
  EXPECT_TRUE(read_one(f.str()).path.closed);
}

TEST(DxfCurves, EllipseWithExtrusionMinusZRunsClockwise) {
  const Vec2 c{10, 10}, major{20, 5};
  DxfBuilder b;
  b.ellipse(c, major, 0.5, 0.3, 2.0, "0", -1).ellipse(c, major, 0.5, 0, 2 * kPi, "0", -1);
  auto r = io::read_dxf_string(b.str(), "e.dxf", {});
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->entities.size(), 2u);
  const auto& part = r->entities[0].path;
  EXPECT_NEAR(dist(part.vertices.front().p, ellipse_point(c, major, 0.5, -1, 0.3)), 0, 1e-9);
  EXPECT_NEAR(dist(part.vertices.back().p, ellipse_point(c, major, 0.5, -1, 2.0)), 0, 1e-9);
  EXPECT_LE(deviation(part, [&](double t) { return ellipse_point(c, major, 0.5, -1, t); }, 0.3, 2.0), kTol);
  EXPECT_LT(path_area(r->entities[1].path), 0);  // clockwise
  EXPECT_NEAR(path_area(r->entities[1].path), -kPi * std::hypot(20, 5) * std::hypot(20, 5) * 0.5, 1.0);
}

TEST(DxfCurves, EllipseInsideAMirroredNonUniformInsert) {
  const Vec2 major{10, 0};
  DxfBuilder b;
  b.begin_block("E").ellipse({0, 0}, major, 0.5, 0, 2 * kPi).end_block();
  b.insert("E", {100, 100}, -2, 3, 30);
  const auto e = read_one(b.str());
  const double r = 30 * kPi / 180;
  auto f = [&](double t) {
    const Vec2 q = ellipse_point({0, 0}, major, 0.5, 1, t);
    const Vec2 s{-2 * q.x, 3 * q.y};
    return Vec2{100 + s.x * std::cos(r) - s.y * std::sin(r), 100 + s.x * std::sin(r) + s.y * std::cos(r)};
  };
  EXPECT_TRUE(e.path.closed);
  EXPECT_LE(deviation(e.path, f, 0, 2 * kPi), kTol);
  EXPECT_LT(path_area(e.path), 0);  // mirrored
}

TEST(DxfCurves, SplineInInchesIsFittedInMillimetres) {
  // The tolerance is in mm: an inch drawing must not get 25.4 times coarser arcs.
  const std::vector<double> U{0, 0, 0, 0, 1, 1, 1, 1};
  const std::vector<Vec2> P{{0, 0}, {1, 3}, {4, -2}, {5, 1}};
  DxfBuilder b;
  b.insunits(1).spline(3, U, P, {}, 8);
  const auto e = read_one(b.str());
  auto f = [&](double t) {
    const double s = 1 - t;
    return Vec2{25.4 * (3 * s * s * t * P[1].x + 3 * s * t * t * P[2].x + t * t * t * P[3].x),
                25.4 * (3 * s * s * t * P[1].y + 3 * s * t * t * P[2].y + t * t * t * P[3].y)};
  };
  EXPECT_LE(deviation(e.path, f, 0, 1), kTol);
}

TEST(DxfCurves, ClosedFitPointSplineIsPeriodic) {
  std::vector<Vec2> fit;
  for (int i = 0; i < 12; ++i) fit.push_back({40 * std::cos(i * kPi / 6), 25 * std::sin(i * kPi / 6)});
  DxfBuilder b;
  b.spline_fit(fit, 1 | 8);
  const auto e = read_one(b.str());
  EXPECT_TRUE(e.path.closed);
  const auto pts = sample(e.path, 100);
  for (const Vec2& f : fit) {
    double best = 1e9;
    for (const Vec2& q : pts) best = std::min(best, dist(q, f));
    EXPECT_LT(best, kTol);
  }
  // A smooth closed curve near the ellipse through the points (no kink where it closes): the
  // area is within 1% of the ellipse's.
  EXPECT_NEAR(path_area(e.path), kPi * 40 * 25, 0.01 * kPi * 40 * 25);
}

}  // namespace
}  // namespace cutroute::test
