// build_nest(): depth and roles on deep nests, concave parts, sheet detection, diagnostics,
// and the containment tree against a brute-force recomputation on a random nest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/geometry/shapes.hpp>
#include <cutroute/model/nest.hpp>

namespace cutroute::model {
namespace {

using geometry::Box;
using geometry::Contour;
using geometry::Vec2;

SourceContour src(Contour c, std::string layer = "0", std::string handle = "", std::optional<long> line = {}) {
  SourceContour s;
  s.contour = std::move(c);
  s.layer = std::move(layer);
  s.handle = std::move(handle);
  s.line = line;
  return s;
}

Contour square(double half, Vec2 c = {0, 0}, bool ccw = true) {
  return geometry::rectangle({c.x - half, c.y - half, c.x + half, c.y + half}, ccw);
}

// Independent containment truth: crossing-number test on a finely flattened polygon.
bool polygon_contains(const std::vector<Vec2>& poly, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
        p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x) {
      in = !in;
    }
  }
  return in;
}

ContourId find(const Nest& nest, const std::string& handle) {
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    if (nest.contours[ContourId(static_cast<int>(i))].source.handle == handle) return ContourId(static_cast<int>(i));
  }
  ADD_FAILURE() << "no contour " << handle;
  return ContourId();
}

// Built by append: GCC 12 warns falsely (-Wrestrict) on "L" + std::to_string(k).
std::string label(std::size_t k) {
  std::string s = "L";
  s += std::to_string(k);
  return s;
}

void check_deep_nest(const std::vector<Contour>& levels) {
  // levels[k] is at depth k; fed in a shuffled order with mixed orientations.
  Rng rng(5);
  std::vector<SourceContour> in;
  for (std::size_t k = 0; k < levels.size(); ++k) {
    Contour c = rng.chance(0.5) ? geometry::reversed(levels[k]) : levels[k];
    in.push_back(src(c, "0", label(k)));
  }
  rng.shuffle(in.begin(), in.end());
  const Nest nest = build_nest(in, NestOptions{});
  EXPECT_TRUE(nest.diagnostics.empty());
  EXPECT_FALSE(nest.sheet);
  ASSERT_EQ(nest.contours.size(), levels.size());
  EXPECT_EQ(nest.max_depth, static_cast<int>(levels.size()) - 1);
  EXPECT_EQ(nest.parts.size(), (levels.size() + 1) / 2);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    SCOPED_TRACE(k);
    const NestContour& c = nest.contours[find(nest, label(k))];
    EXPECT_EQ(c.depth, static_cast<int>(k));
    EXPECT_EQ(c.role, k % 2 == 0 ? ContourRole::outer : ContourRole::hole);
    if (k == 0) {
      EXPECT_FALSE(c.parent.valid());
    } else {
      EXPECT_EQ(c.parent, find(nest, label(k - 1)));
    }
    const Part& part = nest.parts[c.part];
    if (k % 2 == 0) {
      EXPECT_EQ(part.outer, find(nest, label(k)));
      if (k + 1 < levels.size()) {
        ASSERT_EQ(part.holes.size(), 1u);
        EXPECT_EQ(part.holes[0], find(nest, label(k + 1)));
      }
      if (k >= 2) {
        EXPECT_EQ(part.inside_hole, find(nest, label(k - 1)));
        EXPECT_EQ(part.parent_part, nest.contours[find(nest, label(k - 2))].part);
      } else {
        EXPECT_FALSE(part.inside_hole.valid());
        EXPECT_FALSE(part.parent_part.valid());
      }
    } else {
      EXPECT_EQ(part.outer, find(nest, label(k - 1)));
    }
  }
}

TEST(Nest, SquaresNestedSixDeepAlternatePartsAndHoles) {
  std::vector<Contour> levels;
  for (int k = 0; k < 6; ++k) levels.push_back(square(100 - 10 * k));
  check_deep_nest(levels);
}

