// SvgDocument: an SVG picture builder in millimetres (y up, as in the drawing) that keeps arcs as SVG arcs.
#pragma once

#include <string>
#include <vector>

#include <cutroute/geometry/box.hpp>
#include <cutroute/geometry/contour.hpp>

namespace cutroute::io {

// World coordinates are drawing millimetres with y pointing up; the document flips y once here.
// Stroke widths are given in screen pixels (vector-effect non-scaling-stroke), so thin kerf lines
// stay visible on a 3 m sheet. Attribute strings are inserted verbatim: callers pass
// trusted, fixed style text and escape any user text with xml_escape().
class SvgDocument {
 public:
  SvgDocument(const geometry::Box& world, double margin_mm, double width_px);

  void begin_group(const std::string& attributes);
  void end_group();
  // One <path> per contour; several contours in one path (a part with its holes) use evenodd.
  void add_contour(const geometry::Contour& c, const std::string& attributes);
  void add_contours(const std::vector<const geometry::Contour*>& cs, const std::string& attributes);
  void add_line(geometry::Vec2 a, geometry::Vec2 b, const std::string& attributes);
  void add_circle(geometry::Vec2 center, double radius_mm, const std::string& attributes);
  void add_text(geometry::Vec2 at, const std::string& text, double size_mm, const std::string& attributes);
  void add_raw(const std::string& svg);   // trusted markup (e.g. <title>, <style>)

  // Helpers for callers that need screen placement in world units.
  double mm_per_px() const { return mm_per_px_; }
  std::string path_data(const geometry::Contour& c) const;
  std::string str() const;

 private:
  void append_point(std::string& out, geometry::Vec2 p) const;
  // x_name="..." y_name="..." of a world point in document coordinates.
  void append_xy_attributes(std::string& out, const char* x_name, const char* y_name, geometry::Vec2 p) const;

  geometry::Box world_;
  double margin_mm_;
  double width_px_;
  double mm_per_px_;
  std::string body_;
};

std::string xml_escape(const std::string& s);

}  // namespace cutroute::io
