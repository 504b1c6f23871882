// Multi-segment cutting (ECP) in the model: split points, pieces and precedence, checked against
// facts recomputed here (distances, boundary samples, winding numbers), not against multi_segment.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <cutroute/geometry/intersect.hpp>
#include <cutroute/model/cut_job.hpp>
#include <cutroute/model/multi_segment.hpp>

#include "frame_nest.hpp"
#include "support/nest_facts.hpp"

namespace cutroute::model {
namespace {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

Contour rect(const test::Rect& r) {
  return Contour{{Vertex{{r.x, r.y}, 0}, Vertex{{r.x + r.w, r.y}, 0}, Vertex{{r.x + r.w, r.y + r.h}, 0}, Vertex{{r.x, r.y + r.h}, 0}},
                 true};
}

Nest frame_nest() {
  std::vector<SourceContour> cs;
  for (const auto& r : test::kFrameNest) cs.push_back(SourceContour{rect(r), "0", {}, {}, {}});
  NestOptions no_sheet;
  no_sheet.detect_sheet = false;
  return build_nest(std::move(cs), no_sheet);
}

// The nest contour drawn as rectangle r (found by its box, not by id order).
ContourId contour_of(const Nest& nest, const test::Rect& r) {
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    const auto& b = nest.contours[ContourId(static_cast<std::int32_t>(i))].box;
    if (std::abs(b.xmin - r.x) < 1e-9 && std::abs(b.ymin - r.y) < 1e-9 && std::abs(b.width() - r.w) < 1e-9) {
      return ContourId(static_cast<std::int32_t>(i));
    }
  }
  ADD_FAILURE() << "no contour at " << r.x << ", " << r.y;
  return ContourId();
}

const BasicSegment& standard_segment(const CutJob& job, ContourId c) {
  for (const auto& s : job.segments)
    if (s.contours.size() == 1 && s.contours[0] == c) return s;
  throw std::runtime_error("no standard segment");
}

EntryOptions entry_options(double overcut = 0.0) {
  EntryOptions o;
  o.kerf_mm = 0.15;
  o.lead.in_length_mm = 2.0;
  o.lead.in_arc_radius_mm = 1.0;
  o.lead.out_length_mm = 0.5;
  o.lead.overcut_mm = overcut;
  return o;
}

bool is_piece_segment(const BasicSegment& s) {
  return s.contours.empty() && !s.candidates.empty() && s.candidates.front().pieces.size() == 1 &&
         s.candidates.front().pieces.front().kind == PieceKind::contour_part;
}

// Distance from q to an open path (every segment measured).
double distance_to_path(const Contour& path, Vec2 q) {
  double best = 1e300;
  for (std::size_t i = 0; i < geometry::segment_count(path); ++i)
    best = std::min(best, geometry::closest_point(geometry::segment(path, i), q).distance);
  return best;
}

// The farthest two points of a rectangle are opposite corners: the split is its diagonal.
TEST(MultiSegment, FrameIsSplitAtItsFarthestEntryPoints) {
  const Nest nest = frame_nest();
  const CutJob standard = make_cut_job(nest, entry_options());
  const ContourId frame = contour_of(nest, test::kFrameNest[0]);
  const auto plan = plan_split(nest, frame, standard_segment(standard, frame).candidates, MultiSegmentOptions{});
  ASSERT_TRUE(plan.has_value());
  ASSERT_EQ(plan->s_mm.size(), 2u);
  EXPECT_NEAR(plan->span_mm, std::hypot(1500.0, 80.0), 1e-9);
  // Recomputed from the contour itself: the two arc lengths are opposite corners.
  const double perimeter = 2 * (1500.0 + 80.0);
  const double gap = plan->s_mm[1] - plan->s_mm[0];
  EXPECT_NEAR(std::min(gap, perimeter - gap), 1500.0 + 80.0, 1e-9);
  // The short contours (at most 67 mm across here) are not split.
  for (std::size_t i = 1; i < test::kFrameNest.size(); ++i) {
    const ContourId c = contour_of(nest, test::kFrameNest[i]);
    EXPECT_FALSE(plan_split(nest, c, standard_segment(standard, c).candidates, MultiSegmentOptions{}).has_value());
  }
  // Nothing spans 2 km.
  MultiSegmentOptions far;
  far.min_span_mm = 2000;
  EXPECT_FALSE(plan_split(nest, frame, standard_segment(standard, frame).candidates, far).has_value());
}

// Each piece from either end: a lead-in from scrap ending where the piece starts, the stretch to
// the other split point plus the overcut, a lead-out from there; the pieces cover the contour.
TEST(MultiSegment, PiecesCoverTheContourAndEnterFromScrap) {
  for (double overcut : {0.0, 1.5}) {
    SCOPED_TRACE("overcut " + std::to_string(overcut));
    const Nest nest = frame_nest();
    const EntryOptions opt = entry_options(overcut);
    const CutJob standard = make_cut_job(nest, opt);
    const ContourId frame = contour_of(nest, test::kFrameNest[0]);
    const auto plan = plan_split(nest, frame, standard_segment(standard, frame).candidates, MultiSegmentOptions{});
    ASSERT_TRUE(plan.has_value());
    EntryOptions both = opt;
    both.free_direction = true;
    const EntryPlanner planner(nest, both);
    const auto pieces = split_segments(nest, planner, *plan, opt);
    ASSERT_EQ(pieces.size(), 2u);
    const Contour& drawn = nest.contours[frame].source.contour;
    const Vec2 split[2] = {planner.point_at(frame, plan->s_mm[0]), planner.point_at(frame, plan->s_mm[1])};
    double stretches = 0;
    for (const auto& seg : pieces) {
      EXPECT_TRUE(seg.contours.empty());
      ASSERT_EQ(seg.candidates.size(), 2u) << "a convex corner is entered in both directions";
      EXPECT_NE(seg.candidates[0].clockwise, seg.candidates[1].clockwise);
      double len[2];
      for (std::size_t k = 0; k < 2; ++k) {
        const auto& e = seg.candidates[k];
        ASSERT_EQ(e.pieces.size(), 1u);
        const auto& path = e.pieces.front().path;
        EXPECT_EQ(e.pieces.front().kind, PieceKind::contour_part);
        EXPECT_EQ(e.pieces.front().contour, frame);
        ASSERT_GE(path.vertices.size(), 2u);
        const Vec2 start = path.vertices.front().p;
        // Starts on a split point, where the lead-in ends.
        EXPECT_LT(std::min(geometry::distance(start, split[0]), geometry::distance(start, split[1])), 1e-9);
        ASSERT_GE(e.lead_in.vertices.size(), 2u);
        EXPECT_LT(geometry::distance(e.lead_in.vertices.back().p, start), 1e-9);
        EXPECT_FALSE(test::in_material(nest, e.pierce));
        for (int j = 1; j < 10; ++j)
          EXPECT_FALSE(test::in_material(nest, geometry::point_at_length(e.lead_in, geometry::length(e.lead_in) * j / 10.0)));
        // Ends `overcut` past the other split point, on the contour, where the lead-out starts.
        const Vec2 other = geometry::distance(start, split[0]) < 1e-9 ? split[1] : split[0];
        len[k] = geometry::length(path) - overcut;
        EXPECT_LT(distance_to_path(path, other), 1e-9);
        EXPECT_LT(geometry::distance(geometry::point_at_length(path, len[k]), other), 1e-6);
        for (const auto& v : path.vertices) EXPECT_LT(geometry::distance(drawn, v.p), 1e-9);
        if (!e.lead_out.vertices.empty()) {
          EXPECT_LT(geometry::distance(e.lead_out.vertices.front().p, path.vertices.back().p), 1e-9);
        }
      }
      EXPECT_NEAR(len[0], len[1], 1e-9) << "both ways cut the same stretch";
      stretches += len[0];
    }
    EXPECT_NEAR(stretches, geometry::length(drawn), 1e-9);
    // Every boundary point lies on one of the two pieces (sampled every 0.5 mm).
    for (const Vec2 q : test::boundary_samples(drawn, 0.5)) {
      const double d = std::min(distance_to_path(pieces[0].candidates[0].pieces[0].path, q),
                                distance_to_path(pieces[1].candidates[0].pieces[0].path, q));
      ASSERT_LT(d, 1e-9) << "boundary point " << q.x << ", " << q.y << " is cut by no piece";
    }
  }
}

// The hole (and the part inside it) come before every piece of the frame around them.
TEST(MultiSegment, HolesAndInnerPartsComeBeforeEveryPiece) {
  const Nest nest = frame_nest();
  const auto job = make_multi_job(nest, entry_options(), MultiSegmentOptions{});
  ASSERT_TRUE(job.ok()) << job.error().message;
  ASSERT_EQ(job->segments.size(), test::kFrameNest.size() + 1);
  const ContourId hole = contour_of(nest, test::kFrameNest[1]), inner = contour_of(nest, test::kFrameNest[2]);
  // Containment recomputed by winding number: hole inside the frame, the inner part inside the hole.
  const Contour& frame_c = nest.contours[contour_of(nest, test::kFrameNest[0])].source.contour;
  EXPECT_EQ(geometry::locate(frame_c, nest.contours[hole].source.contour.vertices[0].p, 1e-9), geometry::Location::inside);
  EXPECT_EQ(geometry::locate(nest.contours[hole].source.contour, nest.contours[inner].source.contour.vertices[0].p, 1e-9),
            geometry::Location::inside);
  std::int32_t hole_seg = -1, inner_seg = -1;
  std::vector<std::int32_t> piece_segs;
  for (std::size_t k = 0; k < job->segments.size(); ++k) {
    const auto& s = job->segments[k];
    if (is_piece_segment(s)) piece_segs.push_back(static_cast<std::int32_t>(k));
    if (s.contours.size() == 1 && s.contours[0] == hole) hole_seg = static_cast<std::int32_t>(k);
    if (s.contours.size() == 1 && s.contours[0] == inner) inner_seg = static_cast<std::int32_t>(k);
  }
  ASSERT_EQ(piece_segs.size(), 2u);
  const auto& prec = job->precedence;
  auto before = [&](std::int32_t a, std::int32_t b) { return std::find(prec.begin(), prec.end(), std::pair{a, b}) != prec.end(); };
  EXPECT_TRUE(before(inner_seg, hole_seg));
  for (auto p : piece_segs) {
    EXPECT_TRUE(before(hole_seg, p));
    for (const auto& [a, b] : prec) EXPECT_NE(a, p) << "a piece of the frame must precede nothing";
  }
}

// Three pieces: the farthest-point sequence keeps its split points at least the span apart.
TEST(MultiSegment, ThreePiecesKeepTheSpanBetweenTheirSplitPoints) {
  const Nest nest = frame_nest();
  MultiSegmentOptions three;
  three.max_pieces = 3;
  const auto job = make_multi_job(nest, entry_options(), three);
  ASSERT_TRUE(job.ok()) << job.error().message;
  std::vector<Vec2> starts;
  double total = 0;
  int pieces = 0;
  for (const auto& s : job->segments) {
    if (!is_piece_segment(s)) continue;
    ++pieces;
    const auto& e = s.candidates.front();
    starts.push_back(e.pieces.front().path.vertices.front().p);
    total += geometry::length(e.pieces.front().path);
  }
  ASSERT_EQ(pieces, 3);
  EXPECT_NEAR(total, 2 * (1500.0 + 80.0), 1e-9);
  for (std::size_t i = 0; i < starts.size(); ++i)
    for (std::size_t j = i + 1; j < starts.size(); ++j) EXPECT_GE(geometry::distance(starts[i], starts[j]), 300.0);
}

TEST(MultiSegment, NoLongContourMeansNotAvailable) {
  const Nest nest = frame_nest();
  MultiSegmentOptions far;
  far.min_span_mm = 2000;
  const auto job = make_multi_job(nest, entry_options(), far);
  ASSERT_FALSE(job.ok());
  EXPECT_NE(job.error().message.find("multi-segment cutting not available"), std::string::npos) << job.error().message;
}

}  // namespace
}  // namespace cutroute::model
