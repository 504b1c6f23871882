// chain_contours() on parts drawn edge to edge, each with its own entities: the shared edge is
// drawn twice, and every part must come out closed from its own entities.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/geometry/chain.hpp>
#include <cutroute/geometry/shapes.hpp>

namespace cutroute::geometry {
namespace {

ChainPiece piece(Vec2 a, Vec2 b, double bulge, std::int32_t source) {
  return {Contour{{{a, bulge}, {b, 0}}, false}, source, 0};
}

// A grid of cols × rows parts of w × h, each drawn as its own four pieces, ids 4·part + side.
// A vertical edge between two parts is an arc of a random bulge (the same piece for both,
// drawn once by each); every other edge is a line. Truth: each part's contour from its pieces.
struct Grid {
  std::vector<ChainPiece> pieces;
  std::vector<Contour> truth;
};

Grid make_grid(Rng& rng, int cols, int rows, double w, double h) {
  std::map<std::pair<int, int>, double> bulge;  // vertical edge at column x, row y
  for (int x = 1; x < cols; ++x) {
    for (int y = 0; y < rows; ++y) bulge[{x, y}] = rng.chance(0.5) ? 0.0 : 0.4 * rng.uniform01() - 0.2;
  }
  auto vertical = [&](int x, int y) { return bulge.count({x, y}) ? bulge[{x, y}] : 0.0; };
  Grid g;
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      const int part = y * cols + x;
      const Vec2 p0{w * x, h * y}, p1{w * (x + 1), h * y}, p2{w * (x + 1), h * (y + 1)}, p3{w * x, h * (y + 1)};
      // Vertical edges always drawn upwards, so both parts draw the very same piece.
      ChainPiece side[4] = {piece(p0, p1, 0, 4 * part), piece(p1, p2, vertical(x + 1, y), 4 * part + 1),
                            piece(p3, p2, 0, 4 * part + 2), piece(p0, p3, vertical(x, y), 4 * part + 3)};
      g.truth.push_back(Contour{{{p0, 0}, {p1, side[1].path.vertices[0].bulge}, {p2, 0}, {p3, -side[3].path.vertices[0].bulge}},
                                true});
      for (ChainPiece& s : side) {
        if (rng.chance(0.5)) s.path = reversed(s.path);
        g.pieces.push_back(s);
      }
    }
  }
  return g;
}

bool same_piece(const Contour& a, const Contour& b) { return a == b || a == reversed(b); }

std::vector<std::pair<double, double>> corners(const Contour& c) {
  std::vector<std::pair<double, double>> out;
  for (const Vertex& v : c.vertices) out.emplace_back(v.p.x, v.p.y);
  std::sort(out.begin(), out.end());
  return out;
}

// Every part closed once, from its own pieces, except that an edge drawn by two parts may be
// either part's drawing of it. `own_pieces`: the copies must follow the parts (drawn in order).
void expect_parts(const ChainResult& r, const Grid& g, bool own_pieces = false) {
  EXPECT_TRUE(r.open.empty());
  EXPECT_EQ(r.dropped_duplicates, 0u);
  ASSERT_EQ(r.closed.size(), g.truth.size());
  std::map<std::int32_t, const ChainPiece*> by_source;
  for (const ChainPiece& p : g.pieces) by_source[p.source] = &p;
  std::vector<int> seen(g.truth.size(), 0);
  for (const ChainedContour& c : r.closed) {
    std::size_t part = g.truth.size();
    for (std::size_t t = 0; t < g.truth.size(); ++t) {
      if (corners(g.truth[t]) == corners(c.contour)) part = t;
    }
    ASSERT_LT(part, g.truth.size()) << "a contour that is no part";
    ++seen[part];
    ASSERT_EQ(c.sources.size(), 4u);
    for (std::int32_t s : c.sources) {
      if (s / 4 == static_cast<std::int32_t>(part)) continue;
      EXPECT_FALSE(own_pieces) << "piece " << s << " in part " << part;
      bool shared = false;
      for (int side = 0; side < 4; ++side) shared = shared || same_piece(by_source[s]->path, by_source[static_cast<std::int32_t>(4 * part) + side]->path);
      EXPECT_TRUE(shared) << "piece " << s << " of another part in part " << part;
    }
    EXPECT_NEAR(std::abs(signed_area(c.contour)), signed_area(g.truth[part]), 1e-9);
    EXPECT_NEAR(length(c.contour), length(g.truth[part]), 1e-9);
  }
  for (int s : seen) EXPECT_EQ(s, 1);
}

