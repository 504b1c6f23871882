#include <cutroute/nc/compensation_check.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cutroute::nc {
namespace {

using geometry::Vec2;

struct Move {
  Vec2 a, b;
  double bulge = 0;  // 0: a line (arcs the writer turns into chords included)
  double length = 0;
  double radius = 0;
  Vec2 t0, t1;  // unit tangents at the start and the end
};

// The moves of a segment as the writer emits them (gcode_writer.cpp: moves that round to nothing
// are dropped, arcs below 0.02 mm radius are written as chords).
std::vector<Move> moves_of(const CutSegment& seg) {
  constexpr double kDropMm = 1e-4, kChordBelowMm = 0.02;
  std::vector<Move> out;
  for (const auto& piece : seg.pieces) {
    const std::size_t n = geometry::segment_count(piece.path);
    for (std::size_t i = 0; i < n; ++i) {
      const geometry::Segment s = geometry::segment(piece.path, i);
      Move m;
      m.a = s.a;
      m.b = s.b;
      if (s.is_arc() && s.radius() >= kChordBelowMm) {
        m.bulge = s.bulge;
        m.length = s.length();
        m.radius = s.radius();
        m.t0 = s.tangent_at(0);
        m.t1 = s.tangent_at(1);
      } else {
        m.length = geometry::distance(s.a, s.b);
        if (m.length > 0) m.t0 = m.t1 = (s.b - s.a) / m.length;
      }
      if (m.length > kDropMm) out.push_back(m);
    }
  }
  return out;
}

bool at_risk(const CutSegment& seg, double r) {
  const std::vector<Move> ms = moves_of(seg);
  if (ms.empty()) return false;
  const double side = seg.kerf == KerfSide::left ? 1.0 : -1.0;  // G41: the tool left of the path
  // The entry move: the controller moves from the uncompensated point onto the offset path.
  if (ms.front().length <= r || (ms.front().bulge != 0 && ms.front().radius <= r)) return true;
  for (const Move& m : ms)
    if (m.bulge * side > 0 && m.radius <= r) return true;  // curving toward the tool: inside the arc
  // Each inside corner needs r tan(theta / 2) of both moves at it for the offsets to intersect.
  std::vector<double> need(ms.size(), 0.0);
  for (std::size_t i = 0; i + 1 < ms.size(); ++i) {
    const double theta = std::atan2(geometry::cross(ms[i].t1, ms[i + 1].t0), geometry::dot(ms[i].t1, ms[i + 1].t0));
    if (theta * side <= 1e-9) continue;  // straight on, or turning away from the tool
    const double back = r * std::tan(std::min(std::abs(theta), std::numbers::pi - 1e-3) / 2);
    need[i] += back;
    need[i + 1] += back;
  }
  for (std::size_t i = 1; i < ms.size(); ++i)
    if (need[i] > ms[i].length + 1e-9) return true;
  return false;
}

}  // namespace

CompensationHazards compensation_hazards(const Toolpath& path, double tool_radius_mm, std::size_t max_labels) {
  CompensationHazards h;
  if (!(tool_radius_mm > 0)) return h;
  for (const auto& seg : path.segments) {
    if (seg.kerf == KerfSide::none) continue;
    ++h.compensated;
    if (!at_risk(seg, tool_radius_mm)) continue;
    ++h.segments;
    if (h.labels.size() < max_labels) h.labels.push_back(seg.label);
  }
  return h;
}

}  // namespace cutroute::nc
