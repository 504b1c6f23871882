#include "support/dxf_builder.hpp"

#include <charconv>
#include <cstdio>

namespace cutroute::test {

std::string DxfBuilder::num(double v) {
  if (v == 0) v = 0;
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

DxfBuilder& DxfBuilder::insunits(int code) { insunits_ = code; return *this; }
DxfBuilder& DxfBuilder::measurement(int code) { measurement_ = code; return *this; }
DxfBuilder& DxfBuilder::no_header() { header_ = false; return *this; }
DxfBuilder& DxfBuilder::codepage(const std::string& page) { codepage_ = page; return *this; }

void DxfBuilder::begin(const char* type, const std::string& layer) {
  pair(0, std::string(type));
  char h[16];
  std::snprintf(h, sizeof h, "%X", handle_++);
  pair(5, std::string(h));
  pair(8, layer);
}

void DxfBuilder::extrusion(double ez) {
  if (ez == 1) return;
  pair(210, 0.0);
  pair(220, 0.0);
  pair(230, ez);
}

DxfBuilder& DxfBuilder::begin_block(const std::string& name, Vec2 base) {
  in_block_ = true;
  pair(0, std::string("BLOCK"));
  pair(8, std::string("0"));
  pair(2, name);
  pair(70, std::string("0"));
  pair(10, base.x);
  pair(20, base.y);
  pair(30, 0.0);
  pair(3, name);
  return *this;
}

DxfBuilder& DxfBuilder::end_block() {
  pair(0, std::string("ENDBLK"));
  pair(8, std::string("0"));
  in_block_ = false;
  return *this;
}

DxfBuilder& DxfBuilder::line(Vec2 a, Vec2 b, const std::string& layer) {
  begin("LINE", layer);
  pair(10, a.x); pair(20, a.y); pair(30, 0.0);
  pair(11, b.x); pair(21, b.y); pair(31, 0.0);
  return *this;
}

DxfBuilder& DxfBuilder::arc(Vec2 c, double r, double a1, double a2, const std::string& layer, double ez) {
  begin("ARC", layer);
  pair(10, c.x); pair(20, c.y); pair(30, 0.0);
  pair(40, r);
  extrusion(ez);
  pair(50, a1); pair(51, a2);
  return *this;
}

DxfBuilder& DxfBuilder::circle(Vec2 c, double r, const std::string& layer, double ez) {
  begin("CIRCLE", layer);
  pair(10, c.x); pair(20, c.y); pair(30, 0.0);
  pair(40, r);
  extrusion(ez);
  return *this;
}

DxfBuilder& DxfBuilder::lwpolyline(const std::vector<geometry::Vertex>& v, bool closed, const std::string& layer,
                                   double ez) {
  begin("LWPOLYLINE", layer);
  pair(90, std::to_string(v.size()));
  pair(70, std::string(closed ? "1" : "0"));
  for (const auto& x : v) {
    pair(10, x.p.x);
    pair(20, x.p.y);
    if (x.bulge != 0) pair(42, x.bulge);
  }
  extrusion(ez);
  return *this;
}

DxfBuilder& DxfBuilder::polyline(const std::vector<geometry::Vertex>& v, bool closed, const std::string& layer) {
  begin("POLYLINE", layer);
  pair(66, std::string("1"));
  pair(10, 0.0); pair(20, 0.0); pair(30, 0.0);
  pair(70, std::string(closed ? "1" : "0"));
  for (const auto& x : v) {
    begin("VERTEX", layer);
    pair(10, x.p.x); pair(20, x.p.y); pair(30, 0.0);
    if (x.bulge != 0) pair(42, x.bulge);
  }
  begin("SEQEND", layer);
  return *this;
}

DxfBuilder& DxfBuilder::ellipse(Vec2 c, Vec2 major, double ratio, double t0, double t1, const std::string& layer,
                                double ez) {
  begin("ELLIPSE", layer);
  pair(10, c.x); pair(20, c.y); pair(30, 0.0);
  pair(11, major.x); pair(21, major.y); pair(31, 0.0);
  extrusion(ez);
  pair(40, ratio);
  pair(41, t0);
  pair(42, t1);
  return *this;
}

DxfBuilder& DxfBuilder::spline(int degree, const std::vector<double>& knots, const std::vector<Vec2>& control,
                               const std::vector<double>& weights, int flags, const std::string& layer) {
  begin("SPLINE", layer);
  pair(70, std::to_string(flags));
  pair(71, std::to_string(degree));
  pair(72, std::to_string(knots.size()));
  pair(73, std::to_string(control.size()));
  pair(74, std::string("0"));
  for (double k : knots) pair(40, k);
  for (std::size_t i = 0; i < control.size(); ++i) {
    pair(10, control[i].x); pair(20, control[i].y); pair(30, 0.0);
    if (!weights.empty()) pair(41, weights[i]);
  }
  return *this;
}

DxfBuilder& DxfBuilder::spline_fit(const std::vector<Vec2>& fit, int flags, const std::string& layer) {
  begin("SPLINE", layer);
  pair(70, std::to_string(flags));
  pair(71, std::string("3"));
  pair(72, std::string("0"));
  pair(73, std::string("0"));
  pair(74, std::to_string(fit.size()));
  for (const auto& p : fit) {
    pair(11, p.x); pair(21, p.y); pair(31, 0.0);
  }
  return *this;
}

DxfBuilder& DxfBuilder::insert(const std::string& block, Vec2 at, double sx, double sy, double rot,
                               const std::string& layer, int cols, int rows, double colsp, double rowsp, double ez) {
  begin("INSERT", layer);
  pair(2, block);
  pair(10, at.x); pair(20, at.y); pair(30, 0.0);
  if (sx != 1) pair(41, sx);
  if (sy != 1) pair(42, sy);
  if (rot != 0) pair(50, rot);
  if (cols != 1) pair(70, std::to_string(cols));
  if (rows != 1) pair(71, std::to_string(rows));
  if (colsp != 0) pair(44, colsp);
  if (rowsp != 0) pair(45, rowsp);
  extrusion(ez);
  return *this;
}

DxfBuilder& DxfBuilder::text(Vec2 at, const std::string& s, const std::string& layer) {
  begin("TEXT", layer);
  pair(10, at.x); pair(20, at.y); pair(30, 0.0);
  pair(40, 2.5);
  pair(1, s);
  return *this;
}

DxfBuilder& DxfBuilder::mtext(Vec2 at, const std::string& s, const std::string& layer) {
  begin("MTEXT", layer);
  pair(10, at.x); pair(20, at.y); pair(30, 0.0);
  pair(40, 2.5);
  pair(1, s);
  return *this;
}

DxfBuilder& DxfBuilder::point(Vec2 at, const std::string& layer) {
  begin("POINT", layer);
  pair(10, at.x); pair(20, at.y); pair(30, 0.0);
  return *this;
}

DxfBuilder& DxfBuilder::raw(int code, const std::string& value) {
  pair(code, value);
  return *this;
}

std::string DxfBuilder::str() const {
  std::string s = "999\ncutroute test drawing\n";
  if (header_) {
    s += "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n";
    if (insunits_) s += "9\n$INSUNITS\n70\n" + std::to_string(*insunits_) + "\n";
    if (measurement_) s += "9\n$MEASUREMENT\n70\n" + std::to_string(*measurement_) + "\n";
    if (!codepage_.empty()) s += "9\n$DWGCODEPAGE\n3\n" + codepage_ + "\n";
    s += "0\nENDSEC\n";
  }
  if (!blocks_.empty()) s += "0\nSECTION\n2\nBLOCKS\n" + blocks_ + "0\nENDSEC\n";
  s += "0\nSECTION\n2\nENTITIES\n" + entities_ + "0\nENDSEC\n0\nEOF\n";
  return s;
}

std::string DxfBuilder::str_crlf() const {
  std::string s, lf = str();
  for (char c : lf) {
    if (c == '\n') s += "\r\n";
    else s += c;
  }
  return s;
}

std::string DxfBuilder::str_cr() const {
  std::string s = str();
  for (char& c : s) {
    if (c == '\n') c = '\r';
  }
  return s;
}

}  // namespace cutroute::test
