// Which faces of a traced group are parts (chain_faces.hpp, step 4), from how often each edge is drawn.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cutroute::geometry::detail {

// One drawing of an edge: the stretch and the piece (the parent or one of its exact copies).
struct Drawing {
  std::uint32_t sub;
  std::uint32_t piece;  // index into `pieces`
};

// An edge of the planar graph: stretches joining the same two points along the same curve.
struct Edge {
  std::vector<Drawing> drawings;  // ascending piece index
  std::uint32_t rep = 0;          // the stretch whose geometry and direction the edge takes
};

// Faces are numbered as the group's face tracing numbers them: face_of[2e] and face_of[2e + 1]
// are the faces on the two sides of edge e (along and against its stretch `rep`), faces[f] the
// half-edges around face f, `outside` the face that turns clockwise. A result holds per face 1
// (a part) or 0 (scrap).

// Which faces are parts: an edge drawn twice has a part on both sides, an edge drawn once on
// exactly one; the outside is scrap. The faces form one connected dual graph, so the outside and
// the twice-drawn edges fix every face. Empty when no choice fits the drawings.
std::vector<std::int8_t> parts_of(const std::vector<Edge>& edges, const std::vector<std::int32_t>& face_of,
                                  std::size_t faces, std::size_t outside);

// A part's outline drawn twice by mistake: its face's edges each have one drawing too many
// (an edge it shares with a neighbour is drawn three times). Tried when no choice of parts fits
// the drawings: each face whose edges are all drawn at least twice, first those with an edge
// drawn three times, has its edges' latest drawings taken out (they stay dropped as duplicates)
// until the parts fit; then all such faces with an edge drawn three times at once. Empty when
// nothing fits.
std::vector<std::int8_t> parts_without_repeats(std::vector<Edge>& edges, const std::vector<std::int32_t>& face_of,
                                               const std::vector<std::vector<std::uint32_t>>& faces, std::size_t outside);

}  // namespace cutroute::geometry::detail
