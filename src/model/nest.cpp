// build_nest(): the steps listed in nest.hpp, one function each.
#include <cutroute/model/nest.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/tolerances.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>

namespace cutroute::model {

const char* to_string(ContourRole r) {
  switch (r) {
    case ContourRole::outer: return "outer";
    case ContourRole::hole: return "hole";
    case ContourRole::sheet: return "sheet";
  }
  return "outer";
}

namespace {

using geometry::Box;
using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

ContourId cid(std::size_t i) { return ContourId(static_cast<std::int32_t>(i)); }

// "contour 3 (entity 1F, line 120, layer CUT)"
std::string describe(const SourceContour& s, std::size_t input_index) {
  std::string out = "contour " + std::to_string(input_index);
  std::string extra;
  auto add = [&](const std::string& part) { extra += (extra.empty() ? "" : ", ") + part; };
  if (!s.handle.empty()) add("entity " + s.handle);
  if (s.line) add("line " + std::to_string(*s.line));
  if (!s.layer.empty()) add("layer " + s.layer);
  if (!extra.empty()) out += " (" + extra + ")";
  return out;
}

// A length for messages: 3 decimals (µm), trailing zeros kept short, never "-0".
std::string format_mm(double v) {
  if (v == 0.0) v = 0.0;  // folds -0
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 3);
  std::string out(buf, res.ptr);
  if (out.find('.') != std::string::npos) {
    while (out.back() == '0') out.pop_back();
    if (out.back() == '.') out.pop_back();
  }
  if (out == "-0") out = "0";
  return out;
}

std::string format_point(Vec2 p, const DrawingUnit& unit) { return format_position(p.x, p.y, unit); }

Diagnostic diagnostic_for(Severity severity, std::string message, const SourceContour& s, const char* code) {
  Diagnostic d;
  d.severity = severity;
  d.code = code;
  d.message = std::move(message);
  d.line = s.line;
  d.handle = s.handle;
  d.layer = s.layer;
  return d;
}

// --- step 1: prepare ---

bool finite_contour(const Contour& c) {
  for (const Vertex& v : c.vertices) {
    if (!geometry::is_finite(v.p) || !std::isfinite(v.bulge)) return false;
  }
  return true;
}

// The vertex cycle read counter-clockwise from its lexicographically smallest vertex, -0 folded,
// without the vertices that only split a straight edge: a rectangle drawn as a polyline with an
// extra point on one side and again as four LINEs is one outline drawn twice (before, the pair
// was refused as crossing contours).
std::vector<Vertex> canonical_cycle(const Contour& c, double signed_area) {
  Contour ccw = signed_area < 0 ? geometry::reversed(c) : c;
  // One pass drops every vertex between two straight segments running on in one direction (the
  // previous vertex being the last one kept); a second pass catches the one where the cycle closes.
  auto splits_a_side = [](const Vertex& prev, const Vertex& here, Vec2 next) {
    if (prev.bulge != 0.0 || here.bulge != 0.0) return false;
    const Vec2 u = here.p - prev.p, v = next - here.p;
    const double cross = u.x * v.y - u.y * v.x, dot = u.x * v.x + u.y * v.y;
    return dot > 0.0 && std::abs(cross) <= 1e-12 * geometry::norm(u) * geometry::norm(v);
  };
  for (bool removed = true; removed && ccw.vertices.size() > 3;) {
    removed = false;
    const std::vector<Vertex>& v = ccw.vertices;
    const std::size_t m = v.size();
    std::vector<Vertex> kept;
    kept.reserve(m);
    for (std::size_t i = 0; i < m; ++i) {
      const Vertex& prev = kept.empty() ? v[m - 1] : kept.back();
      if (m - (i - kept.size()) > 3 && splits_a_side(prev, v[i], v[(i + 1) % m].p)) {
        removed = true;
        continue;
      }
      kept.push_back(v[i]);
    }
    ccw.vertices = std::move(kept);
  }
  const std::size_t n = ccw.vertices.size();
  std::size_t start = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const Vec2 a = ccw.vertices[i].p, b = ccw.vertices[start].p;
    if (a.x < b.x || (a.x == b.x && a.y < b.y)) start = i;
  }
  std::vector<Vertex> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    Vertex v = ccw.vertices[(start + i) % n];
    v.p.x += 0.0;
    v.p.y += 0.0;
    v.bulge += 0.0;
    out.push_back(v);
  }
  return out;
}

