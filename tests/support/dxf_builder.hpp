// DxfBuilder: writes small ASCII DXF texts entity by entity, for reader tests.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::test {

// Group-code/value text of a DXF file. Entities go to the open block, else to ENTITIES.
// Numbers are written in shortest round-trip form, so the reader sees exactly these doubles.
class DxfBuilder {
 public:
  using Vec2 = geometry::Vec2;

  DxfBuilder& insunits(int code);
  DxfBuilder& measurement(int code);
  DxfBuilder& no_header();  // leave the HEADER section out entirely
  DxfBuilder& codepage(const std::string& page);  // $DWGCODEPAGE, e.g. "ANSI_1251"

  DxfBuilder& begin_block(const std::string& name, Vec2 base = {});
  DxfBuilder& end_block();

  // ez: z of the extrusion direction (+1 or -1)
  DxfBuilder& line(Vec2 a, Vec2 b, const std::string& layer = "0");
  DxfBuilder& arc(Vec2 c, double r, double a1_deg, double a2_deg, const std::string& layer = "0", double ez = 1);
  DxfBuilder& circle(Vec2 c, double r, const std::string& layer = "0", double ez = 1);
  DxfBuilder& lwpolyline(const std::vector<geometry::Vertex>& v, bool closed, const std::string& layer = "0",
                         double ez = 1);
  DxfBuilder& polyline(const std::vector<geometry::Vertex>& v, bool closed, const std::string& layer = "0");
  DxfBuilder& ellipse(Vec2 c, Vec2 major, double ratio, double t0, double t1, const std::string& layer = "0",
                      double ez = 1);
  DxfBuilder& spline(int degree, const std::vector<double>& knots, const std::vector<Vec2>& control,
                     const std::vector<double>& weights, int flags, const std::string& layer = "0");
  DxfBuilder& spline_fit(const std::vector<Vec2>& fit, int flags, const std::string& layer = "0");
  DxfBuilder& insert(const std::string& block, Vec2 at, double sx = 1, double sy = 1, double rot_deg = 0,
                     const std::string& layer = "0", int cols = 1, int rows = 1, double colsp = 0, double rowsp = 0,
                     double ez = 1);
  DxfBuilder& text(Vec2 at, const std::string& s, const std::string& layer = "0");
  DxfBuilder& mtext(Vec2 at, const std::string& s, const std::string& layer = "0");
  DxfBuilder& point(Vec2 at, const std::string& layer = "0");
  DxfBuilder& raw(int code, const std::string& value);  // appended to the current entity list

  std::string str() const;                  // LF line ends
  std::string str_crlf() const;             // CR LF
  std::string str_cr() const;               // CR only

  static std::string num(double v);

 private:
  std::string& target() { return in_block_ ? blocks_ : entities_; }
  void pair(int code, const std::string& value) { target() += std::to_string(code) + "\n" + value + "\n"; }
  void pair(int code, double v) { pair(code, num(v)); }
  void begin(const char* type, const std::string& layer);
  void extrusion(double ez);

  std::optional<int> insunits_, measurement_;
  std::string codepage_;
  bool header_ = true;
  bool in_block_ = false;
  std::string blocks_, entities_;
  unsigned handle_ = 0x100;
};

}  // namespace cutroute::test
