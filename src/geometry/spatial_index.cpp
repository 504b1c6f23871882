// StaticSpatialIndex: Hilbert sort of the box centres, then bottom-up packing of the levels.
#include <cutroute/geometry/spatial_index.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace cutroute::geometry {

namespace {

// Index of (x, y) on the Hilbert curve of order 16 (x, y in [0, 65535]).
std::uint32_t hilbert_index(std::uint32_t x, std::uint32_t y) {
  std::uint32_t d = 0;
  for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
    const std::uint32_t rx = (x & s) ? 1u : 0u;
    const std::uint32_t ry = (y & s) ? 1u : 0u;
    d += s * s * ((3u * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant
      if (rx == 1) {
        x = s - 1 - (x & (s - 1));
        y = s - 1 - (y & (s - 1));
      }
      std::swap(x, y);
    }
    x &= s - 1;
    y &= s - 1;
  }
  return d;
}

bool usable(const Box& b) {
  return !b.empty() && std::isfinite(b.xmin) && std::isfinite(b.ymin) && std::isfinite(b.xmax) &&
         std::isfinite(b.ymax);
}

}  // namespace

StaticSpatialIndex::StaticSpatialIndex(const std::vector<Box>& boxes) : count_(boxes.size()) {
  if (count_ == 0) return;
  Box extent;
  for (const Box& b : boxes) if (usable(b)) extent.add(b);
  const double w = extent.width() > 0 ? extent.width() : 1.0;
  const double h = extent.height() > 0 ? extent.height() : 1.0;
  std::vector<std::uint32_t> keys(count_);
  for (std::size_t i = 0; i < count_; ++i) {
    const Box& b = boxes[i];
    if (!usable(b)) {
      keys[i] = 0xFFFFFFFFu;  // never reported; park at the end
      continue;
    }
    const Vec2 c = b.center();
    const auto qx = static_cast<std::uint32_t>(std::clamp((c.x - extent.xmin) / w, 0.0, 1.0) * 65535.0);
    const auto qy = static_cast<std::uint32_t>(std::clamp((c.y - extent.ymin) / h, 0.0, 1.0) * 65535.0);
    keys[i] = hilbert_index(qx, qy);
  }
  indices_.resize(count_);
  std::iota(indices_.begin(), indices_.end(), 0u);
  std::stable_sort(indices_.begin(), indices_.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });

  nodes_.reserve(count_ + count_ / (kNodeSize - 1) + 2);
  for (std::uint32_t i : indices_) nodes_.push_back(usable(boxes[i]) ? boxes[i] : Box{});
  level_bounds_.push_back(nodes_.size());
  std::size_t level_begin = 0;
  while (nodes_.size() - level_begin > 1) {
    const std::size_t level_end = nodes_.size();
    for (std::size_t i = level_begin; i < level_end; i += kNodeSize) {
      Box parent;
      const std::size_t stop = std::min(i + kNodeSize, level_end);
      for (std::size_t j = i; j < stop; ++j) parent.add(nodes_[j]);
      nodes_.push_back(parent);
    }
    level_begin = level_end;
    level_bounds_.push_back(nodes_.size());
  }
}

void StaticSpatialIndex::query(const Box& q, const std::function<bool(std::uint32_t)>& visit_fn) const {
  visit(q, [&](std::uint32_t i) { return visit_fn(i); });
}

void StaticSpatialIndex::query(const Box& q, std::vector<std::uint32_t>& out) const {
  out.clear();
  visit(q, [&](std::uint32_t i) {
    out.push_back(i);
    return true;
  });
}

}  // namespace cutroute::geometry
