// Box: an axis-aligned bounding box in millimetres; empty until a point is added.
#pragma once

#include <algorithm>
#include <limits>

#include <cutroute/geometry/vec2.hpp>

namespace cutroute::geometry {

struct Box {
  double xmin = std::numeric_limits<double>::infinity();   // [mm]
  double ymin = std::numeric_limits<double>::infinity();   // [mm]
  double xmax = -std::numeric_limits<double>::infinity();  // [mm]
  double ymax = -std::numeric_limits<double>::infinity();  // [mm]

  bool empty() const { return xmin > xmax || ymin > ymax; }
  double width() const { return empty() ? 0.0 : xmax - xmin; }
  double height() const { return empty() ? 0.0 : ymax - ymin; }
  Vec2 center() const { return {(xmin + xmax) / 2, (ymin + ymax) / 2}; }
  void add(Vec2 p) {
    xmin = std::min(xmin, p.x); ymin = std::min(ymin, p.y);
    xmax = std::max(xmax, p.x); ymax = std::max(ymax, p.y);
  }
  void add(const Box& b) {
    if (b.empty()) return;
    xmin = std::min(xmin, b.xmin); ymin = std::min(ymin, b.ymin);
    xmax = std::max(xmax, b.xmax); ymax = std::max(ymax, b.ymax);
  }
  Box inflated(double d) const { return empty() ? *this : Box{xmin - d, ymin - d, xmax + d, ymax + d}; }
  bool contains(Vec2 p) const { return p.x >= xmin && p.x <= xmax && p.y >= ymin && p.y <= ymax; }
  bool contains(const Box& b) const {
    return !b.empty() && b.xmin >= xmin && b.xmax <= xmax && b.ymin >= ymin && b.ymax <= ymax;
  }
  bool intersects(const Box& b) const {
    return !empty() && !b.empty() && b.xmin <= xmax && b.xmax >= xmin && b.ymin <= ymax && b.ymax >= ymin;
  }
};

}  // namespace cutroute::geometry
