#include "refine.hpp"

#include <algorithm>
#include <cmath>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::pipeline {

using geometry::Vec2;

namespace {

double local_price(const cost::RoutePrices& prices, geometry::Vec2 prev, const std::optional<geometry::Vec2>& next,
                   geometry::Vec2 pierce, geometry::Vec2 off, double lead_mm) {
  double v = prices.rapid_price(geometry::distance(prev, pierce)) + prices.cut_price(lead_mm);
  if (next) v += prices.rapid_price(geometry::distance(off, *next));
  return v;
}

}  // namespace

Refined refine_entries(const model::EntryPlanner& planner, const cost::RoutePrices& prices, geometry::Vec2 start,
                       std::optional<geometry::Vec2> park, std::vector<model::EntryCandidate>& seq, int passes,
                       const StopToken& stop, const EntryPenalty& penalty) {
  int moved = 0;
  constexpr int kSamples = 24;
  constexpr int kGoldenSteps = 14;
  constexpr std::size_t kValidated = 4;  // admissibility checks per contour, best sketches first
  const double phi = (std::sqrt(5.0) - 1) / 2;
  std::vector<std::pair<double, double>> tried;  // (price, s)
  for (int pass = 0; pass < passes; ++pass) {
    bool improved = false;
    for (std::size_t k = 0; k < seq.size(); ++k) {
      if (stop.stop_requested()) return {moved, true};
      auto& cur = seq[k];
      // Fallbacks stay where they were put; chains and common-line segments are tied to where their
      // bridges and shared edges are (their candidates were placed there on purpose).
      if (cur.fallback != model::Fallback::none || model::is_multi_piece(cur)) continue;
      const geometry::Vec2 prev = k == 0 ? start : model::tool_off_point(seq[k - 1]);
      const std::optional<geometry::Vec2> next = k + 1 < seq.size() ? std::optional(seq[k + 1].pierce) : park;
      const double len = planner.contour_length(cur.contour);
      if (len <= 0) continue;
      auto price = [&](Vec2 pierce, Vec2 off, double lead_mm) {
        const double v = local_price(prices, prev, next, pierce, off, lead_mm);
        return penalty ? v + penalty(k, prev, pierce, off, next) : v;
      };
      // The penalty is part of every price the search compares: asked only for the candidates that
      // are validated (5 calls a contour instead of about 40), the search settled on positions whose
      // rapids cross and then refused them (3 010 circles: 851 rapids over freed parts instead of
      // 227, T_cut 0.6 % longer).
      const double current = price(cur.pierce, model::tool_off_point(cur), geometry::length(cur.lead_in) + geometry::length(cur.lead_out));
      tried.clear();
      auto eval = [&](double s) {
        s = std::fmod(std::fmod(s, len) + len, len);
        const auto sk = planner.sketch_at(cur.contour, s, cur.clockwise);
        const double v = price(sk.pierce, sk.tool_off, sk.lead_mm);
        tried.emplace_back(v, s);
        return v;
      };
      double best_s = cur.s_mm, best_v = current;
      for (int i = 0; i < kSamples; ++i) {
        const double s = len * i / kSamples;
        const double v = eval(s);
        if (v < best_v) {
          best_v = v;
          best_s = s;
        }
      }
      // Golden-section search in the bracket around the best point (sampled or current).
      double a = best_s - len / kSamples, b = best_s + len / kSamples;
      double x1 = b - phi * (b - a), x2 = a + phi * (b - a);
      double f1 = eval(x1), f2 = eval(x2);
      for (int it = 0; it < kGoldenSteps; ++it) {
        if (f1 < f2) {
          b = x2; x2 = x1; f2 = f1;
          x1 = b - phi * (b - a);
          f1 = eval(x1);
        } else {
          a = x1; x1 = x2; f1 = f2;
          x2 = a + phi * (b - a);
          f2 = eval(x2);
        }
      }
      // Check the cheapest sketches for admissibility; keep the first one that passes.
      std::sort(tried.begin(), tried.end());
      for (std::size_t i = 0; i < std::min(kValidated, tried.size()); ++i) {
        if (tried[i].first >= current - 1e-9) break;
        if (auto e = planner.entry_at(cur.contour, tried[i].second, cur.clockwise)) {
          const double v = price(e->pierce, model::tool_off_point(*e), geometry::length(e->lead_in) + geometry::length(e->lead_out));
          if (v < current - 1e-9) {
            cur = std::move(*e);
            ++moved;
            improved = true;
            break;
          }
        }
      }
    }
    if (!improved) break;
  }
  return {moved, false};
}

}  // namespace cutroute::pipeline
