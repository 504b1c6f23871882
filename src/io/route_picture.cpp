#include <cutroute/io/route_picture.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

#include <cutroute/core/number_format.hpp>
#include <cutroute/io/svg.hpp>

namespace cutroute::io {
namespace {

constexpr const char* kNs = "vector-effect=\"non-scaling-stroke\"";

// Distance from p to box b (0 inside) [mm].
double distance_to(const geometry::Box& b, geometry::Vec2 p) {
  const double dx = std::max({b.xmin - p.x, 0.0, p.x - b.xmax}), dy = std::max({b.ymin - p.y, 0.0, p.y - b.ymax});
  return std::hypot(dx, dy);
}

// A start or park point farther from the nest than the nest is wide stays off the picture: a
// nest drawn far from the machine's origin would otherwise shrink to a corner of it, its pierce
// numbers pushed off the top (a nest at (10 000, 20 000) showed 9 of its 139).
bool far_off(const geometry::Box& nest, geometry::Vec2 p) {
  return !nest.empty() && distance_to(nest, p) > std::max(nest.width(), nest.height());
}

geometry::Box nest_box(const model::Nest& nest, const nc::Toolpath& path, const RoutePictureOptions& options) {
  geometry::Box b;
  for (const auto& c : nest.contours) b.add(c.box);
  for (const auto& [c, why] : options.not_cut)
    for (const auto& v : c.vertices) b.add(v.p);
  for (const auto& s : path.segments) b.add(s.pierce);
  return b;
}

geometry::Box world_box(const geometry::Box& drawn, const nc::Toolpath& path) {
  geometry::Box b = drawn;
  for (const geometry::Vec2 p : {path.start, path.end})
    if (!far_off(drawn, p)) b.add(p);
  if (b.empty()) b = geometry::Box{0, 0, 100, 100};
  return b;
}

// Where the straight line from `from` (outside) to `to` enters box b, clipped to it.
geometry::Vec2 entry_point(const geometry::Box& b, geometry::Vec2 from, geometry::Vec2 to) {
  double t0 = 0.0;
  const geometry::Vec2 d = to - from;
  for (int axis = 0; axis < 2; ++axis) {
    const double p = axis == 0 ? from.x : from.y, v = axis == 0 ? d.x : d.y;
    const double lo = axis == 0 ? b.xmin : b.ymin, hi = axis == 0 ? b.xmax : b.ymax;
    if (v == 0.0) continue;
    t0 = std::max(t0, std::min((lo - p) / v, (hi - p) / v));
  }
  return from + d * std::clamp(t0, 0.0, 1.0);
}

// Cells of the grids below are only looked up, never walked, so their order cannot change a picture.
struct CellHash {
  std::size_t operator()(const std::pair<long long, long long>& c) const {
    const auto x = static_cast<unsigned long long>(c.first), y = static_cast<unsigned long long>(c.second);
    return static_cast<std::size_t>((x * 0x9E3779B97F4A7C15ULL) ^ (y + 0x632BE59BD9B4E019ULL + (x << 6)));
  }
};

// The median over the pierces of the distance to the nearest other pierce [mm]; +inf with fewer
// than two. A grid of cells about the typical spacing finds each one's nearest among the cells
// around it, widening the search until one is found.
double median_pierce_spacing(const nc::Toolpath& path) {
  const std::size_t n = path.segments.size();
  if (n < 2) return std::numeric_limits<double>::infinity();
  geometry::Box b;
  for (const auto& s : path.segments) b.add(s.pierce);
  const double cell = std::max(std::max(b.width(), b.height()) / std::sqrt(static_cast<double>(n)), 1e-3);
  auto key = [&](geometry::Vec2 p) {
    return std::pair{static_cast<long long>(std::floor((p.x - b.xmin) / cell)), static_cast<long long>(std::floor((p.y - b.ymin) / cell))};
  };
  std::unordered_map<std::pair<long long, long long>, std::vector<std::size_t>, CellHash> grid;
  for (std::size_t i = 0; i < n; ++i) grid[key(path.segments[i].pierce)].push_back(i);
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i) {
    const geometry::Vec2 p = path.segments[i].pierce;
    const auto [cx, cy] = key(p);
    // Ring r of cells covers every point nearer than r cells: stop one ring after a find.
    for (long long r = 1; r < 64; ++r) {
      for (long long x = cx - r; x <= cx + r; ++x)
        for (long long y = cy - r; y <= cy + r; ++y) {
          const auto it = grid.find({x, y});
          if (it == grid.end()) continue;
          for (std::size_t j : it->second)
            if (j != i) nearest[i] = std::min(nearest[i], geometry::distance(p, path.segments[j].pierce));
        }
      if (nearest[i] <= static_cast<double>(r - 1) * cell) break;
    }
  }
  std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(n / 2), nearest.end());
  return nearest[n / 2];
}

