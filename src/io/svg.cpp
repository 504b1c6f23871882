#include <cutroute/io/svg.hpp>

#include <cmath>
#include <cstdlib>
#include <string>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/text.hpp>
#include <cutroute/core/tolerances.hpp>

namespace cutroute::io {
namespace {
constexpr int kDecimals = 3;  // 1 µm: finer than any machine, keeps files small
}

SvgDocument::SvgDocument(const geometry::Box& world, double margin_mm, double width_px)
    : world_(world.empty() ? geometry::Box{0, 0, 1, 1} : world), margin_mm_(margin_mm), width_px_(width_px) {
  const double w = std::max(world_.width(), 1e-3) + 2 * margin_mm_;
  mm_per_px_ = w / width_px_;
}

void SvgDocument::append_point(std::string& out, geometry::Vec2 p) const {
  append_fixed(out, p.x - world_.xmin + margin_mm_, kDecimals);
  out += ' ';
  append_fixed(out, world_.ymax - p.y + margin_mm_, kDecimals);
}

std::string SvgDocument::path_data(const geometry::Contour& c) const {
  std::string d;
  const auto& v = c.vertices;
  if (v.empty()) return d;
  d += 'M';
  append_point(d, v[0].p);
  const std::size_t n = c.closed ? v.size() : v.size() - 1;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = v[i];
    const auto& b = v[(i + 1) % v.size()];
    if (std::abs(a.bulge) < tol::kStraightBulge) {
      d += 'L';
      append_point(d, b.p);
      continue;
    }
    // bulge b = tan(θ/4); chord c; radius r = c (1 + b²) / (4 |b|). The chord is taken between
    // the end points as written (to the µm) and r written to 1e-9 mm: near a half circle the arc's
    // bulge off its chord depends steeply on r against c/2, and r rounded apart from them drew slot
    // ends 0.1-0.15 mm off (a radius 30.000 over a chord of 59.9996: the short arc, not the half).
    auto written = [](double coordinate) {
      std::string t;
      append_fixed(t, coordinate, kDecimals);
      return std::strtod(t.c_str(), nullptr);
    };
    const geometry::Vec2 wa{written(a.p.x - world_.xmin + margin_mm_), written(world_.ymax - a.p.y + margin_mm_)};
    const geometry::Vec2 wb{written(b.p.x - world_.xmin + margin_mm_), written(world_.ymax - b.p.y + margin_mm_)};
    const double chord = geometry::distance(wa, wb);
    const double r = chord * (1 + a.bulge * a.bulge) / (4 * std::abs(a.bulge));
    d += 'A';
    append_fixed(d, r, 9);
    d += ' ';
    append_fixed(d, r, 9);
    d += " 0 ";
    d += std::abs(a.bulge) > 1 ? '1' : '0';  // large-arc: sweep beyond 180°
    d += ' ';
    // y is flipped, so a counter-clockwise arc in the drawing is sweep-flag 0 on screen.
    d += a.bulge > 0 ? '0' : '1';
    d += ' ';
    append_point(d, b.p);
  }
  if (c.closed) d += 'Z';
  return d;
}

void SvgDocument::append_xy_attributes(std::string& out, const char* x_name, const char* y_name, geometry::Vec2 p) const {
  out += x_name;
  out += "=\"";
  append_fixed(out, p.x - world_.xmin + margin_mm_, kDecimals);
  out += "\" ";
  out += y_name;
  out += "=\"";
  append_fixed(out, world_.ymax - p.y + margin_mm_, kDecimals);
  out += '"';
}

void SvgDocument::begin_group(const std::string& attributes) { body_ += "<g " + attributes + ">\n"; }
void SvgDocument::end_group() { body_ += "</g>\n"; }

void SvgDocument::add_contour(const geometry::Contour& c, const std::string& attributes) {
  body_ += "<path d=\"" + path_data(c) + "\" " + attributes + "/>\n";
}

void SvgDocument::add_contours(const std::vector<const geometry::Contour*>& cs, const std::string& attributes) {
  std::string d;
  for (const auto* c : cs) d += path_data(*c);
  body_ += "<path fill-rule=\"evenodd\" d=\"" + d + "\" " + attributes + "/>\n";
}

void SvgDocument::add_line(geometry::Vec2 a, geometry::Vec2 b, const std::string& attributes) {
  std::string d = "M";
  append_point(d, a);
  d += 'L';
  append_point(d, b);
  body_ += "<path d=\"" + d + "\" " + attributes + "/>\n";
}

void SvgDocument::add_circle(geometry::Vec2 center, double radius_mm, const std::string& attributes) {
  std::string s = "<circle ";
  append_xy_attributes(s, "cx", "cy", center);
  s += " r=\"";
  append_fixed(s, radius_mm, kDecimals);
  s += "\" " + attributes + "/>\n";
  body_ += s;
}

void SvgDocument::add_text(geometry::Vec2 at, const std::string& text, double size_mm, const std::string& attributes) {
  std::string s = "<text ";
  append_xy_attributes(s, "x", "y", at);
  s += " font-size=\"";
  append_fixed(s, size_mm, kDecimals);
  s += "\" " + attributes + ">" + xml_escape(text) + "</text>\n";
  body_ += s;
}

void SvgDocument::add_raw(const std::string& svg) { body_ += svg; }

std::string SvgDocument::str() const {
  const double w = world_.width() + 2 * margin_mm_;
  const double h = world_.height() + 2 * margin_mm_;
  const double height_px = width_px_ * h / w;
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"";
  append_fixed(s, width_px_, 0);
  s += "\" height=\"";
  append_fixed(s, height_px, 0);
  s += "\" viewBox=\"0 0 ";
  append_fixed(s, w, kDecimals);
  s += ' ';
  append_fixed(s, h, kDecimals);
  s += "\">\n";
  s += body_;
  s += "</svg>\n";
  return s;
}

std::string xml_escape(const std::string& raw) {
  // XML must be UTF-8 (file names and drawing names may not be).
  const std::string in = to_utf8(raw);
  std::string out;
  out.reserve(in.size());
  for (char c : in) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      // XML 1.0 allows no other control characters, escaped or not (a file name may hold one).
      case '\t': case '\n': case '\r': out += c; break;
      default: out += static_cast<unsigned char>(c) < 0x20 || c == 0x7F ? '?' : c;
    }
  }
  return out;
}

}  // namespace cutroute::io