TEST(ChainFaces, TwoSquaresSideBySide) {
  Rng rng(1);
  Grid g = make_grid(rng, 2, 1, 20, 20);
  expect_parts(chain_contours(g.pieces, 0.01), g, true);
  for (int order = 0; order < 8; ++order) {
    rng.shuffle(g.pieces.begin(), g.pieces.end());
    expect_parts(chain_contours(g.pieces, 0.01), g);
  }
}

TEST(ChainFaces, GridsWithLineAndArcEdgesShuffled) {
  Rng rng(44);
  for (int trial = 0; trial < 40; ++trial) {
    const int cols = 1 + static_cast<int>(rng.below(6)), rows = 1 + static_cast<int>(rng.below(5));
    Grid g = make_grid(rng, cols, rows, 20, 15);
    rng.shuffle(g.pieces.begin(), g.pieces.end());
    SCOPED_TRACE(std::to_string(cols) + " x " + std::to_string(rows));
    const ChainResult r = chain_contours(g.pieces, 0.01);
    expect_parts(r, g);
    // A contour starts at its lowest piece, in that piece's direction, as chained contours do.
    std::map<std::int32_t, const ChainPiece*> by_source;
    std::map<std::int32_t, std::size_t> position;
    for (const ChainPiece& p : g.pieces) {
      by_source[p.source] = &p;
      position[p.source] = static_cast<std::size_t>(&p - g.pieces.data());
    }
    for (const ChainedContour& c : r.closed) {
      for (std::int32_t s : c.sources) EXPECT_LE(position[c.sources.front()], position[s]);
      EXPECT_EQ(c.contour.vertices.front().p, by_source[c.sources.front()]->path.vertices.front().p);
      EXPECT_EQ(c.contour.vertices[1].p, by_source[c.sources.front()]->path.vertices.back().p);
    }
  }
}

TEST(ChainFaces, HolesAndLooseContoursAroundTheGrid) {
  Rng rng(7);
  Grid g = make_grid(rng, 3, 3, 20, 15);
  // A circle in each part and a square of lines away from the grid: unchanged by the faces.
  for (int part = 0; part < 9; ++part) {
    g.pieces.push_back({circle({20.0 * (part % 3) + 10, 15.0 * (part / 3) + 7.5}, 3), 1000 + part, 0});
  }
  const std::vector<Vec2> sq{{100, 0}, {110, 0}, {110, 10}, {100, 10}};
  for (int i = 0; i < 4; ++i) g.pieces.push_back(piece(sq[i], sq[(i + 1) % 4], 0, 2000 + i));
  rng.shuffle(g.pieces.begin(), g.pieces.end());
  const ChainResult r = chain_contours(g.pieces, 0.01);
  EXPECT_TRUE(r.open.empty());
  EXPECT_EQ(r.closed.size(), 9u + 9u + 1u);
  ChainResult grid;  // the parts' contours, checked as the grid alone
  for (const ChainedContour& c : r.closed) {
    if (c.sources.front() < 1000) grid.closed.push_back(c);
  }
  expect_parts(grid, g);
}

TEST(ChainFaces, OutputFollowsTheLowestPieceOfEachContour) {
  // Closed inputs, chained contours and faces all come out in order of their lowest piece.
  Rng rng(3);
  Grid g = make_grid(rng, 2, 1, 20, 20);
  std::vector<ChainPiece> pieces;
  pieces.push_back({circle({-50, 0}, 2), 0, 0});
  for (ChainPiece p : g.pieces) {
    p.source += 10;
    pieces.push_back(p);
  }
  pieces.push_back({circle({-60, 0}, 2), 99, 0});
  const ChainResult r = chain_contours(pieces, 0.01);
  ASSERT_EQ(r.closed.size(), 4u);
  EXPECT_EQ(r.closed[0].sources.front(), 0);
  EXPECT_EQ(r.closed[1].sources.front(), 10);
  EXPECT_EQ(r.closed[2].sources.front(), 14);
  EXPECT_EQ(r.closed[3].sources.front(), 99);
}