TEST(Nest, CirclesNestedSevenDeepWithExactArcs) {
  // Circles only: every containment test goes through the exact arc winding number.
  std::vector<Contour> levels;
  for (int k = 0; k < 7; ++k) levels.push_back(geometry::circle({0, 0}, 70 - 10 * k, k % 2 == 0));
  check_deep_nest(levels);
}

TEST(Nest, ArcContainmentNotBoxes) {
  // A small square in the corner of a circle's box: inside the box, outside the circle.
  std::vector<SourceContour> in{src(geometry::circle({0, 0}, 10), "0", "C"), src(square(0.5, {9, 9}), "0", "S"),
                                src(square(0.5, {6.5, 6.5}), "0", "T")};
  const Nest nest = build_nest(in, NestOptions{});
  EXPECT_EQ(nest.contours[find(nest, "S")].depth, 0);
  EXPECT_EQ(nest.contours[find(nest, "T")].depth, 1);  // corner at (7,7): |(7,7)| = 9.9 < 10
  EXPECT_EQ(nest.parts.size(), 2u);
}

TEST(Nest, ConcavePartDoesNotAdoptPartInItsNotch) {
  // U: 30 x 30 with a notch 10..20 x 10..30 open at the top.
  const Contour u = geometry::polygon({{0, 0}, {30, 0}, {30, 30}, {20, 30}, {20, 10}, {10, 10}, {10, 30}, {0, 30}});
  std::vector<SourceContour> in{src(u, "0", "U"), src(square(3, {15, 20}), "0", "in_notch"),
                                src(square(3, {5, 5}), "0", "hole_in_arm"), src(square(1, {5, 5}), "0", "part_in_hole")};
  const Nest nest = build_nest(in, NestOptions{});
  EXPECT_TRUE(nest.diagnostics.empty());
  const NestContour& notch = nest.contours[find(nest, "in_notch")];
  EXPECT_EQ(notch.depth, 0);
  EXPECT_FALSE(notch.parent.valid());
  EXPECT_EQ(notch.role, ContourRole::outer);
  EXPECT_EQ(nest.contours[find(nest, "hole_in_arm")].role, ContourRole::hole);
  EXPECT_EQ(nest.contours[find(nest, "hole_in_arm")].parent, find(nest, "U"));
  const NestContour& inner = nest.contours[find(nest, "part_in_hole")];
  EXPECT_EQ(inner.depth, 2);
  EXPECT_EQ(nest.parts[inner.part].parent_part, nest.contours[find(nest, "U")].part);
  EXPECT_EQ(nest.parts.size(), 3u);
  EXPECT_EQ(nest.max_depth, 2);
}

std::vector<SourceContour> parts_on_sheet(const std::string& sheet_layer, bool with_hole) {
  std::vector<SourceContour> in{src(geometry::rectangle({0, 0, 3000, 1500}), sheet_layer, "SHEET")};
  in.push_back(src(square(100, {200, 200}), "0", "P1"));
  in.push_back(src(geometry::circle({600, 600}, 50), "0", "P2"));
  if (with_hole) in.push_back(src(geometry::circle({200, 200}, 20), "0", "H1"));
  return in;
}

TEST(Nest, SheetByLayerName) {
  for (const char* layer : {"Sheet", "PLATE H475 W595", "border", "Blechrand"}) {
    SCOPED_TRACE(layer);
    const Nest nest = build_nest(parts_on_sheet(layer, false), NestOptions{});
    ASSERT_TRUE(nest.sheet);
    EXPECT_EQ(*nest.sheet, find(nest, "SHEET"));
    EXPECT_EQ(nest.contours[*nest.sheet].role, ContourRole::sheet);
    EXPECT_FALSE(nest.contours[*nest.sheet].part.valid());
    EXPECT_EQ(nest.parts.size(), 2u);
    EXPECT_EQ(nest.contours[find(nest, "P1")].depth, 0);
    EXPECT_FALSE(nest.contours[find(nest, "P1")].parent.valid());
    EXPECT_EQ(nest.max_depth, 0);
    ASSERT_TRUE(nest.sheet_box);
    EXPECT_EQ(nest.sheet_box->xmax, 3000);
  }
}