// A rapid as drawn: straight, or through the waypoints of a detour (shop rules).
void add_rapid(SvgDocument& svg, geometry::Vec2 from, const std::vector<geometry::Vec2>& via, geometry::Vec2 to) {
  const std::string style = std::string("fill=\"none\" stroke=\"#2f6fdf\" stroke-width=\"1\" stroke-dasharray=\"5 4\" ") + kNs;
  for (const auto& p : via) {
    svg.add_line(from, p, style);
    from = p;
  }
  svg.add_line(from, to, style);
}

// 100 (route - bound) / route from the report's solver block, when it has both and the route is
// not proven optimal.
std::optional<double> gap_percent(const nlohmann::json& r) {
  if (!r.is_object() || !r.contains("solver") || !r["solver"].is_object()) return std::nullopt;
  const auto& sv = r["solver"];
  if (sv.value("status", std::string()) == "optimal") return std::nullopt;
  if (!sv.contains("objective") || !sv["objective"].is_number() || !sv.contains("lower_bound") || !sv["lower_bound"].is_number())
    return std::nullopt;
  const double objective = sv["objective"].get<double>(), bound = sv["lower_bound"].get<double>();
  if (!(objective > 0.0)) return std::nullopt;
  return 100.0 * (objective - bound) / objective;
}

}  // namespace

