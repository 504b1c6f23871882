// Entries of common-line segments: every pierce and lead in scrap (checked by an independent
// parity test on the original parts), trails entered from the outside of their group.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <cutroute/geometry/shapes.hpp>
#include <cutroute/model/common_lines.hpp>

namespace cutroute::model {
namespace {

using geometry::Box;
using geometry::Contour;
using geometry::Vec2;

Nest nest_on_sheet(const std::vector<Contour>& parts) {
  std::vector<SourceContour> in;
  in.push_back(SourceContour{geometry::rectangle(Box{-50, -50, 600, 400}), "sheet", {}, {}, {}});
  for (const auto& c : parts) in.push_back(SourceContour{c, "0", {}, {}, {}});
  return build_nest(std::move(in), NestOptions{});
}

// Inside the material of some part: inside an odd number of part contours (crossing-number test
// on a flattened copy, not the library's winding code).
bool in_material(const Nest& nest, Vec2 p) {
  int inside = 0;
  for (const auto& c : nest.contours) {
    if (c.role == ContourRole::sheet) continue;
    const auto poly = geometry::flatten(c.source.contour, 1e-4);
    bool in = false;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
      if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
          p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
        in = !in;
    inside += in;
  }
  return inside % 2 == 1;
}

// Lead points, all but the last `skip` mm (where it meets the cut), lie in scrap.
void expect_lead_in_scrap(const Nest& nest, const Contour& lead, double skip, bool skip_at_end) {
  if (lead.vertices.size() < 2) return;
  const double len = geometry::length(lead);
  for (int k = 0; k <= 50; ++k) {
    const double s = len * k / 50.0;
    if (skip_at_end ? s > len - skip : s < skip) continue;
    const Vec2 p = geometry::point_at_length(lead, s);
    EXPECT_FALSE(in_material(nest, p)) << "lead point (" << p.x << ", " << p.y << ") inside a part";
  }
}

void check_entries(const Nest& nest, const CommonLinePlan& plan, const EntryOptions& opt) {
  Diagnostics diags;
  const auto entries = plan_common_entries(nest, plan, opt, diags);
  ASSERT_EQ(entries.size(), plan.segments.size());
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    const auto& seg = plan.segments[i];
    ASSERT_FALSE(entries[i].empty()) << i;
    for (const auto& e : entries[i]) {
      // The cut path is the segment (plus the overcut on closed ones), from the entry point.
      const double len = geometry::length(seg.path);
      EXPECT_NEAR(pieces_length(e), seg.path.closed ? len + opt.lead.overcut_mm : len, 1e-6);
      ASSERT_FALSE(e.pieces.empty());
      EXPECT_LT(geometry::distance(e.pieces.front().path.vertices.front().p, e.point), 1e-9);
      for (std::size_t k = 1; k < e.pieces.size(); ++k)
        EXPECT_LT(geometry::distance(e.pieces[k - 1].path.vertices.back().p, e.pieces[k].path.vertices.front().p), 1e-6);
      // What each piece is: trails only common edges (and connectors), loops only boundary pieces.
      for (const auto& p : e.pieces) {
        if (p.kind == PieceKind::bridge) continue;
        EXPECT_EQ(p.kind, seg.kind == CommonSegmentKind::trail ? PieceKind::common_edge : PieceKind::contour);
        EXPECT_TRUE(std::binary_search(seg.contours.begin(), seg.contours.end(), p.contour));
      }
      ASSERT_TRUE(e.contour.valid());
      if (e.fallback == Fallback::on_contour) continue;
      EXPECT_FALSE(in_material(nest, e.pierce));
      ASSERT_GE(e.lead_in.vertices.size(), 2u);
      EXPECT_LT(geometry::distance(e.lead_in.vertices.back().p, e.point), 1e-9);
      expect_lead_in_scrap(nest, e.lead_in, 0.05, true);
      expect_lead_in_scrap(nest, e.lead_out, 0.05, false);
      if (seg.kind == CommonSegmentKind::trail) {
        // Entered from an end on the group's outer boundary, in the direction allowed there.
        const bool at_start = geometry::distance(e.point, seg.path.vertices.front().p) < 1e-9;
        EXPECT_TRUE(at_start ? seg.enter_at_start && seg.start_on_loop : seg.enter_at_end && seg.end_on_loop);
      }
    }
  }
}

Contour rect(double x0, double y0, double x1, double y1) { return geometry::rectangle(Box{x0, y0, x1, y1}); }

TEST(CommonEntries, GridAndLoosePart) {
  const Nest nest = nest_on_sheet({rect(0, 0, 100, 60), rect(100, 0, 200, 60), rect(0, 60, 100, 120),
                                   rect(100, 60, 200, 120), rect(300, 0, 400, 100), geometry::circle({350, 50}, 20)});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  EXPECT_EQ(plan.segments.size(), 2u + 1u + 2u);  // loose part and its hole, one loop, two trails
  check_entries(nest, plan, EntryOptions{});
  Diagnostics diags;
  const auto entries = plan_common_entries(nest, plan, EntryOptions{}, diags);
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    if (plan.segments[i].kind == CommonSegmentKind::trail) {
      // Both ends of a straight line through the grid can be entered, with the full straight lead.
      ASSERT_GE(entries[i].size(), 2u);
      for (const auto& e : entries[i]) {
        EXPECT_EQ(e.fallback, Fallback::none);
        EXPECT_FALSE(e.lead_out.vertices.empty());
      }
    }
    if (plan.segments[i].kind == CommonSegmentKind::contour) {
      for (const auto& e : entries[i]) EXPECT_EQ(e.contour, plan.segments[i].contours.front());
    }
  }
}