TEST(Nest, PartsFlushWithOrJustOverTheBorderKeepTheSheet) {
  // As nesting tools write them: parts flush with the border, one 0.01 mm over it.
  std::vector<SourceContour> in{src(geometry::rectangle({0, 0, 600, 200}), "Plate H200 W600", "S"),
                                src(geometry::rectangle({-0.01, -0.01, 150, 150}), "Elements", "A"),
                                src(geometry::circle({300, 100}, 40), "Elements", "B"),
                                src(geometry::rectangle({500, 100, 600, 200}), "Elements", "C")};
  const Nest nest = build_nest(in, NestOptions{});
  ASSERT_TRUE(nest.sheet);
  EXPECT_EQ(nest.parts.size(), 3u);
  EXPECT_FALSE(has_errors(nest.diagnostics));
  ASSERT_EQ(nest.diagnostics.size(), 2u);  // A and C
  EXPECT_EQ(nest.diagnostics[0].handle, "A");
  EXPECT_EQ(nest.diagnostics[1].handle, "C");
  // 2 mm over the border is not a sheet layout any more: no sheet, and the crossing is an error.
  in[1] = src(geometry::rectangle({-2, -2, 150, 150}), "Elements", "A");
  const Nest over = build_nest(in, NestOptions{});
  EXPECT_FALSE(over.sheet);
  EXPECT_TRUE(has_errors(over.diagnostics));
}

TEST(Nest, SheetByGeometryNeedsAPartWithAHole) {
  // Parts with a hole inside an enclosing rectangle on layer "0": a sheet.
  Nest nest = build_nest(parts_on_sheet("0", true), NestOptions{});
  ASSERT_TRUE(nest.sheet);
  EXPECT_EQ(nest.parts.size(), 2u);
  EXPECT_EQ(nest.contours[find(nest, "H1")].role, ContourRole::hole);
  EXPECT_EQ(nest.contours[find(nest, "H1")].depth, 1);
  EXPECT_EQ(nest.max_depth, 1);
  // A rectangular plate with plain holes: a part, not a sheet.
  nest = build_nest(parts_on_sheet("0", false), NestOptions{});
  EXPECT_FALSE(nest.sheet);
  EXPECT_EQ(nest.parts.size(), 1u);
  EXPECT_EQ(nest.contours[find(nest, "P1")].role, ContourRole::hole);
  // Detection off: never a sheet.
  NestOptions off;
  off.detect_sheet = false;
  nest = build_nest(parts_on_sheet("Sheet", true), off);
  EXPECT_FALSE(nest.sheet);
  EXPECT_EQ(nest.max_depth, 2);
}

