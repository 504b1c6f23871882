// Uniform box grid of the kerf offset (see offset_grid.hpp).
#include "geometry/offset_grid.hpp"

#include <algorithm>
#include <cmath>

namespace cutroute::geometry::offset_detail {

BoxGrid::BoxGrid(const std::vector<Box>& boxes, double margin) : seen_(boxes.size(), 0) {
  std::vector<Box> grown(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    grown[i] = boxes[i].inflated(margin);
    extent_.add(grown[i]);
  }
  if (extent_.empty()) {
    start_.assign(2, 0);
    return;
  }
  if (boxes.size() <= kSmall) {
    items_.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) items_[i] = i;
    start_ = {0, items_.size()};
    return;
  }
  // About 4 cells per box over the extent, square cells.
  const double w = std::max(extent_.width(), 1e-9), h = std::max(extent_.height(), 1e-9);
  const double cells = 4.0 * static_cast<double>(boxes.size()) + 16.0;
  cell_ = std::sqrt(w * h / cells);
  cell_ = std::max({cell_, w / cells, h / cells});  // a thin extent still gets <= `cells` cells
  nx_ = static_cast<std::size_t>(std::min(std::ceil(w / cell_), cells)) + 1;
  ny_ = static_cast<std::size_t>(std::min(std::ceil(h / cell_), cells)) + 1;

  std::vector<std::size_t> count(nx_ * ny_ + 1, 0);
  auto for_cells = [&](const Box& b, auto&& g) {
    for (std::size_t cy = cell_y(b.ymin); cy <= cell_y(b.ymax); ++cy)
      for (std::size_t cx = cell_x(b.xmin); cx <= cell_x(b.xmax); ++cx) g(cy * nx_ + cx);
  };
  for (const Box& b : grown) for_cells(b, [&](std::size_t c) { ++count[c + 1]; });
  for (std::size_t c = 0; c < nx_ * ny_; ++c) count[c + 1] += count[c];
  start_ = count;
  items_.resize(count.back());
  for (std::size_t i = 0; i < grown.size(); ++i) for_cells(grown[i], [&](std::size_t c) { items_[count[c]++] = i; });
}

std::size_t BoxGrid::cell_x(double x) const {
  const double c = std::floor((x - extent_.xmin) / cell_);
  return static_cast<std::size_t>(std::clamp(c, 0.0, static_cast<double>(nx_ - 1)));
}

std::size_t BoxGrid::cell_y(double y) const {
  const double c = std::floor((y - extent_.ymin) / cell_);
  return static_cast<std::size_t>(std::clamp(c, 0.0, static_cast<double>(ny_ - 1)));
}

}  // namespace cutroute::geometry::offset_detail