std::string route_to_svg(const model::Nest& nest, const nc::Toolpath& path, const RoutePictureOptions& options) {
  const geometry::Box drawn = nest_box(nest, path, options);
  const geometry::Box world = world_box(drawn, path);
  const double span = std::max(world.width(), world.height());
  const double margin = span * 0.02 + 1.0;
  // Marks and numbers are sized for the nest seen whole, but no larger than the spacing of its
  // pierces allows (a number 0.8, a mark 0.25 of the median distance to the nearest other
  // pierce), so that on dense nests they stay beside their own pierce when zoomed in (d2g_DRAAK:
  // numbers of 4.6 mm instead of 53 mm).
  const double spacing = median_pierce_spacing(path);
  const double label_mm = std::max(std::min(span / 90.0, 0.8 * spacing), 0.5);
  const double mark_mm = std::max(std::min(span / 400.0, 0.25 * spacing), 0.2);
  // The caption's line goes below the drawing and below the start's label (written under its
  // mark); the scale depends on the width alone.
  const double caption_mm = 15.0 * (world.width() + 2 * margin) / options.width_px;
  const double caption_y = world.ymin - mark_mm * 6 - 0.5 * label_mm - 1.3 * caption_mm;
  geometry::Box page = world;
  if (!options.caption.empty()) page.ymin = caption_y - 0.4 * caption_mm;
  SvgDocument svg(page, margin, options.width_px);
  if (!options.title.empty()) svg.add_raw("<title>" + xml_escape(options.title) + "</title>\n");
  svg.add_raw("<desc>cut: red (pieces of one contour cut in several segments: orange and ochre); lead-in and lead-out: green; "
              "bridge: violet; rapid: dashed blue; tab (material left, the head moves over it with the beam off): teal; "
              "pierce: orange dot with its number; compensation may be refused: red ring; not cut: dashed orange; "
              "gap closed in the drawing: magenta ring</desc>\n");
  svg.add_raw("<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");
  if (nest.sheet) {
    svg.add_contour(nest.contours[*nest.sheet].source.contour,
                    std::string("fill=\"#eef0f2\" stroke=\"#7a828a\" stroke-width=\"1.5\" ") + kNs);
  }
  svg.begin_group("class=\"parts\" fill=\"#dbe7f3\" stroke=\"#9fb4c8\" stroke-width=\"0.8\"");
  for (const auto& part : nest.parts) {
    std::vector<const geometry::Contour*> rings{&nest.contours[part.outer].source.contour};
    for (auto h : part.holes) rings.push_back(&nest.contours[h].source.contour);
    svg.add_contours(rings, kNs);
  }
  svg.end_group();
  if (!options.not_cut.empty()) {
    svg.begin_group("class=\"not-cut\" fill=\"none\" stroke=\"#e67e22\" stroke-width=\"1.5\" stroke-dasharray=\"3 3\"");
    for (const auto& [c, why] : options.not_cut) {
      svg.begin_group("");
      svg.add_raw("<title>" + xml_escape(why) + "</title>\n");
      svg.add_contour(c, kNs);
      svg.end_group();
    }
    svg.end_group();
  }

  if (!options.gaps_closed.empty()) {
    svg.begin_group("class=\"gaps\" fill=\"none\" stroke=\"#c2188b\" stroke-width=\"2\" " + std::string(kNs));
    for (const auto& [p, why] : options.gaps_closed) {
      svg.begin_group("");
      svg.add_raw("<title>" + xml_escape(why) + "</title>\n");
      svg.add_circle(p, mark_mm * 3, kNs);
      svg.end_group();
    }
    svg.end_group();
  }

  // Contours whose cut is shared out over several segments (multi-segment cutting, common lines):
  // their pieces are drawn apart (class "piece"), so that where one stops and the next starts shows.
  std::vector<std::size_t> last_seg(nest.contours.size(), 0), segs_on(nest.contours.size(), 0);
  for (std::size_t k = 0; k < path.segments.size(); ++k)
    for (const auto& piece : path.segments[k].pieces) {
      if (piece.role != nc::PieceRole::contour || piece.contour < 0) continue;
      const auto c = static_cast<std::size_t>(piece.contour);
      if (c >= segs_on.size() || (segs_on[c] > 0 && last_seg[c] == k)) continue;
      ++segs_on[c];
      last_seg[c] = k;
    }
  std::vector<std::size_t> pieces_drawn(nest.contours.size(), 0);
  geometry::Vec2 at = path.start;
  // A number spans its digits to the right of its x: bold sans-serif digits advance up to 0.7 of
  // the size (DejaVu Sans Bold, the browsers' sans-serif on Debian), plus a tenth of the size kept
  // free; its digits rise about 0.75 of the size above the baseline.
  auto width_of = [label_mm](std::size_t number) { return label_mm * (0.7 * static_cast<double>(std::to_string(number).size()) + 0.1); };
  // Each number goes to the first free place of a ring of places round its pierce mark, nearest
  // first, and stays within three label heights of it; where all are taken (a dense nest seen
  // whole) it is left out, the segment's <title> and the page's slider still name it. Before, a
  // number only moved up its column until free: on d2g_DRAAK 707 of 904 numbers stood nearer
  // another pierce than their own (one 8.7 m above it) and 282 were pushed off the picture.
  // Placed labels are looked up in a grid of label-sized cells.
  const double cell = label_mm * 1.2;
  std::unordered_map<std::pair<long long, long long>, std::vector<geometry::Box>, CellHash> taken;
  auto key = [cell](double x, double y) {
    auto c = [cell](double v) {
      const double q = v / cell;
      return std::isfinite(q) ? static_cast<long long>(std::floor(std::clamp(q, -1e15, 1e15))) : 0LL;
    };
    return std::pair{c(x), c(y)};
  };
  auto free_at = [&](const geometry::Box& b) {
    const auto lo = key(b.xmin, b.ymin), hi = key(b.xmax, b.ymax);
    for (long long i = lo.first; i <= hi.first; ++i)
      for (long long j = lo.second; j <= hi.second; ++j) {
        const auto it = taken.find({i, j});
        if (it == taken.end()) continue;
        for (const auto& o : it->second)
          if (b.xmin < o.xmax && o.xmin < b.xmax && b.ymin < o.ymax && o.ymin < b.ymax) return false;
      }
    return true;
  };
  auto take = [&](const geometry::Box& b) {
    const auto lo = key(b.xmin, b.ymin), hi = key(b.xmax, b.ymax);
    for (long long i = lo.first; i <= hi.first; ++i)
      for (long long j = lo.second; j <= hi.second; ++j) taken[{i, j}].push_back(b);
  };
  const double rise = label_mm * 0.75, gap = mark_mm * 1.5;
  const geometry::Box frame{world.xmin - margin, world.ymin - margin, world.xmax + margin, world.ymax + margin};
  // Places by distance: beside the mark (upper right first, as before), then one and two label
  // heights further out.
  // Every pierce mark is kept clear, so that no number sits on another segment's mark.
  for (const auto& seg : path.segments)
    take({seg.pierce.x - mark_mm, seg.pierce.y - mark_mm, seg.pierce.x + mark_mm, seg.pierce.y + mark_mm});
  std::vector<geometry::Vec2> offsets;  // of the label's lower-left corner, width 0
  for (int ring = 0; ring < 3; ++ring) {
    const double d = gap + ring * label_mm;
    for (const geometry::Vec2 o : {geometry::Vec2{d, d}, {d, -d - rise}, {-d, d}, {-d, -d - rise}, {d, -rise / 2}, {-d, -rise / 2},
                                   {0, d}, {0, -d - rise}})
      offsets.push_back(o);
  }
  std::vector<std::size_t> risky = options.compensation_at_risk;
  std::sort(risky.begin(), risky.end());
  for (std::size_t k = 0; k < path.segments.size(); ++k) {
    const auto& s = path.segments[k];
    svg.begin_group("class=\"seg\" data-k=\"" + std::to_string(k + 1) + "\"");
    const bool at_risk = std::binary_search(risky.begin(), risky.end(), k + 1);
    svg.add_raw("<title>" + std::to_string(k + 1) + ": " + xml_escape(s.label) +
                (at_risk ? " (details finer than the kerf: the controller's compensation may refuse this cut)" : "") +
                "</title>\n");
    add_rapid(svg, at, s.rapid_via, s.pierce);
    // Over a tab the head moves with the beam off along the contour: that stretch is the tab,
    // drawn thick (under a pierce mark of a millimetre it would not show); its pierce mark small.
    const bool tab = s.after_tab && !s.pieces.empty() && s.pieces.front().role != nc::PieceRole::lead_in;
    if (tab) {
      geometry::Vec2 from = at;
      for (const geometry::Vec2 p : s.rapid_via) {
        svg.add_line(from, p, std::string("class=\"tab\" stroke=\"#16a085\" stroke-width=\"5\" stroke-linecap=\"round\" ") + kNs);
        from = p;
      }
      svg.add_line(from, s.pierce, std::string("class=\"tab\" stroke=\"#16a085\" stroke-width=\"5\" stroke-linecap=\"round\" ") + kNs);
    }
    for (const auto& piece : s.pieces) {
      const bool lead = piece.role == nc::PieceRole::lead_in || piece.role == nc::PieceRole::lead_out;
      const bool bridge = piece.role == nc::PieceRole::bridge;
      const bool shared = piece.role == nc::PieceRole::contour && piece.contour >= 0 &&
                          static_cast<std::size_t>(piece.contour) < segs_on.size() && segs_on[static_cast<std::size_t>(piece.contour)] > 1;
      // Bridges (chain cutting) drawn thicker in violet: a cut through scrap that is easy to miss;
      // pieces of a contour cut in several segments in orange and ochre by turns (each with its
      // own pierce number), so that two pieces meeting at a split point look different.
      const bool odd = shared && pieces_drawn[static_cast<std::size_t>(piece.contour)]++ % 2 == 1;
      const char* colour = lead ? "#1a9c3a" : bridge ? "#8e44ad" : shared ? (odd ? "#b7950b" : "#d35400") : "#c0392b";
      const char* width = lead ? "1.5" : bridge ? "2.4" : shared ? "2.0" : "1.6";
      const char* cls = bridge ? "class=\"bridge\" " : shared ? "class=\"piece\" " : "";
      svg.add_contour(piece.path, std::string("fill=\"none\" stroke=\"") + colour + "\" stroke-width=\"" + width + "\" " + cls + kNs);
    }
    svg.add_circle(s.pierce, s.after_tab ? mark_mm * 0.4 : mark_mm, "fill=\"#f39c12\" stroke=\"#7a4a00\" stroke-width=\"0.6\" " + std::string(kNs));
    if (at_risk) svg.add_circle(s.pierce, mark_mm * 3, "class=\"risk\" fill=\"none\" stroke=\"#e00000\" stroke-width=\"2\" " + std::string(kNs));
    // The number at the first free place round its mark (see above); "left" places end at the mark.
    const double width = width_of(k + 1);
    for (const geometry::Vec2 o : offsets) {
      const double x = o.x < 0 ? s.pierce.x + o.x - width : o.x == 0 ? s.pierce.x - width / 2 : s.pierce.x + o.x;
      const geometry::Box box{x, s.pierce.y + o.y, x + width, s.pierce.y + o.y + rise};
      if (box.xmin < frame.xmin || box.xmax > frame.xmax || box.ymin < frame.ymin || box.ymax > frame.ymax || !free_at(box)) continue;
      take(box);
      svg.add_text({box.xmin, box.ymin}, std::to_string(k + 1), label_mm, "fill=\"#5b1a12\" font-family=\"sans-serif\" font-weight=\"bold\"");
      break;
    }
    svg.end_group();
    at = nc::tool_off_point(s);
  }
  svg.begin_group("class=\"seg\" data-k=\"" + std::to_string(path.segments.size() + 1) + "\"");
  add_rapid(svg, at, path.end_via, path.end);
  svg.end_group();
  // A start off the picture is marked where its rapid comes in, with its coordinates.
  const bool start_off = far_off(drawn, path.start);
  const geometry::Vec2 first = path.segments.empty() ? path.end : path.segments.front().pierce;
  const geometry::Vec2 start_mark = start_off ? entry_point(world, path.start, first) : path.start;
  svg.add_circle(start_mark, mark_mm * 2.5, "fill=\"none\" stroke=\"#111111\" stroke-width=\"2\" " + std::string(kNs));
  const std::string start_text =
      start_off ? "start (" + format_fixed(path.start.x, 1) + ", " + format_fixed(path.start.y, 1) + ")" : "start";
  // Written to the left of the mark where it would run past the picture's right edge (a far
  // start comes in at an edge); sans-serif letters advance about 0.6 of the size.
  const double text_mm = 0.6 * label_mm * static_cast<double>(start_text.size());
  const double right = start_mark.x + mark_mm * 3 + text_mm > world.xmax + margin ? -mark_mm * 3 - text_mm : mark_mm * 3;
  svg.add_text(start_mark + geometry::Vec2{std::max(right, world.xmin - margin - start_mark.x), -mark_mm * 6}, start_text,
               label_mm, "fill=\"#111111\" font-family=\"sans-serif\"");
  if (!options.caption.empty())
    svg.add_text({world.xmin, caption_y}, options.caption, caption_mm,
                 "class=\"caption\" fill=\"#222222\" font-family=\"sans-serif\"");
  return svg.str();
}

