// nest_to_svg(): a picture of a loaded nest: parts filled, holes, open paths dashed, sheet outline.
#pragma once

#include <string>

#include <cutroute/io/nest_loader.hpp>

namespace cutroute::io {

struct NestSvgOptions {
  double width_px = 1200;   // picture width on screen [px]
  bool label_parts = true;  // part numbers at each part's box centre
};

std::string nest_to_svg(const LoadedNest& nest, const NestSvgOptions& options = {});

}  // namespace cutroute::io
