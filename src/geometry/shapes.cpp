// Contour constructors and rigid transforms.
#include <cutroute/geometry/shapes.hpp>

#include <cmath>

namespace cutroute::geometry {

Contour circle(Vec2 center, double radius, bool ccw) {
  const double b = ccw ? 1.0 : -1.0;
  return Contour{{{center + Vec2{radius, 0.0}, b}, {center - Vec2{radius, 0.0}, b}}, true};
}

Contour rectangle(const Box& box, bool ccw) {
  Contour c{{{{box.xmin, box.ymin}, 0.0}, {{box.xmax, box.ymin}, 0.0}, {{box.xmax, box.ymax}, 0.0},
             {{box.xmin, box.ymax}, 0.0}},
            true};
  return ccw ? c : reversed(c);
}

Contour polygon(const std::vector<Vec2>& points, bool closed) {
  Contour c;
  c.closed = closed;
  c.vertices.reserve(points.size());
  for (Vec2 p : points) c.vertices.push_back({p, 0.0});
  return c;
}

Contour translated(const Contour& c, Vec2 offset) {
  Contour r = c;
  for (Vertex& v : r.vertices) v.p += offset;
  return r;
}

Contour rotated_about(const Contour& c, Vec2 pivot, double angle_rad) {
  const double cs = std::cos(angle_rad), sn = std::sin(angle_rad);
  Contour r = c;
  for (Vertex& v : r.vertices) {
    const Vec2 d = v.p - pivot;
    v.p = pivot + Vec2{d.x * cs - d.y * sn, d.x * sn + d.y * cs};
  }
  return r;
}

Contour mirrored_x(const Contour& c) {
  Contour r = c;
  for (Vertex& v : r.vertices) {
    v.p.x = -v.p.x;
    v.bulge = -v.bulge;
  }
  return r;
}

}  // namespace cutroute::geometry