std::vector<std::pair<std::string, std::string>> report_summary(const nlohmann::json& r) {
  std::vector<std::pair<std::string, std::string>> rows;
  auto num = [&](const char* key, int decimals) {
    return r.contains(key) && r[key].is_number() ? format_fixed(r[key].get<double>(), decimals) : std::string("-");
  };
  auto str = [&](const char* key) { return r.contains(key) && r[key].is_string() ? r[key].get<std::string>() : std::string("-"); };
  rows.emplace_back("material", str("material") + " " + num("thickness_mm", 2) + " mm" +
                                    (r.value("measured_speed_row", true) ? "" : " (extrapolated speed row)"));
  rows.emplace_back("pierces", num("pierces", 0));
  rows.emplace_back("cut length L_on", num("cut_length_mm", 1) + " mm");
  rows.emplace_back("rapid length L_off", num("rapid_length_mm", 1) + " mm");
  rows.emplace_back("frames n", num("frames", 0));
  rows.emplace_back("set speed V_on", num("v_on_set_m_s", 4) + " m/s");
  rows.emplace_back("working speed V_on*(n)", num("v_on_m_s", 4) + " m/s (" + str("v_on_regime") + ")");
  rows.emplace_back("T_cut, eq. 10", num("t_cut_s", 2) + " s");
  rows.emplace_back("T_cut at the set speed, eq. 1", num("t_cut_const_speed_s", 2) + " s");
  if (r.contains("breakdown")) {
    const auto& b = r["breakdown"];
    rows.emplace_back("cutting / rapid / pierce", format_fixed(b.value("cutting_s", 0.0), 1) + " / " +
                                                      format_fixed(b.value("rapid_s", 0.0), 1) + " / " +
                                                      format_fixed(b.value("pierce_s", 0.0), 1) + " s");
  }
  rows.emplace_back("lead-in", str("lead_in"));
  if (r.contains("compensation") && r["compensation"].value("at_risk", 0) > 0)
    rows.emplace_back("compensation at risk", std::to_string(r["compensation"].value("at_risk", 0)) + " of " +
                                                  std::to_string(r["compensation"].value("blocks", 0)) +
                                                  " cuts have details finer than the kerf (red rings)");
  if (r.contains("diagnostics")) {
    const auto gaps = std::count_if(r["diagnostics"].begin(), r["diagnostics"].end(),
                                    [](const nlohmann::json& d) { return d.value("code", "") == "chain.gap_closed"; });
    if (gaps > 0)
      rows.emplace_back("gaps closed in the drawing", std::to_string(gaps) + ", each end moved by half the gap (magenta rings)");
  }
  if (r.contains("kerf_mode")) {
    const std::string mode = str("kerf_mode");
    rows.emplace_back("kerf", num("kerf_mm", 3) + " mm, " +
                                  (mode == "cam" ? std::string("cam (toolpath drawn offset by kerf/2)")
                                   : mode == "controller" ? std::string("controller (G41/G42)") : mode));
  }
  // GSCCP: each set of basic segments compared, the chosen one first named.
  if (r.contains("alternatives") && r["alternatives"].is_array()) {
    std::string alts;
    for (const auto& a : r["alternatives"]) {
      if (!a.is_object() || !a.value("available", false)) continue;
      if (!alts.empty()) alts += "; ";
      alts += a.value("name", std::string("?")) + " " + std::to_string(a.value("pierces", 0)) + " pierces " +
              format_fixed(a.value("t_cut_s", 0.0), 2) + " s";
    }
    rows.emplace_back("technique", str("chosen") + (alts.empty() ? "" : " (" + alts + ")"));
  }
  if (r.contains("solver")) {
    const auto& sv = r["solver"];
    const std::string status = sv.value("status", std::string("-"));
    std::string text = sv.value("name", std::string("-")) + ", " + status;
    // The route search's bound, so a feasible route shows how far from the best it can be at most.
    if (sv.contains("objective") && sv["objective"].is_number() && sv.contains("lower_bound") && sv["lower_bound"].is_number()) {
      const double objective = sv["objective"].get<double>(), bound = sv["lower_bound"].get<double>();
      const std::string unit = r.contains("cost_unit") && r["cost_unit"].is_string() ? " " + r["cost_unit"].get<std::string>() : "";
      text += "; route " + format_fixed(objective, 2) + unit + ", lower bound " + format_fixed(bound, 2) + unit;
      if (const auto gap = gap_percent(r)) text += " (gap " + format_fixed(*gap, 2) + " %)";
    }
    rows.emplace_back("solver", text);
  }
  return rows;
}