// A nest drawn rotated, its border with it: on a sheet layer, or named by --sheet, the border is
// the sheet (it was taken for a part, and every part became a hole cut with its kerf inside the
// part), as by its shape alone.
TEST(Nest, ARotatedBorderIsTheSheet) {
  const double a = 37 * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  const auto turned = [&](const geometry::Contour& in) {
    geometry::Contour out = in;
    for (auto& v : out.vertices) v.p = {1000 + c * v.p.x - s * v.p.y, 200 + s * v.p.x + c * v.p.y};
    return out;
  };
  const auto nest_on = [&](const std::string& layer) -> std::vector<SourceContour> {
    std::vector<SourceContour> in = parts_on_sheet(layer, true);
    for (auto& sc : in) sc.contour = turned(sc.contour);
    // The border starting mid-side, as some writers leave it: still four sides.
    auto& v = in[0].contour.vertices;
    EXPECT_EQ(v.size(), 4u);
    const geometry::Vertex mid{(v[0].p + v[1].p) / 2, 0.0};
    v = {mid, v[1], v[2], v[3], v[0]};
    return in;
  };
  Nest nest = build_nest(nest_on("Sheet"), NestOptions{});
  ASSERT_TRUE(nest.sheet);
  EXPECT_EQ(*nest.sheet, find(nest, "SHEET"));
  EXPECT_EQ(nest.parts.size(), 2u);
  EXPECT_EQ(nest.contours[find(nest, "P1")].role, ContourRole::outer);
  EXPECT_EQ(nest.contours[find(nest, "H1")].role, ContourRole::hole);
  NestOptions sized;
  sized.sheet_size = Vec2{1500, 3000};
  nest = build_nest(nest_on("0"), sized);
  ASSERT_TRUE(nest.sheet);
  EXPECT_EQ(nest.parts.size(), 2u);
  for (const auto& d : nest.diagnostics) EXPECT_NE(d.code, "nest.sheet_size") << d.message;
  // Layer "0", no size: a border by its shape as an axis-aligned one, holding a part with a hole.
  nest = build_nest(nest_on("0"), NestOptions{});
  ASSERT_TRUE(nest.sheet);
  EXPECT_EQ(nest.contours[find(nest, "P1")].role, ContourRole::outer);
  // A rotated rectangular plate with plain holes: a part, not a sheet, as when axis-aligned.
  std::vector<SourceContour> plate = nest_on("0");
  plate.pop_back();  // H1: no part with a hole left
  nest = build_nest(plate, NestOptions{});
  EXPECT_FALSE(nest.sheet);
  EXPECT_EQ(nest.contours[find(nest, "P1")].role, ContourRole::hole);
  // A rotated rhombus of the same area on a sheet layer is no rectangle.
  std::vector<SourceContour> rh = nest_on("Sheet");
  rh[0].contour.vertices[1].p = rh[0].contour.vertices[1].p + Vec2{0, 50};
  nest = build_nest(rh, NestOptions{});
  EXPECT_FALSE(nest.sheet);
}

TEST(Nest, SheetBySizeOption) {
  NestOptions opt;
  opt.sheet_size = Vec2{1500, 3000};  // either way round
  Nest nest = build_nest(parts_on_sheet("0", false), opt);
  ASSERT_TRUE(nest.sheet);
  EXPECT_EQ(nest.parts.size(), 2u);
  // No border drawn: the sheet is the given size at the origin, no contour is the sheet.
  std::vector<SourceContour> in = parts_on_sheet("0", false);
  in.erase(in.begin());
  opt.sheet_size = Vec2{3000, 1500};
  nest = build_nest(in, opt);
  EXPECT_FALSE(nest.sheet);
  ASSERT_TRUE(nest.sheet_box);
  EXPECT_EQ(nest.sheet_box->xmax, 3000);
  EXPECT_EQ(nest.sheet_box->ymax, 1500);
  EXPECT_EQ(nest.parts.size(), 2u);
}

// A --sheet size that no rectangle round the parts has was passed over without a word: said, with
// what is left uncut instead (the border found by its layer, or nothing).
TEST(Nest, ASheetSizeMatchingNoBorderIsSaid) {
  auto said = [](const Nest& n) {
    std::string m;
    for (const auto& d : n.diagnostics)
      if (d.code == "nest.sheet_size") m += d.message;
    return m;
  };
  NestOptions opt;
  opt.sheet_size = Vec2{3000, 1500};
  EXPECT_EQ(said(build_nest(parts_on_sheet("0", false), opt)), "");
  opt.sheet_size = Vec2{3000, 1000};
  Nest nest = build_nest(parts_on_sheet("Sheet", true), opt);
  EXPECT_TRUE(nest.sheet);  // still found by its layer
  EXPECT_EQ(said(nest), "--sheet 3000,1000 matches no rectangle drawn round the parts (within 0.5 mm): the border found by its layer, "
                        "3000 x 1500 mm, is left uncut");
  nest = build_nest(parts_on_sheet("0", false), opt);
  EXPECT_FALSE(nest.sheet);
  EXPECT_NE(said(nest).find(": no border is left out, every closed contour is cut"), std::string::npos) << said(nest);
}

