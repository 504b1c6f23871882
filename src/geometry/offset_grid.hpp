// Private uniform grid over the boxes of a contour's pieces, for the offset's "what is near
// this point / box" questions.
#pragma once

// Why not geometry/spatial_index.hpp: the offset is built and tested on its own while that index
// is being written; a uniform grid is enough here because the queries are small (a point's
// |d|-neighbourhood, one piece's box) and the pieces of one contour are of similar size.

#include <algorithm>
#include <cstddef>
#include <vector>

#include <cutroute/geometry/box.hpp>

namespace cutroute::geometry::offset_detail {

class BoxGrid {
 public:
  // Registers every box, grown by `margin` mm, in the cells it overlaps. At most about
  // 4 * boxes.size() + 16 cells; a box covering the whole extent is listed in every cell.
  // Up to kSmall boxes, a single cell (a plain scan is cheaper than cell arithmetic).
  BoxGrid(const std::vector<Box>& boxes, double margin);

  // Calls f(index) once for every box whose grown box may overlap `query`; stops early when
  // f returns true, and then returns true.
  template <class F>
  bool any_near(const Box& query, F&& f) const {
    if (query.empty() || extent_.empty() || !query.intersects(extent_)) return false;
    if (nx_ == 1 && ny_ == 1) {  // small contours: one cell, every box listed once
      for (std::size_t i : items_)
        if (f(i)) return true;
      return false;
    }
    const std::size_t x0 = cell_x(query.xmin), x1 = cell_x(query.xmax);
    const std::size_t y0 = cell_y(query.ymin), y1 = cell_y(query.ymax);
    if (++stamp_ == 0) {  // wrapped: forget every old visit
      std::fill(seen_.begin(), seen_.end(), 0u);
      stamp_ = 1;
    }
    for (std::size_t cy = y0; cy <= y1; ++cy)
      for (std::size_t cx = x0; cx <= x1; ++cx) {
        const std::size_t cell = cy * nx_ + cx;
        for (std::size_t k = start_[cell]; k < start_[cell + 1]; ++k) {
          const std::size_t i = items_[k];
          if (seen_[i] == stamp_) continue;
          seen_[i] = stamp_;
          if (f(i)) return true;
        }
      }
    return false;
  }

 private:
  static constexpr std::size_t kSmall = 32;

  std::size_t cell_x(double x) const;
  std::size_t cell_y(double y) const;

  Box extent_;                      // union of the grown boxes [mm]
  double cell_ = 1.0;               // cell side [mm]
  std::size_t nx_ = 1, ny_ = 1;
  std::vector<std::size_t> start_;  // CSR: items_[start_[c] .. start_[c+1]) are in cell c
  std::vector<std::size_t> items_;
  mutable std::vector<unsigned> seen_;  // per box: stamp of the last query that visited it
  mutable unsigned stamp_ = 0;
};

}  // namespace cutroute::geometry::offset_detail
