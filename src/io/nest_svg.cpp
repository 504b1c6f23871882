#include <cutroute/io/nest_svg.hpp>

#include <algorithm>

#include <cutroute/core/number_format.hpp>
#include <cutroute/io/svg.hpp>

namespace cutroute::io {

std::string nest_to_svg(const LoadedNest& loaded, const NestSvgOptions& options) {
  const model::Nest& nest = loaded.nest;
  geometry::Box world;
  for (const auto& c : nest.contours) world.add(c.box);
  for (const auto& p : loaded.open_paths) world.add(geometry::bounding_box(p.path));
  if (world.empty()) world = geometry::Box{0, 0, 100, 100};
  const double margin = std::max(world.width(), world.height()) * 0.02 + 1.0;
  SvgDocument svg(world, margin, options.width_px);
  const double label_mm = std::max(world.width(), world.height()) / 80.0;

  svg.add_raw("<title>" + xml_escape(loaded.file) + "</title>\n");
  svg.add_raw("<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");

  if (nest.sheet) {
    svg.add_contour(nest.contours[*nest.sheet].source.contour,
                    "fill=\"#eef0f2\" stroke=\"#7a828a\" stroke-width=\"1.5\" vector-effect=\"non-scaling-stroke\"");
  }

  // Parts in order of depth so that a part inside another part's hole is drawn on top of it.
  std::vector<model::PartId> order;
  for (std::size_t i = 0; i < nest.parts.size(); ++i) order.emplace_back(static_cast<std::int32_t>(i));
  std::stable_sort(order.begin(), order.end(), [&](model::PartId a, model::PartId b) {
    return nest.contours[nest.parts[a].outer].depth < nest.contours[nest.parts[b].outer].depth;
  });
  svg.begin_group("class=\"parts\" fill=\"#b9d3ee\" stroke=\"#1f4e79\" stroke-width=\"1\" vector-effect=\"non-scaling-stroke\"");
  for (auto pid : order) {
    const auto& part = nest.parts[pid];
    std::vector<const geometry::Contour*> rings{&nest.contours[part.outer].source.contour};
    for (auto h : part.holes) rings.push_back(&nest.contours[h].source.contour);
    svg.add_contours(rings, "vector-effect=\"non-scaling-stroke\"");
  }
  svg.end_group();

  if (options.label_parts) {
    svg.begin_group("class=\"labels\" fill=\"#0b2540\" font-family=\"sans-serif\" text-anchor=\"middle\"");
    for (std::size_t i = 0; i < nest.parts.size(); ++i) {
      const auto& box = nest.contours[nest.parts[model::PartId(static_cast<std::int32_t>(i))].outer].box;
      const double size = std::min(label_mm, std::max(box.height(), 1.0) * 0.4);
      svg.add_text(box.center(), std::to_string(i + 1), size, "");
    }
    svg.end_group();
  }

  if (!loaded.open_paths.empty()) {
    svg.begin_group("class=\"open\" fill=\"none\" stroke=\"#d9730d\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\"");
    for (const auto& p : loaded.open_paths) svg.add_contour(p.path, "vector-effect=\"non-scaling-stroke\"");
    svg.end_group();
  }

  // A gap closed in the drawing changed it: a magenta ring each, its warning as the tooltip, sized
  // for the picture so that a 0.01 mm gap can be found on a 3 m sheet.
  if (!loaded.gaps_closed.empty()) {
    svg.begin_group("class=\"gaps\" fill=\"none\" stroke=\"#c2188b\" stroke-width=\"2\" vector-effect=\"non-scaling-stroke\"");
    for (const auto& [at, why] : loaded.gaps_closed) {
      svg.begin_group("");
      svg.add_raw("<title>" + xml_escape(why) + "</title>\n");
      svg.add_circle(at, label_mm * 0.6, "vector-effect=\"non-scaling-stroke\"");
      svg.end_group();
    }
    svg.end_group();
  }

  std::string caption = loaded.file + ": " + std::to_string(nest.parts.size()) + " parts, " +
                        std::to_string(nest.contours.size()) + " closed contours, " +
                        std::to_string(loaded.open_paths.size()) + " open paths" +
                        (loaded.gaps_closed.empty() ? std::string() : ", " + std::to_string(loaded.gaps_closed.size()) + " gaps closed (magenta rings)");
  svg.add_text({world.xmin, world.ymax + margin * 0.35}, caption, margin * 0.4,
               "fill=\"#333333\" font-family=\"sans-serif\"");
  return svg.str();
}

}  // namespace cutroute::io
