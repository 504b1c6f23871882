#include "support/common_program_check.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <numeric>

#include <cutroute/geometry/contour.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>

#include "support/move_index.hpp"
#include "support/nest_facts.hpp"

namespace cutroute::test {
namespace {

using geometry::Vec2;

struct UnionFind {
  std::vector<std::size_t> p;
  explicit UnionFind(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), std::size_t{0}); }
  std::size_t find(std::size_t x) { return p[x] == x ? x : p[x] = find(p[x]); }
};

// A move as geometry segments (an arc in two halves, so that a full circle has a bulge too).
std::vector<geometry::Segment> move_segments(const ProbeMove& m) {
  const Vec2 a{m.x0, m.y0}, b{m.x1, m.y1};
  if (m.arc == 0) return {geometry::Segment{a, b, 0}};
  const Vec2 c{m.cx, m.cy};
  double sweep = std::atan2(b.y - c.y, b.x - c.x) - std::atan2(a.y - c.y, a.x - c.x);
  if (m.arc > 0 && sweep <= 1e-12) sweep += 2 * std::numbers::pi;
  if (m.arc < 0 && sweep >= -1e-12) sweep -= 2 * std::numbers::pi;
  const double r = geometry::distance(a, c), a0 = std::atan2(a.y - c.y, a.x - c.x) + sweep / 2;
  const Vec2 mid = c + Vec2{std::cos(a0), std::sin(a0)} * r;
  const double bulge = std::tan(sweep / 8);
  return {geometry::Segment{a, mid, bulge}, geometry::Segment{mid, b, bulge}};
}

}  // namespace

