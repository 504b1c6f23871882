// Private helpers of common-line cutting: material side of a contour, joining path pieces with connectors.
#pragma once

#include <cutroute/core/drawing_unit.hpp>

#include <string>

#include <cutroute/geometry/contour.hpp>
#include <cutroute/model/nest.hpp>

namespace cutroute::model::detail {

// Does the part's material lie left of the stored contour's direction of travel? (Inside an outer
// contour, outside a hole.)
bool material_left(const NestContour& c);

// "(x, y)" of a point [mm] in the drawing's unit, for messages (format_position()).
std::string point_text(geometry::Vec2 p, const DrawingUnit& unit);

// Builds one path from pieces that should meet end to start: where a piece starts away from the
// current end (parts drawn kerf apart meet at a junction's centre), a straight connector joins them.
class PathJoiner {
 public:
  void move_to(geometry::Vec2 p);
  void line_to(geometry::Vec2 p);       // no-op when p is the current end
  void append(const geometry::Contour& piece);  // open piece; connector to its start first
  geometry::Contour open() const { return path_; }
  geometry::Contour closed() const;     // the last point dropped when it repeats the first
  bool empty() const { return path_.vertices.empty(); }

 private:
  geometry::Contour path_;
};

}  // namespace cutroute::model::detail
