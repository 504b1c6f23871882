// read_dxf(): pre-scan (dxf_scan), dxflib for the entity data, then INSERT expansion, OCS and
// unit transforms and curve conversion (curve_fit) into DxfEntity contours in millimetres.
#include <cutroute/io/dxf.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <sstream>

#include <dl_creationadapter.h>
#include <dl_dxf.h>

#include <cutroute/core/file.hpp>
#include <cutroute/core/units.hpp>

#include "io/curve_fit.hpp"
#include "io/dxf_scan.hpp"

namespace cutroute::io {

namespace {

using detail::Affine;
using detail::ScanEntity;
using detail::ScanResult;
using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

constexpr double kPi = std::numbers::pi;

struct Vec3 {
  double x = 0, y = 0, z = 1;
};

// Entity data as dxflib reports it, in the entity's own coordinates (OCS or WCS).
struct Payload {
  bool set = false;
  Vec3 extrusion;
  // LINE
  Vec2 p1, p2;
  // ARC, CIRCLE, ELLIPSE
  Vec2 center;
  double radius = 0, a1 = 0, a2 = 0;  // ARC angles [deg]
  Vec2 major;
  double ratio = 1, t0 = 0, t1 = 2 * kPi;  // ELLIPSE parameters [rad]
  // LWPOLYLINE, POLYLINE
  int flags = 0;
  std::vector<Vertex> vertices;
  // SPLINE (its number arrays come from the scan: ScanSpline)
  int degree = 3;
  Vec2 tan_start, tan_end;
  // INSERT
  Vec2 ins;
  double sx = 1, sy = 1, angle = 0, colsp = 0, rowsp = 0;
  int cols = 1, rows = 1;
};

// Receives dxflib's callbacks and files each under the scan record it belongs to: the record is
// found from the stream position (see dxf_scan.hpp), because dxflib itself knows no lines.
class Collector : public DL_CreationAdapter {
 public:
  Collector(const ScanResult& scan, std::istream& in, std::vector<Payload>& out) : scan_(scan), in_(in), out_(out) {}

  void addLine(const DL_LineData& d) override {
    if (Payload* p = slot()) {
      p->p1 = {d.x1, d.y1};
      p->p2 = {d.x2, d.y2};
    }
  }
  void addArc(const DL_ArcData& d) override {
    if (Payload* p = slot()) {
      p->center = {d.cx, d.cy};
      p->radius = d.radius;
      p->a1 = d.angle1;
      p->a2 = d.angle2;
    }
  }
  void addCircle(const DL_CircleData& d) override {
    if (Payload* p = slot()) {
      p->center = {d.cx, d.cy};
      p->radius = d.radius;
    }
  }
  void addEllipse(const DL_EllipseData& d) override {
    if (Payload* p = slot()) {
      p->center = {d.cx, d.cy};
      p->major = {d.mx, d.my};
      p->ratio = d.ratio;
      p->t0 = d.angle1;
      p->t1 = d.angle2;
    }
  }
  void addPolyline(const DL_PolylineData& d) override {
    if (Payload* p = slot()) p->flags = d.flags;
  }
  void addVertex(const DL_VertexData& d) override {
    int rec = -1;
    if (Payload* p = slot(&rec)) {
      // Spline frame control points of a spline-fit POLYLINE are not on the curve.
      const ScanEntity& e = scan_.entities[static_cast<std::size_t>(rec)];
      if (e.type == "VERTEX" && (e.flags & 16) != 0) return;
      p->vertices.push_back({{d.x, d.y}, d.bulge});
    }
  }
  void addSpline(const DL_SplineData& d) override {
    if (Payload* p = slot()) {
      // dxflib reads group 71 as unsigned: a written -1 arrives as 2^32 - 1 and is reported as -1.
      p->degree = static_cast<int>(d.degree);
      p->flags = d.flags;
      p->tan_start = {d.tangentStartX, d.tangentStartY};
      p->tan_end = {d.tangentEndX, d.tangentEndY};
    }
  }
  void addInsert(const DL_InsertData& d) override {
    if (Payload* p = slot()) {
      p->ins = {d.ipx, d.ipy};
      p->sx = d.sx;
      p->sy = d.sy;
      p->angle = d.angle;
      p->cols = d.cols;
      p->rows = d.rows;
      p->colsp = d.colSp;
      p->rowsp = d.rowSp;
    }
  }

 private:
  Payload* slot(int* record = nullptr) {
    const auto pos = in_.tellg();
    if (pos < 0) return nullptr;
    const auto off = static_cast<std::size_t>(pos);
    const auto it = std::lower_bound(scan_.zero_offsets.begin(), scan_.zero_offsets.end(), off);
    if (it == scan_.zero_offsets.end() || *it != off || it == scan_.zero_offsets.begin()) return nullptr;
    const int rec = scan_.zero_entities[static_cast<std::size_t>(it - scan_.zero_offsets.begin()) - 1];
    if (rec < 0) return nullptr;
    if (record) *record = rec;
    const ScanEntity& e = scan_.entities[static_cast<std::size_t>(rec)];
    const int target = e.owner >= 0 ? e.owner : rec;
    Payload& p = out_[static_cast<std::size_t>(target)];
    if (!p.set) {
      p.set = true;
      if (const DL_Extrusion* x = getExtrusion()) {
        const double* dir = x->getDirection();
        if (dir) p.extrusion = {dir[0], dir[1], dir[2]};
      }
    }
    return &p;
  }

