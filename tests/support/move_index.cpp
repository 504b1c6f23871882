#include "support/move_index.hpp"

namespace cutroute::test {

namespace {

std::vector<geometry::Box> move_boxes(const std::vector<const ProbeMove*>& moves, double reach) {
  std::vector<geometry::Box> boxes;
  boxes.reserve(moves.size());
  for (const auto* m : moves) {
    geometry::Box b;
    for (int j = 0; j <= 16; ++j) {
      geometry::Vec2 q;
      probe_point(*m, j / 16.0, q.x, q.y);
      b.add(q);
    }
    // Between two of these points an arc (sweep up to 360°) strays by less than 5 % of their
    // distance along it (the sagitta of 22.5°): the margin.
    boxes.push_back(b.inflated(reach + 0.05 * m->length / 16.0));
  }
  return boxes;
}

}  // namespace

MoveIndex::MoveIndex(std::vector<const ProbeMove*> moves, double reach)
    : moves_(std::move(moves)), index_(move_boxes(moves_, reach)) {}

std::size_t MoveIndex::first_within(geometry::Vec2 q, double d) const {
  std::size_t first = moves_.size();
  index_.visit(geometry::Box{q.x, q.y, q.x, q.y}, [&](std::uint32_t c) {
    if (c < first && probe_distance(*moves_[c], q.x, q.y) <= d) first = c;
    return true;
  });
  return first;
}

}  // namespace cutroute::test