TEST(Nest, CrossingContoursDiagnosedNamingBoth) {
  std::vector<SourceContour> in{src(geometry::circle({0, 0}, 10), "CUT", "1A", 120),
                                src(geometry::circle({15, 0}, 10), "CUT", "2B", 300),
                                src(square(2, {0, 0}), "CUT", "3C", 400)};
  const Nest nest = build_nest(in, NestOptions{});
  ASSERT_EQ(nest.diagnostics.size(), 1u);
  const Diagnostic& d = nest.diagnostics[0];
  EXPECT_EQ(d.severity, Severity::error);
  EXPECT_NE(d.message.find("entity 1A"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("entity 2B"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("line 300"), std::string::npos) << d.message;
  // Where, and how deep: the circles meet at (7.5, ±6.614); each reaches 5 mm into the other.
  EXPECT_NE(d.message.find("near (7.5, "), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("by at least 5 mm"), std::string::npos) << d.message;
  EXPECT_EQ(d.handle, "1A");
  EXPECT_EQ(d.line, 120);
  EXPECT_FALSE(nest.contours[find(nest, "2B")].parent.valid());
  EXPECT_EQ(nest.contours[find(nest, "3C")].parent, find(nest, "1A"));
  EXPECT_EQ(d.code, "nest.crossing");
  // A common edge (parts placed edge to edge) is a warning naming both: each part can still be
  // cut whole (the edge twice), or once with common-line cutting.
  const Nest shared = build_nest({src(geometry::rectangle({0, 0, 1, 1}), "0", "L"), src(geometry::rectangle({1, 0.5, 2, 3}), "0", "R")},
                                 NestOptions{});
  ASSERT_EQ(shared.diagnostics.size(), 1u);
  EXPECT_EQ(shared.diagnostics[0].severity, Severity::warning);
  EXPECT_EQ(shared.diagnostics[0].code, "nest.common_edge");
  EXPECT_NE(shared.diagnostics[0].message.find("share a boundary stretch"), std::string::npos);
  EXPECT_NE(shared.diagnostics[0].message.find("entity R"), std::string::npos);
}

Contour polygon(std::vector<Vec2> pts) {
  Contour c;
  for (const Vec2 p : pts) c.vertices.push_back({p, 0.0});
  c.closed = true;
  return c;
}

// A contour that crosses or touches itself has loops of opposite sense (a lead-in and the kerf
// would go on the part's side of one): an error like two crossing contours. The zig-zag that
// snapping leaves at a contour's closing (a few µm) is not.
TEST(Nest, ContourCrossingItselfIsAnError) {
  const Nest eight = build_nest({src(polygon({{0, 0}, {100, 60}, {100, 0}, {0, 40}}), "CUT", "8A", 12)}, NestOptions{});
  ASSERT_EQ(eight.diagnostics.size(), 1u);
  EXPECT_EQ(eight.diagnostics[0].severity, Severity::error);
  EXPECT_EQ(eight.diagnostics[0].code, "nest.crossing");
  EXPECT_EQ(eight.diagnostics[0].message, "contour 0 (entity 8A, line 12, layer CUT) crosses or touches itself near (40, 24)");
  // Said once: not again after the message by format().
  EXPECT_EQ(format(eight.diagnostics[0]), "line 12: error: " + eight.diagnostics[0].message);
  // Touching itself at one point (two squares joined at a corner, drawn as one contour).
  const Nest touch = build_nest({src(polygon({{0, 0}, {10, 0}, {10, 10}, {20, 10}, {20, 20}, {10, 20}, {10, 10}, {0, 10}}))}, NestOptions{});
  ASSERT_FALSE(touch.diagnostics.empty());
  EXPECT_NE(touch.diagnostics[0].message.find("crosses or touches itself near (10, 10)"), std::string::npos) << touch.diagnostics[0].message;
  // A zig-zag of a few µm next to a corner: below the loop tolerance, a simple square.
  const Nest zig = build_nest({src(polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0.002}, {0.003, 0.004}, {-0.002, 0.004}}))}, NestOptions{});
  EXPECT_TRUE(zig.diagnostics.empty()) << zig.diagnostics[0].message;
  NestOptions strict;
  strict.self_loop_tol_mm = 0.0;
  EXPECT_FALSE(build_nest({src(polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0.002}, {0.003, 0.004}, {-0.002, 0.004}}))}, strict)
                   .diagnostics.empty());
}

