// StaticSpatialIndex: a packed, build-once index over many boxes (e.g. contours) for overlap queries.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <cutroute/geometry/box.hpp>

namespace cutroute::geometry {

// Built once from a list of boxes (flat arrays, no per-node allocation); queries visit the
// indices of boxes that intersect a query box, and the visitor may stop early by returning
// false. Queries are const and thread-safe.
class StaticSpatialIndex {
 public:
  StaticSpatialIndex() = default;
  explicit StaticSpatialIndex(const std::vector<Box>& boxes);

  std::size_t size() const { return count_; }

  // Calls visit(i) for each i with boxes[i] intersecting query; stops when visit returns false.
  void query(const Box& query, const std::function<bool(std::uint32_t)>& visit) const;
  // Appends the indices to out (cleared first); out is the caller's scratch buffer.
  void query(const Box& query, std::vector<std::uint32_t>& out) const;

 private:
  std::size_t count_ = 0;
  std::vector<Box> nodes_;               // all levels, leaves first
  std::vector<std::uint32_t> indices_;   // leaf order -> caller's index
  std::vector<std::size_t> level_bounds_;
};

}  // namespace cutroute::geometry