std::uint64_t hash_cycle(const std::vector<Vertex>& cycle) {
  std::uint64_t h = 0x84222325CBF29CE4ull;
  for (const Vertex& v : cycle) {
    for (double x : {v.p.x, v.p.y, v.bulge}) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &x, sizeof bits);
      h = (h ^ bits) * 0x100000001B3ull;
      h ^= h >> 29;
    }
  }
  return h;
}

struct Prepared {
  std::vector<std::size_t> input_index;        // ContourId -> index in the caller's vector
  std::vector<geometry::SegmentSet> segments;  // ContourId -> indexed segments
};

// Kept contours by the 1 mm cell of their box's lower left corner: a copy nudged by less than
// kNearDuplicateMm has its corner in the same or a neighbouring cell.
struct CornerGrid {
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
  static std::int64_t cell(double v) { return static_cast<std::int64_t>(std::floor(std::clamp(v, -1e15, 1e15))); }
  static std::uint64_t key(std::int64_t x, std::int64_t y) {
    return static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(y);
  }
  void add(const Box& b, std::size_t kept) { cells[key(cell(b.xmin), cell(b.ymin))].push_back(kept); }
  template <class F>
  void near(const Box& b, F&& f) const {
    const std::int64_t x = cell(b.xmin), y = cell(b.ymin);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        if (const auto it = cells.find(key(x + dx, y + dy)); it != cells.end())
          for (const std::size_t k : it->second) f(k);
  }
};

// Is the outline `s` (box b, area a) drawn again, within kNearDuplicateMm, as kept contour k?
// Every sample of each boundary (vertices, quarter points) lies that close to the other's.
bool near_duplicate(const geometry::SegmentSet& s, const Box& b, double a, const NestContour& kept, const geometry::SegmentSet& ks) {
  const double tol = tol::kNearDuplicateMm;
  const Box& kb = kept.box;
  if (std::abs(b.xmin - kb.xmin) > tol || std::abs(b.ymin - kb.ymin) > tol || std::abs(b.xmax - kb.xmax) > tol ||
      std::abs(b.ymax - kb.ymax) > tol)
    return false;
  if (std::abs(std::abs(a) - kept.area_mm2) > tol * 2 * (b.width() + b.height())) return false;
  const auto one_way = [tol](const geometry::SegmentSet& x, const geometry::SegmentSet& y) {
    const geometry::BoundarySides sides = geometry::boundary_sides(x, y, tol);
    return sides.inside == 0 && sides.outside == 0;
  };
  return one_way(s, ks) && one_way(ks, s);
}

