// Point-in-contour with arcs: exact cases near arc bulges, and agreement with a fine polygon.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/geometry/contour.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/shapes.hpp>

namespace cutroute::geometry {
namespace {

constexpr double kPi = std::numbers::pi;

// Independent truth: classic crossing-number test on a finely flattened copy, used only for
// points that are clearly farther from the boundary than the flattening error.
int polygon_winding(const std::vector<Vec2>& poly, Vec2 p) {
  int w = 0;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % n];
    const double s = cross(b - a, p - a);
    if (a.y <= p.y) {
      if (b.y > p.y && s > 0) ++w;
    } else if (b.y <= p.y && s < 0) {
      --w;
    }
  }
  return w;
}

TEST(Winding, CircleFromTwoHalfArcs) {
  const Contour ccw = circle({0, 0}, 1), cw = circle({0, 0}, 1, false);
  EXPECT_EQ(winding_number(ccw, {0, 0}), 1);  // on the (degenerate) chord polygon
  EXPECT_EQ(winding_number(cw, {0, 0}), -1);
  EXPECT_EQ(winding_number(ccw, {0.999, 0}), 1);
  EXPECT_EQ(winding_number(ccw, {-0.999, 0}), 1);
  EXPECT_EQ(winding_number(ccw, {1.001, 0}), 0);
  EXPECT_EQ(winding_number(ccw, {0, 0.999}), 1);
  EXPECT_EQ(winding_number(ccw, {0, -0.999}), 1);
  EXPECT_EQ(winding_number(ccw, {0, 1.001}), 0);
  EXPECT_EQ(locate(ccw, {0, 1}, 1e-9), Location::on_boundary);
  EXPECT_EQ(locate(ccw, {std::cos(1.0), std::sin(1.0)}, 1e-9), Location::on_boundary);
  EXPECT_EQ(locate(ccw, {0.5, 0.5}, 1e-9), Location::inside);
  EXPECT_EQ(locate(ccw, {0.8, 0.8}, 1e-9), Location::outside);
}

TEST(Winding, PointsInsideArcBulgesOutsideChordPolygon) {
  // Stadium 10 x 4 with half circles r = 2 at both ends.
  const Contour stadium{{{{0, 0}, 0}, {{10, 0}, 1}, {{10, 4}, 0}, {{0, 4}, 1}}, true};
  EXPECT_EQ(locate(stadium, {11.99, 2}, 1e-9), Location::inside);
  EXPECT_EQ(locate(stadium, {12.01, 2}, 1e-9), Location::outside);
  EXPECT_EQ(locate(stadium, {-1.99, 2}, 1e-9), Location::inside);
  EXPECT_EQ(locate(stadium, {-2.01, 2}, 1e-9), Location::outside);
  EXPECT_EQ(locate(stadium, {10 + 2 * std::cos(0.3) - 1e-7, 2 + 2 * std::sin(0.3)}, 1e-9), Location::inside);
  EXPECT_EQ(locate(stadium, {10 + 2 * std::cos(0.3) + 1e-7, 2 + 2 * std::sin(0.3)}, 1e-9), Location::outside);
  EXPECT_EQ(locate(stadium, {12, 2}, 1e-9), Location::on_boundary);
  EXPECT_EQ(locate(stadium, {10, -0.5}, 1e-9), Location::outside);  // on the chord line, past the chord
  EXPECT_EQ(locate(stadium, {10, 2}, 1e-9), Location::inside);   // on the chord itself
  // Inward arc: the dent of a square is outside.
  const Contour dented{{{{0, 0}, 0}, {{4, 0}, 0}, {{4, 4}, -1}, {{0, 4}, 0}}, true};
  EXPECT_EQ(locate(dented, {2, 3}, 1e-9), Location::outside);
  EXPECT_EQ(locate(dented, {2, 1.9}, 1e-9), Location::inside);
  EXPECT_EQ(locate(dented, {0.1, 3.9}, 1e-9), Location::outside);  // the dent reaches the corner
  EXPECT_EQ(locate(dented, {3.9, 0.5}, 1e-9), Location::inside);
  EXPECT_EQ(locate(dented, {2, 2}, 1e-9), Location::on_boundary);
}

