#include <cutroute/model/common_lines.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <tuple>

#include <cutroute/core/number_format.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>

#include "common_detail.hpp"
#include "path_ops.hpp"

namespace cutroute::model {

using geometry::Segment;
using geometry::Vec2;

const char* to_string(CommonSegmentKind k) {
  switch (k) {
    case CommonSegmentKind::contour: return "contour";
    case CommonSegmentKind::loop: return "loop";
    case CommonSegmentKind::trail: return "trail";
  }
  return "contour";
}

namespace detail {

bool material_left(const NestContour& c) {
  const bool ccw = geometry::orientation(c.source.contour) == geometry::Orientation::ccw;
  return ccw == (c.role != ContourRole::hole);
}

std::string point_text(Vec2 p, const DrawingUnit& unit) { return format_position(p.x, p.y, unit); }

void PathJoiner::move_to(Vec2 p) { path_.vertices = {geometry::Vertex{p, 0}}; }

void PathJoiner::line_to(Vec2 p) {
  if (path_.vertices.empty()) {
    move_to(p);
    return;
  }
  if (geometry::distance(path_.vertices.back().p, p) <= tol::kSamePointMm) return;
  path_.vertices.back().bulge = 0;
  path_.vertices.push_back({p, 0});
}

void PathJoiner::append(const geometry::Contour& piece) {
  if (piece.vertices.empty()) return;
  line_to(piece.vertices.front().p);
  path_.vertices.back().bulge = piece.vertices.front().bulge;
  for (std::size_t i = 1; i < piece.vertices.size(); ++i) path_.vertices.push_back(piece.vertices[i]);
  path_.vertices.back().bulge = 0;
}

geometry::Contour PathJoiner::closed() const {
  geometry::Contour c = path_;
  c.closed = true;
  if (c.vertices.size() > 1 && geometry::distance(c.vertices.front().p, c.vertices.back().p) <= tol::kSamePointMm)
    c.vertices.pop_back();
  return c;
}

}  // namespace detail

std::vector<CommonPiece> pieces_along(const CommonSegment& segment, double s_mm, bool forward, double length_mm) {
  std::vector<CommonPiece> order = segment.pieces;
  if (!forward) {
    std::reverse(order.begin(), order.end());
    for (auto& p : order) p.path = geometry::reversed(p.path);
    s_mm = geometry::length(segment.path) - s_mm;
  }
  std::vector<double> len;
  double total = 0;
  for (const auto& p : order) {
    len.push_back(geometry::length(p.path));
    total += len.back();
  }
  std::vector<CommonPiece> out;
  if (order.empty() || !(total > 0)) return out;
  if (segment.path.closed) {
    s_mm = std::fmod(s_mm, total);
    if (s_mm < 0) s_mm += total;
  }
  // The piece holding s (the first one on a tie with a piece end), then onwards.
  std::size_t k = 0;
  while (k + 1 < order.size() && s_mm >= len[k]) s_mm -= len[k++];
  double remaining = length_mm;
  for (std::size_t guard = 0; remaining > tol::kSamePointMm && guard < 2 * order.size() + 2; ++guard) {
    const double take = std::min(remaining, len[k] - s_mm);
    if (take > tol::kSamePointMm) {
      CommonPiece p = order[k];
      p.path = detail::sub_path(order[k].path, s_mm, take);
      out.push_back(std::move(p));
      remaining -= take;
    }
    s_mm = 0;
    if (++k == order.size()) {
      if (!segment.path.closed) break;
      k = 0;
    }
  }
  return out;
}

EnteredContour entered_contour(const Nest& nest, const std::vector<CommonPiece>& pieces) {
  EnteredContour out;
  const auto it = std::find_if(pieces.begin(), pieces.end(), [](const CommonPiece& p) { return !p.connector(); });
  if (it == pieces.end()) return out;
  const geometry::Contour& c = nest.contours[it->contour].source.contour;
  out.contour = it->contour;
  out.s_mm = geometry::closest_point(c, it->path.vertices.front().p).length_along;
  // Along the stored contour or against it: compare the directions in the middle of the piece.
  const double half = 0.5 * geometry::length(it->path);
  const auto mid = detail::at_length(it->path, half);
  const auto on = detail::at_length(c, geometry::closest_point(c, mid.point).length_along);
  const bool along = geometry::dot(mid.tangent, on.tangent) > 0;
  const bool stored_cw = geometry::orientation(c) == geometry::Orientation::cw;
  out.clockwise = along == stored_cw;
  return out;
}

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// A shared stretch of two segments in their own terms: t* are fractions of each segment's length
// beside centre.a (t*0) and centre.b (t*1); centre runs in the direction of segment i.
struct Match {
  Segment centre;
  double gap = 0;
  double ti0 = 0, ti1 = 0, tj0 = 0, tj1 = 0;
};

// Is the distance (at both ends of the overlap) 0 or kerf? Returns the gap when it is.
std::optional<double> gap_of(double d0, double d1, const CommonLineOptions& o) {
  if (std::abs(d0 - d1) > o.tol_mm) return std::nullopt;
  const double g = 0.5 * (d0 + d1);
  if (std::abs(d0) <= o.tol_mm && std::abs(d1) <= o.tol_mm) return g;
  if (o.kerf_mm > o.tol_mm && std::abs(std::abs(d0) - o.kerf_mm) <= o.tol_mm &&
      std::abs(std::abs(d1) - o.kerf_mm) <= o.tol_mm && d0 * d1 > 0)
    return g;
  return std::nullopt;
}

std::optional<Match> match_lines(const Segment& si, bool mli, const Segment& sj, bool mlj,
                                 const CommonLineOptions& o) {
  const double len = geometry::distance(si.a, si.b);
  if (!(len > 0)) return std::nullopt;
  const Vec2 u = (si.b - si.a) / len, n = geometry::perp(u);
  const double pa = geometry::dot(u, sj.a - si.a), pb = geometry::dot(u, sj.b - si.a);
  if (std::abs(pb - pa) < o.min_length_mm) return std::nullopt;  // no overlap long enough either way
  const double lo = std::max(0.0, std::min(pa, pb)), hi = std::min(len, std::max(pa, pb));
  if (hi - lo < o.min_length_mm) return std::nullopt;
  const double da = geometry::dot(n, sj.a - si.a), db = geometry::dot(n, sj.b - si.a);
  const auto dist = [&](double x) { return da + (x - pa) / (pb - pa) * (db - da); };
  const auto gap = gap_of(dist(lo), dist(hi), o);
  if (!gap) return std::nullopt;
  // The two parts' material on opposite sides of the common cut, and a kerf gap in scrap.
  const Vec2 ni = mli ? n : -n;
  const Vec2 uj = geometry::normalized(sj.b - sj.a);
  const Vec2 nj = mlj ? geometry::perp(uj) : -geometry::perp(uj);
  if (geometry::dot(ni, nj) >= 0) return std::nullopt;
  if (std::abs(*gap) > o.tol_mm && *gap * geometry::dot(n, ni) > 0) return std::nullopt;
  Match m;
  m.gap = std::abs(*gap);
  const Vec2 shift = n * (0.5 * *gap);
  m.centre = Segment{si.a + u * lo + shift, si.a + u * hi + shift, 0};
  m.ti0 = lo / len;
  m.ti1 = hi / len;
  m.tj0 = (lo - pa) / (pb - pa);
  m.tj1 = (hi - pa) / (pb - pa);
  return m;
}

// Counter-clockwise angular interval of an arc: start angle and width [rad].
struct Span {
  double start = 0, width = 0;
};
Span span_of(const Segment& s) {
  const Vec2 c = s.center();
  const double a0 = std::atan2(s.a.y - c.y, s.a.x - c.x);
  const double th = s.sweep();
  return th > 0 ? Span{a0, th} : Span{a0 + th, -th};
}
// Fraction of the arc's length at angle offset `rel` from its span start.
double t_of(double rel, const Segment& s, const Span& sp) { return s.sweep() > 0 ? rel / sp.width : 1 - rel / sp.width; }

std::vector<Match> match_arcs(const Segment& si, bool mli, const Segment& sj, bool mlj, const CommonLineOptions& o) {
  std::vector<Match> out;
  const Vec2 ci = si.center(), cj = sj.center();
  const double ri = si.radius(), rj = sj.radius();
  if (geometry::distance(ci, cj) > o.tol_mm) return out;
  const auto gap = gap_of(rj - ri, rj - ri, o);
  if (!gap) return out;
  // Material toward the centre: left of a counter-clockwise arc.
  const bool in_i = mli == (si.sweep() > 0), in_j = mlj == (sj.sweep() > 0);
  if (in_i == in_j) return out;
  if (std::abs(*gap) > o.tol_mm && (ri < rj) != in_i) return out;  // the inner arc's part lies inside
  const Span a = span_of(si), b = span_of(sj);
  const double rm = 0.5 * (ri + rj);
  const Vec2 c = (ci + cj) * 0.5;
  double x = std::fmod(b.start - a.start, kTwoPi);
  if (x < 0) x += kTwoPi;
  for (double shift : {x, x - kTwoPi}) {
    const double lo = std::max(0.0, shift), hi = std::min(a.width, shift + b.width);
    if ((hi - lo) * rm < o.min_length_mm) continue;
    Match m;
    m.gap = std::abs(*gap);
    const double p0 = a.start + lo, p1 = a.start + hi;
    const Vec2 q0 = c + Vec2{std::cos(p0), std::sin(p0)} * rm, q1 = c + Vec2{std::cos(p1), std::sin(p1)} * rm;
    const double bulge = std::tan((hi - lo) / 4);
    const bool fwd = si.sweep() > 0;
    m.centre = fwd ? Segment{q0, q1, bulge} : Segment{q1, q0, -bulge};
    const double ta = t_of(lo, si, a), tb = t_of(hi, si, a);
    const double ua = t_of(lo - shift, sj, b), ub = t_of(hi - shift, sj, b);
    m.ti0 = fwd ? ta : tb;
    m.ti1 = fwd ? tb : ta;
    m.tj0 = fwd ? ua : ub;
    m.tj1 = fwd ? ub : ua;
    out.push_back(m);
  }
  return out;
}

struct ContourData {
  geometry::SegmentSet set;
  std::vector<double> start_s;  // arc length at the start of each segment [mm]
  bool mat_left = true;
  std::vector<std::pair<double, double>> taken;  // stretch intervals found so far [mm]
};

bool overlaps_taken(const ContourData& d, double s0, double s1, double tol) {
  const double lo = std::min(s0, s1), hi = std::max(s0, s1);
  return std::any_of(d.taken.begin(), d.taken.end(),
                     [&](const auto& iv) { return std::min(hi, iv.second) - std::max(lo, iv.first) > tol; });
}

}  // namespace