Prepared prepare(std::vector<SourceContour> contours, Nest& nest) {
  Prepared prep;
  std::unordered_multimap<std::uint64_t, std::size_t> kept_by_hash;  // hash -> position in nest.contours
  CornerGrid corners;
  std::vector<std::vector<Vertex>> cycles;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    SourceContour& s = contours[i];
    const Contour& c = s.contour;
    const double a = c.closed && finite_contour(c) ? geometry::signed_area(c) : 0.0;
    if (!c.closed || c.vertices.empty() || !finite_contour(c) || !(geometry::length(c) > 0.0)) {
      const char* why = !c.closed ? "is not closed" : (!finite_contour(c) ? "has a non-finite coordinate" : "has no length");
      // A closed contour of no length is a point: nothing to cut, so only a warning.
      const bool pointlike = c.closed && finite_contour(c);
      nest.diagnostics.push_back(diagnostic_for(pointlike ? Severity::warning : Severity::error,
                                                describe(s, i) + " " + why + "; left out of the nest", s,
                                                pointlike ? "nest.degenerate" : "nest.invalid"));
      ++nest.dropped_invalid;
      continue;
    }
    std::vector<Vertex> cycle = canonical_cycle(c, a);
    const std::uint64_t h = hash_cycle(cycle);
    bool duplicate = false;
    const auto [first, last] = kept_by_hash.equal_range(h);
    for (auto it = first; it != last; ++it) {
      const std::size_t kept = it->second;
      if (cycles[kept] == cycle) {
        const std::size_t first_input = prep.input_index[kept];
        // The same outline drawn twice (two layers, two passes): cut once, and say so.
        nest.diagnostics.push_back(diagnostic_for(
            Severity::warning,
            describe(s, i) + " duplicates " + describe(nest.contours[cid(kept)].source, first_input) + "; the copy is left out",
            s, "nest.duplicate"));
        ++nest.dropped_duplicates;
        duplicate = true;
        break;
      }
    }
    if (duplicate) continue;
    // The same outline drawn again a few micrometres off (exact copies are caught above).
    geometry::SegmentSet segments = geometry::make_segment_set(c);
    const Box box = geometry::bounding_box(c);
    corners.near(box, [&](std::size_t kept) {
      if (duplicate || !near_duplicate(segments, box, a, nest.contours[cid(kept)], prep.segments[kept])) return;
      nest.diagnostics.push_back(diagnostic_for(Severity::warning,
                                                describe(s, i) + " duplicates " +
                                                    describe(nest.contours[cid(kept)].source, prep.input_index[kept]) +
                                                    " within " + format_fixed(tol::kNearDuplicateMm, 2) +
                                                    " mm everywhere (cut, both would run along one kerf); the copy is left out",
                                                s, "nest.duplicate"));
      ++nest.dropped_duplicates;
      duplicate = true;
    });
    if (duplicate) continue;
    if (geometry::orientation(c) == geometry::Orientation::degenerate) {
      // Still cut (a slot traced there and back, a figure 8), but it can hold nothing.
      nest.diagnostics.push_back(diagnostic_for(Severity::warning, describe(s, i) + " encloses no area", s, "nest.no_area"));
    }
    NestContour nc;
    nc.area_mm2 = std::abs(a);
    nc.box = box;
    nc.source = std::move(s);
    kept_by_hash.emplace(h, nest.contours.size());
    corners.add(box, nest.contours.size());
    cycles.push_back(std::move(cycle));
    prep.input_index.push_back(i);
    prep.segments.push_back(std::move(segments));
    nest.contours.push_back(std::move(nc));
  }
  return prep;
}

// --- step 2: sheet candidate ---

bool layer_names_sheet(const std::string& layer) {
  std::string l = layer;
  std::transform(l.begin(), l.end(), l.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  for (const char* word : {"sheet", "plate", "border", "blech"}) {
    if (l.find(word) != std::string::npos) return true;
  }
  return false;
}

// The side lengths of a rectangle in any orientation (a nest drawn rotated, its border with it);
// nullopt for any other contour. Collinear pieces of a side count as one.
std::optional<Vec2> rectangle_sides(const NestContour& nc) {
  const Contour& c = nc.source.contour;
  const double tol = tol::kSheetRectangleMm;
  std::vector<Vec2> sides;  // side vectors, collinear pieces summed
  const auto continues = [&](Vec2 a, Vec2 b) { return std::abs(geometry::cross(a, b)) <= tol * geometry::norm(a) && geometry::dot(a, b) > 0; };
  for (std::size_t i = 0; i < geometry::segment_count(c); ++i) {
    const geometry::Segment s = geometry::segment(c, i);
    const Vec2 d = s.b - s.a;
    const double len = geometry::norm(d);
    if (s.is_arc() && len * std::abs(s.bulge) / 2.0 > tol) return std::nullopt;
    if (len <= tol) continue;
    if (!sides.empty() && continues(sides.back(), d)) {
      sides.back() = sides.back() + d;
      continue;
    }
    sides.push_back(d);
  }
  if (sides.size() == 5 && continues(sides.front(), sides.back())) {
    sides.front() = sides.front() + sides.back();  // the first side began mid-way
    sides.pop_back();
  }
  if (sides.size() != 4) return std::nullopt;
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec2 a = sides[i], b = sides[(i + 1) % 4];
    if (std::abs(geometry::dot(a, b)) > tol * geometry::norm(a)) return std::nullopt;
  }
  const double w = geometry::norm(sides[0]), h = geometry::norm(sides[1]);
  if (std::abs(geometry::norm(sides[2]) - w) > tol || std::abs(geometry::norm(sides[3]) - h) > tol) return std::nullopt;
  return Vec2{w, h};
}