TEST(Winding, MajorArcAndPacMan) {
  const double r = 3, c45 = r * std::cos(kPi / 4);
  const Contour pac{{{{0, 0}, 0}, {{c45, c45}, std::tan(1.5 * kPi / 4)}, {{c45, -c45}, 0}}, true};
  EXPECT_EQ(locate(pac, {-2.99, 0}, 1e-9), Location::inside);
  EXPECT_EQ(locate(pac, {0, 2.99}, 1e-9), Location::inside);
  EXPECT_EQ(locate(pac, {1.0, 0}, 1e-9), Location::outside);  // in the mouth
  EXPECT_EQ(locate(pac, {-1.0, 0.01}, 1e-9), Location::inside);
  EXPECT_EQ(locate(pac, {-3.01, 0}, 1e-9), Location::outside);
}

TEST(Winding, NearlyStraightArcKeepsItsBulge) {
  // Chord 1000 mm, bulge 1e-6: sagitta 5e-4 mm. Points between chord and arc are inside.
  const double d = 1000, beta = 1e-6, sag = d * beta / 2;
  const Contour c{{{{0, 0}, beta}, {{d, 0}, 0}, {{d, 10}, 0}, {{0, 10}, 0}}, true};
  EXPECT_EQ(locate(c, {d / 2, -sag * 0.5}, 1e-9), Location::inside);
  EXPECT_EQ(locate(c, {d / 2, -sag * 1.5}, 1e-9), Location::outside);
}

TEST(Winding, AgreesWithFinePolygonOnRandomPoints) {
  // A contour with minor, major, cw and ccw arcs.
  const Contour shapes[] = {
      Contour{{{{0, 0}, 0.4}, {{10, 0}, -0.3}, {{10, 8}, 1.8}, {{4, 6}, 0}, {{0, 8}, -0.7}}, true},
      circle({5, 5}, 4, false),
      Contour{{{{0, 0}, 0}, {{4, 0}, 0}, {{4, 4}, -1}, {{0, 4}, 0}}, true},
  };
  Rng rng(42);
  int checked = 0;
  for (const Contour& c : shapes) {
    const std::vector<Vec2> poly = flatten(c, 1e-5);
    const Box box = bounding_box(c).inflated(2);
    for (int i = 0; i < 4000; ++i) {
      const Vec2 p{box.xmin + rng.uniform01() * box.width(), box.ymin + rng.uniform01() * box.height()};
      if (distance(c, p) < 1e-3) continue;
      ASSERT_EQ(winding_number(c, p), polygon_winding(poly, p)) << p.x << "," << p.y;
      ++checked;
    }
    // Same along the chord lines and through vertices' y, where ties are most likely.
    for (const Vertex& v : c.vertices) {
      for (double dx = -12; dx <= 12; dx += 0.37) {
        const Vec2 p{v.p.x + dx, v.p.y};
        if (distance(c, p) < 1e-3) continue;
        ASSERT_EQ(winding_number(c, p), polygon_winding(poly, p)) << p.x << "," << p.y;
      }
    }
  }
  EXPECT_GT(checked, 10000);
}

TEST(Winding, SegmentSetAgreesWithContourVersions) {
  std::vector<Vec2> pts;
  Rng rng(11);
  for (int i = 0; i < 500; ++i) {
    const double a = 2 * kPi * i / 500, r = 8 + 2 * rng.uniform01();
    pts.push_back({r * std::cos(a), r * std::sin(a)});
  }
  Contour gear = polygon(pts);
  for (std::size_t i = 0; i < gear.vertices.size(); i += 3) gear.vertices[i].bulge = rng.uniform01() - 0.5;
  const Contour shapes[] = {gear, circle({1, 2}, 3), Contour{{{{0, 0}, 0}, {{4, 0}, 0}, {{4, 4}, -1}, {{0, 4}, 0}}, true}};
  for (const Contour& c : shapes) {
    const SegmentSet set = make_segment_set(c);
    const Box box = bounding_box(c).inflated(1);
    for (int i = 0; i < 3000; ++i) {
      const Vec2 p{box.xmin + rng.uniform01() * box.width(), box.ymin + rng.uniform01() * box.height()};
      ASSERT_EQ(winding_number(set, p), winding_number(c, p));
      ASSERT_EQ(locate(set, p, 0.01), locate(c, p, 0.01));
    }
    for (const Vertex& v : c.vertices) ASSERT_EQ(locate(set, v.p, 1e-9), Location::on_boundary);
    const Contour other = circle({0.5, 0.5}, 9);
    EXPECT_EQ(count_close_segment_pairs(set, make_segment_set(other), 1e-6, 1000),
              count_close_segment_pairs(c, other, 1e-6, 1000));
  }
}

