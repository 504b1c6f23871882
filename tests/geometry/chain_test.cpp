// chain_contours(): shuffled and reversed pieces reproduce the polygons; drops and leftovers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/geometry/chain.hpp>
#include <cutroute/geometry/shapes.hpp>

namespace cutroute::geometry {
namespace {

constexpr double kPi = std::numbers::pi;

ChainPiece line(Vec2 a, Vec2 b, std::int32_t source = -1) { return {Contour{{{a, 0}, {b, 0}}, false}, source, 0}; }

// A star-shaped polygon of n edges around c (radius varies, so every polygon is different).
std::vector<Vec2> star(Rng& rng, Vec2 c, int n) {
  std::vector<Vec2> pts;
  for (int i = 0; i < n; ++i) {
    const double ang = 2 * kPi * i / n, r = 3 + 2 * rng.uniform01();
    pts.push_back(c + Vec2{std::cos(ang), std::sin(ang)} * r);
  }
  return pts;
}

TEST(Chain, ShuffledReversedLinesReproducePolygons) {
  Rng rng(2024);
  const int polys = 60, edges = 25;
  std::vector<std::vector<Vec2>> originals;
  std::vector<ChainPiece> pieces;
  for (int p = 0; p < polys; ++p) {
    originals.push_back(star(rng, {12.0 * (p % 10), 12.0 * (p / 10)}, edges));
    const auto& pts = originals.back();
    for (int i = 0; i < edges; ++i) {
      ChainPiece piece = line(pts[i], pts[(i + 1) % edges], p * edges + i);
      if (rng.chance(0.5)) piece.path = reversed(piece.path);
      pieces.push_back(piece);
    }
  }
  rng.shuffle(pieces.begin(), pieces.end());
  const std::vector<ChainPiece> before = pieces;
  const ChainResult r = chain_contours(pieces, 0.01);
  ASSERT_EQ(r.closed.size(), static_cast<std::size_t>(polys));
  EXPECT_TRUE(r.open.empty());
  EXPECT_EQ(r.dropped_duplicates, 0u);
  EXPECT_EQ(r.dropped_zero_length, 0u);
  for (std::size_t i = 0; i < pieces.size(); ++i) ASSERT_EQ(pieces[i].path, before[i].path) << "input modified";
  std::vector<int> seen(polys, 0);
  for (const ChainedContour& c : r.closed) {
    ASSERT_EQ(c.sources.size(), static_cast<std::size_t>(edges));
    const int p = c.sources.front() / edges;
    ++seen[p];
    for (std::int32_t s : c.sources) EXPECT_EQ(s / edges, p) << "pieces of two polygons mixed";
    const Contour truth = polygon(originals[p]);
    EXPECT_NEAR(std::abs(signed_area(c.contour)), signed_area(truth), 1e-9);
    EXPECT_NEAR(length(c.contour), length(truth), 1e-9);
    ASSERT_EQ(c.contour.vertices.size(), static_cast<std::size_t>(edges));
    for (const Vertex& v : c.contour.vertices) {
      EXPECT_NE(std::find(originals[p].begin(), originals[p].end(), v.p), originals[p].end());
    }
  }
  for (int p = 0; p < polys; ++p) EXPECT_EQ(seen[p], 1);
  // Same input, same output (determinism).
  const ChainResult again = chain_contours(pieces, 0.01);
  ASSERT_EQ(again.closed.size(), r.closed.size());
  for (std::size_t i = 0; i < r.closed.size(); ++i) EXPECT_EQ(again.closed[i].contour, r.closed[i].contour);
}

TEST(Chain, CircleAsTwoHalfArcsInAnyDirection) {
  const double r = 5;
  ChainPiece top{Contour{{{{r, 0}, 1}, {{-r, 0}, 0}}, false}, 1, 0};
  ChainPiece bottom{Contour{{{{-r, 0}, 1}, {{r, 0}, 0}}, false}, 2, 0};
  for (bool flip : {false, true}) {
    std::vector<ChainPiece> pieces{bottom, top};
    if (flip) pieces[0].path = reversed(pieces[0].path);
    const ChainResult res = chain_contours(pieces, 0.01);
    ASSERT_EQ(res.closed.size(), 1u);
    const Contour& c = res.closed[0].contour;
    EXPECT_TRUE(c.closed);
    EXPECT_EQ(c.vertices.size(), 2u);
    EXPECT_NEAR(std::abs(signed_area(c)), kPi * r * r, 1e-9);
    EXPECT_NEAR(length(c), 2 * kPi * r, 1e-9);
  }
}

TEST(Chain, RoundedRectanglesFromShuffledLinesAndArcs) {
  // 30 rounded rectangles (w x h, corner radius r), each as 4 LINEs and 4 quarter ARCs, all
  // shuffled and half reversed: area w·h - (4 - π) r² and length 2(w + h) - (8 - 2π) r exactly.
  Rng rng(8);
  const double w = 20, h = 12, r = 3, q = std::tan(kPi / 8);
  std::vector<ChainPiece> pieces;
  for (int k = 0; k < 30; ++k) {
    const Vec2 o{40.0 * (k % 6), 30.0 * (k / 6)};
    const Vec2 p[8] = {o + Vec2{r, 0},     o + Vec2{w - r, 0}, o + Vec2{w, r},     o + Vec2{w, h - r},
                       o + Vec2{w - r, h}, o + Vec2{r, h},     o + Vec2{0, h - r}, o + Vec2{0, r}};
    for (int i = 0; i < 8; ++i) {
      ChainPiece piece{Contour{{{p[i], i % 2 == 1 ? q : 0.0}, {p[(i + 1) % 8], 0.0}}, false}, k * 8 + i, 0};
      if (rng.chance(0.5)) piece.path = reversed(piece.path);
      pieces.push_back(piece);
    }
  }
  rng.shuffle(pieces.begin(), pieces.end());
  const ChainResult res = chain_contours(pieces, 0.01);
  ASSERT_EQ(res.closed.size(), 30u);
  EXPECT_TRUE(res.open.empty());
  for (const ChainedContour& c : res.closed) {
    EXPECT_NEAR(std::abs(signed_area(c.contour)), w * h - (4 - kPi) * r * r, 1e-9);
    EXPECT_NEAR(length(c.contour), 2 * (w + h) - (8 - 2 * kPi) * r, 1e-9);
    EXPECT_EQ(c.contour.vertices.size(), 8u);
  }
}

TEST(Chain, GapsWithinSnapCloseExactlyAtMidpoints) {
  const double g = 0.004;  // each corner misses by g in x: inside the 0.01 snap
  std::vector<ChainPiece> pieces{line({0, 0}, {10, 0}), line({10 + g, 0}, {10, 10}), line({10, 10}, {0, 10}),
                                 line({0, 10}, {g, 0})};
  const ChainResult r = chain_contours(pieces, 0.01);
  ASSERT_EQ(r.closed.size(), 1u);
  const Contour& c = r.closed[0].contour;
  ASSERT_EQ(c.vertices.size(), 4u);
  // Joints moved to the midpoints; the contour closes exactly (no gap left anywhere).
  EXPECT_EQ(c.vertices[0].p, (Vec2{0, 0} + Vec2{g, 0}) * 0.5);
  EXPECT_EQ(c.vertices[1].p, (Vec2{10, 0} + Vec2{10 + g, 0}) * 0.5);
  EXPECT_EQ(c.vertices[2].p, (Vec2{10, 10}));
  // With a snap below the gap, nothing closes: one open chain through the two exact corners.
  const ChainResult tight = chain_contours(pieces, 0.001);
  EXPECT_TRUE(tight.closed.empty());
  ASSERT_EQ(tight.open.size(), 2u);
}

TEST(Chain, GapsBeyondTheSnapCloseInASecondPassAndAreListed) {
  // A square whose corners (10,0) and (0,0) miss by 0.03 and 0.02 mm, and two strokes 0.2 mm apart.
  std::vector<ChainPiece> pieces{line({0, 0}, {10, 0}, 0), line({10.03, 0}, {10, 10}, 1), line({10, 10}, {0, 10}, 2),
                                 line({0, 10}, {0, 0.02}, 3), line({50, 0}, {60, 0}, 4), line({60.2, 0}, {70, 0}, 5)};
  const ChainResult off = chain_contours(pieces, 0.01);
  EXPECT_TRUE(off.closed.empty());
  EXPECT_EQ(off.open.size(), 4u);
  EXPECT_TRUE(off.gaps_closed.empty());

  const ChainResult r = chain_contours(pieces, 0.01, 0.05);
  ASSERT_EQ(r.closed.size(), 1u);
  const ChainedContour& sq = r.closed[0];
  EXPECT_TRUE(sq.contour.closed);
  std::vector<std::int32_t> sources = sq.sources;
  std::sort(sources.begin(), sources.end());
  EXPECT_EQ(sources, (std::vector<std::int32_t>{0, 1, 2, 3}));
  // The corners at the midpoints of the gaps' ends; the exact corners where they were.
  std::vector<Vec2> corners;
  for (const Vertex& v : sq.contour.vertices) corners.push_back(v.p);
  ASSERT_EQ(corners.size(), 4u);
  for (Vec2 want : {Vec2{10.015, 0}, Vec2{0, 0.01}, Vec2{10, 10}, Vec2{0, 10}})
    EXPECT_EQ(std::count_if(corners.begin(), corners.end(), [&](Vec2 p) { return distance(p, want) < 1e-12; }), 1)
        << want.x << "," << want.y;
  EXPECT_NEAR(std::abs(signed_area(sq.contour)), 100.0, 0.2);
  // Each closed gap listed once, with its width, midpoint and the pieces whose ends met.
  ASSERT_EQ(r.gaps_closed.size(), 2u);
  std::vector<ClosedGap> gaps = r.gaps_closed;
  std::sort(gaps.begin(), gaps.end(), [](const ClosedGap& a, const ClosedGap& b) { return a.width_mm < b.width_mm; });
  EXPECT_NEAR(gaps[0].width_mm, 0.02, 1e-12);
  EXPECT_NEAR(distance(gaps[0].at, {0, 0.01}), 0, 1e-12);
  EXPECT_EQ(std::min(gaps[0].source_a, gaps[0].source_b), 0);
  EXPECT_EQ(std::max(gaps[0].source_a, gaps[0].source_b), 3);
  EXPECT_NEAR(gaps[1].width_mm, 0.03, 1e-12);
  EXPECT_NEAR(distance(gaps[1].at, {10.015, 0}), 0, 1e-12);
  EXPECT_EQ(std::min(gaps[1].source_a, gaps[1].source_b), 0);
  EXPECT_EQ(std::max(gaps[1].source_a, gaps[1].source_b), 1);
  // Strokes farther apart than the gap stay open, one chain each, with the distance that would join them.
  ASSERT_EQ(r.open.size(), 2u);
  EXPECT_EQ(r.open[0].sources, (std::vector<std::int32_t>{4}));
  EXPECT_EQ(r.open[1].sources, (std::vector<std::int32_t>{5}));
  EXPECT_NEAR(r.open[0].nearest_end_mm, 0.2, 1e-9);
  EXPECT_NEAR(r.open[1].nearest_end_mm, 0.2, 1e-9);
  // Beyond kGapHintMm, or alone, there is nothing to say; a single line never closes on itself.
  std::vector<ChainPiece> apart{line({0, 0}, {10, 0}, 0), line({11.5, 0}, {20, 0}, 1), line({30, 0}, {30, 0.5}, 2)};
  for (const ChainedContour& c : chain_contours(apart, 0.01, 0.05).open) EXPECT_LT(c.nearest_end_mm, 0) << c.sources[0];
  // A polyline whose own ends are 0.4 mm apart could close by itself.
  std::vector<ChainPiece> hook{{polygon({{0, 0}, {5, 0}, {5, 5}, {0, 0.4}}, false), 0, 0}};
  const ChainResult h = chain_contours(hook, 0.01, 0.05);
  ASSERT_EQ(h.open.size(), 1u);
  EXPECT_NEAR(h.open[0].nearest_end_mm, 0.4, 1e-9);
  // Groups stay apart across gaps too.
  std::vector<ChainPiece> grouped = pieces;
  grouped[0].group = 3;
  const ChainResult g = chain_contours(grouped, 0.01, 0.05);
  EXPECT_TRUE(g.closed.empty());
  EXPECT_TRUE(g.gaps_closed.empty());
}

TEST(Chain, AnOutlineClosesItsOwnGapBeforeANearerStrangerEnd) {
  // A polyline outline open by 0.04 mm at (10, 5) and a bend line ending 0.036 mm from both ends
  // (the nearest pair): the outline closes on itself, the bend line stays a stroke.
  const std::vector<ChainPiece> bend{
      {polygon({{10, 5.02}, {10, 10}, {0, 10}, {0, 0}, {10, 0}, {10, 4.98}}, false), 0, 0},
      line({10.03, 5}, {30, 5}, 1)};
  const ChainResult r = chain_contours(bend, 0.01, 0.05);
  ASSERT_EQ(r.closed.size(), 1u);
  EXPECT_EQ(r.closed[0].sources, (std::vector<std::int32_t>{0}));
  ASSERT_EQ(r.open.size(), 1u);
  EXPECT_EQ(r.open[0].sources, (std::vector<std::int32_t>{1}));
  // Two outlines 0.03 mm apart whose 0.04 mm gaps face each other: two parts, not one figure.
  const std::vector<ChainPiece> pair{
      {polygon({{10, 5.02}, {10, 10}, {0, 10}, {0, 0}, {10, 0}, {10, 4.98}}, false), 0, 0},
      {polygon({{10.03, 4.98}, {10.03, 0}, {20, 0}, {20, 10}, {10.03, 10}, {10.03, 5.02}}, false), 1, 0}};
  const ChainResult two = chain_contours(pair, 0.01, 0.05);
  ASSERT_EQ(two.closed.size(), 2u);
  for (const ChainedContour& c : two.closed) EXPECT_NEAR(std::abs(signed_area(c.contour)), 100, 0.5);
}

TEST(Chain, PartsDrawnEdgeToEdgeWithAGapInOneAreBothClosed) {
  // Two 100 x 50 parts side by side, each drawn with its own lines (the shared edge twice), the
  // left one open by 0.04 mm on its outer side: both close. Before, the gap kept the pair from being
  // traced as faces, the right part's copy of the shared edge was dropped, and it stayed open.
  const std::vector<ChainPiece> pieces{
      line({10, 10}, {110, 10}, 0),  line({110, 10}, {110, 60}, 1), line({110, 60}, {10, 60}, 2),
      line({10, 60}, {10, 30.04}, 3), line({10, 30}, {10, 10}, 4),   line({110, 10}, {210, 10}, 5),
      line({210, 10}, {210, 60}, 6), line({210, 60}, {110, 60}, 7), line({110, 60}, {110, 10}, 8)};
  const ChainResult r = chain_contours(pieces, 0.01, 0.05);
  ASSERT_EQ(r.closed.size(), 2u);
  EXPECT_TRUE(r.open.empty());
  for (const ChainedContour& c : r.closed) {
    EXPECT_NEAR(std::abs(signed_area(c.contour)), 5000, 1);
    EXPECT_EQ(c.sources.size(), c.sources.front() < 5 ? 5u : 4u);
  }
  ASSERT_EQ(r.gaps_closed.size(), 1u);
  EXPECT_NEAR(distance(r.gaps_closed[0].at, {10, 30.02}), 0, 1e-12);
}

TEST(Chain, MarksWhoseEndsMeetAcrossAGapStayOpen) {
  // A V of two lines whose open ends lie 0.04 mm apart, and a polyline there and back ending
  // 0.03 mm from its start: closed, each would be a sliver cut as a slit through the part it marks.
  std::vector<ChainPiece> v{line({50, 20}, {65, 25}, 0), line({65, 25}, {50.04, 20}, 1),
                            {polygon({{0, 0}, {20, 0}, {20, 0.001}, {0.03, 0.0}}, false), 2, 0}};
  const ChainResult r = chain_contours(v, 0.01, 0.05);
  EXPECT_TRUE(r.closed.empty());
  EXPECT_TRUE(r.gaps_closed.empty());
  ASSERT_EQ(r.open.size(), 2u);
  // Nor does a warning offer a --close-gaps that would close them.
  for (const ChainedContour& c : r.open) EXPECT_LT(c.nearest_end_mm, 0) << c.sources[0];
  // The same within the snap: ends 0.005 mm apart, or a polyline there and back to its start
  // exactly (cut, each was a slit through the part it marks).
  std::vector<ChainPiece> snapped{line({50, 20}, {65, 25}, 0), line({65, 25}, {50.005, 20}, 1),
                                  {polygon({{0, 0}, {20, 0}, {20, 5}, {20, 0}, {0, 0}}, false), 2, 0}};
  const ChainResult sn = chain_contours(snapped, 0.01, 0.05);
  EXPECT_TRUE(sn.closed.empty());
  ASSERT_EQ(sn.open.size(), 2u);
  for (const ChainedContour& c : sn.open) {
    EXPECT_FALSE(c.contour.closed);
    EXPECT_LT(c.nearest_end_mm, 0) << c.sources[0];
  }
  // A triangle of the same size drawn with its corner 0.04 mm open is an outline: closed.
  std::vector<ChainPiece> tri{line({50, 20}, {65, 25}, 0), line({65, 25}, {60, 35}, 1), line({60, 35}, {50.04, 20}, 2)};
  const ChainResult t = chain_contours(tri, 0.01, 0.05);
  EXPECT_EQ(t.closed.size(), 1u);
  EXPECT_EQ(t.gaps_closed.size(), 1u);
}

TEST(Chain, OneArcClosingOnItselfIsItsCircle) {
  // An ARC of r = 4 round (10, 20) from 0° to 359.6° (ends 0.028 mm apart, closed across the gap)
  // and one of 359.99999° (within the snap), each way round: as one vertex either was a loop of no
  // length, and a hole drawn so was left out of the nest.
  for (const double sweep_deg : {359.6, 359.99999, -359.6}) {
    const double sweep = sweep_deg * kPi / 180, r = 4;
    const Vec2 c{10, 20}, a = c + Vec2{r, 0}, b = c + Vec2{std::cos(sweep), std::sin(sweep)} * r;
    const std::vector<ChainPiece> arc{{Contour{{{a, std::tan(sweep / 4)}, {b, 0}}, false}, 7, 0}};
    const ChainResult res = chain_contours(arc, 0.01, 0.05);
    ASSERT_EQ(res.closed.size(), 1u) << sweep_deg;
    const Contour& k = res.closed[0].contour;
    ASSERT_EQ(k.vertices.size(), 2u);
    EXPECT_EQ(res.closed[0].sources, (std::vector<std::int32_t>{7}));
    EXPECT_NEAR(length(k), 2 * kPi * r, 1e-3) << sweep_deg;
    EXPECT_NEAR(signed_area(k), (sweep > 0 ? 1 : -1) * kPi * r * r, 1e-2) << sweep_deg;
    for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(distance(segment(k, i).center(), c), 0, 1e-6);
  }
}

// A piece drawn again a hair off (another program's rounding) is a copy like an exact repeat: left
// in, its ends took the original's as partners, and the rectangle lost its edge (fuzzing, session 49).
TEST(Chain, APieceDrawnAgainAHairOffIsACopy) {
  for (const double off : {1e-9, 1e-6, 5e-5}) {
    const std::vector<ChainPiece> pieces{line({0, 0}, {100, 0}, 0), line({100, 0}, {100, 50}, 1), line({100, 50}, {0, 50}, 2),
                                         line({0, 50}, {0.005, 0}, 3), line({100, off}, {0, off}, 4)};
    const ChainResult r = chain_contours(pieces, 0.01, 0.05);
    ASSERT_EQ(r.closed.size(), 1u) << off;
    EXPECT_TRUE(r.open.empty()) << off;
    EXPECT_EQ(r.dropped_duplicates, 1u) << off;
    EXPECT_NEAR(std::abs(signed_area(r.closed[0].contour)), 5000, 0.5) << off;
  }
  // Two strokes 0.02 mm apart are two strokes; so are two 0.005 mm apart (within the snap): two
  // outlines drawn that close lost edges to each other when copies were looked for at the snap.
  for (const double apart : {0.02, 0.005}) {
    const std::vector<ChainPiece> two{line({0, 0}, {100, 0}, 0), line({0, apart}, {100, apart}, 1)};
    EXPECT_EQ(chain_contours(two, 0.01, 0.05).dropped_duplicates, 0u) << apart;
  }
}

TEST(Chain, DuplicatesAndZeroLengthDroppedAndCounted) {
  std::vector<ChainPiece> pieces{line({0, 0}, {1, 0}, 0), line({1, 0}, {1, 1}, 1), line({1, 1}, {0, 0}, 2),
                                 line({1, 0}, {0, 0}, 3),  // reversed copy of 0
                                 line({1, 0}, {1, 1}, 4),  // exact copy of 1
                                 line({5, 5}, {5, 5}, 5),  // zero length
                                 line({5, 5}, {5 + 1e-9, 5}, 6)};
  ChainPiece arc_copy{Contour{{{{3, 0}, 0.5}, {{4, 0}, 0}}, false}, 7, 0};
  ChainPiece arc_back{reversed(arc_copy.path), 8, 0};
  ChainPiece arc_other_side{Contour{{{{3, 0}, -0.5}, {{4, 0}, 0}}, false}, 9, 0};  // not a duplicate
  pieces.push_back(arc_copy);
  pieces.push_back(arc_back);
  pieces.push_back(arc_other_side);
  const ChainResult r = chain_contours(pieces, 0.01);
  EXPECT_EQ(r.dropped_duplicates, 3u);
  EXPECT_EQ(r.dropped_zero_length, 2u);
  ASSERT_EQ(r.closed.size(), 2u);  // the triangle, and the lens of the two different arcs
  EXPECT_EQ(r.closed[0].sources, (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(r.closed[1].sources, (std::vector<std::int32_t>{7, 9}));
  EXPECT_TRUE(r.open.empty());
}

TEST(Chain, OpenChainsStayOpenAndClosedInputsPassThrough) {
  std::vector<ChainPiece> pieces{line({2, 0}, {2, 3}, 0), line({0, 0}, {2, 0}, 1), line({9, 9}, {8, 8}, 2)};
  ChainPiece closed{circle({20, 20}, 1), 3, 0};
  pieces.push_back(closed);
  // An open polyline whose ends meet closes by itself.
  pieces.push_back({polygon({{30, 0}, {31, 0}, {31, 1}, {30.001, 0.001}}, false), 4, 0});
  const ChainResult r = chain_contours(pieces, 0.01);
  ASSERT_EQ(r.open.size(), 2u);
  EXPECT_EQ(r.open[0].contour.vertices.size(), 3u);
  EXPECT_FALSE(r.open[0].contour.closed);
  EXPECT_EQ(r.open[0].sources.size(), 2u);
  EXPECT_EQ(r.open[1].sources, (std::vector<std::int32_t>{2}));
  ASSERT_EQ(r.closed.size(), 2u);
  EXPECT_EQ(r.closed[0].contour, closed.path);
  EXPECT_EQ(r.closed[1].sources, (std::vector<std::int32_t>{4}));
  EXPECT_EQ(r.closed[1].contour.vertices.size(), 3u);
  EXPECT_TRUE(r.closed[1].contour.closed);
}

TEST(Chain, NearestPartnerWinsAndGroupsStayApart) {
  // Three ends near (1,0): the two closest join, the third stays free.
  std::vector<ChainPiece> pieces{line({0, 0}, {1, 0}, 0), line({1.003, 0}, {2, 0}, 1), line({1.001, 0}, {1, 5}, 2)};
  const ChainResult r = chain_contours(pieces, 0.01);
  ASSERT_EQ(r.open.size(), 2u);
  EXPECT_EQ(r.open[0].sources, (std::vector<std::int32_t>{0, 2}));
  // Different groups never join.
  std::vector<ChainPiece> grouped{line({0, 0}, {1, 0}, 0), line({1, 0}, {1, 1}, 1)};
  grouped[1].group = 7;
  EXPECT_EQ(chain_contours(grouped, 0.01).open.size(), 2u);
}

TEST(Chain, FanOfLinesFromOnePointStaysFastAndPairsUp) {
  // 3000 spokes from the origin: 3000 ends within one snap circle. Each pair of spokes can join
  // at the centre; every end finds a partner, nothing closes (spokes' outer ends are apart).
  std::vector<ChainPiece> pieces;
  for (int i = 0; i < 3000; ++i) {
    const double a = 2 * kPi * i / 3000;
    pieces.push_back(line({0, 0}, {100 * std::cos(a), 100 * std::sin(a)}, i));
  }
  const ChainResult r = chain_contours(pieces, 0.01);
  EXPECT_TRUE(r.closed.empty());
  EXPECT_EQ(r.open.size(), 1500u);
  for (const ChainedContour& c : r.open) EXPECT_EQ(c.sources.size(), 2u);
}

TEST(Chain, OpenChainsRepeatingAClosedContourAreDropped) {
  // A closed square (a polyline) and lines over it: one along an edge, a chain of two along two
  // edges, one that leaves the edge halfway, one across, and one along an edge on another layer.
  std::vector<ChainPiece> pieces{{polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), 0, 0},
                                 line({2, 0}, {7, 0}, 1),
                                 line({10, 3}, {10, 10}, 2),
                                 line({10, 10}, {4, 10}, 3),
                                 line({5, 10}, {5, 20}, 4),
                                 line({0, 5}, {15, 5}, 5),
                                 line({0, 2}, {0, 8}, 6)};
  pieces.back().group = 1;
  const ChainResult r = chain_contours(pieces, 0.01);
  EXPECT_EQ(r.dropped_duplicates, 3u);  // piece 1, and the chain of pieces 2 and 3
  ASSERT_EQ(r.open.size(), 3u);
  EXPECT_EQ(r.open[0].sources, (std::vector<std::int32_t>{4}));
  EXPECT_EQ(r.open[1].sources, (std::vector<std::int32_t>{5}));
  EXPECT_EQ(r.open[2].sources, (std::vector<std::int32_t>{6}));
  ASSERT_EQ(r.closed.size(), 1u);
}

TEST(Chain, NonFiniteAndNoPieces) {
  EXPECT_TRUE(chain_contours({}, 0.01).closed.empty());
  std::vector<ChainPiece> pieces{line({0, 0}, {std::nan(""), 0}), line({0, 0}, {1e300, 1e300})};
  const ChainResult r = chain_contours(pieces, std::nan(""));
  EXPECT_EQ(r.dropped_invalid, 1u);
  EXPECT_EQ(r.open.size(), 1u);
}

}  // namespace
}  // namespace cutroute::geometry
