#include "support/program_check.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <numbers>
#include <set>

#include <cutroute/core/number_format.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>

#include "support/move_index.hpp"
#include "support/nest_facts.hpp"

namespace cutroute::test {
namespace {

using geometry::Vec2;

std::string at(const ProbeMove& m) { return "line " + std::to_string(m.line); }

}  // namespace

ProgramCheck check_program(const model::Nest& nest, const std::string& gcode, const ProgramCheckOptions& opt) {
  ProgramCheck out;
  out.probe = probe_gcode(gcode);
  const ProbeResult& p = out.probe;
  for (const auto& e : p.errors) out.failures.push_back("parse: " + e);
  if (p.cut_with_beam_off) out.failures.push_back("a feed move with the beam off");
  if (!p.ended) out.failures.push_back("no program end (M2/M30)");
  out.cut_length = p.cut_length;
  out.rapid_length = p.rapid_length;

  // Cut contours and an index over their boxes.
  std::vector<const model::NestContour*> cut;
  std::vector<int> cut_of(nest.contours.size(), -1);
  std::vector<geometry::Box> boxes;
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    const auto& c = nest.contours[model::ContourId(static_cast<std::int32_t>(i))];
    if (c.role == model::ContourRole::sheet) continue;
    cut_of[i] = static_cast<int>(cut.size());
    cut.push_back(&c);
    boxes.push_back(c.box);
  }
  const geometry::StaticSpatialIndex index(boxes);
  std::vector<std::uint32_t> hits;
  std::vector<geometry::SegmentSet> sets;
  sets.reserve(cut.size());
  for (const auto* c : cut) sets.push_back(geometry::make_segment_set(c->source.contour));

  // Distance from q to contour k, exact where it is below `cap` (else some value >= cap).
  auto dist_to = [&](int k, Vec2 q, double cap = 1.0) {
    double best = cap;
    const auto& set = sets[static_cast<std::size_t>(k)];
    set.index.visit(geometry::Box{q.x, q.y, q.x, q.y}.inflated(cap), [&](std::uint32_t s) {
      best = std::min(best, geometry::closest_point(set.segments[s], q).distance);
      return true;
    });
    return best;
  };