  const ScanResult& scan_;
  std::istream& in_;
  std::vector<Payload>& out_;
};

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return s;
}

std::optional<double> option_units_mm(const std::string& u) {
  const std::string l = upper(u);
  if (l == "MM") return 1.0;
  if (l == "CM") return units::kMmPerCm;
  if (l == "M") return units::kMmPerM;
  if (l == "IN" || l == "INCH") return units::kMmPerInch;
  if (l == "FT" || l == "FOOT") return units::kMmPerFoot;
  return std::nullopt;
}

struct UnitsDecision {
  std::string units_in_file = "unitless";
  std::string source = "default";
  double mm_per_unit = 1.0;
  std::string unit_name = "mm";  // the unit the numbers are read in
};

// The --units value as a unit's name ("inch" -> "in").
std::string option_unit_name(const std::string& u) {
  const std::string l = upper(u);
  if (l == "INCH") return "in";
  if (l == "FOOT") return "ft";
  std::string name = u;
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name;
}

UnitsDecision decide_units(std::optional<int> insunits, std::optional<int> measurement, const DxfOptions& opt) {
  UnitsDecision d;
  if (insunits && detail::insunits_mm(*insunits)) {
    d.units_in_file = detail::insunits_name(*insunits);
    d.source = "$INSUNITS";
    d.mm_per_unit = *detail::insunits_mm(*insunits);
    d.unit_name = detail::insunits_name(*insunits);
  } else if (insunits && *insunits == 0) {
    // $INSUNITS 0 says "unitless" explicitly: the drawing's numbers are millimetres for a
    // cutting machine (the foundation issue: unitless files read as mm). $MEASUREMENT, a
    // drafting default for linetype scales, is only consulted when $INSUNITS is absent.
    d.source = "$INSUNITS";
  } else if (measurement && (*measurement == 0 || *measurement == 1)) {
    d.units_in_file = *measurement == 0 ? "in" : "mm";
    d.source = "$MEASUREMENT";
    d.mm_per_unit = *measurement == 0 ? units::kMmPerInch : 1.0;
    d.unit_name = d.units_in_file;
  }
  if (opt.units) {
    if (auto mm = option_units_mm(*opt.units)) {
      d.source = "option";
      d.mm_per_unit = *mm;
      d.unit_name = option_unit_name(*opt.units);
    }
  }
  return d;
}

double units_rule(std::optional<int> insunits, std::optional<int> measurement, const void* ctx) {
  return decide_units(insunits, measurement, *static_cast<const DxfOptions*>(ctx)).mm_per_unit;
}

// Object coordinate system of an extrusion direction (DXF "arbitrary axis algorithm"), projected
// onto the XY plane: for (0,0,-1) this is x -> -x, which also reverses arc directions. A plane
// tilted from XY at height `elevation` along its normal lies shifted by that height's XY share.
Affine ocs(Vec3 n, double elevation = 0) {
  const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  if (!(len > 0) || !std::isfinite(len)) return Affine{};
  n = {n.x / len, n.y / len, n.z / len};
  Vec3 ax;
  if (std::abs(n.x) < 1.0 / 64 && std::abs(n.y) < 1.0 / 64) {
    ax = {n.z, 0, -n.x};  // Wy x N = (0,1,0) x N
  } else {
    ax = {-n.y, n.x, 0};  // Wz x N
  }
  const double al = std::sqrt(ax.x * ax.x + ax.y * ax.y + ax.z * ax.z);
  ax = {ax.x / al, ax.y / al, ax.z / al};
  const Vec3 ay{n.y * ax.z - n.z * ax.y, n.z * ax.x - n.x * ax.z, n.x * ax.y - n.y * ax.x};
  Affine a;
  a.m00 = ax.x;
  a.m01 = ay.x;
  a.m10 = ax.y;
  a.m11 = ay.y;
  a.t = {elevation * n.x, elevation * n.y};
  return a;
}

// The extrusion of a plane more than about 0.1 degree off the XY plane (real drawings carry
// normals a few 1e-9 off -Z).
bool tilted(Vec3 n) {
  const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  return len > 0 && std::isfinite(len) && std::hypot(n.x, n.y) > 2e-3 * len;
}

bool within_limit(Vec2 p) {
  return geometry::is_finite(p) && std::abs(p.x) <= units::kMaxCoordinateMm && std::abs(p.y) <= units::kMaxCoordinateMm;
}

class Expander {
 public:
  Expander(const ScanResult& scan, const std::vector<Payload>& pay, const DxfOptions& opt, DxfDrawing& out)
      : scan_(scan), pay_(pay), opt_(opt), out_(out) {
    for (std::size_t i = 0; i < scan.blocks.size(); ++i) {
      blocks_.emplace(upper(scan.blocks[i].name), static_cast<int>(i));
    }
    for (const auto& l : opt.layers) keep_.push_back(upper(l));
    for (const auto& l : opt.ignore_layers) drop_.push_back(upper(l));
  }

  std::optional<Diagnostic> check_expansion();
  std::optional<Diagnostic> run();
  std::optional<Diagnostic> check_layer_filters();