enum class SheetReason { size, layer, geometry };
struct SheetCandidate {
  std::size_t index;
  SheetReason reason;
  Vec2 sides;  // its side lengths [mm]
};

std::optional<SheetCandidate> find_sheet_candidate(const Nest& nest, const NestOptions& options) {
  if (nest.contours.empty()) return std::nullopt;
  if (!options.sheet_size && !options.detect_sheet) return std::nullopt;
  std::size_t largest = 0;
  for (std::size_t i = 1; i < nest.contours.size(); ++i) {
    if (nest.contours[cid(i)].area_mm2 > nest.contours[cid(largest)].area_mm2) largest = i;
  }
  const NestContour& c = nest.contours[cid(largest)];
  // A rectangle in any orientation (a nest drawn rotated, its border with it: taken for a part,
  // it made every part a hole).
  const std::optional<Vec2> sides = rectangle_sides(c);
  if (!sides) return std::nullopt;
  const Box outer = c.box.inflated(std::max(options.touch_tol_mm, tol::kSheetOverhangMm));
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    if (i != largest && !outer.contains(nest.contours[cid(i)].box)) return std::nullopt;
  }
  if (options.sheet_size) {
    const Vec2 want = *options.sheet_size;
    auto near = [](double a, double b) { return std::abs(a - b) < tol::kSheetSizeMm; };
    const bool fits = (near(sides->x, want.x) && near(sides->y, want.y)) || (near(sides->x, want.y) && near(sides->y, want.x));
    if (fits) return SheetCandidate{largest, SheetReason::size, *sides};
  }
  if (!options.detect_sheet || nest.contours.size() < 2) return std::nullopt;
  if (layer_names_sheet(c.source.layer)) return SheetCandidate{largest, SheetReason::layer, *sides};
  return SheetCandidate{largest, SheetReason::geometry, *sides};
}

// --- step 3: containment tree ---

struct Tree {
  std::vector<std::int32_t> parent;  // -1 at the top
  std::vector<std::pair<std::int32_t, std::int32_t>> shared_edges;  // every pair, listed or not
  Diagnostics crossings;
  std::size_t unlisted_errors = 0;    // pairs beyond kMaxPairDiagnostics
  std::size_t unlisted_warnings = 0;

  // A drawing of thousands of mutually overlapping contours must not produce millions of
  // messages: the first kMaxPairDiagnostics pairs are listed, the rest counted.
  static constexpr std::size_t kMaxPairDiagnostics = 1000;
  void report(Diagnostic d) {
    if (crossings.size() < kMaxPairDiagnostics) {
      crossings.push_back(std::move(d));
    } else {
      ++(d.severity == Severity::error ? unlisted_errors : unlisted_warnings);
    }
  }
};