// The same outline drawn twice, once with an extra point on a straight side (a polyline and an
// exploded copy of LINEs): one contour, the copy left out with a warning, in either order and
// direction. A point off the side by 0.01 mm, or the whole copy nudged by 0.005 mm, is the same
// outline drawn again within kNearDuplicateMm: cut, both would run along one kerf. A point 0.2 mm
// off makes another outline (then the pair crosses).
TEST(Nest, DuplicateOutlineWithAPointOnAStraightSideIsOneContour) {
  const Contour plain = polygon({{0, 0}, {100, 0}, {100, 50}, {0, 50}});
  const Contour split = polygon({{0, 50}, {0, 0}, {50, 0}, {100, 0}, {100, 50}});
  for (const bool reversed_copy : {false, true}) {
    const Contour copy = reversed_copy ? geometry::reversed(split) : split;
    const Nest nest = build_nest({src(plain, "0", "P", 5), src(copy, "0", "L", 33)}, NestOptions{});
    ASSERT_EQ(nest.contours.size(), 1u) << reversed_copy;
    EXPECT_EQ(nest.dropped_duplicates, 1u);
    ASSERT_EQ(nest.diagnostics.size(), 1u);
    EXPECT_EQ(nest.diagnostics[0].code, "nest.duplicate");
    EXPECT_NE(nest.diagnostics[0].message.find("duplicates contour 0"), std::string::npos) << nest.diagnostics[0].message;
  }
  for (const Contour& near : {polygon({{0, 50}, {0, 0}, {50, 0.01}, {100, 0}, {100, 50}}),
                              polygon({{0.005, 0}, {100.005, 0}, {100.005, 50}, {0.005, 50}})}) {
    const Nest nest = build_nest({src(plain, "0", "P", 5), src(near, "0", "L", 33)}, NestOptions{});
    ASSERT_EQ(nest.contours.size(), 1u);
    EXPECT_EQ(nest.dropped_duplicates, 1u);
    ASSERT_EQ(nest.diagnostics.size(), 1u);
    EXPECT_EQ(nest.diagnostics[0].code, "nest.duplicate");
    EXPECT_NE(nest.diagnostics[0].message.find("duplicates contour 0 (entity P, line 5, layer 0) within 0.05 mm everywhere"),
              std::string::npos)
        << nest.diagnostics[0].message;
  }
  const Nest off = build_nest({src(plain), src(polygon({{0, 50}, {0, 0}, {50, 0.2}, {100, 0}, {100, 50}}))}, NestOptions{});
  EXPECT_EQ(off.contours.size(), 2u);
  EXPECT_EQ(off.dropped_duplicates, 0u);
  // A hole 0.1 mm inside a part's outline all round is no copy of it: the boxes differ by more.
  const Nest ring = build_nest({src(plain), src(polygon({{0.1, 0.1}, {99.9, 0.1}, {99.9, 49.9}, {0.1, 49.9}}))}, NestOptions{});
  EXPECT_EQ(ring.contours.size(), 2u);
}