 private:
  struct Top {
    std::string handle;
    long line = 0;
  };
  std::optional<Diagnostic> emit(int idx, const Affine& t, const std::string& inherited, const Top& top, int depth,
                                 const std::string& block);
  std::optional<Diagnostic> curve(const ScanEntity& e, const Payload& p, const Affine& t, const std::string& layer,
                                  const Top& top, const std::string& block);
  // Expanded entity count of a block (saturating), or an error for cycles and depth.
  std::optional<Diagnostic> count_block(int b, int depth, double& count);
  int find_block(const std::string& name) const {
    const auto it = blocks_.find(upper(name));
    return it == blocks_.end() ? -1 : it->second;
  }
  bool layer_kept(const std::string& layer) const {
    const std::string u = upper(layer);
    if (!keep_.empty() && std::find(keep_.begin(), keep_.end(), u) == keep_.end()) return false;
    return std::find(drop_.begin(), drop_.end(), u) == drop_.end();
  }
  Diagnostic entity_error(const std::string& msg, const Top& top) const {
    Diagnostic d = make_error(msg, out_.file, top.line);
    d.handle = top.handle;
    return d;
  }
  void warn_entity(const std::string& msg, const ScanEntity& e, const std::string& layer,
                   const char* code = "dxf.entity_skipped") {
    Diagnostic d = make_warning(msg, out_.file, e.line);
    d.code = code;
    d.handle = e.handle;
    d.layer = layer;
    out_.diagnostics.push_back(std::move(d));
  }
  // Arcs under a non-uniform scale are fitted again within tol_mm.
  Contour transform(const Contour& c, const Affine& a, double& dev, double tol_mm) const;

