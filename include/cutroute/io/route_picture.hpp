// route_to_svg() / route_to_html(): pictures of a cutting route to check at a glance.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <cutroute/model/nest.hpp>
#include <cutroute/nc/toolpath.hpp>

namespace cutroute::io {

struct RoutePictureOptions {
  double width_px = 1400;
  std::string title;
  // Segments (numbered from 1, as drawn) whose cut a controller's compensation may refuse: their
  // pierce gets a red ring and their title says why (report "compensation").
  std::vector<std::size_t> compensation_at_risk;
  // Drawn paths the program does not cut (open contours), each with what to say of it: dashed
  // orange, so that a part missing from the program shows (its holes would look like parts).
  std::vector<std::pair<geometry::Contour, std::string>> not_cut;
  // Gaps closed in the drawing (io::LoadedNest::gaps_closed), each with its warning: magenta rings.
  std::vector<std::pair<geometry::Vec2, std::string>> gaps_closed;
  // One line of figures written under the picture (report_caption()), so that a standalone SVG
  // says what it shows; empty: none (the HTML page has its table).
  std::string caption;
};

// The caption of a standalone picture: material, technique, pierces, lengths, T_cut and how good
// the route is, from an optimize report.
std::string report_caption(const nlohmann::json& report);

// The report's compensation.at_risk_segments, for RoutePictureOptions (empty when absent).
std::vector<std::size_t> compensation_at_risk(const nlohmann::json& report);

// Parts (filled, holes open), then per cutting segment in order: the rapid to its pierce (dashed),
// the pierce mark, the lead-in, the cut, the lead-out, and the segment's order number beside the
// pierce (marks and numbers sized for the nest seen whole but at most a fraction of the pierces'
// median spacing; each number at the first free place of eight round its mark at three distances,
// clear of every mark and earlier number; with none free it is left out, the segment's <title>
// still names it); the start point is marked. A start or park point
// farther from the nest than the nest is wide is left out of the frame, and the start is marked
// where its rapid comes in, with its coordinates. Each segment is one <g class="seg" data-k="k">
// (k from 1).
std::string route_to_svg(const model::Nest& nest, const nc::Toolpath& path, const RoutePictureOptions& options);

// One self-contained HTML page: the picture, a summary table (label, value rows as given) and a
// slider with a play button that shows the cutting order step by step; the address fragment #k
// opens the page at step k. No external resources.
std::string route_to_html(const model::Nest& nest, const nc::Toolpath& path,
                          const std::vector<std::pair<std::string, std::string>>& summary,
                          const RoutePictureOptions& options);

// The rows a person wants from an optimize report: pierces, lengths, frames, speeds, times.
std::vector<std::pair<std::string, std::string>> report_summary(const nlohmann::json& report);

// How good the route is, from the report's solver block: "optimal" when proven, "gap Z % to its
// lower bound" (Z = 100 (route - bound) / route) when a bound came with it, else empty.
std::string route_quality(const nlohmann::json& report);

}  // namespace cutroute::io