CommonProgramCheck check_common_program(const model::Nest& nest, const std::string& gcode, double on_mm,
                                        bool group_rule, double tab_width_mm, double fit_radius_mm) {
  CommonProgramCheck out;
  out.probe = probe_gcode(gcode);
  const auto& moves = out.probe.moves;
  for (const auto& e : out.probe.errors) out.failures.push_back("parse: " + e);
  if (out.probe.cut_with_beam_off) out.failures.push_back("a feed move with the beam off");
  if (!out.probe.ended) out.failures.push_back("no program end (M2/M30)");

  std::vector<const model::NestContour*> parts;
  std::vector<geometry::Box> part_boxes;
  for (const auto& c : nest.contours)
    if (c.role != model::ContourRole::sheet) {
      parts.push_back(&c);
      part_boxes.push_back(c.box);
    }
  const geometry::StaticSpatialIndex part_index(part_boxes);
  std::vector<geometry::SegmentSet> sets;
  for (const auto* c : parts) sets.push_back(geometry::make_segment_set(c->source.contour));
  std::vector<std::uint32_t> hits;
  // Is contour k within d of q? Only its segments whose boxes come that near are measured.
  const auto within = [&](std::size_t k, Vec2 q, double d) {
    bool hit = false;
    sets[k].index.visit(geometry::Box{q.x, q.y, q.x, q.y}.inflated(d), [&](std::uint32_t s) {
      hit = geometry::closest_point(sets[k].segments[s], q).distance <= d;
      return !hit;
    });
    return hit;
  };
  // Contours within d of q, in index order.
  const auto near_parts = [&](Vec2 q, double d) {
    part_index.query(geometry::Box{q.x, q.y, q.x, q.y}.inflated(d), hits);
    std::sort(hits.begin(), hits.end());
    std::vector<std::size_t> found;
    for (const auto h : hits)
      if (within(h, q, d)) found.push_back(h);
    return found;
  };
  const auto on_boundary = [&](Vec2 q, std::size_t& which) {
    const auto n = near_parts(q, on_mm);
    if (n.empty()) return false;
    which = n.front();
    return true;
  };
  const auto in_material = [&](Vec2 q) {
    part_index.query(geometry::Box{q.x, q.y, q.x, q.y}, hits);
    int inside = 0;
    for (const auto h : hits) inside += geometry::locate(sets[h], q, 1e-9) == geometry::Location::inside;
    return inside % 2 == 1;
  };

  // Distance from a segment to the material of the nearest part: 0 inside one, else to the
  // nearest drawn boundary (up to 10 mm).
  const auto material_distance = [&](const geometry::Segment& s) {
    if (in_material(s.a)) return 0.0;
    double best = 10;
    std::vector<std::uint32_t> near;
    part_index.query(s.bounding_box().inflated(best), near);
    for (const auto h : near)
      sets[h].index.visit(s.bounding_box().inflated(best), [&](std::uint32_t k) {
        const auto& b = sets[h].segments[k];
        best = std::min(best, s.a == s.b ? geometry::closest_point(b, s.a).distance : geometry::distance(s, b));
        return true;
      });
    return best;
  };
  const auto nearest = [&](const geometry::Segment& s, int line) {
    const double d = material_distance(s);
    if (d < out.nearest_uncompensated_mm) {
      out.nearest_uncompensated_mm = d;
      out.nearest_line = line;
    }
  };

  // Beam-on moves in program order; leads and connectors checked as they come.
  std::vector<std::size_t> cuts;
  std::vector<std::vector<std::size_t>> common_of;  // per cut: the contours a common line separates
  bool beam = false;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const auto& m = moves[i];
    if (m.rapid || !m.beam_on) {
      beam = beam && !m.rapid;
      continue;
    }
    std::size_t k = 0;
    if (!beam) {
      beam = true;
      ++out.runs;
      const Vec2 pierce{m.x0, m.y0};
      nearest(geometry::Segment{pierce, pierce, 0}, m.line);
      if (on_boundary(pierce, k))
        ++out.pierces_on_a_cut;
      else if (in_material(pierce))
        out.failures.push_back("line " + std::to_string(m.line) + ": pierce inside a part");
    }
    cuts.push_back(i);
    if (!m.compensated)
      for (const auto& s : move_segments(m)) nearest(s, m.line);
    bool all_on = true;
    std::vector<std::size_t> on_all;  // contours the whole move lies on
    for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      Vec2 q;
      probe_point(m, t, q.x, q.y);
      all_on = all_on && on_boundary(q, k);
      const auto n = near_parts(q, on_mm);
      if (t == 0.0) {
        on_all = n;
      } else {
        std::vector<std::size_t> both;
        std::set_intersection(on_all.begin(), on_all.end(), n.begin(), n.end(), std::back_inserter(both));
        on_all = std::move(both);
      }
    }
    common_of.push_back(on_all.size() >= 2 ? on_all : std::vector<std::size_t>{});
    if (all_on) {
      out.boundary_cut_mm += m.length;
      continue;
    }
    for (int j = 1; j < 20; ++j) {
      Vec2 q;
      probe_point(m, j / 20.0, q.x, q.y);
      if (m.length * std::min(j, 20 - j) / 20.0 < 0.05) continue;  // where it meets a cut
      if (!on_boundary(q, k) && in_material(q)) {
        out.failures.push_back("line " + std::to_string(m.line) + ": a move off the boundaries runs through a part");
        break;
      }
    }
  }

  // When is each boundary point first cut? (Index into `cuts`.)
  std::vector<const ProbeMove*> cut_moves;
  for (const auto c : cuts) cut_moves.push_back(&moves[c]);
  const MoveIndex move_index(std::move(cut_moves), on_mm);
  std::vector<std::vector<Vec2>> samples(parts.size());
  std::vector<std::vector<std::size_t>> cut_at(parts.size());
  std::vector<std::size_t> done(parts.size(), 0);
  const bool tabs = tab_width_mm > 0;
  if (tabs) out.uncut.resize(parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const bool tabbed = tabs && parts[k]->role == model::ContourRole::outer;
    samples[k] = boundary_samples(parts[k]->source.contour, tabbed ? 0.02 : 0.5);
    const double spacing = geometry::length(parts[k]->source.contour) / static_cast<double>(samples[k].size());
    bool open_run = false;  // the previous sample was left uncut
    for (const Vec2 q : samples[k]) {
      const std::size_t first = move_index.first_within(q, on_mm);
      cut_at[k].push_back(first);
      if (first < cuts.size()) {
        done[k] = std::max(done[k], first);
        open_run = false;
        continue;
      }
      // A tool of radius fit_radius_mm cannot reach q from scrap (32 directions; a disc clear of
      // every contour and out of material): no toolpath on the kerf offset passes there.
      if (fit_radius_mm > 0) {
        bool fits = false;
        for (int a = 0; a < 32 && !fits; ++a) {
          const double t = 2 * std::numbers::pi * a / 32;
          const Vec2 c = q + Vec2{std::cos(t), std::sin(t)} * fit_radius_mm;
          fits = !in_material(c) && near_parts(c, fit_radius_mm - 1e-4).empty();
        }
        if (!fits) continue;
      }
      if (!tabbed || near_parts(q, tab_width_mm / 2).size() > 1) {
        out.failures.push_back("contour " + std::to_string(k + 1) + ": boundary point (" + std::to_string(q.x) + ", " +
                               std::to_string(q.y) + ") is never cut");
        break;
      }
      if (!open_run) out.uncut[k].push_back(0.0);
      out.uncut[k].back() += spacing;
      open_run = true;
    }
    // A stretch running through the first sample began at the end of the boundary.
    if (tabbed && out.uncut[k].size() >= 2 && open_run && cut_at[k].front() == cuts.size()) {
      out.uncut[k].front() += out.uncut[k].back();
      out.uncut[k].pop_back();
    }
  }
  if (!out.failures.empty()) return out;

  // Holes before their part, parts in a hole before the hole.
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const auto parent = parts[k]->parent;
    if (!parent.valid()) continue;
    const auto pk = static_cast<std::size_t>(
        std::find(parts.begin(), parts.end(), &nest.contours[parent]) - parts.begin());
    if (pk < parts.size() && done[k] >= done[pk])
      out.failures.push_back("contour " + std::to_string(k + 1) + " is finished after the contour around it");
  }

  if (!group_rule) return out;
  // Groups: contours separated by common lines (moves lying on two boundaries at once). Every
  // point first cut by such a move is cut before the group's own outer boundary is complete.
  UnionFind uf(parts.size());
  for (const auto& on : common_of)
    for (std::size_t j = 1; j < on.size(); ++j) uf.p[uf.find(on[j])] = uf.find(on[0]);
  std::vector<std::vector<char>> shared(parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) {
    shared[k].assign(samples[k].size(), 0);
    for (std::size_t s = 0; s < samples[k].size(); ++s) shared[k][s] = cut_at[k][s] < cuts.size() && !common_of[cut_at[k][s]].empty();
  }
  std::vector<std::size_t> outer_done(parts.size(), 0), shared_done(parts.size(), 0);
  std::vector<char> has_shared(parts.size(), 0);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::size_t g = uf.find(k);
    for (std::size_t s = 0; s < samples[k].size(); ++s) {
      if (cut_at[k][s] == cuts.size()) continue;  // a tab
      if (shared[k][s]) {
        has_shared[g] = 1;
        shared_done[g] = std::max(shared_done[g], cut_at[k][s]);
      } else if (parts[k]->role == model::ContourRole::outer) {
        outer_done[g] = std::max(outer_done[g], cut_at[k][s]);
      }
    }
  }
  for (std::size_t g = 0; g < parts.size(); ++g)
    if (has_shared[g] && shared_done[g] >= outer_done[g])
      out.failures.push_back("a common line of the group of contour " + std::to_string(g + 1) +
                             " is cut after the group's outer boundary");
  return out;
}

}  // namespace cutroute::test