TEST(Nest, ThousandsOfOverlapsAreCountedNotListed) {
  // 300 circles of r = 10 on a line, 1 mm apart: each crosses its neighbours within 20 mm,
  // 19 or so each side: ~5600 crossing pairs.
  std::vector<SourceContour> in;
  for (int i = 0; i < 300; ++i) in.push_back(src(geometry::circle({1.0 * i, 0}, 10)));
  const Nest nest = build_nest(in, NestOptions{});
  ASSERT_EQ(nest.diagnostics.size(), 1001u);
  const std::string& last = nest.diagnostics.back().message;
  EXPECT_NE(last.find("more pairs of contours cross or overlap"), std::string::npos) << last;
  // Neighbours closer than 20 mm cross (error); those exactly 20 mm apart touch (warning).
  std::size_t crossing = 0;
  for (int i = 0; i < 300; ++i) crossing += static_cast<std::size_t>(std::min(299 - i, 19));
  const std::size_t touching = 300 - 20;
  std::size_t listed_errors = 0, listed_warnings = 0;
  for (std::size_t k = 0; k + 1 < nest.diagnostics.size(); ++k) {
    ++(nest.diagnostics[k].severity == Severity::error ? listed_errors : listed_warnings);
  }
  std::size_t unlisted_errors = 0, unlisted_warnings = 0;
  ASSERT_EQ(std::sscanf(last.c_str(), "%zu more pairs of contours cross or overlap and %zu", &unlisted_errors,
                        &unlisted_warnings),
            2);
  EXPECT_EQ(listed_errors + unlisted_errors, crossing);
  EXPECT_EQ(listed_warnings + unlisted_warnings, touching);
  EXPECT_EQ(nest.parts.size(), 300u);
}

TEST(Nest, PointTouchIsAWarningAndStillNests) {
  // Two tangent circles side by side: a warning, both stay top-level parts.
  const Nest side = build_nest({src(geometry::circle({0, 0}, 1), "0", "A"), src(geometry::circle({2, 0}, 1), "0", "B")}, NestOptions{});
  ASSERT_EQ(side.diagnostics.size(), 1u);
  EXPECT_EQ(side.diagnostics[0].severity, Severity::warning);
  EXPECT_EQ(side.parts.size(), 2u);
  // A circle inscribed in a square touches it in 4 points and is its hole.
  const Nest inscribed = build_nest({src(square(2), "0", "SQ"), src(geometry::circle({0, 0}, 2), "0", "IN")}, NestOptions{});
  EXPECT_FALSE(has_errors(inscribed.diagnostics));
  EXPECT_EQ(inscribed.contours[find(inscribed, "IN")].parent, find(inscribed, "SQ"));
  EXPECT_EQ(inscribed.contours[find(inscribed, "IN")].role, ContourRole::hole);
  // A circle crossing the square's corner region: error, no parent.
  const Nest crossing = build_nest({src(square(2), "0", "SQ"), src(geometry::circle({2, 2}, 1), "0", "X")}, NestOptions{});
  ASSERT_EQ(crossing.diagnostics.size(), 1u);
  EXPECT_EQ(crossing.diagnostics[0].severity, Severity::error);
  EXPECT_FALSE(crossing.contours[find(crossing, "X")].parent.valid());
}

TEST(Nest, DuplicatesAndInvalidDroppedWithErrors) {
  const Contour s = square(5);
  Contour rotated_start = s;
  std::rotate(rotated_start.vertices.begin(), rotated_start.vertices.begin() + 2, rotated_start.vertices.end());
  std::vector<SourceContour> in{src(s, "0", "A"), src(geometry::reversed(rotated_start), "0", "B"),
                                src(Contour{s.vertices, false}, "0", "OPEN"), src(square(1), "0", "IN")};
  const Nest nest = build_nest(in, NestOptions{});
  EXPECT_EQ(nest.dropped_duplicates, 1u);
  EXPECT_EQ(nest.dropped_invalid, 1u);
  ASSERT_EQ(nest.contours.size(), 2u);
  EXPECT_EQ(nest.diagnostics.size(), 2u);
  EXPECT_TRUE(has_errors(nest.diagnostics));
  bool named_both = false;
  for (const Diagnostic& d : nest.diagnostics) {
    named_both |= d.message.find("entity A") != std::string::npos && d.message.find("entity B") != std::string::npos;
  }
  EXPECT_TRUE(named_both);
  EXPECT_EQ(nest.contours[find(nest, "IN")].role, ContourRole::hole);
}

