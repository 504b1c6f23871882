#include <cutroute/io/dxf_writer.hpp>

#include <charconv>
#include <cmath>
#include <set>

#include <cutroute/core/units.hpp>

namespace cutroute::io {

namespace {

struct Unit {
  double mm;
  int insunits;
  int measurement;
};

Unit unit_of(const std::string& u) {
  if (u == "cm") return {units::kMmPerCm, 5, 1};
  if (u == "m") return {units::kMmPerM, 6, 1};
  if (u == "in") return {units::kMmPerInch, 1, 0};
  if (u == "ft") return {units::kMmPerFoot, 2, 0};
  return {1.0, 4, 1};
}

class Out {
 public:
  void pair(int code, std::string_view value) {
    s += std::to_string(code);
    s += '\n';
    s += value;
    s += '\n';
  }
  void pair(int code, double v) {
    if (v == 0) v = 0;  // never "-0"
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    pair(code, std::string_view(buf, static_cast<std::size_t>(r.ptr - buf)));
  }
  void pair(int code, int v) { pair(code, std::string_view(std::to_string(v))); }
  std::string handle() {
    char buf[16];
    const auto r = std::to_chars(buf, buf + sizeof buf, next_handle++, 16);
    std::string h(buf, r.ptr);
    for (char& c : h) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return h;
  }
  std::string s;
  unsigned next_handle = 0x20;
};

// Layer names may not contain line breaks; empty means layer 0.
std::string clean_layer(const std::string& l) {
  if (l.empty()) return "0";
  std::string r = l;
  for (char& c : r) {
    if (c == '\n' || c == '\r') c = '_';
  }
  return r;
}

bool is_full_circle(const geometry::Contour& c) {
  return c.closed && c.vertices.size() == 2 && std::abs(c.vertices[0].bulge) == 1.0 &&
         c.vertices[0].bulge == c.vertices[1].bulge && !(c.vertices[0].p == c.vertices[1].p);
}

}  // namespace

std::string write_dxf(const std::vector<DxfWriteEntity>& entities, const DxfWriteOptions& options) {
  const Unit u = unit_of(options.units);
  const double k = 1.0 / u.mm;
  Out o;
  o.pair(999, "cutroute");
  o.pair(0, "SECTION");
  o.pair(2, "HEADER");
  o.pair(9, "$ACADVER");
  o.pair(1, "AC1015");
  o.pair(9, "$INSUNITS");
  o.pair(70, u.insunits);
  o.pair(9, "$MEASUREMENT");
  o.pair(70, u.measurement);
  o.pair(0, "ENDSEC");

  std::set<std::string> layers{"0"};
  for (const auto& e : entities) layers.insert(clean_layer(e.layer));
  o.pair(0, "SECTION");
  o.pair(2, "TABLES");
  o.pair(0, "TABLE");
  o.pair(2, "LAYER");
  o.pair(5, o.handle());
  o.pair(100, "AcDbSymbolTable");
  o.pair(70, static_cast<int>(layers.size()));
  for (const auto& l : layers) {
    o.pair(0, "LAYER");
    o.pair(5, o.handle());
    o.pair(100, "AcDbSymbolTableRecord");
    o.pair(100, "AcDbLayerTableRecord");
    o.pair(2, l);
    o.pair(70, 0);
    o.pair(62, 7);
    o.pair(6, "CONTINUOUS");
  }
  o.pair(0, "ENDTAB");
  o.pair(0, "ENDSEC");

  o.pair(0, "SECTION");
  o.pair(2, "ENTITIES");
  for (const auto& e : entities) {
    const auto& c = e.path;
    if (c.vertices.empty()) continue;
    const std::string layer = clean_layer(e.layer);
    if (is_full_circle(c)) {
      const geometry::Vec2 ctr = (c.vertices[0].p + c.vertices[1].p) * 0.5;
      o.pair(0, "CIRCLE");
      o.pair(5, o.handle());
      o.pair(100, "AcDbEntity");
      o.pair(8, layer);
      o.pair(100, "AcDbCircle");
      o.pair(10, ctr.x * k);
      o.pair(20, ctr.y * k);
      o.pair(30, 0.0);
      o.pair(40, geometry::distance(c.vertices[0].p, c.vertices[1].p) * 0.5 * k);
      continue;
    }
    o.pair(0, "LWPOLYLINE");
    o.pair(5, o.handle());
    o.pair(100, "AcDbEntity");
    o.pair(8, layer);
    o.pair(100, "AcDbPolyline");
    o.pair(90, static_cast<int>(c.vertices.size()));
    o.pair(70, c.closed ? 1 : 0);
    for (std::size_t i = 0; i < c.vertices.size(); ++i) {
      const auto& v = c.vertices[i];
      o.pair(10, v.p.x * k);
      o.pair(20, v.p.y * k);
      // The last vertex of an open contour has no segment, hence no bulge.
      const bool has_segment = c.closed || i + 1 < c.vertices.size();
      if (has_segment && v.bulge != 0) o.pair(42, v.bulge);
    }
  }
  o.pair(0, "ENDSEC");
  o.pair(0, "EOF");
  return std::move(o.s);
}

}  // namespace cutroute::io