  const ScanResult& scan_;
  const std::vector<Payload>& pay_;
  const DxfOptions& opt_;
  DxfDrawing& out_;
  std::map<std::string, int> blocks_;
  std::vector<std::string> keep_, drop_;
  std::vector<int> state_;      // 0 new, 1 visiting, 2 done (cycle detection)
  std::vector<double> counts_;  // expanded entity count per block
  std::vector<int> path_;       // blocks being visited, for the cycle message
  std::size_t undefined_warnings_ = 0;
  std::size_t degenerate_warnings_ = 0;
  // Curves read from layers the drawing hides (by index in scan_.hidden_layers), and from
  // entities marked invisible: cut like any other, and said.
  std::map<std::size_t, std::size_t> hidden_read_;
  std::size_t invisible_read_ = 0;
  std::size_t tilted_ = 0;  // entities in tilted planes (the first is said)
};

// MINSERT rows and columns; 0 or negative counts (invalid) are read as 1.
std::pair<int, int> grid(const Payload& p) { return {std::max(1, p.rows), std::max(1, p.cols)}; }

std::optional<Diagnostic> Expander::count_block(int b, int depth, double& count) {
  const std::size_t bi = static_cast<std::size_t>(b);
  if (state_[bi] == 2) {
    count = counts_[bi];
    return std::nullopt;
  }
  double total = 0;
  state_[bi] = 1;
  path_.push_back(b);
  for (int idx : scan_.blocks[bi].entities) {
    const ScanEntity& e = scan_.entities[static_cast<std::size_t>(idx)];
    total += 1;
    if (e.type != "INSERT") continue;
    const int child = find_block(e.block_name);
    if (child < 0) continue;
    const Top at{e.handle, e.line};
    if (state_[static_cast<std::size_t>(child)] == 1) {
      std::string cycle;
      auto it = std::find(path_.begin(), path_.end(), child);
      for (; it != path_.end(); ++it) cycle += "'" + scan_.blocks[static_cast<std::size_t>(*it)].name + "' -> ";
      cycle += "'" + scan_.blocks[static_cast<std::size_t>(child)].name + "'";
      return entity_error("INSERT cycle: block " + cycle, at);
    }
    if (depth + 1 > opt_.max_insert_depth) {
      return entity_error("INSERT nesting deeper than " + std::to_string(opt_.max_insert_depth) + " levels", at);
    }
    double c = 0;
    if (auto d = count_block(child, depth + 1, c)) return d;
    const auto [rows, cols] = grid(pay_[static_cast<std::size_t>(idx)]);
    total += static_cast<double>(rows) * static_cast<double>(cols) * c;
    total = std::min(total, 1e300);
  }
  path_.pop_back();
  state_[bi] = 2;
  counts_[bi] = total;
  count = total;
  return std::nullopt;
}

std::optional<Diagnostic> Expander::check_expansion() {
  state_.assign(scan_.blocks.size(), 0);
  counts_.assign(scan_.blocks.size(), 0.0);
  double total = 0;
  for (int idx : scan_.modelspace) {
    const ScanEntity& e = scan_.entities[static_cast<std::size_t>(idx)];
    total += 1;
    if (e.type == "INSERT") {
      const int b = find_block(e.block_name);
      if (b >= 0) {
        double c = 0;
        if (opt_.max_insert_depth < 1) {
          return entity_error("INSERT nesting deeper than " + std::to_string(opt_.max_insert_depth) + " levels",
                              {e.handle, e.line});
        }
        if (auto d = count_block(b, 1, c)) return d;
        const auto [rows, cols] = grid(pay_[static_cast<std::size_t>(idx)]);
        total += static_cast<double>(rows) * static_cast<double>(cols) * c;
      }
    }
    if (total > static_cast<double>(opt_.max_entities)) {
      char buf[32];
      const auto r = std::to_chars(buf, buf + sizeof buf, total, std::chars_format::general, 3);
      return entity_error("INSERT expansion gives " + std::string(buf, r.ptr) + " entities, more than the limit of " +
                              std::to_string(opt_.max_entities),
                          {e.handle, e.line});
    }
  }
  return std::nullopt;
}

Contour Expander::transform(const Contour& c, const Affine& a, double& dev, double tol_mm) const {
  Contour r;
  r.closed = c.closed;
  const std::size_t n = c.vertices.size();
  if (a.is_similarity()) {
    const double s = a.det() < 0 ? -1.0 : 1.0;
    r.vertices.reserve(n);
    for (const Vertex& v : c.vertices) r.vertices.push_back({a.apply(v.p), v.bulge * s});
    return r;
  }
  // A non-uniform scale turns arcs into elliptic arcs: fit them again.
  const std::size_t segs = c.closed ? n : (n == 0 ? 0 : n - 1);
  for (std::size_t i = 0; i < segs; ++i) {
    const Vertex& v = c.vertices[i];
    const Vec2 b = c.vertices[(i + 1) % n].p;
    if (std::abs(v.bulge) < tol::kStraightBulge) {
      r.vertices.push_back({a.apply(v.p), 0.0});
      continue;
    }
    const detail::ArcSeg s{v.p, b, v.bulge};
    const Vec2 ctr = detail::arc_center(s);
    const double rad = geometry::distance(ctr, v.p);
    const double stretch = a.stretch_bound();
    if (!within_limit(a.apply(ctr)) || !within_limit(a.apply(v.p)) || !(rad * stretch < units::kMaxCoordinateMm)) {
      r.vertices.push_back({a.apply(v.p), 0.0});  // out of range: the caller's limit check reports it
      continue;
    }
    const double th = std::atan2(v.p.y - ctr.y, v.p.x - ctr.x);
    const double sweep = 4 * std::atan(v.bulge);
    detail::ParamCurve pc;
    pc.point = [=](double t) { return a.apply(ctr + Vec2{std::cos(th + t * sweep), std::sin(th + t * sweep)} * rad); };
    pc.derivative = [=](double t) {
      return a.apply_linear(Vec2{-std::sin(th + t * sweep), std::cos(th + t * sweep)} * (rad * sweep));
    };
    pc.t0 = 0;
    pc.t1 = 1;
    dev = std::max(dev, detail::fit_biarcs(pc, tol_mm, r.vertices));
  }
  if (!c.closed && n > 0) r.vertices.push_back({a.apply(c.vertices.back().p), 0.0});
  return r;
}

// Removes consecutive repeated vertices (and a closing repeat of the first vertex on a closed
// contour), which some writers emit; the geometry is unchanged.
void drop_repeats(Contour& c) {
  std::vector<Vertex> v;
  v.reserve(c.vertices.size());
  for (const Vertex& x : c.vertices) {
    if (!v.empty() && geometry::distance(v.back().p, x.p) <= tol::kSamePointMm) {
      v.back().bulge = x.bulge;  // the zero-length segment's bulge is meaningless
      continue;
    }
    v.push_back(x);
  }
  if (c.closed && v.size() > 2 && geometry::distance(v.back().p, v.front().p) <= tol::kSamePointMm) v.pop_back();
  c.vertices = std::move(v);
}

std::optional<Diagnostic> Expander::curve(const ScanEntity& e, const Payload& p, const Affine& t,
                                          const std::string& layer, const Top& top, const std::string& block) {
  if (!p.set) {
    warn_entity(e.type + " has no data", e, layer);
    return std::nullopt;
  }
  const double tol = opt_.curve_tol_mm;
  std::vector<Contour> results;
  double dev = 0;
  const Affine to = t.then_after(ocs(p.extrusion, e.elevation));
  if (e.type != "LINE" && e.type != "SPLINE" && tilted(p.extrusion) && tilted_++ == 0)
    warn_entity(e.type + " lies in a plane tilted from the XY plane: its outline as seen from above is cut", e, layer,
                "dxf.tilted_plane");
  if (e.type == "LINE") {
    Contour c;
    c.vertices = {{t.apply(p.p1), 0.0}, {t.apply(p.p2), 0.0}};
    results.push_back(std::move(c));
  } else if (e.type == "ARC" || e.type == "CIRCLE") {
    if (!(p.radius > 0)) {
      if (degenerate_warnings_++ < 20) warn_entity(e.type + " with radius <= 0 skipped", e, layer);
      return std::nullopt;
    }
    Contour c;
    double sweep = 2 * kPi;
    double a1 = 0;
    if (e.type == "ARC") {
      // Beyond a million degrees an angle is no drawing's (1e300 read as some arc of fmod's choosing).
      if (!(std::abs(p.a1) <= 1e6 && std::abs(p.a2) <= 1e6)) return entity_error("ARC angle beyond ±1e6 degrees", top);
      a1 = p.a1 * kPi / 180;
      // Angles count modulo 360 (AutoCAD, ezdxf): -30..390 is the 60° arc 330..30. An end a whole
      // number of turns from the start (0..360, 0..0) is a full circle.
      sweep = std::fmod(p.a2 - p.a1, 360.0);
      if (sweep < 0) sweep += 360.0;
      if (sweep <= 1e-9 || sweep >= 360.0 - 1e-9) sweep = 360.0;
      sweep *= kPi / 180;
    }
    if (sweep >= 2 * kPi - 1e-12) {
      const Vec2 a = p.center + Vec2{std::cos(a1), std::sin(a1)} * p.radius;
      const Vec2 b = p.center - Vec2{std::cos(a1), std::sin(a1)} * p.radius;
      c.vertices = {{a, 1.0}, {b, 1.0}};
      c.closed = true;
    } else {
      const Vec2 a = p.center + Vec2{std::cos(a1), std::sin(a1)} * p.radius;
      const Vec2 b = p.center + Vec2{std::cos(a1 + sweep), std::sin(a1 + sweep)} * p.radius;
      c.vertices = {{a, std::tan(sweep / 4)}, {b, 0.0}};
    }
    results.push_back(transform(c, to, dev, tol));
  } else if (e.type == "LWPOLYLINE" || e.type == "POLYLINE") {
    Contour c;
    c.vertices = p.vertices;
    c.closed = (p.flags & 1) != 0;
    const bool poly3d = e.type == "POLYLINE" && (p.flags & 8) != 0;
    if (poly3d) {
      for (Vertex& v : c.vertices) v.bulge = 0;  // 3D polylines have no arcs; coordinates are WCS
    }
    for (Vertex& v : c.vertices) {
      if (!std::isfinite(v.bulge) || std::abs(v.bulge) > 1e9) {
        return entity_error(e.type + " has an invalid bulge", top);
      }
    }
    if (c.vertices.empty()) {
      warn_entity(e.type + " without vertices skipped", e, layer);
      return std::nullopt;
    }
    results.push_back(transform(c, poly3d ? t : to, dev, tol));
  } else if (e.type == "ELLIPSE") {
    // WCS: P(u) = C + M cos u + ratio (N x M) sin u, u from start to end parameter (radians,
    // not angles); with N = (0,0,-1) the minor axis flips and the ellipse runs clockwise.
    const Vec2 M = p.major;
    const Vec3 n = p.extrusion;
    const double nl = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!(geometry::norm(M) > 0) || !(p.ratio > 0) || !(nl > 0)) {
      if (degenerate_warnings_++ < 20) warn_entity("degenerate ELLIPSE skipped", e, layer);
      return std::nullopt;
    }
    const Vec2 m = Vec2{-n.z * M.y, n.z * M.x} * (p.ratio / nl);  // (N x M).xy with M in the XY plane
    // Parameters count modulo 2π, as ARC angles do: an end a whole number of turns from the start
    // is the full ellipse.
    if (!(std::abs(p.t0) <= 1e6 && std::abs(p.t1) <= 1e6)) return entity_error("ELLIPSE parameter beyond ±1e6", top);
    double span = std::fmod(p.t1 - p.t0, 2 * kPi);
    if (span < 0) span += 2 * kPi;
    const bool full = span <= 1e-9 || span >= 2 * kPi - 1e-9;
    const double u0 = p.t0, u1 = p.t0 + (full ? 2 * kPi : span);
    const Vec2 C = p.center;
    if (!within_limit(t.apply(C)) ||
        !(geometry::norm(t.apply_linear(M)) + geometry::norm(t.apply_linear(m)) < units::kMaxCoordinateMm)) {
      return entity_error(e.type + " lies more than 1e6 mm from the origin after INSERT and unit scaling", top);
    }
    detail::ParamCurve pc;
    pc.point = [=](double u) { return t.apply(C + M * std::cos(u) + m * std::sin(u)); };
    pc.derivative = [=](double u) { return t.apply_linear(M * -std::sin(u) + m * std::cos(u)); };
    Contour c;
    // Quarter-turn pieces keep each biarc well conditioned.
    const int pieces = std::max(1, static_cast<int>(std::ceil((u1 - u0) / (kPi / 2) - 1e-9)));
    for (int i = 0; i < pieces; ++i) {
      pc.t0 = u0 + (u1 - u0) * i / pieces;
      pc.t1 = u0 + (u1 - u0) * (i + 1) / pieces;
      dev = std::max(dev, detail::fit_biarcs(pc, tol, c.vertices));
    }
    if (full) c.closed = true;
    else c.vertices.push_back({pc.point(u1), 0.0});
    results.push_back(std::move(c));
  } else if (e.type == "SPLINE") {
    Contour c;
    const bool closed_flag = (p.flags & 1) != 0;
    const detail::ScanSpline& arrays = scan_.splines[static_cast<std::size_t>(e.spline)];
    if (!arrays.control.empty()) {
      detail::Nurbs s;
      s.degree = p.degree;
      for (const Vec2& q : arrays.control) {
        s.control.push_back(t.apply(q));
        // The curve lies in the hull of its control points (positive weights).
        if (!within_limit(s.control.back())) {
          return entity_error(e.type + " lies more than 1e6 mm from the origin after INSERT and unit scaling", top);
        }
      }
      s.knots = arrays.knots;
      bool rational = false;
      for (double w : arrays.weights) rational = rational || w != 1.0;
      if (rational) {
        // Missing trailing weights are 1, as dxflib would have them.
        s.weights = arrays.weights;
        s.weights.resize(s.control.size(), 1.0);
      }
      for (double w : s.weights) {
        if (!(w > 0)) return entity_error("SPLINE has a weight <= 0", top);
      }
      for (std::size_t i = 1; i < s.knots.size(); ++i) {
        if (s.knots[i] < s.knots[i - 1]) return entity_error("SPLINE knots are not in increasing order", top);
      }
      if (s.degree < 1 || s.degree > detail::kMaxSplineDegree)
        return entity_error("SPLINE of degree " + std::to_string(s.degree) + ": only degrees 1 to " +
                                std::to_string(detail::kMaxSplineDegree) + " are read",
                            top);
      const std::size_t need = s.control.size() + static_cast<std::size_t>(s.degree) + 1;
      if (s.control.size() < static_cast<std::size_t>(s.degree) + 1 || s.knots.size() != need) {
        return entity_error("SPLINE of degree " + std::to_string(s.degree) + " with " + std::to_string(s.control.size()) +
                                " control points needs " + std::to_string(need) + " knots, has " +
                                std::to_string(s.knots.size()),
                            top);
      }
      c.vertices = detail::nurbs_to_arcs(s, tol, &dev);
      if (closed_flag && c.vertices.size() > 1 &&
          geometry::distance(c.vertices.front().p, c.vertices.back().p) > tol::kSnapMm) {
        // A periodic spline stored without its wrapped control points: wrap them.
        detail::Nurbs w = s;
        const auto pdeg = static_cast<std::size_t>(s.degree);
        for (std::size_t i = 0; i < pdeg; ++i) {
          w.control.push_back(s.control[i]);
          if (!w.weights.empty()) w.weights.push_back(s.weights[i]);
          w.knots.push_back(w.knots.back() + (s.knots[pdeg + i + 1] - s.knots[pdeg + i]));
        }
        double dev2 = 0;
        auto v2 = detail::nurbs_to_arcs(w, tol, &dev2);
        if (v2.size() > 1 && geometry::distance(v2.front().p, v2.back().p) <= tol::kSnapMm) {
          c.vertices = std::move(v2);
          dev = dev2;
        }
      }
    } else if (arrays.fit.size() >= 2) {
      std::vector<Vec2> pts;
      for (const Vec2& q : arrays.fit) {
        pts.push_back(t.apply(q));
        if (!within_limit(pts.back())) {
          return entity_error(e.type + " lies more than 1e6 mm from the origin after INSERT and unit scaling", top);
        }
      }
      const bool has_ts = geometry::norm(p.tan_start) > 0, has_te = geometry::norm(p.tan_end) > 0;
      // Without its end tangents (codes 12, 13) the file leaves the curve's ends open to choice:
      // natural ends (no curvature) here; CAD programs estimate directions each their own way
      // (ezdxf's estimates for BricsCAD lie 0.5-1.2 mm from natural ends on 50-mm curves).
      if (!closed_flag && (!has_ts || !has_te))
        warn_entity("SPLINE through fit points without its end tangents: its ends are taken as natural (no curvature); "
                    "the CAD program that drew it may bend them otherwise, by up to about 1 mm near the ends",
                    e, layer, "dxf.spline_fit_ends");
      if (t.is_similarity()) {
        const Vec2 ts = t.apply_linear(p.tan_start), te = t.apply_linear(p.tan_end);
        c.vertices = detail::fit_points_to_arcs(pts, closed_flag, has_ts ? &ts : nullptr, has_te ? &te : nullptr, tol, &dev);
        if (closed_flag && c.vertices.size() > 2) c.closed = true;
      } else {
        // The curve through the fit points is the block's, spaced by chord length there: a
        // non-uniform scale changes the chords' ratios, so fitting the scaled points would draw
        // another curve (0.65 mm off under a 3 x 0.5 scale). Fitted in the block, then scaled, the
        // two steps sharing the tolerance.
        const double stretch = t.stretch_bound();
        double block_dev = 0;
        Contour local;
        local.vertices = detail::fit_points_to_arcs(arrays.fit, closed_flag, has_ts ? &p.tan_start : nullptr,
                                                    has_te ? &p.tan_end : nullptr, 0.5 * tol / stretch, &block_dev);
        local.closed = closed_flag && local.vertices.size() > 2;
        double scaled_dev = 0;
        c = transform(local, t, scaled_dev, 0.5 * tol);
        dev = block_dev * stretch + scaled_dev;
      }
    } else {
      warn_entity("SPLINE without control or fit points skipped", e, layer);
      return std::nullopt;
    }
    if (!std::isfinite(dev)) return entity_error(e.type + " has no finite points (overflowing numbers)", top);
    if (!c.closed && closed_flag && c.vertices.size() > 2 &&
        geometry::distance(c.vertices.front().p, c.vertices.back().p) <= tol::kSnapMm) {
      c.vertices.pop_back();
      c.closed = true;
    }
    if (c.vertices.size() < 2) {
      warn_entity("SPLINE of zero length skipped", e, layer);
      return std::nullopt;
    }
    results.push_back(std::move(c));
  } else {
    return std::nullopt;
  }
  if (!std::isfinite(dev)) return entity_error(e.type + " has no finite points (overflowing numbers)", top);
  if (dev > tol) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, dev, std::chars_format::general, 3);
    warn_entity(e.type + " converted to arcs with a deviation of " + std::string(buf, r.ptr) + " mm (tolerance exceeded)",
                e, layer);
  }
  for (Contour& c : results) {
    drop_repeats(c);
    for (const Vertex& v : c.vertices) {
      if (!within_limit(v.p)) {
        return entity_error(e.type + " lies more than 1e6 mm from the origin after INSERT and unit scaling", top);
      }
    }
    if (c.vertices.empty()) continue;
    // Arcs bulge out between their end points (a CIRCLE centred at (0, 5e5) of radius 9e5 has
    // both vertices in range): the extent, not only the vertices, must stay within the limit.
    if (const geometry::Box b = geometry::bounding_box(c);
        !within_limit({b.xmin, b.ymin}) || !within_limit({b.xmax, b.ymax})) {
      return entity_error(e.type + " lies more than 1e6 mm from the origin after INSERT and unit scaling", top);
    }
    DxfEntity out;
    out.path = std::move(c);
    out.type = e.type;
    out.layer = layer;
    out.handle = top.handle;
    out.line = top.line;
    out.block = block;
    out.source_line = e.line;
    out_.entities.push_back(std::move(out));
  }
  return std::nullopt;
}