std::vector<CommonStretch> find_common_stretches(const Nest& nest, const CommonLineOptions& options) {
  const std::size_t n = nest.contours.size();
  std::vector<ContourData> data(n);
  std::vector<geometry::Box> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = nest.contours[ContourId(static_cast<std::int32_t>(i))];
    if (c.role == ContourRole::sheet) continue;  // its box stays empty: never reported
    boxes[i] = c.box;
    auto& d = data[i];
    d.set = geometry::make_segment_set(c.source.contour);
    d.mat_left = detail::material_left(c);
    double acc = 0;
    for (const auto& s : d.set.segments) {
      d.start_s.push_back(acc);
      acc += s.length();
    }
  }
  const geometry::StaticSpatialIndex index(boxes);
  const double reach = options.kerf_mm + options.tol_mm;
  std::vector<CommonStretch> out;
  std::vector<std::uint32_t> near;
  for (std::size_t i = 0; i < n; ++i) {
    if (boxes[i].empty()) continue;
    index.query(boxes[i].inflated(reach), near);
    std::sort(near.begin(), near.end());
    // Per segment of i, in order: matches against every later contour, sorted for determinism.
    std::vector<std::tuple<std::size_t, double, std::uint32_t, std::size_t, Match>> found;
    for (const std::uint32_t j : near) {
      if (j <= i) continue;
      const auto& di = data[i];
      const auto& dj = data[j];
      for (std::size_t ki = 0; ki < di.set.segments.size(); ++ki) {
        const Segment& si = di.set.segments[ki];
        dj.set.index.visit(di.set.boxes[ki].inflated(reach), [&](std::uint32_t kj) {
          const Segment& sj = dj.set.segments[kj];
          std::vector<Match> ms;
          if (!si.is_arc() && !sj.is_arc()) {
            if (auto m = match_lines(si, di.mat_left, sj, dj.mat_left, options)) ms.push_back(*m);
          } else if (si.is_arc() && sj.is_arc()) {
            ms = match_arcs(si, di.mat_left, sj, dj.mat_left, options);
          }
          for (const auto& m : ms) found.emplace_back(ki, m.ti0, j, kj, m);
          return true;
        });
      }
    }
    std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) {
      return std::tie(std::get<0>(x), std::get<1>(x), std::get<2>(x), std::get<3>(x)) <
             std::tie(std::get<0>(y), std::get<1>(y), std::get<2>(y), std::get<3>(y));
    });
    for (const auto& [ki, t, j, kj, m] : found) {
      auto& di = data[i];
      auto& dj = data[j];
      const double li = di.set.segments[ki].length(), lj = dj.set.segments[kj].length();
      CommonStretch st;
      st.centre = m.centre;
      st.first = ContourId(static_cast<std::int32_t>(i));
      st.second = ContourId(static_cast<std::int32_t>(j));
      st.gap_mm = m.gap;
      st.first_s0 = di.start_s[ki] + m.ti0 * li;
      st.first_s1 = di.start_s[ki] + m.ti1 * li;
      st.second_s0 = dj.start_s[kj] + m.tj0 * lj;
      st.second_s1 = dj.start_s[kj] + m.tj1 * lj;
      if (overlaps_taken(di, st.first_s0, st.first_s1, options.tol_mm) ||
          overlaps_taken(dj, st.second_s0, st.second_s1, options.tol_mm))
        continue;
      di.taken.emplace_back(std::min(st.first_s0, st.first_s1), std::max(st.first_s0, st.first_s1));
      dj.taken.emplace_back(std::min(st.second_s0, st.second_s1), std::max(st.second_s0, st.second_s1));
      out.push_back(st);
    }
  }
  return out;
}

}  // namespace cutroute::model