Tree build_tree(const Nest& nest, const Prepared& prep, std::optional<std::size_t> excluded, double tol_mm,
                double crossing_tol_mm) {
  const std::size_t n = nest.contours.size();
  Tree tree;
  tree.parent.assign(n, -1);
  std::vector<Box> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (excluded && *excluded == i) continue;  // an empty box is never reported
    boxes[i] = nest.contours[cid(i)].box.inflated(tol_mm);
  }
  const geometry::StaticSpatialIndex index(boxes);
  // "a is bigger than b": larger area, ties by position, so parents always precede children.
  auto bigger = [&](std::size_t a, std::size_t b) {
    const double aa = nest.contours[cid(a)].area_mm2, ab = nest.contours[cid(b)].area_mm2;
    return aa > ab || (aa == ab && a < b);
  };
  std::vector<std::uint32_t> hits;
  for (std::size_t i = 0; i < n; ++i) {
    if (boxes[i].empty()) continue;
    index.query(boxes[i], hits);
    for (std::uint32_t j32 : hits) {
      const std::size_t j = j32;
      if (j <= i) continue;
      const NestContour& ci = nest.contours[cid(i)];
      const NestContour& cj = nest.contours[cid(j)];
      const std::size_t big = bigger(i, j) ? i : j;
      const std::size_t small = big == i ? j : i;
      const NestContour& cb = nest.contours[cid(big)];
      const NestContour& cs = nest.contours[cid(small)];
      const bool box_inside = cb.box.inflated(tol_mm).contains(cs.box);
      const geometry::BoundaryContact contact = geometry::boundary_contact(prep.segments[i], prep.segments[j], tol_mm);
      if (contact.any()) {
        // Boundaries meet: sample both boundaries against the other region to tell touching
        // (each boundary on one side of the other) from crossing.
        const geometry::BoundarySides s_in_b = geometry::boundary_sides(prep.segments[small], prep.segments[big], tol_mm);
        const geometry::BoundarySides b_in_s = geometry::boundary_sides(prep.segments[big], prep.segments[small], tol_mm);
        const bool crossing = (s_in_b.inside > 0 && s_in_b.outside > 0) || (b_in_s.inside > 0 && b_in_s.outside > 0);
        const bool undecided = s_in_b.inside + s_in_b.outside == 0 || b_in_s.inside + b_in_s.outside == 0;
        const std::string pair = describe(ci.source, prep.input_index[i]) + " and " + describe(cj.source, prep.input_index[j]);
        const std::string where = " near " + format_point(contact.first, nest.unit);
        const double depth = crossing ? std::max(s_in_b.depth, b_in_s.depth) : 0.0;
        // Curves converted to arcs (SPLINE, ELLIPSE) may cross a neighbour they only touched in
        // the drawing, by up to the conversion tolerance: that is touching, not an overlap.
        const bool shallow = crossing && !undecided && depth <= crossing_tol_mm;
        if (shallow) {
          tree.report(diagnostic_for(Severity::warning,
                                     pair + " cross by about " + format_mm(depth) + " mm" + where +
                                         ", within the curve tolerance: treated as touching",
                                     ci.source, "nest.touch"));
          if (!box_inside || s_in_b.inside <= s_in_b.outside) continue;
          const std::int32_t current = tree.parent[small];
          if (current < 0 || bigger(static_cast<std::size_t>(current), big)) tree.parent[small] = static_cast<std::int32_t>(big);
          continue;
        }
        if (crossing || undecided) {
          std::string message = pair + " cross or overlap" + where;
          if (crossing) {
            message += ", by at least ";
            message += format_mm(std::max(s_in_b.depth, b_in_s.depth));
            message += " mm";
          }
          tree.report(diagnostic_for(Severity::error, std::move(message), ci.source, "nest.crossing"));
          continue;
        }
        // Parts placed edge to edge can still be cut one after the other (the shared edge twice,
        // or once with common-line cutting): a warning, not an error.
        if (contact.overlaps > 0) {
          tree.shared_edges.emplace_back(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j));
          tree.report(diagnostic_for(Severity::warning, pair + " share a boundary stretch (common edge)" + where,
                                     ci.source, "nest.common_edge"));
        } else {
          tree.report(diagnostic_for(Severity::warning, pair + " touch" + where, ci.source, "nest.touch"));
        }
        // Touching from inside still nests: every decisive sample of the smaller is inside.
        if (!box_inside || s_in_b.inside == 0) continue;
      } else {
        if (!box_inside) continue;
        // Boundaries are farther apart than tol, so any vertex of the smaller one decides.
        if (geometry::locate(prep.segments[big], cs.source.contour.vertices.front().p, tol_mm) !=
            geometry::Location::inside) {
          continue;
        }
      }
      const std::int32_t current = tree.parent[small];
      if (current < 0 || bigger(static_cast<std::size_t>(current), big)) tree.parent[small] = static_cast<std::int32_t>(big);
    }
  }
  return tree;
}

