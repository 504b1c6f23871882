// ShopRules: the switchable technological rules of `cutroute optimize` (heat, tip-up, part and sheet rigidity, tabs); docs/SHOP-RULES.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace cutroute::pipeline {

enum class ClampSide { left, right, bottom, top };
const char* to_string(ClampSide s);
std::optional<ClampSide> parse_clamp_side(const std::string& s);

// How a cut resumes after a micro-joint gap: pierced on the path (off), or entered from scrap by
// the job's lead-in (on); automatic: with a lead-in where the post dialect cannot keep controller
// compensation on over the gap (torch-height or M62-M68 codes: plasma), on the path elsewhere.
enum class TabLeadIn { automatic, on, off };
const char* to_string(TabLeadIn t);  // "auto", "on", "off"
std::optional<TabLeadIn> parse_tab_lead_in(const std::string& s);

// Every rule is off by default; a default run is byte-identical to a run without rules. Weights
// are in the objective's unit (seconds for --objective time, cost units for cost) and are added
// to the route's price only while sequencing: the report's T_cut stays the machine time.
struct ShopRules {
  // Heat: two contours cut within heat_memory segments of each other should be at least
  // heat_distance_mm apart. Each pair closer than that costs heat_weight for the previous
  // segment, half of it for the one before, a quarter for the one before that, ...
  double heat_distance_mm = 0.0;    // D [mm]; 0: off
  double heat_weight = 30.0;        // [objective unit] per close pair, at distance 1 segment
  int heat_memory = 1;              // segments looked back (1: only the previous cut)

  // Tip-up: rapids never pass over a part already cut free. While sequencing, each rapid whose
  // straight line passes over a freed part costs tip_up_weight; in the program such rapids are
  // routed around the freed parts (extra G0 moves through corners tip_up_margin_mm off them).
  bool avoid_tip_up = false;
  double tip_up_weight = 2.0;       // [objective unit] per rapid over a freed part
  double tip_up_margin_mm = 2.0;    // [mm] distance of detour corners from the parts

  // Part rigidity: outer contours are entered at a corner (only corner candidates, no sliding
  // refinement), the corner nearest to the material still uncut after the part (the centre of the
  // parts cut later; the sheet's centre for the last part): the cut, which ends at its entry,
  // ends where the part is held longest.
  bool part_rigidity = false;

  // Sheet rigidity: the cut order sweeps away from the clamped side. Cutting a part whose centre
  // lies behind the sweep front (the farthest centre from the clamp cut so far) by more than
  // sheet_band_mm costs sheet_weight per mm behind.
  std::optional<ClampSide> sheet_clamp;
  double sheet_weight_per_mm = 0.05;  // [objective unit / mm]
  double sheet_band_mm = 0.0;         // [mm] allowed step back

  // Micro-joints: tabs uncut gaps of tab_width_mm on every outer contour (nc/micro_joints.hpp).
  // Parts held by tabs do not fall or tip: with tabs no part counts as cut free for tip-up.
  int tabs = 0;
  double tab_width_mm = 1.0;        // [mm]
  // A cut resumed on the path after a gap starts with a pierce mark on the part's edge and, where
  // the controller switched compensation off over the gap, with an entry move from half a kerf
  // inside the part; a lead-in from scrap avoids both, at the price of its length.
  TabLeadIn tab_lead_in = TabLeadIn::automatic;

  // Evaluation budget of the history-dependent local search (solve/history_search.hpp).
  long long search_evaluations = 400000;

  bool orders() const { return heat_distance_mm > 0 || (avoid_tip_up && tabs <= 0) || sheet_clamp.has_value(); }
  bool any() const { return orders() || avoid_tip_up || part_rigidity || tabs > 0; }
};

// Human-readable problems with the rules (empty when valid), e.g. "--tab-width must be > 0".
std::vector<std::string> check(const ShopRules& r);

}  // namespace cutroute::pipeline