std::string report_caption(const nlohmann::json& r) {
  if (!r.is_object()) return {};
  auto num = [&](const char* key, int decimals) {
    return r.contains(key) && r[key].is_number() ? format_fixed(r[key].get<double>(), decimals) : std::string("-");
  };
  std::string out = r.value("material", std::string("-")) + " " + num("thickness_mm", 2) + " mm";
  if (r.contains("chosen") && r["chosen"].is_string()) out += " · " + r["chosen"].get<std::string>() + " cutting";
  out += " · " + num("pierces", 0) + " pierces · cut " + num("cut_length_mm", 1) + " mm · rapid " + num("rapid_length_mm", 1) +
         " mm · T_cut " + num("t_cut_s", 2) + " s (eq. 10)";
  if (const std::string q = route_quality(r); !q.empty()) out += " · route " + q;
  return out;
}

std::string route_quality(const nlohmann::json& r) {
  if (r.is_object() && r.contains("solver") && r["solver"].is_object() && r["solver"].value("status", std::string()) == "optimal")
    return "optimal";
  const auto gap = gap_percent(r);
  return gap ? "gap " + format_fixed(*gap, 2) + " % to its lower bound" : "";
}

std::string route_to_html(const model::Nest& nest, const nc::Toolpath& path,
                          const std::vector<std::pair<std::string, std::string>>& summary,
                          const RoutePictureOptions& options) {
  std::string rows;
  for (const auto& [label, value] : summary) {
    rows += "<tr><th>" + xml_escape(label) + "</th><td>" + xml_escape(value) + "</td></tr>\n";
  }
  const std::size_t n = path.segments.size();
  std::string html;
  html += "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" + xml_escape(options.title) +
          "</title>\n<style>\n"
          "body{font-family:sans-serif;margin:16px;color:#222}\n"
          "#controls{margin:8px 0;display:flex;gap:12px;align-items:center}\n"
          "#step{width:480px}\n"
          "table{border-collapse:collapse;margin-top:12px}th,td{border:1px solid #ccc;padding:3px 8px;text-align:left}\n"
          "th{background:#f3f5f7;font-weight:normal;color:#555}\n"
          "svg{max-width:100%;height:auto;border:1px solid #ddd}\n"
          "</style></head><body>\n";
  html += "<h1>" + xml_escape(options.title) + "</h1>\n";
  html += "<div id=\"controls\"><button id=\"play\" type=\"button\">Play</button>"
          "<input id=\"step\" type=\"range\" min=\"0\" max=\"" + std::to_string(n + 1) + "\" value=\"" + std::to_string(n + 1) +
          "\"><span id=\"label\"></span></div>\n";
  html += "<p id=\"legend\">"
          "<span style=\"color:#c0392b\">&#9644; cut</span> &nbsp; "
          "<span style=\"color:#d35400\">&#9644;</span><span style=\"color:#b7950b\">&#9644; pieces of one contour</span> &nbsp; "
          "<span style=\"color:#1a9c3a\">&#9644; lead-in / lead-out</span> &nbsp; "
          "<span style=\"color:#8e44ad\">&#9644; bridge</span> &nbsp; "
          "<span style=\"color:#2f6fdf\">- - rapid</span> &nbsp; "
          "<span style=\"color:#16a085\">&#9644; tab (material left)</span> &nbsp; "
          "<span style=\"color:#f39c12\">&#9679; pierce</span> &nbsp; "
          "<span style=\"color:#e00000\">&#9711; compensation may be refused</span> &nbsp; "
          "<span style=\"color:#e67e22\">- - not cut (open contour)</span> &nbsp; "
          "<span style=\"color:#c2188b\">&#9711; gap closed in the drawing</span></p>\n";
  RoutePictureOptions in_page = options;
  in_page.caption.clear();  // the table below says it all
  html += route_to_svg(nest, path, in_page).substr(std::string("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n").size());
  html += "<table>\n" + rows + "</table>\n";
  html += "<script>\n"
          "const segs=[...document.querySelectorAll('g.seg')];\n"
          "const step=document.getElementById('step'),label=document.getElementById('label'),play=document.getElementById('play');\n"
          "function show(k){segs.forEach(g=>{g.style.display=(+g.dataset.k<=k)?'':'none';});\n"
          " const g=segs.find(g=>+g.dataset.k===k);const t=g&&g.querySelector('title');\n"
          " const last=segs.length-1;\n"
          " label.textContent=(k>last?last+' / '+last+'  park':k+' / '+last)+(t?'  '+t.textContent:'');}\n"
          "let timer=null;\n"
          "step.addEventListener('input',()=>show(+step.value));\n"
          "play.addEventListener('click',()=>{if(timer){clearInterval(timer);timer=null;play.textContent='Play';return;}\n"
          " if(+step.value>=+step.max)step.value=0;play.textContent='Pause';\n"
          " timer=setInterval(()=>{step.value=+step.value+1;show(+step.value);\n"
          "  if(+step.value>=+step.max){clearInterval(timer);timer=null;play.textContent='Play';}},Math.max(60,6000/segs.length));});\n"
          "const k0=parseInt(location.hash.slice(1),10);if(k0>=0&&k0<=+step.max)step.value=k0;\n"
          "show(+step.value);\n"
          "</script>\n</body></html>\n";
  return html;
}

std::vector<std::size_t> compensation_at_risk(const nlohmann::json& report) {
  std::vector<std::size_t> out;
  if (!report.contains("compensation")) return out;
  for (const auto& k : report["compensation"].value("at_risk_segments", nlohmann::json::array()))
    if (k.is_number_unsigned()) out.push_back(k.get<std::size_t>());
  return out;
}

}  // namespace cutroute::io