// --- step 4: accept a border found by geometry alone ---

// Inside a sheet there are several parts and at least one of them has a hole; inside a
// rectangular plate there are holes, which rarely hold anything. Without the rectangle, the
// tree `tree` must therefore have >= 2 top-level contours and some contour with a parent.
bool looks_like_sheet(const Tree& tree) {
  std::size_t roots = 0;
  bool nested = false;
  for (std::int32_t p : tree.parent) {
    if (p >= 0) nested = true; else ++roots;
  }
  return nested && roots >= 3;  // the rectangle itself is a root of `tree` too (excluded, parent -1)
}

// --- step 5: depth, roles, parts ---

void assign_tree(Nest& nest, const Tree& tree, std::optional<std::size_t> sheet) {
  const std::size_t n = nest.contours.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double aa = nest.contours[cid(a)].area_mm2, ab = nest.contours[cid(b)].area_mm2;
    return aa > ab || (aa == ab && a < b);
  });
  nest.max_depth = 0;
  for (std::size_t i : order) {  // parents come first in this order
    NestContour& c = nest.contours[cid(i)];
    if (sheet && *sheet == i) {
      c.role = ContourRole::sheet;
      c.depth = 0;
      continue;
    }
    const std::int32_t p = tree.parent[i];
    c.parent = p >= 0 ? ContourId(p) : ContourId();
    c.depth = p >= 0 ? nest.contours[cid(static_cast<std::size_t>(p))].depth + 1 : 0;
    c.role = c.depth % 2 == 0 ? ContourRole::outer : ContourRole::hole;
    nest.max_depth = std::max(nest.max_depth, c.depth);
  }
  // Parts in contour order; holes attached in contour order too (deterministic).
  for (std::size_t i = 0; i < n; ++i) {
    NestContour& c = nest.contours[cid(i)];
    if (c.role != ContourRole::outer) continue;
    c.part = nest.parts.next_id();
    Part part;
    part.outer = ContourId(static_cast<std::int32_t>(i));
    if (c.parent.valid()) {
      part.inside_hole = c.parent;
    }
    nest.parts.push_back(part);
  }
  for (std::size_t i = 0; i < n; ++i) {
    NestContour& c = nest.contours[cid(i)];
    if (c.role != ContourRole::hole) continue;
    c.part = nest.contours[c.parent].part;
    nest.parts[c.part].holes.push_back(ContourId(static_cast<std::int32_t>(i)));
  }
  for (Part& part : nest.parts) {
    if (part.inside_hole.valid()) part.parent_part = nest.contours[part.inside_hole].part;
  }
}

void warn_touching_sheet(Nest& nest, const Prepared& prep, std::size_t sheet, double tol_mm) {
  const Box inner = nest.contours[cid(sheet)].box;
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    if (i == sheet) continue;
    const Box& b = nest.contours[cid(i)].box;
    const bool touches = b.xmin <= inner.xmin + tol_mm || b.ymin <= inner.ymin + tol_mm ||
                         b.xmax >= inner.xmax - tol_mm || b.ymax >= inner.ymax - tol_mm;
    if (touches) {
      nest.diagnostics.push_back(diagnostic_for(
          Severity::warning,
          describe(nest.contours[cid(i)].source, prep.input_index[i]) + " touches or crosses the sheet border",
          nest.contours[cid(i)].source, "nest.sheet_touch"));
    }
  }
}

}  // namespace