TEST(Nest, ZeroAreaContourStaysWithAWarning) {
  // A slot traced there and back inside a square: kept (it is cut), holds nothing.
  const Contour slot{{{{-1, 0}, 0}, {{1, 0}, 0}}, true};
  const Nest nest = build_nest({src(square(5), "0", "SQ"), src(slot, "0", "SLOT")}, NestOptions{});
  ASSERT_EQ(nest.contours.size(), 2u);
  EXPECT_FALSE(has_errors(nest.diagnostics));
  ASSERT_EQ(nest.diagnostics.size(), 1u);
  EXPECT_EQ(nest.diagnostics[0].handle, "SLOT");
  EXPECT_EQ(nest.contours[find(nest, "SLOT")].parent, find(nest, "SQ"));
}

TEST(Nest, RandomNestMatchesBruteForceContainment) {
  // Cells of a grid, each with a random stack of concentric shapes (circles, squares, stadiums)
  // and sometimes two side-by-side children: parents must be the smallest polygon container.
  Rng rng(99);
  std::vector<SourceContour> in;
  for (int cell = 0; cell < 40; ++cell) {
    const Vec2 c{100.0 * (cell % 8), 100.0 * (cell / 8)};
    double size = 45;
    const int depth = static_cast<int>(rng.below(5));
    for (int k = 0; k <= depth; ++k) {
      Contour shape = rng.chance(0.5) ? geometry::circle(c, size, rng.chance(0.5)) : square(size / std::sqrt(2.0) * 0.99, c);
      in.push_back(src(shape, "0", std::to_string(in.size())));
      size *= 0.6;
    }
    if (rng.chance(0.5)) {
      in.push_back(src(geometry::circle(c + Vec2{size * 0.7, 0}, size * 0.25), "0", std::to_string(in.size())));
    }
  }
  rng.shuffle(in.begin(), in.end());
  const Nest nest = build_nest(in, NestOptions{});
  EXPECT_TRUE(nest.diagnostics.empty());
  const std::size_t n = nest.contours.size();
  ASSERT_EQ(n, in.size());
  std::vector<std::vector<Vec2>> polys;
  for (const NestContour& c : nest.contours) polys.push_back(geometry::flatten(c.source.contour, 1e-5));
  for (std::size_t i = 0; i < n; ++i) {
    const NestContour& ci = nest.contours[ContourId(static_cast<int>(i))];
    const Vec2 probe = ci.source.contour.vertices.front().p;
    int best = -1;
    for (std::size_t j = 0; j < n; ++j) {
      const NestContour& cj = nest.contours[ContourId(static_cast<int>(j))];
      if (j == i || cj.area_mm2 <= ci.area_mm2) continue;
      if (!polygon_contains(polys[j], probe)) continue;
      if (best < 0 || cj.area_mm2 < nest.contours[ContourId(best)].area_mm2) best = static_cast<int>(j);
    }
    EXPECT_EQ(ci.parent.value(), best) << "contour " << ci.source.handle;
    // Depth recomputed by walking parents.
    int depth = 0;
    for (ContourId p = ci.parent; p.valid(); p = nest.contours[p].parent) ++depth;
    EXPECT_EQ(ci.depth, depth);
    EXPECT_EQ(ci.role, depth % 2 == 0 ? ContourRole::outer : ContourRole::hole);
  }
  // Each hole is listed in exactly the part of its parent outer.
  std::size_t holes = 0;
  for (const Part& p : nest.parts) {
    for (ContourId h : p.holes) EXPECT_EQ(nest.contours[h].parent, p.outer);
    holes += p.holes.size();
  }
  EXPECT_EQ(holes + nest.parts.size(), n);
}

}  // namespace
}  // namespace cutroute::model