std::optional<Diagnostic> Expander::emit(int idx, const Affine& t, const std::string& inherited, const Top& top,
                                         int depth, const std::string& block) {
  const ScanEntity& e = scan_.entities[static_cast<std::size_t>(idx)];
  const Payload& p = pay_[static_cast<std::size_t>(idx)];
  // Entities on layer "0" inside a block take the layer of the INSERT that places them.
  const std::string layer = (depth > 0 && e.layer == "0") ? inherited : e.layer;
  const Top here = depth == 0 ? Top{e.handle, e.line} : top;
  if (e.type == "INSERT") {
    if (layer_kept(layer)) ++out_.entity_counts["INSERT"];
    const int b = find_block(e.block_name);
    if (b < 0) {
      if (undefined_warnings_++ < 20) warn_entity("INSERT of undefined block '" + e.block_name + "' skipped", e, layer);
      return std::nullopt;
    }
    const auto& blk = scan_.blocks[static_cast<std::size_t>(b)];
    if ((blk.flags & 4) != 0) {
      warn_entity("INSERT of external reference '" + blk.name + "' skipped", e, layer);
      return std::nullopt;
    }
    // As for ARC angles: a rotation no drawing has would place the block where fmod chose.
    if (!(std::abs(p.angle) <= 1e6)) return entity_error("INSERT rotation beyond ±1e6 degrees", here);
    if (!(std::abs(p.sx) > 0) || !(std::abs(p.sy) > 0)) {
      if (degenerate_warnings_++ < 20) warn_entity("INSERT with zero scale skipped", e, layer);
      return std::nullopt;
    }
    const auto [rows, cols] = grid(p);
    const Affine base = t.then_after(ocs(p.extrusion, e.elevation))
                            .then_after(Affine::translate(p.ins))
                            .then_after(Affine::rotate(p.angle * kPi / 180));
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        // MINSERT cells are spaced along the rotated axes, unscaled.
        const Affine cell = base.then_after(Affine::translate({c * p.colsp, r * p.rowsp}))
                                .then_after(Affine::scale(p.sx, p.sy))
                                .then_after(Affine::translate(-blk.base));
        for (int child : blk.entities) {
          if (auto d = emit(child, cell, layer, here, depth + 1, blk.name)) return d;
        }
      }
    }
    return std::nullopt;
  }
  ++out_.layers[layer];
  if (!layer_kept(layer)) return std::nullopt;
  ++out_.entity_counts[e.type];
  if (!e.forwarded) {
    ++out_.skipped[e.type];
    return std::nullopt;
  }
  if (!scan_.hidden_layers.empty()) {
    const std::string u = upper(layer);
    for (std::size_t h = 0; h < scan_.hidden_layers.size(); ++h)
      if (upper(scan_.hidden_layers[h].first) == u) ++hidden_read_[h];
  }
  if (e.invisible) ++invisible_read_;
  auto d = curve(e, p, t, layer, here, block);
  // An error in a block's entity is reported at its top-level INSERT; name the entity itself too.
  if (d && depth > 0) {
    d->message += " (in block '" + block + "' at line " + std::to_string(e.line) +
                  (e.handle.empty() ? std::string() : ", entity " + e.handle) + ", inserted here)";
  }
  return d;
}

