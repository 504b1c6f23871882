// Toolpath post-passes of the shop rules: micro-joints (arcs split exactly) and rapid detours.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <cutroute/geometry/shapes.hpp>
#include <cutroute/model/nest.hpp>
#include <cutroute/nc/micro_joints.hpp>
#include <cutroute/nc/rapid_detours.hpp>

namespace cutroute::nc {
namespace {

using geometry::Vec2;

model::Nest nest_of(const std::vector<geometry::Contour>& outers) {
  std::vector<model::SourceContour> src;
  for (const auto& c : outers) {
    model::SourceContour s;
    s.contour = c;
    src.push_back(s);
  }
  model::NestOptions o;
  o.detect_sheet = false;
  return model::build_nest(std::move(src), o);
}

// One segment per outer contour: pierce on the contour, the whole contour from vertex 0, no leads.
Toolpath whole_contours(const model::Nest& nest) {
  Toolpath tp;
  for (const auto& part : nest.parts) {
    CutSegment s;
    geometry::Contour open = nest.contours[part.outer].source.contour;
    open.vertices.push_back({open.vertices.front().p, 0.0});
    open.closed = false;
    s.pierce = open.vertices.front().p;
    s.pieces.push_back({open, PieceRole::contour, part.outer.value()});
    tp.segments.push_back(std::move(s));
  }
  return tp;
}

TEST(MicroJoints, CircleGetsNGapsOfWidthWAlongTheArc) {
  const double r = 20;
  const auto nest = nest_of({geometry::circle({50, 50}, r)});
  ASSERT_EQ(nest.parts.size(), 1u);
  Toolpath tp = whole_contours(nest);
  const int n = 4;
  const double w = 2.0;
  const auto st = add_micro_joints(tp, nest, {n, w, {}, {}});
  EXPECT_EQ(st.contours, 1);
  EXPECT_EQ(st.tabs, n);
  ASSERT_EQ(tp.segments.size(), static_cast<std::size_t>(n + 1));
  double cut = 0;
  for (std::size_t k = 0; k < tp.segments.size(); ++k) {
    const auto& piece = tp.segments[k].pieces.front().path;
    cut += geometry::length(piece);
    // Every point of every piece stays on the circle (arcs split exactly, not flattened).
    for (double t : {0.0, 0.3, 0.7, 1.0}) {
      const Vec2 p = geometry::point_at_length(piece, t * geometry::length(piece));
      EXPECT_NEAR(geometry::distance(p, {50, 50}), r, 1e-9);
    }
    if (k > 0) {
      // The gap before this piece: from the previous end to this pierce, w along the circle.
      const Vec2 a = tp.segments[k - 1].pieces.back().path.vertices.back().p, b = tp.segments[k].pierce;
      const double chord = geometry::distance(a, b);
      EXPECT_NEAR(2 * r * std::asin(chord / (2 * r)), w, 1e-9);
    }
  }
  EXPECT_NEAR(cut, 2 * std::numbers::pi * r - n * w, 1e-9);
}

geometry::Contour open_path(std::initializer_list<Vec2> points) {
  geometry::Contour c;
  c.closed = false;
  for (const Vec2 p : points) c.vertices.push_back({p, 0.0});
  return c;
}

// Common lines: parts A (0..100 x 0..50) and B (100..200 x 0..50) share the edge x = 100, cut once
// by a trail; the group's outline runs A's own edges from (100, 0), a 2-mm piece first (the loop's
// entry stretch), then B's. Each part's gaps are spread over its own pieces' usable length, at
// least max(w, 1 mm) + w/2 from a piece's ends: A (w = 2, N = 2): pieces of 2 and 248 mm, the
// first too short, usable 248 - 6 = 242, gaps centred 3 + 60.5 and 3 + 181.5 mm into the second.
// The common line keeps no gap.
TEST(MicroJoints, CommonLinesGapsGoOnEachPartsOwnEdgesAwayFromTheJunctions) {
  const auto nest = nest_of({geometry::rectangle({0, 0, 100, 50}), geometry::rectangle({100, 0, 200, 50})});
  ASSERT_EQ(nest.parts.size(), 2u);
  const std::int32_t a = nest.parts[model::PartId(0)].outer.value(), b = nest.parts[model::PartId(1)].outer.value();
  ASSERT_LT(nest.contours[model::ContourId(a)].box.xmax, 150);
  Toolpath tp;
  CutSegment trail;
  trail.pierce = {100, -3};
  trail.pieces.push_back({open_path({{100, -3}, {100, 0}}), PieceRole::lead_in, -1});
  trail.pieces.push_back({open_path({{100, 0}, {100, 50}}), PieceRole::contour, a, b});
  tp.segments.push_back(trail);
  CutSegment loop;
  loop.pierce = {100, -3};
  loop.pieces.push_back({open_path({{100, -3}, {100, 0}}), PieceRole::lead_in, -1});
  loop.pieces.push_back({open_path({{100, 0}, {98, 0}}), PieceRole::contour, a});
  loop.pieces.push_back({open_path({{98, 0}, {0, 0}, {0, 50}, {100, 50}}), PieceRole::contour, a});
  loop.pieces.push_back({open_path({{100, 50}, {200, 50}, {200, 0}, {100, 0}}), PieceRole::contour, b});
  tp.segments.push_back(loop);
  const auto st = add_micro_joints(tp, nest, {2, 2.0, {}, {}});
  EXPECT_EQ(st.contours, 2);
  EXPECT_EQ(st.tabs, 4);
  EXPECT_EQ(st.skipped, 0);
  EXPECT_TRUE(st.enclosed.empty());
  // The trail, then the outline in 5 segments (4 gaps).
  ASSERT_EQ(tp.segments.size(), 1u + 5u);
  EXPECT_EQ(tp.segments[0].pieces.size(), 2u);
  std::vector<Vec2> centres;
  for (std::size_t k = 2; k < tp.segments.size(); ++k) {
    const Vec2 end = tp.segments[k - 1].pieces.back().path.vertices.back().p, resume = tp.segments[k].pierce;
    EXPECT_NEAR(geometry::distance(end, resume), 2.0, 1e-9);
    EXPECT_TRUE(tp.segments[k].after_tab);
    centres.push_back((end + resume) * 0.5);
  }
  // B: one piece of 250 mm, usable 244, gaps 3 + 61 and 3 + 183 mm into it.
  const std::vector<Vec2> want{{98 - 63.5, 0}, {36.5, 50}, {164, 50}, {164, 0}};
  ASSERT_EQ(centres.size(), want.size());
  for (std::size_t k = 0; k < want.size(); ++k) {
    EXPECT_NEAR(centres[k].x, want[k].x, 1e-9) << k;
    EXPECT_NEAR(centres[k].y, want[k].y, 1e-9) << k;
  }

  // A part whose whole outline is shared gets none, and is named.
  Toolpath shared;
  CutSegment all;
  all.pierce = {0, 0};
  all.pieces.push_back({open_path({{0, 0}, {100, 0}, {100, 50}, {0, 50}, {0, 0}}), PieceRole::contour, a, b});
  shared.segments.push_back(all);
  const auto none = add_micro_joints(shared, nest, {2, 2.0, {}, {}});
  EXPECT_EQ(none.tabs, 0);
  EXPECT_EQ(none.skipped, 2);
  EXPECT_EQ(none.enclosed, (std::vector<std::int32_t>{a, b}));
  EXPECT_EQ(shared.segments.size(), 1u);
}

// A gap where `holds` says no (a neighbour's cut along that edge) moves by max(w, 1 mm) at a time,
// further on first, to the nearest place that holds, up to half the spacing less w; where none
// does it stays and is counted. 100 mm square from (0, 0), N = 2, w = 2: gaps at 100 and 300 mm;
// nothing holds over 60-160 mm, so the first moves to 58 (back 42) rather than 162 (on 62).
TEST(MicroJoints, GapsMoveOffEdgesWhereTheyHoldNothing) {
  const auto nest = nest_of({geometry::rectangle({0, 0, 100, 100})});
  Toolpath tp = whole_contours(nest);
  const geometry::Contour loop = tp.segments.front().pieces.front().path;
  auto along = [&](Vec2 p) { return geometry::closest_point(loop, p).length_along; };
  MicroJointOptions o{2, 2.0, {}, [&](std::int32_t, const geometry::Contour& gap) {
                        return along(gap.vertices.back().p) < 60 || along(gap.vertices.front().p) > 160;
                      }};
  const auto st = add_micro_joints(tp, nest, o);
  EXPECT_EQ(st.tabs, 2);
  EXPECT_EQ(st.unheld, 0);
  ASSERT_EQ(tp.segments.size(), 3u);
  EXPECT_NEAR(along(tp.segments[1].pierce), 59, 1e-9);
  EXPECT_NEAR(along(tp.segments[2].pierce), 301, 1e-9);

  Toolpath nowhere = whole_contours(nest);
  const auto none = add_micro_joints(nowhere, nest, {2, 2.0, {}, [](std::int32_t, const geometry::Contour&) { return false; }});
  EXPECT_EQ(none.unheld, 2);
  ASSERT_EQ(nowhere.segments.size(), 3u);
  EXPECT_NEAR(along(nowhere.segments[1].pierce), 101, 1e-9);
}

// Under controller compensation a cut resumed just before a corner starts with a move too short
// to offset: gap ends keep corner_clearance_mm from corners where a place within reach allows.
// 100 mm square, N = 2, w = 2: gaps centred on the corners at 100 and 300 mm end 1 mm from them;
// with 1.5 mm they move on to 104 and 304 (102 and 98 leave an end 1 mm off the corner).
TEST(MicroJoints, GapEndsKeepOffCorners) {
  const auto nest = nest_of({geometry::rectangle({0, 0, 100, 100})});
  const geometry::Contour loop = whole_contours(nest).segments.front().pieces.front().path;
  auto along = [&](Vec2 p) { return geometry::closest_point(loop, p).length_along; };
  for (const double clearance : {0.0, 1.5}) {
    Toolpath tp = whole_contours(nest);
    const auto st = add_micro_joints(tp, nest, {2, 2.0, {}, {}, clearance});
    EXPECT_EQ(st.tabs, 2);
    ASSERT_EQ(tp.segments.size(), 3u);
    const double moved = clearance > 0 ? 4 : 0;
    EXPECT_NEAR(along(tp.segments[1].pierce), 101 + moved, 1e-9) << clearance;
    EXPECT_NEAR(along(tp.segments[2].pierce), 301 + moved, 1e-9) << clearance;
  }
}

TEST(MicroJoints, TooShortContoursStayWholeAndHolesAreNeverTabbed) {
  auto outer = geometry::rectangle({0, 0, 100, 100});
  auto hole = geometry::rectangle({40, 40, 60, 60});
  auto tiny = geometry::rectangle({120, 0, 123, 3});
  const auto nest = nest_of({outer, hole, tiny});
  Toolpath tp = whole_contours(nest);
  // The hole as its own segment too.
  CutSegment hs;
  geometry::Contour h = hole;
  h.vertices.push_back({h.vertices.front().p, 0.0});
  h.closed = false;
  hs.pierce = h.vertices.front().p;
  model::ContourId hole_id;
  for (std::size_t i = 0; i < nest.contours.size(); ++i)
    if (nest.contours[model::ContourId(static_cast<std::int32_t>(i))].role == model::ContourRole::hole) hole_id = model::ContourId(static_cast<std::int32_t>(i));
  ASSERT_TRUE(hole_id.valid());
  hs.pieces.push_back({h, PieceRole::contour, hole_id.value()});
  tp.segments.insert(tp.segments.begin(), hs);
  const auto st = add_micro_joints(tp, nest, {2, 4.0, {}, {}});  // tiny: 12 mm < 2 * 2 * 4 mm
  EXPECT_EQ(st.contours, 1);
  EXPECT_EQ(st.skipped, 1);
  EXPECT_EQ(tp.segments.size(), 1u + 3u + 1u);
}

// With lead-ins the cut after each gap starts with the lead-in the callback gives; a gap whose
// resumed cut gets none is moved along the contour (by a gap width or 1 mm at a time, further on
// first, up to a quarter of the spacing less a gap width) to the nearest place that gets one.
TEST(MicroJoints, LeadInsAfterGapsAndGapsMovedToWhereOneFits) {
  const auto nest = nest_of({geometry::rectangle({0, 0, 100, 100})});
  Toolpath tp = whole_contours(nest);
  const geometry::Contour loop = tp.segments.front().pieces.front().path;  // 400 mm from its first vertex
  auto along = [&](Vec2 p) { return geometry::closest_point(loop, p).length_along; };
  const double w = 2.0;
  // The callback stands for the entry planner: a 3-mm lead wherever the cut resumes 90-100 mm or
  // 290-310 mm along the loop, no room elsewhere.
  std::vector<double> asked;
  MicroJointOptions o{2, w, [&](std::int32_t, const geometry::Contour& resumed) -> std::optional<geometry::Contour> {
                        const double s = along(resumed.vertices.front().p);
                        asked.push_back(s);
                        if (!((s >= 90 && s < 100) || (s >= 290 && s <= 310))) return std::nullopt;
                        geometry::Contour lead;
                        lead.closed = false;
                        lead.vertices = {{resumed.vertices.front().p + Vec2{0, -3}, 0.0}, {resumed.vertices.front().p, 0.0}};
                        return lead;
                      },
                      {}};
  const auto st = add_micro_joints(tp, nest, o);
  EXPECT_EQ(st.tabs, 2);
  EXPECT_EQ(st.lead_ins, 2);
  EXPECT_EQ(st.on_path, 0);
  // Gap 1 (centre 100: the cut resumes at 101) moves: 103 refused, then 99; gap 2 (301) stays.
  ASSERT_EQ(asked.size(), 4u);
  EXPECT_NEAR(asked[0], 101, 1e-9);
  EXPECT_NEAR(asked[1], 103, 1e-9);
  EXPECT_NEAR(asked[2], 99, 1e-9);
  EXPECT_NEAR(asked[3], 301, 1e-9);
  ASSERT_EQ(tp.segments.size(), 3u);
  for (std::size_t k = 1; k < tp.segments.size(); ++k) {
    const auto& seg = tp.segments[k];
    ASSERT_EQ(seg.pieces.size(), 2u);
    EXPECT_EQ(seg.pieces[0].role, PieceRole::lead_in);
    EXPECT_FALSE(seg.after_tab);
    EXPECT_EQ(seg.pierce, seg.pieces[0].path.vertices.front().p);
    const Vec2 resume = seg.pieces[1].path.vertices.front().p;
    EXPECT_EQ(seg.pieces[0].path.vertices.back().p, resume) << "the lead ends where the cut resumes";
    // Every gap is w long along the loop, wherever it went.
    const Vec2 end_before = tp.segments[k - 1].pieces.back().path.vertices.back().p;
    EXPECT_NEAR(along(resume) - along(end_before), w, 1e-9);
    EXPECT_NEAR(along(resume), k == 1 ? 99 : 301, 1e-9);
  }
  EXPECT_NEAR(along(tp.segments.back().pieces.back().path.vertices.back().p), 0, 1e-9) << "the last piece ends the loop";
}

TEST(RapidDetours, CrossingIsDetectedCornerToCornerAndDetourKeepsClear) {
  const auto nest = nest_of({geometry::rectangle({10, 10, 30, 30}), geometry::rectangle({50, 50, 70, 70})});
  const PartObstacles obs(nest, 2.0);
  // Exactly through two corners of the first square: a crossing test alone would miss it.
  EXPECT_TRUE(obs.crosses(0, {0, 0}, {40, 40}));
  EXPECT_FALSE(obs.crosses(0, {0, 40}, {40, 40}));
  EXPECT_FALSE(obs.crosses(0, {0, 30}, {40, 30}));  // along an edge: touching is not passing over
  EXPECT_EQ(obs.crossed({0, 0}, {80, 80}), (std::vector<int>{0, 1}));
  std::vector<char> freed{1, 1};
  const auto via = obs.detour({0, 0}, {80, 80}, freed);
  ASSERT_TRUE(via.has_value());
  ASSERT_FALSE(via->empty());
  Vec2 at{0, 0};
  std::vector<Vec2> legs = *via;
  legs.push_back({80, 80});
  double len = 0;
  for (const auto& p : legs) {
    EXPECT_TRUE(obs.crossed(at, p).empty()) << "leg to (" << p.x << ", " << p.y << ")";
    // Independent check: samples of every leg keep the 2 mm margin from both squares (Euclidean).
    for (int s = 0; s <= 100; ++s) {
      const Vec2 q = at + (p - at) * (s / 100.0);
      for (const geometry::Box b : {geometry::Box{10, 10, 30, 30}, geometry::Box{50, 50, 70, 70}}) {
        const double dx = std::max({0.0, b.xmin - q.x, q.x - b.xmax}), dy = std::max({0.0, b.ymin - q.y, q.y - b.ymax});
        EXPECT_GE(std::hypot(dx, dy), 2.0 - 1e-9) << "(" << q.x << ", " << q.y << ")";
      }
    }
    len += geometry::distance(at, p);
    at = p;
  }
  EXPECT_LT(len, std::hypot(80, 80) * 1.3);
  // Nothing freed: no detour needed.
  const std::vector<char> none{0, 0};
  EXPECT_TRUE(obs.detour({0, 0}, {80, 80}, none)->empty());
}

// A 10 x 10 grid of squares cut row by row, the second half in reverse: its rapids run back across
// the freed half. With a margin of a metre every freed part is in every detour leg's way.
struct FreedGrid {
  model::Nest nest;
  Toolpath path;
  FreedGrid() {
    std::vector<geometry::Contour> grid;
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j) grid.push_back(geometry::rectangle({i * 30.0, j * 30.0, i * 30.0 + 10, j * 30.0 + 10}));
    nest = nest_of(grid);
    path = whole_contours(nest);
    std::reverse(path.segments.begin() + 50, path.segments.end());
  }
  // Rapids (the park move included) whose straight line passes over a part cut before them,
  // counted with PartObstacles::crossed() alone.
  int rapids_over_freed() const {
    const PartObstacles obs(nest, 1000.0);
    std::vector<char> freed(nest.parts.size(), 0);
    int over = 0;
    auto count = [&](Vec2 a, Vec2 b) {
      const auto hit = obs.crossed(a, b);
      over += std::any_of(hit.begin(), hit.end(), [&](int k) { return freed[static_cast<std::size_t>(k)] != 0; });
    };
    Vec2 at = path.start;
    for (const auto& seg : path.segments) {
      count(at, seg.pierce);
      freed[nest.contours[model::ContourId(seg.pieces.front().contour)].part.index()] = 1;
      at = tool_off_point(seg);
    }
    count(at, path.end);
    return over;
  }
};

// Found by fuzzing: with a margin of a metre every part is in every leg's way, and the searches of
// 3 000 small parts ran for minutes past the time limit. A spent budget gives up (left straight).
TEST(RapidDetours, SearchGivesUpWhenItsBudgetIsSpent) {
  const auto nest = nest_of({geometry::rectangle({10, 10, 30, 30}), geometry::rectangle({50, 50, 70, 70})});
  const PartObstacles obs(nest, 2.0);
  const std::vector<char> freed{1, 1};
  std::size_t plenty = 1'000'000;
  const auto via = obs.detour({0, 0}, {80, 80}, freed, &plenty);
  ASSERT_TRUE(via.has_value());
  EXPECT_FALSE(via->empty());
  const std::size_t used = 1'000'000 - plenty;
  EXPECT_GT(used, 2u);
  std::size_t short_budget = used / 2;
  EXPECT_FALSE(obs.detour({0, 0}, {80, 80}, freed, &short_budget).has_value());
  EXPECT_EQ(short_budget, 0u);
  std::size_t exact = used;
  EXPECT_EQ(obs.detour({0, 0}, {80, 80}, freed, &exact), via);  // the same route with just enough
  // The post pass counts rapids it left straight for want of budget among the unavoidable ones.
  FreedGrid g;
  const auto st = route_rapids_around_freed_parts(g.path, g.nest, 1000.0, StopToken{});
  EXPECT_EQ(st.rapids_over_freed, g.rapids_over_freed());
  EXPECT_EQ(st.detours + st.unavoidable, st.rapids_over_freed);
  EXPECT_LE(st.over_budget, st.unavoidable);
  EXPECT_EQ(st.left_at_time_limit, 0);  // a token without deadline, not cancelled
}

// A run stopped (its deadline passed, or SIGINT/SIGTERM) before the post-pass: no search runs and
// every rapid over a freed part stays straight, counted as left at the time limit.
void expect_every_rapid_left_straight(const StopToken& stop) {
  FreedGrid g;
  const int over = g.rapids_over_freed();
  ASSERT_GT(over, 10);
  const auto st = route_rapids_around_freed_parts(g.path, g.nest, 1000.0, stop);
  EXPECT_EQ(st.rapids_over_freed, over);
  EXPECT_EQ(st.left_at_time_limit, over);
  EXPECT_EQ(st.unavoidable, over);
  EXPECT_EQ(st.detours, 0);
  EXPECT_EQ(st.over_budget, 0);
  EXPECT_EQ(st.extra_mm, 0.0);
  for (const auto& seg : g.path.segments) EXPECT_TRUE(seg.rapid_via.empty());
  EXPECT_TRUE(g.path.end_via.empty());
  // A search handed such a token gives up before its first leg-part test.
  const PartObstacles obs(g.nest, 1000.0);
  const std::vector<char> freed(g.nest.parts.size(), 1);
  std::size_t tests_left = 1'000'000;
  EXPECT_FALSE(obs.detour({-20, -20}, {320, 320}, freed, &tests_left, &stop).has_value());
  EXPECT_EQ(tests_left, 1'000'000u);
}

TEST(RapidDetours, ExpiredDeadlineLeavesEveryRapidOverAFreedPartStraight) {
  const StopToken expired = StopToken{}.with_time_limit(-1.0);  // a deadline a second ago
  ASSERT_TRUE(expired.deadline_passed());
  expect_every_rapid_left_straight(expired);
}

TEST(RapidDetours, CancelledRunLeavesEveryRapidOverAFreedPartStraight) {
  const StopToken cancelled;
  cancelled.request_stop();
  expect_every_rapid_left_straight(cancelled);
}

TEST(RapidDetours, PostPassRoutesOnlyAroundPartsAlreadyCut) {
  const auto nest = nest_of({geometry::rectangle({10, 10, 30, 30}), geometry::rectangle({50, 50, 70, 70})});
  Toolpath tp = whole_contours(nest);  // part 1 cut first from (10,10), then part 2 from (50,50)
  tp.start = {0, 0};
  tp.end = {0, 0};
  const auto st = route_rapids_around_freed_parts(tp, nest, 2.0, StopToken{});
  // (0,0) -> (10,10): nothing free yet. (10,10) -> (50,50): runs diagonally over part 1, now free
  // -> detour. Back from (50,50) to (0,0): over both -> detour.
  EXPECT_TRUE(tp.segments[0].rapid_via.empty());
  EXPECT_FALSE(tp.segments[1].rapid_via.empty());
  EXPECT_EQ(st.rapids_over_freed, 2);
  EXPECT_EQ(st.detours, 2);
  EXPECT_EQ(st.unavoidable, 0);
  EXPECT_FALSE(tp.end_via.empty());
  EXPECT_GT(st.extra_mm, 0);
}

}  // namespace
}  // namespace cutroute::nc