TEST(ChainFaces, RepeatedOutlinesAndStrayCopiesStayDropped) {
  const std::vector<Vec2> sq{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  // The whole outline drawn twice: one contour, four copies dropped.
  std::vector<ChainPiece> twice;
  for (int copy = 0; copy < 2; ++copy) {
    for (int i = 0; i < 4; ++i) twice.push_back(piece(sq[i], sq[(i + 1) % 4], 0, 4 * copy + i));
  }
  ChainResult r = chain_contours(twice, 0.01);
  EXPECT_EQ(r.closed.size(), 1u);
  EXPECT_TRUE(r.open.empty());
  EXPECT_EQ(r.dropped_duplicates, 4u);
  // One edge drawn twice by mistake, next to a part that really shares an edge: the stray copy
  // makes an odd point, so its group keeps the end pairing.
  std::vector<ChainPiece> stray;
  for (int i = 0; i < 4; ++i) stray.push_back(piece(sq[i], sq[(i + 1) % 4], 0, i));
  stray.push_back(piece(sq[0], sq[1], 0, 4));
  r = chain_contours(stray, 0.01);
  EXPECT_EQ(r.closed.size(), 1u);
  EXPECT_EQ(r.dropped_duplicates, 1u);
  // Three parts on one edge (drawn three times): not a planar drawing of parts; left alone.
  std::vector<ChainPiece> three;
  for (int part = 0; part < 3; ++part) {
    three.push_back(piece({0, 0}, {10, 0}, 0, 10 * part));
    three.push_back(piece({10, 0}, {5, 5.0 * (part + 1)}, 0, 10 * part + 1));
    three.push_back(piece({5, 5.0 * (part + 1)}, {0, 0}, 0, 10 * part + 2));
  }
  r = chain_contours(three, 0.01);
  EXPECT_EQ(r.dropped_duplicates, 2u);
}

// Rectangles of a guillotine layout: a rectangle cut in two, each half cut again across, and so
// on, so that a long side of one part often meets the shorter sides of two neighbours (T-junctions)
// and sides meet partly (the halves were cut at different heights).
void guillotine(Rng& rng, double x0, double y0, double x1, double y1, int depth, std::vector<std::array<double, 4>>& out) {
  const bool vertical = depth % 2 == 0;
  const double span = vertical ? x1 - x0 : y1 - y0;
  if (depth == 0 || span < 8 || rng.chance(0.15)) {
    out.push_back({x0, y0, x1, y1});
    return;
  }
  const double cut = std::round(span * (0.25 + 0.5 * rng.uniform01()));
  if (vertical) {
    guillotine(rng, x0, y0, x0 + cut, y1, depth - 1, out);
    guillotine(rng, x0 + cut, y0, x1, y1, depth - 1, out);
  } else {
    guillotine(rng, x0, y0, x1, y0 + cut, depth - 1, out);
    guillotine(rng, x0, y0 + cut, x1, y1, depth - 1, out);
  }
}

TEST(ChainFaces, GuillotineLayoutsWithTJunctionsAndPolylineParts) {
  Rng rng(45);
  for (int trial = 0; trial < 60; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    std::vector<std::array<double, 4>> rects;
    guillotine(rng, 0, 0, 200, 120, 1 + static_cast<int>(rng.below(6)), rects);
    std::vector<ChainPiece> pieces;
    std::vector<char> as_polyline(rects.size(), 0);
    for (std::size_t r = 0; r < rects.size(); ++r) {
      const auto& [x0, y0, x1, y1] = rects[r];
      const Vec2 c[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
      const auto id = static_cast<std::int32_t>(4 * r);
      if (rng.chance(0.2)) {
        as_polyline[r] = 1;
        pieces.push_back({polygon({c[0], c[1], c[2], c[3]}), id, 0});
        continue;
      }
      for (int k = 0; k < 4; ++k) {
        ChainPiece p = piece(c[k], c[(k + 1) % 4], 0, id + k);
        if (rng.chance(0.5)) p.path = reversed(p.path);
        pieces.push_back(p);
      }
    }
    rng.shuffle(pieces.begin(), pieces.end());
    const ChainResult res = chain_contours(pieces, 0.01);
    EXPECT_TRUE(res.open.empty());
    ASSERT_EQ(res.closed.size(), rects.size());
    std::vector<int> seen(rects.size(), 0);
    for (const ChainedContour& c : res.closed) {
      // Each part whole, one vertex per corner: a neighbour's drawing of a stretch of its side
      // would leave a vertex in the middle of that side.
      ASSERT_EQ(c.contour.vertices.size(), 4u);
      const Box b = bounding_box(c.contour);
      std::size_t r = 0;
      while (r < rects.size() && !(rects[r][0] == b.xmin && rects[r][1] == b.ymin && rects[r][2] == b.xmax && rects[r][3] == b.ymax)) ++r;
      ASSERT_LT(r, rects.size()) << "a contour that is no part";
      ++seen[r];
      EXPECT_NEAR(std::abs(signed_area(c.contour)), (rects[r][2] - rects[r][0]) * (rects[r][3] - rects[r][1]), 1e-9);
      if (as_polyline[r]) continue;
      int own = 0;
      for (std::int32_t src : c.sources) own += src / 4 == static_cast<std::int32_t>(r);
      // A side that a neighbour draws exactly alike may come from either drawing; a side that
      // neighbours draw in stretches is the part's own.
      EXPECT_GE(own, 1);
    }
    for (int k : seen) EXPECT_EQ(k, 1);
  }
}

// A curved T: one part's arc side (a circle of radius 25 about (0, 15), from (-20, 0) to (20, 0)
// through (0, -10)) meets the arc sides of two parts below it, each drawn as its own half of that
// arc. All three close, the upper one with its arc whole; together they fill 40 x 50 mm.
TEST(ChainFaces, ArcSideMetByTheArcsOfTwoNeighbours) {
  const double whole = std::tan(std::atan2(20.0, 15.0) / 2), half = std::tan(std::atan2(20.0, 15.0) / 4);
  const std::vector<ChainPiece> pieces{
      piece({-20, 0}, {20, 0}, whole, 0),    piece({20, 0}, {20, 20}, 0, 1),    piece({20, 20}, {-20, 20}, 0, 2),
      piece({-20, 20}, {-20, 0}, 0, 3),      piece({-20, 0}, {0, -10}, half, 4), piece({0, -10}, {0, -30}, 0, 5),
      piece({0, -30}, {-20, -30}, 0, 6),     piece({-20, -30}, {-20, 0}, 0, 7), piece({0, -10}, {20, 0}, half, 8),
      piece({20, 0}, {20, -30}, 0, 9),       piece({20, -30}, {0, -30}, 0, 10), piece({0, -30}, {0, -10}, 0, 11)};
  const ChainResult r = chain_contours(pieces, 0.01);
  EXPECT_TRUE(r.open.empty());
  ASSERT_EQ(r.closed.size(), 3u);
  const double segment = 25.0 * 25.0 / 2 * (2 * std::atan2(20.0, 15.0) - std::sin(2 * std::atan2(20.0, 15.0)));
  EXPECT_EQ(r.closed[0].sources, (std::vector<std::int32_t>{0, 1, 2, 3}));
  EXPECT_NEAR(std::abs(signed_area(r.closed[0].contour)), 40 * 20 + segment, 1e-6);
  double total = 0;
  for (const ChainedContour& c : r.closed) {
    EXPECT_EQ(c.contour.vertices.size(), 4u);
    for (std::int32_t s : c.sources) EXPECT_EQ(s / 4, c.sources.front() / 4);
    total += std::abs(signed_area(c.contour));
  }
  EXPECT_NEAR(total, 40 * 50, 1e-6);
}

// A round part drawn as one open arc (its ends 0.001 mm apart) touched at its leftmost point by
// the corners of two squares drawn edge to edge: the arc is cut there, and the round part's face
// is made of that one arc's two stretches only. All three close (before this was handled, the
// round part's face was dropped: a part lost).
TEST(ChainFaces, RoundPartOfOneArcTouchedByACornerOfTwoParts) {
  const double end = -0.0001;  // [rad] short of a full turn
  const double sweep = 2 * std::numbers::pi + end;
  std::vector<ChainPiece> pieces{piece({10, 0}, Vec2{std::cos(end), std::sin(end)} * 10, std::tan(sweep / 4), 0)};
  const std::vector<Vec2> a{{-30, 0}, {-10, 0}, {-10, 10}, {-30, 10}}, b{{-30, -10}, {-10, -10}, {-10, 0}, {-30, 0}};
  for (int i = 0; i < 4; ++i) {
    pieces.push_back(piece(a[i], a[(i + 1) % 4], 0, 1 + i));
    pieces.push_back(piece(b[i], b[(i + 1) % 4], 0, 5 + i));
  }
  const ChainResult r = chain_contours(pieces, 0.01);
  EXPECT_TRUE(r.open.empty());
  ASSERT_EQ(r.closed.size(), 3u);
  double round = 0, squares = 0;
  for (const ChainedContour& c : r.closed) (c.sources.front() == 0 ? round : squares) += std::abs(signed_area(c.contour));
  EXPECT_NEAR(round, std::numbers::pi * 100, 0.05);  // its ends joined at their midpoint
  EXPECT_NEAR(squares, 400, 1e-9);
}

TEST(ChainFaces, TouchingCornersAndStrokesEndingOnAnEdge) {
  // Two squares touching at a corner: two contours, whatever the order of their lines.
  const std::vector<Vec2> a{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, b{{10, 10}, {20, 10}, {20, 20}, {10, 20}};
  std::vector<ChainPiece> corner;
  for (int i = 0; i < 4; ++i) {
    corner.push_back(piece(a[i], a[(i + 1) % 4], 0, i));
    corner.push_back(piece(b[i], b[(i + 1) % 4], 0, 4 + i));
  }
  Rng rng(5);
  for (int order = 0; order < 8; ++order) {
    rng.shuffle(corner.begin(), corner.end());
    const ChainResult r = chain_contours(corner, 0.01);
    ASSERT_EQ(r.closed.size(), 2u);
    for (const ChainedContour& c : r.closed) {
      EXPECT_EQ(c.contour.vertices.size(), 4u);
      EXPECT_NEAR(std::abs(signed_area(c.contour)), 100, 1e-9);
      for (std::int32_t s : c.sources) EXPECT_EQ(s / 4, c.sources.front() / 4);
    }
  }
  // A stroke ending on a side (a mark, a construction line): the square stays as drawn, the
  // stroke open; nothing is cut at the point where it ends.
  std::vector<ChainPiece> stroke;
  for (int i = 0; i < 4; ++i) stroke.push_back(piece(a[i], a[(i + 1) % 4], 0, i));
  stroke.push_back(piece({10, 5}, {15, 5}, 0, 9));
  const ChainResult r = chain_contours(stroke, 0.01);
  ASSERT_EQ(r.closed.size(), 1u);
  EXPECT_EQ(r.closed[0].contour.vertices.size(), 4u);
  ASSERT_EQ(r.open.size(), 1u);
  EXPECT_EQ(r.open[0].sources, (std::vector<std::int32_t>{9}));
}

// A part of a grid drawn twice by mistake (its four lines again, before or after the rest): its
// edges shared with neighbours are then drawn three times. The second outline is dropped as
// duplicates and every part closes once (before, the part and its neighbours were left open).
TEST(ChainFaces, PartOfAGridDrawnTwice) {
  for (const int twice : {0, 4}) {  // a corner part, the middle one
    for (const bool before : {false, true}) {
      SCOPED_TRACE("part " + std::to_string(twice) + (before ? ", repeated first" : ", repeated last"));
      Rng rng(9);
      Grid g = make_grid(rng, 3, 3, 20, 15);
      std::vector<ChainPiece> repeat;
      for (int side = 0; side < 4; ++side) {
        ChainPiece p = g.pieces[static_cast<std::size_t>(4 * twice + side)];
        p.source += 1000;
        repeat.push_back(p);
      }
      std::vector<ChainPiece> pieces = g.pieces;
      pieces.insert(before ? pieces.begin() : pieces.end(), repeat.begin(), repeat.end());
      const ChainResult r = chain_contours(pieces, 0.01);
      EXPECT_TRUE(r.open.empty());
      EXPECT_EQ(r.dropped_duplicates, 4u);
      ASSERT_EQ(r.closed.size(), 9u);
      double area = 0;
      for (const ChainedContour& c : r.closed) {
        EXPECT_EQ(c.contour.vertices.size(), 4u);
        area += std::abs(signed_area(c.contour));
      }
      EXPECT_NEAR(area, 60.0 * 45.0, 1e-9);
    }
  }
}

TEST(ChainFaces, RepeatRunsGiveTheSameContours) {
  Rng rng(11);
  const Grid g = make_grid(rng, 4, 3, 20, 15);
  std::vector<ChainPiece> pieces = g.pieces;
  const ChainResult first = chain_contours(pieces, 0.01);
  for (int i = 0; i < 5; ++i) {
    const ChainResult again = chain_contours(pieces, 0.01);
    ASSERT_EQ(again.closed.size(), first.closed.size());
    for (std::size_t c = 0; c < first.closed.size(); ++c) {
      EXPECT_EQ(again.closed[c].contour, first.closed[c].contour);
      EXPECT_EQ(again.closed[c].sources, first.closed[c].sources);
    }
  }
}

}  // namespace
}  // namespace cutroute::geometry
