// StaticSpatialIndex: a packed, build-once index over many boxes (e.g. contours) for overlap queries.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <cutroute/geometry/box.hpp>

namespace cutroute::geometry {

// Built once from a list of boxes (flat arrays, no per-node allocation); queries visit the
// indices of boxes that intersect a query box, and the visitor may stop early by returning
// false. Queries are const and thread-safe.
//
// Layout: a packed Hilbert R-tree. Boxes are sorted by the Hilbert index of their centres
// (16 bits per axis over the extent of all boxes) and grouped kNodeSize at a time, level by
// level, into one array `nodes_` (leaves first, root last); node k of a level has its children
// at kNodeSize·k.. of the level below, so the tree is implicit and needs no pointers.
// Build O(n log n); a query visits O(log n + hits) nodes for well-spread boxes.
// Empty boxes (and boxes with NaN) are kept but never reported.
class StaticSpatialIndex {
 public:
  static constexpr std::size_t kNodeSize = 16;

  StaticSpatialIndex() = default;
  explicit StaticSpatialIndex(const std::vector<Box>& boxes);

  std::size_t size() const { return count_; }

  // Calls visit(i) for each i with boxes[i] intersecting query; stops when visit returns false.
  void query(const Box& query, const std::function<bool(std::uint32_t)>& visit) const;
  // Appends the indices to out (cleared first); out is the caller's scratch buffer.
  void query(const Box& query, std::vector<std::uint32_t>& out) const;

  // The same as the std::function overload for any callable bool(std::uint32_t), inlined for
  // hot loops. Does not allocate (fixed-size traversal stack).
  template <class Visit>
  void visit(const Box& query, Visit&& visit) const;

 private:
  std::size_t count_ = 0;
  std::vector<Box> nodes_;               // all levels, leaves first
  std::vector<std::uint32_t> indices_;   // leaf order -> caller's index
  std::vector<std::size_t> level_bounds_;  // end (exclusive) of each level in nodes_
};

template <class Visit>
void StaticSpatialIndex::visit(const Box& query, Visit&& visit) const {
  if (count_ == 0 || query.empty()) return;
  // Children are tested before they are pushed, and a leaf's box is reported from its parent's
  // loop: pushing every child to test it when popped was most of the query's time (a sixth of
  // planning the entries of 72 000 contours). The bare comparisons suffice: the query is not
  // empty, and an empty node keeps Box{}'s infinite bounds, which no query overlaps.
  const Box* const nodes = nodes_.data();
  auto overlaps = [&query, nodes](std::size_t k) {
    const Box& b = nodes[k];
    return query.xmin <= b.xmax && query.xmax >= b.xmin && query.ymin <= b.ymax && query.ymax >= b.ymin;
  };
  const std::size_t root = nodes_.size() - 1;
  if (!overlaps(root)) return;
  if (level_bounds_.size() == 1) {  // one box: the root is the leaf
    visit(indices_[0]);
    return;
  }
  // Depth-first; at most kNodeSize entries per level wait on the stack, and a 32-bit count of
  // boxes needs at most 8 levels of 16.
  struct Entry {
    std::size_t node;
    std::size_t level;
  };
  Entry stack[kNodeSize * 10];
  std::size_t top = 0;
  stack[top++] = {root, level_bounds_.size() - 1};
  while (top > 0) {
    const Entry e = stack[--top];  // a node above the leaves that overlaps the query
    const std::size_t level_start = level_bounds_[e.level - 1];
    const std::size_t child_level_start = e.level >= 2 ? level_bounds_[e.level - 2] : 0;
    const std::size_t first = child_level_start + (e.node - level_start) * kNodeSize;
    const std::size_t last = std::min(first + kNodeSize, level_bounds_[e.level - 1]);
    if (e.level == 1) {
      for (std::size_t c = first; c < last; ++c)
        if (overlaps(c) && !visit(indices_[c])) return;
      continue;
    }
    // Pushed in reverse so children are visited in leaf order (deterministic, Hilbert order).
    for (std::size_t c = last; c-- > first;)
      if (overlaps(c)) stack[top++] = {c, e.level - 1};
  }
}

}  // namespace cutroute::geometry