Nest build_nest(std::vector<SourceContour> contours, const NestOptions& options) {
  const double tol_mm = options.touch_tol_mm >= 0.0 ? options.touch_tol_mm : 0.0;
  Nest nest;
  nest.unit = options.position_unit;
  const Prepared prep = prepare(std::move(contours), nest);
  std::optional<SheetCandidate> sheet = find_sheet_candidate(nest, options);
  std::optional<std::size_t> excluded;
  if (sheet) excluded = sheet->index;
  Tree tree = build_tree(nest, prep, excluded, tol_mm, options.crossing_tol_mm);
  if (sheet && sheet->reason == SheetReason::geometry && !looks_like_sheet(tree)) {
    {
      sheet.reset();
      tree = build_tree(nest, prep, std::nullopt, tol_mm, options.crossing_tol_mm);
    }
  }
  // A contour that crosses or touches itself has no inside to speak of: its loops run in opposite
  // senses, so one of them would get its lead-in and kerf on the part's side. As with two contours
  // that cross, the drawing is wrong (--allow-crossing cuts it anyway).
  for (std::size_t i = 0; i < nest.contours.size(); ++i)
    if (const auto at = geometry::self_contact(prep.segments[i], options.self_loop_tol_mm))
      tree.report(diagnostic_for(Severity::error,
                                 describe(nest.contours[cid(i)].source, prep.input_index[i]) + " crosses or touches itself near " +
                                     format_point(*at, nest.unit),
                                 nest.contours[cid(i)].source, "nest.crossing"));
  std::optional<std::size_t> sheet_index;
  if (sheet) sheet_index = sheet->index;
  assign_tree(nest, tree, sheet_index);
  nest.diagnostics.insert(nest.diagnostics.end(), tree.crossings.begin(), tree.crossings.end());
  std::sort(tree.shared_edges.begin(), tree.shared_edges.end());
  for (const auto& [a, b] : tree.shared_edges) nest.shared_edges.emplace_back(ContourId(a), ContourId(b));
  if (tree.unlisted_errors + tree.unlisted_warnings > 0) {
    Diagnostic d;
    d.severity = tree.unlisted_errors > 0 ? Severity::error : Severity::warning;
    d.code = tree.unlisted_errors > 0 ? "nest.crossing" : "nest.touch";
    d.message = std::to_string(tree.unlisted_errors) + " more pairs of contours cross or overlap and " +
                std::to_string(tree.unlisted_warnings) + " more touch (not listed)";
    nest.diagnostics.push_back(std::move(d));
  }
  if (sheet) {
    nest.sheet = ContourId(static_cast<std::int32_t>(sheet->index));
    nest.sheet_box = nest.contours[cid(sheet->index)].box;
    warn_touching_sheet(nest, prep, sheet->index, tol_mm);
  } else if (options.sheet_size) {
    nest.sheet_box = Box{0.0, 0.0, options.sheet_size->x, options.sheet_size->y};
  }
  // --sheet names the border to leave uncut by its size; a size that matches no rectangle drawn
  // round the parts (a slip, or W and H of another sheet) was passed over without a word, and the
  // border then depended on what the drawing showed.
  if (options.sheet_size && !(sheet && sheet->reason == SheetReason::size)) {
    std::string msg = "--sheet " + format_fixed(options.sheet_size->x, 3) + "," + format_fixed(options.sheet_size->y, 3) +
                      " matches no rectangle drawn round the parts (within " + format_fixed(tol::kSheetSizeMm, 3) + " mm)";
    if (sheet) {
      msg += ": the border found by its " + std::string(sheet->reason == SheetReason::layer ? "layer" : "shape") + ", " +
             format_fixed(sheet->sides.x, 3) + " x " + format_fixed(sheet->sides.y, 3) + " mm, is left uncut";
    } else {
      msg += ": no border is left out, every closed contour is cut";
    }
    Diagnostic w = make_warning(std::move(msg));
    w.code = "nest.sheet_size";
    nest.diagnostics.push_back(std::move(w));
  }
  return nest;
}

}  // namespace cutroute::model