std::optional<Diagnostic> Expander::run() {
  const Affine units = Affine::scale(out_.mm_per_unit, out_.mm_per_unit);
  for (int idx : scan_.modelspace) {
    if (auto d = emit(idx, units, {}, {}, 0, {})) return d;
  }
  for (const auto& [type, n] : out_.skipped) {
    out_.diagnostics.push_back(make_warning(std::to_string(n) + " " + type + " entit" + (n == 1 ? "y" : "ies") +
                                                " skipped (not cut)",
                                            out_.file));
    out_.diagnostics.back().code = "dxf.type_skipped";
  }
  // A layer turned off or frozen in the CAD program (construction lines, an old revision) shows
  // nothing there, so a drawing that looks right can cut more than it shows.
  for (const auto& [h, n] : hidden_read_) {
    const std::string& name = scan_.hidden_layers[h].first;
    Diagnostic d = make_warning("a layer " + scan_.hidden_layers[h].second +
                                    " in the drawing (the CAD program does not show it) has " + std::to_string(n) +
                                    " curve entit" + (n == 1 ? "y, cut" : "ies, cut") + " like the others: --ignore-layers " +
                                    name + " leaves " + (n == 1 ? "it" : "them") + " out",
                                out_.file);
    d.code = "dxf.hidden_layer";
    d.layer = name;
    out_.diagnostics.push_back(std::move(d));
  }
  if (invisible_read_ > 0) {
    out_.diagnostics.push_back(make_warning(std::to_string(invisible_read_) + " curve entit" +
                                                (invisible_read_ == 1 ? "y" : "ies") +
                                                " marked invisible (group 60), which the CAD program does not show, "
                                                "cut like the others",
                                            out_.file));
    out_.diagnostics.back().code = "dxf.invisible";
  }
  return check_layer_filters();
}