  // Which contours does a move lie on? All whose distance stays within the tolerance (of the
  // kerf offset, on the contour's scrap side) at five points along it (parts placed edge to edge
  // share a stretch: a move there lies on both).
  // The offset of a cut move from its drawn contour: kerf_offset_mm, or uncompensated_offset_mm
  // for a move outside G41/G42 in a program that writes some cuts on their offset.
  const double off_max = std::max(opt.kerf_offset_mm, opt.uncompensated_offset_mm);
  auto off_of = [&](const ProbeMove& m) {
    return !m.compensated && opt.uncompensated_offset_mm > 0 ? opt.uncompensated_offset_mm : opt.kerf_offset_mm;
  };
  auto on_scrap_side = [&](int k, Vec2 q, double off) {
    if (off <= 0) return true;
    const bool inside = geometry::locate(sets[static_cast<std::size_t>(k)], q, 1e-9) == geometry::Location::inside;
    return cut[static_cast<std::size_t>(k)]->role == model::ContourRole::hole ? inside : !inside;
  };
  auto contours_of = [&](const ProbeMove& m) {
    const double off = off_of(m);
    std::vector<int> on;
    Vec2 mid;
    probe_point(m, 0.5, mid.x, mid.y);
    index.query(geometry::Box{mid.x, mid.y, mid.x, mid.y}.inflated(off + opt.on_contour_mm), hits);
    for (auto h : hits) {
      const int k = static_cast<int>(h);
      bool all = true;
      for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        Vec2 q;
        probe_point(m, t, q.x, q.y);
        if (std::abs(dist_to(k, q, off + 2 * opt.on_contour_mm) - off) > opt.on_contour_mm || !on_scrap_side(k, q, off)) {
          all = false;
          break;
        }
      }
      if (all) on.push_back(k);
    }
    std::sort(on.begin(), on.end());
    return on;
  };

  // Scrap test for pierce points: inside an even number of cut contours.
  auto in_material = [&](Vec2 q) {
    index.query(geometry::Box{q.x, q.y, q.x, q.y}, hits);
    int inside = 0;
    for (auto h : hits) {
      inside += geometry::locate(sets[h], q, 1e-9) == geometry::Location::inside;
    }
    return inside % 2 == 1;
  };

  // Group the beam-on moves into runs (pierce to beam off), then give each move the contour its
  // run cuts when it lies on it (a shared edge belongs to the part being cut), else the lowest.
  std::vector<double> covered(cut.size(), 0.0);
  std::vector<char> offset_cut(cut.size(), 0);  // cut on its offset outside G41/G42 (uncompensated_offset_mm)
  out.arc_moves.assign(cut.size(), 0);
  std::vector<std::set<int>> runs_of(cut.size());
  bool beam = false;
  std::vector<std::vector<std::pair<const ProbeMove*, int>>> run_moves;
  std::vector<std::vector<std::vector<int>>> run_on;
  for (const auto& m : p.moves) {
    if (m.rapid) {
      beam = false;
      continue;
    }
    if (!m.beam_on) continue;
    if (!beam) {
      beam = true;
      run_moves.emplace_back();
      run_on.emplace_back();
      const Vec2 pierce{m.x0, m.y0};
      // The last-resort fallback pierces on the contour itself (said in the diagnostics).
      bool on_a_contour = false;
      index.query(geometry::Box{pierce.x, pierce.y, pierce.x, pierce.y}.inflated(off_max + opt.on_contour_mm), hits);
      for (const double off : {opt.kerf_offset_mm, opt.uncompensated_offset_mm})
        for (auto h : hits)
          on_a_contour |= std::abs(dist_to(static_cast<int>(h), pierce, off + 2 * opt.on_contour_mm) - off) < opt.on_contour_mm;
      if (!on_a_contour && in_material(pierce)) {
        out.failures.push_back(at(m) + ": pierce at (" + format_fixed(m.x0, 3) + ", " + format_fixed(m.y0, 3) +
                               ") inside a part");
      }
    }
    run_moves.back().push_back({&m, -1});
    run_on.back().push_back(contours_of(m));
  }
  auto assign = [&](std::size_t r, std::size_t i, int k) {
    run_moves[r][i].second = k;
    if (k < 0) return;
    covered[static_cast<std::size_t>(k)] += run_moves[r][i].first->length;
    if (off_of(*run_moves[r][i].first) != opt.kerf_offset_mm) offset_cut[static_cast<std::size_t>(k)] = 1;
    out.arc_moves[static_cast<std::size_t>(k)] += run_moves[r][i].first->arc != 0;
    runs_of[static_cast<std::size_t>(k)].insert(static_cast<int>(r));
  };
  // Runs that lie wholly on a stretch two contours share (a piece between tabs on a part whose
  // neighbours' cuts run along it): nothing in the program says which contour they cut, so they
  // are given, after all other runs, to the candidate whose boundary they cut where no other run
  // of it does.
  std::vector<std::pair<std::size_t, std::vector<int>>> shared_runs;
  for (std::size_t r = 0; r < run_moves.size(); ++r) {
    std::vector<int> common;
    bool first = true;
    for (const auto& on : run_on[r]) {
      if (on.empty()) continue;
      if (first) {
        common = on;
        first = false;
      } else {
        std::vector<int> both;
        std::set_intersection(common.begin(), common.end(), on.begin(), on.end(), std::back_inserter(both));
        common = std::move(both);
      }
    }
    if (common.size() >= 2) {
      shared_runs.emplace_back(r, std::move(common));
      continue;
    }
    std::map<int, double> length_on;
    for (std::size_t i = 0; i < run_moves[r].size(); ++i) {
      for (int k : run_on[r][i]) length_on[k] += run_moves[r][i].first->length;
    }
    int main_contour = -1;
    double best = 0;
    for (const auto& [k, len] : length_on) {
      if (len > best) {
        best = len;
        main_contour = k;
      }
    }
    // A move on several contours (a stretch shared by parts drawn edge to edge) goes to the one
    // the run stays on the longest around it: the run cuts that contour whole, or between its tabs,
    // and a neighbour only along the shared stretch. That tells the two apart in a chain of
    // touching parts too, where a neighbour outside the chain may have more length in the run
    // than the chain's part. Ties: the run's main contour, then the lowest.
    const auto& moves = run_moves[r];
    auto around = [&](std::size_t i, int k) {
      auto has = [&](std::size_t j) { return std::find(run_on[r][j].begin(), run_on[r][j].end(), k) != run_on[r][j].end(); };
      double len = 0;
      for (std::size_t j = i; j < moves.size() && has(j); ++j) len += moves[j].first->length;
      for (std::size_t j = i; j-- > 0 && has(j);) len += moves[j].first->length;
      return len;
    };
    for (std::size_t i = 0; i < moves.size(); ++i) {
      const auto& on = run_on[r][i];
      int k = on.empty() ? -1 : on.front();
      double longest = -1;
      // A single candidate needs no scan (a long run's streak would cost its length per move).
      for (std::size_t x = 0; on.size() > 1 && x < on.size(); ++x) {
        const double len = around(i, on[x]);
        if (len > longest + 1e-9 || (std::abs(len - longest) <= 1e-9 && on[x] == main_contour)) {
          longest = len;
          k = on[x];
        }
      }
      assign(r, i, k);
    }
  }

  // A pierce starts a run even where the probe saw the beam switched on without a move.
  out.runs = static_cast<int>(run_moves.size());

  // The cut moves of contour k's runs that lie on it, in program order.
  auto moves_on = [&](std::size_t k) {
    std::vector<const ProbeMove*> on_k;
    for (const int run : runs_of[k])
      for (const auto& [m, on] : run_moves[static_cast<std::size_t>(run)])
        if (on == static_cast<int>(k)) on_k.push_back(m);
    return on_k;
  };

  for (const auto& [r, candidates] : shared_runs) {
    std::vector<const ProbeMove*> run_cut;
    for (std::size_t i = 0; i < run_moves[r].size(); ++i)
      if (!run_on[r][i].empty()) run_cut.push_back(run_moves[r][i].first);
    const double off = off_max;
    const MoveIndex by_run(run_cut, opt.on_contour_mm + off);
    int k = -1;
    int most = -1;
    for (const int c : candidates) {
      const MoveIndex by_c(moves_on(static_cast<std::size_t>(c)), opt.on_contour_mm + off);
      int fills = 0;
      for (const Vec2 q : boundary_samples(cut[static_cast<std::size_t>(c)]->source.contour, 0.5)) {
        fills += by_run.first_within(q, opt.on_contour_mm + off) != by_run.size() &&
                 by_c.first_within(q, opt.on_contour_mm + off) == by_c.size();
      }
      if (fills > most) {
        most = fills;
        k = c;
      }
    }
    for (std::size_t i = 0; i < run_moves[r].size(); ++i) assign(r, i, run_on[r][i].empty() ? -1 : k);
  }

  // With a kerf offset: the run passes within `off` of every drawn point where the tool fits, and
  // is no longer than the offset curve can be.
  auto check_offset_cover = [&](std::size_t k, const std::string& name, double cut_len, double len, double off) {
    const bool hole = cut[k]->role == model::ContourRole::hole;
    const auto runs = static_cast<double>(runs_of[k].size());
    const double most = len + (hole ? -1 : 1) * 2 * std::numbers::pi * off + runs * opt.max_overcut_mm + 1e-3;
    if (cut_len > most) out.failures.push_back(name + " is cut over " + format_fixed(cut_len, 3) + " mm (at most " +
                                               format_fixed(most, 3) + " with the kerf offset): twice?");
    // Indexed: spline outlines have thousands of arcs, and every drawn point asks for its distance.
    const double reach = off + opt.on_contour_mm + 0.001;
    const MoveIndex path(moves_on(k), reach);
    const auto& drawn = cut[k]->source.contour;
    const bool ccw = geometry::signed_area(drawn) > 0;
    int missed = 0;
    Vec2 first_missed;
    for (std::size_t i = 0; i < geometry::segment_count(drawn); ++i) {
      const auto seg = geometry::segment(drawn, i);
      for (double t : {0.25, 0.5, 0.75}) {
        const Vec2 q = seg.point_at(t);
        // The scrap-side normal: left of travel is inside for a counter-clockwise contour.
        const Vec2 left = geometry::perp(seg.tangent_at(t));
        const Vec2 n = (hole == ccw) ? left : -left;
        const Vec2 centre = q + n * off;
        // At a micro-zigzag of a fitted spline the local normal can point into the material.
        bool fits = on_scrap_side(static_cast<int>(k), centre, off);
        index.query(geometry::Box{centre.x, centre.y, centre.x, centre.y}.inflated(off), hits);
        for (auto h : hits) fits = fits && dist_to(static_cast<int>(h), centre, off) > off - 1e-4;
        if (!fits) continue;
        if (path.first_within(q, reach) == path.size() && missed++ == 0) first_missed = q;
      }
    }
    if (missed > 0)
      out.failures.push_back(name + ": its cut misses " + std::to_string(missed) + " drawn points where the tool fits, e.g. (" +
                             format_fixed(first_missed.x, 4) + ", " + format_fixed(first_missed.y, 4) + ")");
  };

  // Every boundary point of contour k within on_contour_mm of a move of its runs that lies on it
  // (several runs: pieces that must meet without a gap).
  // With tabs, the samples in their gaps (at most w / 0.5 + 1 each) are left uncut on purpose.
  auto check_pieces_cover = [&](std::size_t k, const std::string& name, int tabs) {
    const MoveIndex index_k(moves_on(k), opt.on_contour_mm);
    int missed = 0;
    Vec2 first_missed;
    for (const Vec2 q : boundary_samples(cut[k]->source.contour, 0.5))
      if (index_k.first_within(q, opt.on_contour_mm) == index_k.size() && missed++ == 0) first_missed = q;
    if (missed > tabs * static_cast<int>(std::floor(opt.tab_width_mm / 0.5) + 1))
      out.failures.push_back(name + ": " + std::to_string(missed) + " boundary points cut by none of its " +
                             std::to_string(runs_of[k].size()) + " runs, e.g. (" + format_fixed(first_missed.x, 4) + ", " +
                             format_fixed(first_missed.y, 4) + ")");
  };

  // Every contour once, whole, in one run (or in several pieces that cover it together).
  std::vector<int> run_of(cut.size(), -1), last_run_of(cut.size(), -1);
  out.runs_per_contour.assign(cut.size(), 0);
  for (std::size_t k = 0; k < cut.size(); ++k) {
    const double len = geometry::length(cut[k]->source.contour);
    const std::string name = "contour " + std::to_string(k + 1) + " (" + model::to_string(cut[k]->role) + ", length " +
                             format_fixed(len, 3) + ")";
    if (runs_of[k].empty()) {
      out.failures.push_back(name + " is never cut");
      continue;
    }
    // With micro-joints an outer contour is cut in tabs + 1 runs, short of tabs gaps.
    // A contour too short to leave a gap width of cut between its gaps (2 · tabs · w > length) is cut whole.
    const bool tabbed = opt.tabs > 0 && cut[k]->role == model::ContourRole::outer && len >= 2 * opt.tabs * opt.tab_width_mm;
    const std::size_t want_runs = tabbed ? static_cast<std::size_t>(opt.tabs) + 1 : 1;
    const double gaps = tabbed ? opt.tabs * opt.tab_width_mm : 0.0;
    const std::size_t runs = runs_of[k].size();
    // Multi-segment pieces: up to max_runs_per_contour runs, each tab adding one more.
    const std::size_t max_pieces = static_cast<std::size_t>(std::max(1, opt.max_runs_per_contour));
    const bool pieces = runs > want_runs && runs < want_runs + max_pieces;
    if (runs != want_runs && !pieces)
      out.failures.push_back(name + " is cut in " + std::to_string(runs) + " runs (want " + std::to_string(want_runs) + ")");
    run_of[k] = *runs_of[k].begin();
    last_run_of[k] = *runs_of[k].rbegin();
    out.runs_per_contour[k] = static_cast<int>(runs);
    out.split_contours += pieces;
    const double overcuts = pieces ? static_cast<double>(runs - want_runs + 1) * opt.max_overcut_mm : opt.max_overcut_mm;
    if (const double off = offset_cut[k] ? opt.uncompensated_offset_mm : opt.kerf_offset_mm; off > 0) {
      check_offset_cover(k, name, covered[k], len, off);
    } else {
      // Every vertex is rounded to the dialect's resolution (1 µm), so a contour's cut length may
      // differ from the drawing's by a few µm; a real gap would be a tenth of a kerf or more.
      if (covered[k] < len - gaps - 0.01 - len * 1e-5) out.failures.push_back(name + " is cut only over " + format_fixed(covered[k], 3) + " mm");
      if (covered[k] > len - gaps + overcuts + 1e-3) out.failures.push_back(name + " is cut over " + format_fixed(covered[k], 3) + " mm: twice?");
      if (pieces) check_pieces_cover(k, name, tabbed ? opt.tabs : 0);
    }
    ++out.contours_cut;
  }

  // Precedence: everything inside a contour is cut before it (before any of its runs).
  for (std::size_t k = 0; k < cut.size(); ++k) {
    const auto& parent = cut[k]->parent;
    if (!parent.valid() || run_of[k] < 0) continue;
    const int pk = cut_of[parent.index()];
    if (pk < 0 || run_of[static_cast<std::size_t>(pk)] < 0) continue;
    if (last_run_of[k] > run_of[static_cast<std::size_t>(pk)])
      out.failures.push_back("contour " + std::to_string(k + 1) + " is cut after the contour around it (" +
                             std::to_string(pk + 1) + ")");
  }

  // Leads: only at the ends of a run, short, clear of other contours, not touching their own early.
  // Bridges: moves off the contours between two contour moves of different contours (chain
  // cutting): through scrap only, clear of every other contour.
  for (const auto& moves : run_moves) {
    std::size_t first = moves.size(), last = 0;
    for (std::size_t i = 0; i < moves.size(); ++i) {
      if (moves[i].second >= 0) {
        first = std::min(first, i);
        last = i;
      }
    }
    if (first == moves.size()) {
      out.failures.push_back(at(*moves.front().first) + ": a beam-on run that cuts no contour");
      continue;
    }
    double lead_len = 0;
    // Samples of move m must stay out of material (within 2 µm of an end contour allowed: a lead
    // or bridge meets its contour there, and a tangential arc grazes it within the output
    // resolution) and keep the clearance from every contour but those at its ends.
    auto check_scrap_move = [&](const ProbeMove& m, int end_a, int end_b, const char* what) {
      for (int s = 0; s <= 20; ++s) {
        const double t = s / 20.0;
        Vec2 q;
        probe_point(m, t, q.x, q.y);
        const bool at_end = dist_to(end_a, q, 0.01) <= 0.002 || (end_b >= 0 && dist_to(end_b, q, 0.01) <= 0.002);
        if (!at_end && in_material(q)) {
          out.failures.push_back(at(m) + ": " + what + " enters material at t=" + format_fixed(t, 2) + " (" +
                                 format_fixed(q.x, 4) + ", " + format_fixed(q.y, 4) + ")");
          return;
        }
        index.query(geometry::Box{q.x, q.y, q.x, q.y}.inflated(opt.clearance_mm), hits);
        for (auto h : hits) {
          const int kk = static_cast<int>(h);
          if (kk == end_a || kk == end_b) continue;
          const double d = dist_to(kk, q, opt.clearance_mm);
          if (d < opt.clearance_mm * 0.999) {
            out.failures.push_back(at(m) + ": " + what + " comes " + format_fixed(d, 4) + " mm close to contour " +
                                   std::to_string(kk + 1) + " at t=" + format_fixed(t, 2) + " (" + format_fixed(q.x, 4) +
                                   ", " + format_fixed(q.y, 4) + ")");
            return;
          }
        }
      }
    };
    for (std::size_t i = 0; i < moves.size(); ++i) {
      const auto& [m, k] = moves[i];
      if (k >= 0) continue;
      if (i > first && i < last) {
        // The contours cut just before and just after this stretch off the contours.
        int before = -1, after = -1;
        for (std::size_t j = i; j-- > first;)
          if (moves[j].second >= 0) { before = moves[j].second; break; }
        for (std::size_t j = i + 1; j <= last; ++j)
          if (moves[j].second >= 0) { after = moves[j].second; break; }
        if (before == after) {
          out.failures.push_back(at(*m) + ": a move off the contours in the middle of a cut");
          continue;
        }
        ++out.bridges;
        out.bridge_length += m->length;
        check_scrap_move(*m, before, after, "bridge");
        continue;
      }
      lead_len += m->length;
      // The lead meets its contour at its end (lead-in) or its start (lead-out).
      check_scrap_move(*m, i < first ? moves[first].second : moves[last].second, -1, "lead");
    }
    if (lead_len > opt.max_lead_mm) out.failures.push_back(at(*moves.front().first) + ": leads of " + format_fixed(lead_len, 3) + " mm");
  }
  return out;
}

}  // namespace cutroute::test