// A part 1.5 mm above the common line's upper end: the lead there must turn or shrink, never run
// into that part; the clearance to it is kept.
TEST(CommonEntries, NeighbourBlocksStraightLead) {
  const Contour blocker = rect(90, 61.5, 110, 90);
  const Nest nest = nest_on_sheet({rect(0, 0, 100, 60), rect(100, 0, 200, 60), blocker});
  const auto plan = plan_common_lines(nest, CommonLineOptions{});
  EntryOptions opt;
  check_entries(nest, plan, opt);
  Diagnostics diags;
  const auto entries = plan_common_entries(nest, plan, opt, diags);
  const double clearance = opt.kerf_mm + 1.0;
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    if (plan.segments[i].kind == CommonSegmentKind::trail) {
      // No lead fits at the upper end (1.5 mm below the neighbour): entered from below only.
      ASSERT_FALSE(entries[i].empty());
      for (const auto& e : entries[i]) {
        EXPECT_EQ(e.fallback, Fallback::none);
        EXPECT_NEAR(e.point.y, 0, 1e-9);
      }
    }
    if (plan.segments[i].kind == CommonSegmentKind::contour) continue;  // the neighbour's own leads
    for (const auto& e : entries[i])
      for (const auto* lead : {&e.lead_in, &e.lead_out}) {
        if (lead->vertices.size() < 2) continue;
        for (int k = 0; k <= 50; ++k) {
          const Vec2 p = geometry::point_at_length(*lead, geometry::length(*lead) * k / 50.0);
          EXPECT_GE(geometry::distance(blocker, p), clearance - 1e-9)
              << "lead near the neighbour: " << to_string(plan.segments[i].kind) << (lead == &e.lead_in ? " in " : " out ")
              << to_string(e.fallback) << " at (" << p.x << ", " << p.y << ")";
        }
      }
  }
}

// Parts drawn kerf apart: the trail's lead runs down the middle of the gap's extension.
TEST(CommonEntries, KerfGapRow) {
  const double k = 0.2;
  const Nest nest = nest_on_sheet({rect(0, 0, 100, 50), rect(100 + k, 0, 200 + k, 50)});
  CommonLineOptions co;
  co.kerf_mm = k;
  EntryOptions opt;
  opt.kerf_mm = k;
  const auto plan = plan_common_lines(nest, co);
  check_entries(nest, plan, opt);
  Diagnostics diags;
  const auto entries = plan_common_entries(nest, plan, opt, diags);
  for (std::size_t i = 0; i < plan.segments.size(); ++i)
    if (plan.segments[i].kind == CommonSegmentKind::trail) {
      ASSERT_FALSE(entries[i].empty());
      EXPECT_NEAR(entries[i].front().pierce.x, 100 + k / 2, 1e-9);
    }
}

// The T of parts drawn kerf apart (two side by side under a long one), laser and plasma kerfs:
// every pierce off the cut line, and every trail lead and lead-out, keeps its kerf off the parts
// (half a kerf from every part, as the common lines). Before, a lead turned by 45° into the
// vertical gap passed 0.53 mm from a corner at kerf 1.5, and the long part's edge across the
// stem's mouth was a loop pierced inside the long part.
TEST(CommonEntries, KerfGapTeeKeepsHalfAKerfOffTheParts) {
  for (const double k : {0.15, 1.5}) {
    SCOPED_TRACE("kerf " + std::to_string(k));
    const Nest nest = nest_on_sheet({rect(10, 10, 40, 60), rect(40 + k, 10, 70 + k, 60), rect(10, 60 + k, 70 + k, 80 + k)});
    CommonLineOptions co;
    co.kerf_mm = k;
    EntryOptions opt;
    opt.kerf_mm = k;
    const auto plan = plan_common_lines(nest, co);
    check_entries(nest, plan, opt);
    Diagnostics diags;
    const auto entries = plan_common_entries(nest, plan, opt, diags);
    // Distance to the nearest part's material (0 inside one).
    const auto clear = [&](Vec2 p) {
      double d = 1e300;
      for (const auto& c : nest.contours)
        if (c.role != ContourRole::sheet) d = std::min(d, geometry::distance(c.source.contour, p));
      return in_material(nest, p) ? 0.0 : d;
    };
    for (std::size_t i = 0; i < plan.segments.size(); ++i) {
      const auto& seg = plan.segments[i];
      for (const auto& e : entries[i]) {
        if (seg.kind != CommonSegmentKind::trail && e.fallback == Fallback::on_contour) continue;  // on its own edge
        EXPECT_GE(clear(e.pierce), k / 2 - 1e-6) << to_string(seg.kind) << " pierce (" << e.pierce.x << ", " << e.pierce.y << ")";
        if (seg.kind != CommonSegmentKind::trail) continue;  // loop leads: compensated onto the loop
        for (const auto* lead : {&e.lead_in, &e.lead_out}) {
          if (lead->vertices.size() < 2) continue;
          for (int j = 0; j <= 200; ++j) {
            const Vec2 p = geometry::point_at_length(*lead, geometry::length(*lead) * j / 200.0);
            EXPECT_GE(clear(p), k / 2 - 1e-6) << (lead == &e.lead_in ? "lead-in" : "lead-out") << " at (" << p.x << ", " << p.y << ")";
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace cutroute::model