// A layer filter naming no layer of the drawing (a typo, another drawing's name) would cut nothing
// or everything without a word: named, with the drawing's layers to choose from. When none of the
// --layers names exists, nothing is left to cut: an error.
std::optional<Diagnostic> Expander::check_layer_filters() {
  auto exists = [&](const std::string& name) {
    for (const auto& [l, n] : out_.layers)
      if (upper(l) == upper(name)) return true;
    return false;
  };
  std::string listed;
  for (const auto& [l, n] : out_.layers)
    listed += (listed.empty() ? "" : ", ") + (l.empty() ? std::string("(no name)") : l) + " (" + std::to_string(n) + ")";
  if (listed.empty()) listed = "none";
  std::string missing;
  std::size_t found = 0;
  for (const auto& l : opt_.layers) {
    if (exists(l)) ++found;
    else missing += (missing.empty() ? "'" : ", '") + l + "'";
  }
  if (!opt_.layers.empty() && found == 0)
    return make_error("no layer given with --layers is in the drawing (" + missing + "); its layers, with their entities: " + listed,
                      out_.file);
  if (!missing.empty()) {
    out_.diagnostics.push_back(make_warning("layer " + missing + " (--layers) is not in the drawing; its layers: " + listed, out_.file));
    out_.diagnostics.back().code = "dxf.layer_missing";
  }
  std::string unknown;
  for (const auto& l : opt_.ignore_layers)
    if (!exists(l)) unknown += (unknown.empty() ? "'" : ", '") + l + "'";
  if (!unknown.empty()) {
    out_.diagnostics.push_back(make_warning("layer " + unknown + " (--ignore-layers) is not in the drawing; its layers: " + listed, out_.file));
    out_.diagnostics.back().code = "dxf.layer_missing";
  }
  return std::nullopt;
}

}  // namespace

