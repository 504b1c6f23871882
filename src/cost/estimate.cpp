#include <cutroute/cost/estimate.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <cutroute/core/tolerances.hpp>
#include <cutroute/core/units.hpp>

namespace cutroute::cost {

namespace {

std::string mm(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", t);
  return buf;
}

}  // namespace

SpeedAtFrames CuttingConditions::v_on_star(double n) const {
  auto s = speed.at(n);
  s.v_m_s *= v_set_m_s / speed.v_set_m_s();
  if (s.regime == Regime::set) s.v_m_s = v_set_m_s;  // exact at n0, whatever the rounding
  return s;
}

Result<CuttingConditions> make_conditions(const MachineProfile& profile, const SpeedTable& table,
                                          const std::string& material, double thickness_mm,
                                          bool interpolate) {
  auto q = find_speed(table, material, thickness_mm, interpolate);
  if (!q) return q.error();
  CuttingConditions c;
  c.material = q->material;
  c.thickness_mm = thickness_mm;
  c.speed = *q;
  c.warnings = q->warnings;
  c.rapid_speed_m_s = profile.rapid_speed_m_s;
  c.head_lift_lower_s = profile.head_lift_lower_s;
  c.costs = profile.costs;

  // The technology row: exact thickness, or (interpolating) the two neighbours of the same material.
  const CuttingParams* below = nullptr;
  const CuttingParams* above = nullptr;
  const CuttingParams* exact = nullptr;
  std::string have;
  for (const auto& p : profile.cutting) {
    auto canon = table.resolve_material(p.material);
    if (!canon || *canon != c.material) continue;
    have += (have.empty() ? "" : ", ") + mm(p.thickness_mm);
    if (std::abs(p.thickness_mm - thickness_mm) <= tol::kThicknessMm)
      exact = &p;
    else if (p.thickness_mm < thickness_mm && (!below || p.thickness_mm > below->thickness_mm))
      below = &p;
    else if (p.thickness_mm > thickness_mm && (!above || p.thickness_mm < above->thickness_mm))
      above = &p;
  }
  if (exact) {
    c.technology = *exact;
    c.pierce_time_s = exact->pierce_time_s;
    c.v_set_m_s = exact->v_set_m_s ? *exact->v_set_m_s : q->v_set_m_s();
  } else if (interpolate && below && above) {
    const double w = (thickness_mm - below->thickness_mm) / (above->thickness_mm - below->thickness_mm);
    const auto blend = [w](double lo, double hi) { return (1.0 - w) * lo + w * hi; };
    c.technology.material = below->material;
    c.technology.thickness_mm = thickness_mm;
    c.technology.pierce_time_s = blend(below->pierce_time_s, above->pierce_time_s);
    c.technology.kerf_mm = blend(below->kerf_mm, above->kerf_mm);
    c.technology.lead_in_mm = blend(below->lead_in_mm, above->lead_in_mm);
    c.technology.lead_out_mm = blend(below->lead_out_mm, above->lead_out_mm);
    c.pierce_time_s = c.technology.pierce_time_s;
    if (below->v_set_m_s || above->v_set_m_s) {
      // The profile overrides a set speed: blend the overrides, falling back to the table per side.
      c.v_set_m_s = (1.0 - w) * (below->v_set_m_s ? *below->v_set_m_s : q->lower.v_set_m_s) +
                    w * (above->v_set_m_s ? *above->v_set_m_s : q->upper.v_set_m_s);
    } else {
      c.v_set_m_s = q->v_set_m_s();
    }
    c.technology.v_set_m_s = c.v_set_m_s;
    c.warnings.push_back("pierce time, kerf and leads interpolated between the profile's " +
                         mm(below->thickness_mm) + " and " + mm(above->thickness_mm) + " mm rows");
  } else {
    return make_error("machine profile " + profile.file + " has no cutting row for " + c.material + " " +
                      mm(thickness_mm) + " mm (it has " +
                      (have.empty() ? std::string("none") : have + " mm") + ")");
  }
  return c;
}

TimeEstimate estimate_time(const ProgramTotals& p, const CuttingConditions& c) {
  TimeEstimate e;
  const double l_on_m = p.cut_length_mm / units::kMmPerM;
  const double l_off_m = p.rapid_length_mm / units::kMmPerM;
  const auto n_pt = static_cast<double>(p.pierces);
  const auto star = c.v_on_star(static_cast<double>(p.frames));
  e.v_on_set_m_s = c.v_set_m_s;
  e.v_on_m_s = star.v_m_s;
  e.regime = star.regime;
  e.rapid_s = l_off_m / c.rapid_speed_m_s;
  e.pierce_s = n_pt * c.pierce_time_s;
  e.cutting_s = l_on_m / e.v_on_m_s;
  e.t_cut_const_speed_s = l_on_m / e.v_on_set_m_s + e.rapid_s + e.pierce_s;
  e.t_cut_s = e.cutting_s + e.rapid_s + e.pierce_s;
  e.dwell_s = p.dwell_s;
  e.feed_off_s = p.feed_off_time_s + p.feed_off_length_no_feed_mm / units::kMmPerM / c.v_set_m_s;
  e.head_s = n_pt * c.head_lift_lower_s;
  e.pierce_replaced_s = static_cast<double>(std::min(p.pierce_dwells, p.pierces)) * c.pierce_time_s;
  e.total_s = e.t_cut_s + e.dwell_s - e.pierce_replaced_s + e.feed_off_s + e.head_s;
  if (c.costs) {
    e.cost = l_off_m * c.costs->c_off_per_m + l_on_m * c.costs->c_on_per_m + n_pt * c.costs->c_pt;
    e.cost_unit = c.costs->unit;
  } else {
    e.cost = e.t_cut_s;  // eq. 3 with C_on = 1/V_on*(n), C_off = 1/V_off, C_pt = t_pt
    e.cost_unit.assign(1, 's');
  }
  return e;
}

ProgramTotals program_totals(const nc::ProgramStats& s) {
  ProgramTotals t;
  t.cut_length_mm = s.cut_length_mm;
  t.rapid_length_mm = s.rapid_length_mm;
  t.feed_off_length_mm = s.feed_off_length_mm;
  t.feed_off_time_s = s.feed_off_time_s;
  t.feed_off_length_no_feed_mm = s.feed_off_length_no_feed_mm;
  t.dwell_s = s.dwell_s;
  t.pierce_dwells = s.pierce_dwells;
  t.pierces = s.pierces;
  t.frames = s.frames;
  return t;
}

}  // namespace cutroute::cost