// A path set (no index) counts close pairs as an indexed set and as the contour version do, on
// either side and against another path set, with and without a limit: random open paths of 1-4
// lines and arcs thrown over a 500-segment gear, a circle and a rectangle with an arc.
TEST(Winding, PathSetsCountCloseSegmentPairsLikeIndexedSets) {
  Rng rng(23);
  std::vector<Vec2> pts;
  for (int i = 0; i < 500; ++i) {
    const double a = 2 * kPi * i / 500, r = 8 + 2 * rng.uniform01();
    pts.push_back({r * std::cos(a), r * std::sin(a)});
  }
  const Contour shapes[] = {polygon(pts), circle({1, 2}, 3), Contour{{{{0, 0}, 0}, {{4, 0}, 0}, {{4, 4}, -1}, {{0, 4}, 0}}, true}};
  int touching = 0;
  for (const Contour& c : shapes) {
    const SegmentSet indexed = make_segment_set(c), unindexed = make_path_set(c);
    for (int trial = 0; trial < 400; ++trial) {
      Contour path;
      Vec2 at{-11 + 22 * rng.uniform01(), -11 + 22 * rng.uniform01()};
      const int n = 1 + static_cast<int>(rng.below(4));
      for (int k = 0; k <= n; ++k) {
        path.vertices.push_back({at, rng.chance(0.4) ? 2 * rng.uniform01() - 1 : 0.0});
        at = at + Vec2{-3 + 6 * rng.uniform01(), -3 + 6 * rng.uniform01()};
      }
      const SegmentSet path_set = make_path_set(path), path_indexed = make_segment_set(path);
      for (const std::size_t limit : {std::size_t{1}, std::size_t{1000}}) {
        const std::size_t truth = count_close_segment_pairs(path, c, 0.05, limit);
        touching += truth > 0 && limit == 1;
        ASSERT_EQ(count_close_segment_pairs(path_set, indexed, 0.05, limit), truth) << trial;
        ASSERT_EQ(count_close_segment_pairs(indexed, path_set, 0.05, limit), truth) << trial;
        ASSERT_EQ(count_close_segment_pairs(path_set, unindexed, 0.05, limit), truth) << trial;
        ASSERT_EQ(count_close_segment_pairs(path_indexed, indexed, 0.05, limit), truth) << trial;
      }
    }
  }
  EXPECT_GT(touching, 100);  // both outcomes are exercised (254 of 1 200)
  EXPECT_LT(touching, 1100);
}

TEST(Winding, TransformsMovePointsWithTheContour) {
  const Contour c{{{{0, 0}, 0.4}, {{10, 0}, -0.3}, {{10, 8}, 1.8}, {{4, 6}, 0}, {{0, 8}, -0.7}}, true};
  const Contour before = c;
  const Vec2 shift{-313.25, 77.5};
  const Contour moved = translated(c, shift), turned = rotated_about(c, {0, 0}, kPi), back = reversed(c);
  Rng rng(3);
  const Box box = bounding_box(c).inflated(1);
  for (int i = 0; i < 3000; ++i) {
    const Vec2 p{box.xmin + rng.uniform01() * box.width(), box.ymin + rng.uniform01() * box.height()};
    if (distance(c, p) < 1e-6) continue;
    const int w = winding_number(c, p);
    ASSERT_EQ(winding_number(moved, p + shift), w);
    ASSERT_EQ(winding_number(turned, -p), w);
    ASSERT_EQ(winding_number(back, p), -w);
    ASSERT_EQ(locate(moved, p + shift, 1e-9), locate(c, p, 1e-9));
  }
  EXPECT_EQ(c, before);
}

TEST(Winding, OpenContourHasNoInside) {
  const Contour open{{{{0, 0}, 0}, {{4, 0}, 0}, {{4, 4}, 0}}, false};
  EXPECT_EQ(winding_number(open, {3, 1}), 0);
}

}  // namespace
}  // namespace cutroute::geometry
