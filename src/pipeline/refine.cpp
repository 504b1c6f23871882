#include "refine.hpp"

#include <cmath>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::pipeline {

geometry::Vec2 tool_off(const model::EntryCandidate& e) {
  if (!e.lead_out.vertices.empty()) return e.lead_out.vertices.back().p;
  if (!e.path.vertices.empty()) return e.path.vertices.back().p;
  return e.pierce;
}

namespace {

double lead_price(const cost::RoutePrices& prices, const model::EntryCandidate& e) {
  return prices.cut_price(geometry::length(e.lead_in) + geometry::length(e.lead_out));
}

double local_price(const cost::RoutePrices& prices, geometry::Vec2 prev, const std::optional<geometry::Vec2>& next,
                   const model::EntryCandidate& e) {
  double v = prices.rapid_price(geometry::distance(prev, e.pierce)) + lead_price(prices, e);
  if (next) v += prices.rapid_price(geometry::distance(tool_off(e), *next));
  return v;
}

}  // namespace

int refine_entries(const model::EntryPlanner& planner, const cost::RoutePrices& prices, geometry::Vec2 start,
                   std::optional<geometry::Vec2> park, std::vector<model::EntryCandidate>& seq, int passes,
                   const StopToken& stop) {
  int moved = 0;
  constexpr int kSamples = 24;
  constexpr int kGoldenSteps = 14;
  const double phi = (std::sqrt(5.0) - 1) / 2;
  for (int pass = 0; pass < passes; ++pass) {
    bool improved = false;
    for (std::size_t k = 0; k < seq.size(); ++k) {
      if (stop.stop_requested()) return moved;
      auto& cur = seq[k];
      if (cur.fallback != model::Fallback::none) continue;  // fallbacks stay where they were put
      const geometry::Vec2 prev = k == 0 ? start : tool_off(seq[k - 1]);
      const std::optional<geometry::Vec2> next = k + 1 < seq.size() ? std::optional(seq[k + 1].pierce) : park;
      double best = local_price(prices, prev, next, cur);
      std::optional<model::EntryCandidate> best_e;
      double best_s = cur.s_mm;
      const double len = planner.contour_length(cur.contour);
      if (len <= 0) continue;
      auto eval = [&](double s, std::optional<model::EntryCandidate>& out) -> double {
        out = planner.entry_at(cur.contour, std::fmod(s + len, len), cur.clockwise);
        return out ? local_price(prices, prev, next, *out) : 1e300;
      };
      for (int i = 0; i < kSamples; ++i) {
        const double s = len * i / kSamples;
        std::optional<model::EntryCandidate> e;
        const double v = eval(s, e);
        if (v < best - 1e-12) {
          best = v;
          best_e = std::move(e);
          best_s = s;
        }
      }
      // Golden-section search in the bracket around the best point (sampled or current).
      double a = best_s - len / kSamples, b = best_s + len / kSamples;
      double x1 = b - phi * (b - a), x2 = a + phi * (b - a);
      std::optional<model::EntryCandidate> e1, e2;
      double f1 = eval(x1, e1), f2 = eval(x2, e2);
      for (int it = 0; it < kGoldenSteps; ++it) {
        if (f1 < f2) {
          b = x2; x2 = x1; f2 = f1; e2 = std::move(e1);
          x1 = b - phi * (b - a);
          f1 = eval(x1, e1);
        } else {
          a = x1; x1 = x2; f1 = f2; e1 = std::move(e2);
          x2 = a + phi * (b - a);
          f2 = eval(x2, e2);
        }
      }
      if (f1 < best - 1e-12 && e1) { best = f1; best_e = std::move(e1); }
      if (f2 < best - 1e-12 && e2) { best = f2; best_e = std::move(e2); }
      if (best_e) {
        cur = std::move(*best_e);
        ++moved;
        improved = true;
      }
    }
    if (!improved) break;
  }
  return moved;
}

}  // namespace cutroute::pipeline