Result<DxfDrawing> read_dxf_string(const std::string& content, const std::string& name, const DxfOptions& options) {
  if (options.units && !option_units_mm(*options.units)) {
    return make_error("unknown units '" + *options.units + "' (use mm, cm, m, in or ft)", name);
  }
  if (!(options.curve_tol_mm >= 1e-6) || !(options.curve_tol_mm <= 100.0)) {
    return make_error("curve tolerance must be between 1e-6 and 100 mm", name);
  }
  auto scan = detail::scan_dxf(content, name, &units_rule, &options);
  if (!scan) return scan.error();
  ScanResult& s = scan.value();

  DxfDrawing d;
  d.file = name;
  d.insunits = s.insunits;
  d.measurement = s.measurement;
  const UnitsDecision u = decide_units(s.insunits, s.measurement, options);
  d.units_in_file = u.units_in_file;
  d.units_source = u.source;
  d.mm_per_unit = u.mm_per_unit;
  d.unit_name = u.unit_name;
  if (s.insunits && *s.insunits != 0 && !detail::insunits_mm(*s.insunits)) {
    d.diagnostics.push_back(make_warning("$INSUNITS " + std::to_string(*s.insunits) + " (" +
                                             detail::insunits_name(*s.insunits) + ") is not supported; ignored: its numbers are read as " +
                                             (d.mm_per_unit == 1.0 ? std::string("millimetres") : d.units_in_file) + " (" +
                                             d.units_source + "); --units gives the drawing's unit",
                                         name));
    d.diagnostics.back().code = "dxf.units_ignored";
  }
  for (auto& w : s.warnings) d.diagnostics.push_back(std::move(w));

  std::vector<Payload> payloads(s.entities.size());
  try {
    // dxflib sees only the sanitised text of the scan; it has no error reporting of its own.
    std::istringstream in(s.dxflib_text);
    Collector collector(s, in, payloads);
    DL_Dxf dxf;
    dxf.in(in, &collector);
  } catch (const std::exception& x) {
    return make_error(std::string("DXF parser failed: ") + x.what(), name);
  }

  Expander ex(s, payloads, options, d);
  if (auto e = ex.check_expansion()) return *e;
  if (auto e = ex.run()) return *e;
  return d;
}

Result<DxfDrawing> read_dxf(const std::string& path, const DxfOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return make_error("is a directory, not a DXF file", path);
  // A pipe or FIFO too (`optimize <(unzip -p nests.zip a.dxf)`, a batch fed through FIFOs).
  auto content = read_file(path);
  if (!content) return content.error();
  return read_dxf_string(*content, path, options);
}

}  // namespace cutroute::io
