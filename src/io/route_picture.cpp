#include <cutroute/io/route_picture.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
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

geometry::Box nest_box(const model::Nest& nest, const nc::Toolpath& path) {
  geometry::Box b;
  for (const auto& c : nest.contours) b.add(c.box);
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
  const geometry::Box drawn = nest_box(nest, path);
  const geometry::Box world = world_box(drawn, path);
  const double span = std::max(world.width(), world.height());
  const double margin = span * 0.02 + 1.0;
  SvgDocument svg(world, margin, options.width_px);
  const double label_mm = std::max(span / 90.0, 0.5);
  const double mark_mm = std::max(span / 400.0, 0.2);

  if (!options.title.empty()) svg.add_raw("<title>" + xml_escape(options.title) + "</title>\n");
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
  // free. Two numbers overlap across when their spans meet (with a fixed 1.6 sizes, 281 pairs of
  // d2g_DRAAK's 3- and 4-digit numbers overprinted).
  auto width_of = [label_mm](std::size_t number) { return label_mm * (0.7 * static_cast<double>(std::to_string(number).size()) + 0.1); };
  struct Placed {
    geometry::Vec2 at;
    double width;
  };
  std::vector<Placed> placed;  // labels so far
  // A label keeps its x and only moves up, so only labels in its column can push it: they are
  // looked up by column (cells of the widest number's span in x), in the order they were placed,
  // which gives the same positions as scanning every label. That scan was O(n^2): 5 000 parts
  // with two holes each (13 333 pierces) spent 1 s in each picture.
  const double push_x = width_of(path.segments.size()), push_y = label_mm * 0.9;
  std::map<long long, std::vector<std::size_t>> columns;  // column -> indices into `placed`
  auto column_of = [push_x](double x) {
    const double c = x / push_x;
    return std::isfinite(c) ? static_cast<long long>(std::floor(std::clamp(c, -1e15, 1e15))) : 0LL;
  };
  std::vector<std::size_t> near;
  // A number pushed above the picture's top edge could not be seen: it is left out (the page's
  // slider names every step from its segment's title) and pushes no other. On dense nests the
  // stacks grew metres tall: 24 000 parts with two holes each, 56 000 pierces, spent 6 s in each
  // picture and wrote 62 MB.
  const double top = world.ymax + margin;
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
    svg.add_circle(s.pierce, mark_mm, "fill=\"#f39c12\" stroke=\"#7a4a00\" stroke-width=\"0.6\" " + std::string(kNs));
    if (at_risk) svg.add_circle(s.pierce, mark_mm * 3, "class=\"risk\" fill=\"none\" stroke=\"#e00000\" stroke-width=\"2\" " + std::string(kNs));
    // Numbers of pierces that stand close together are stacked upwards instead of overprinted.
    geometry::Vec2 label_at = s.pierce + geometry::Vec2{mark_mm * 1.5, mark_mm * 1.5};
    const double width = width_of(k + 1);
    const long long col = column_of(label_at.x);
    near.clear();
    // Two columns either side: x / push_x may round across a cell boundary. Labels lower than the
    // push distance below the start can never be reached (twice that, for rounding).
    const double y0 = label_at.y;
    for (auto it = columns.lower_bound(col - 2); it != columns.end() && it->first <= col + 2; ++it)
      for (std::size_t i : it->second)
        if (placed[i].at.x < label_at.x + width && label_at.x < placed[i].at.x + placed[i].width && placed[i].at.y > y0 - 2 * push_y)
          near.push_back(i);
    std::sort(near.begin(), near.end());
    for (bool moved = true; moved && label_at.y <= top;) {
      moved = false;
      for (std::size_t i : near) {
        if (std::abs(placed[i].at.y - label_at.y) < push_y) {
          label_at.y = placed[i].at.y + label_mm;
          moved = true;
          if (label_at.y > top) break;
        }
      }
    }
    if (label_at.y <= top) {
      columns[col].push_back(placed.size());
      placed.push_back({label_at, width});
      svg.add_text(label_at, std::to_string(k + 1), label_mm,
                   "fill=\"#5b1a12\" font-family=\"sans-serif\" font-weight=\"bold\"");
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
  svg.add_text(start_mark + geometry::Vec2{mark_mm * 3, -mark_mm * 6},
               start_off ? "start (" + format_fixed(path.start.x, 1) + ", " + format_fixed(path.start.y, 1) + ")" : "start",
               label_mm, "fill=\"#111111\" font-family=\"sans-serif\"");
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
  if (r.contains("breakdown_s")) {
    const auto& b = r["breakdown_s"];
    rows.emplace_back("cutting / rapid / pierce", format_fixed(b.value("cutting", 0.0), 1) + " / " +
                                                      format_fixed(b.value("rapid", 0.0), 1) + " / " +
                                                      format_fixed(b.value("pierce", 0.0), 1) + " s");
  }
  rows.emplace_back("lead-in", str("lead_in"));
  if (r.contains("compensation") && r["compensation"].value("at_risk", 0) > 0)
    rows.emplace_back("compensation at risk", std::to_string(r["compensation"].value("at_risk", 0)) + " of " +
                                                  std::to_string(r["compensation"].value("blocks", 0)) +
                                                  " cuts have details finer than the kerf (red rings)");
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
  html += route_to_svg(nest, path, options).substr(std::string("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n").size());
  html += "<table>\n" + rows + "</table>\n";
  html += "<script>\n"
          "const segs=[...document.querySelectorAll('g.seg')];\n"
          "const step=document.getElementById('step'),label=document.getElementById('label'),play=document.getElementById('play');\n"
          "function show(k){segs.forEach(g=>{g.style.display=(+g.dataset.k<=k)?'':'none';});\n"
          " const g=segs.find(g=>+g.dataset.k===k);const t=g&&g.querySelector('title');\n"
          " label.textContent=k+' / '+(segs.length)+(t?'  '+t.textContent:'');}\n"
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
