// parts_of(), parts_without_repeats(): see chain_face_parts.hpp.
#include "chain_face_parts.hpp"

#include <algorithm>

namespace cutroute::geometry::detail {

std::vector<std::int8_t> parts_of(const std::vector<Edge>& edges, const std::vector<std::int32_t>& face_of,
                                  std::size_t faces, std::size_t outside) {
  std::vector<std::int8_t> part(faces, -1);
  part[outside] = 0;
  std::vector<std::vector<std::size_t>> across(faces);
  std::vector<std::size_t> queue{outside};
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto a = static_cast<std::size_t>(face_of[2 * i]), b = static_cast<std::size_t>(face_of[2 * i + 1]);
    if (a == b || edges[i].drawings.size() > 2) return {};
    if (edges[i].drawings.size() == 2) {
      for (std::size_t f : {a, b}) {
        if (part[f] == 0) return {};
        if (part[f] == -1) queue.push_back(f);
        part[f] = 1;
      }
    } else {
      across[a].push_back(b);
      across[b].push_back(a);
    }
  }
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const std::size_t f = queue[q];
    for (std::size_t o : across[f]) {
      if (part[o] == -1) {
        part[o] = static_cast<std::int8_t>(1 - part[f]);
        queue.push_back(o);
      } else if (part[o] == part[f]) {
        return {};
      }
    }
  }
  for (std::int8_t p : part) {
    if (p == -1) return {};
  }
  return part;
}

std::vector<std::int8_t> parts_without_repeats(std::vector<Edge>& edges, const std::vector<std::int32_t>& face_of,
                                               const std::vector<std::vector<std::uint32_t>>& faces, std::size_t outside) {
  constexpr std::size_t kMaxTries = 16;
  auto all_doubled = [&](std::size_t f) {
    for (std::uint32_t h : faces[f]) {
      if (edges[h / 2].drawings.size() < 2) return false;
    }
    return true;
  };
  auto tripled = [&](std::size_t f) {
    for (std::uint32_t h : faces[f]) {
      if (edges[h / 2].drawings.size() > 2) return true;
    }
    return false;
  };
  std::vector<std::size_t> candidates;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (all_doubled(f) && tripled(f) == (pass == 0)) candidates.push_back(f);
    }
  }
  auto without = [&](const std::vector<std::size_t>& drop) {
    std::vector<Edge> fewer = edges;
    for (std::size_t f : drop) {
      for (std::uint32_t h : faces[f]) {
        auto& d = fewer[h / 2].drawings;
        if (d.size() < 2) return std::vector<Edge>{};
        d.erase(std::max_element(d.begin(), d.end(), [](const Drawing& x, const Drawing& y) { return x.piece < y.piece; }));
      }
    }
    return fewer;
  };
  auto attempt = [&](const std::vector<std::size_t>& drop) {
    std::vector<Edge> fewer = without(drop);
    if (fewer.empty()) return std::vector<std::int8_t>{};
    std::vector<std::int8_t> part = parts_of(fewer, face_of, faces.size(), outside);
    if (!part.empty()) edges = std::move(fewer);
    return part;
  };
  for (std::size_t i = 0; i < candidates.size() && i < kMaxTries; ++i) {
    if (auto part = attempt({candidates[i]}); !part.empty()) return part;
  }
  std::vector<std::size_t> with_triples;
  for (std::size_t f : candidates) {
    if (tripled(f)) with_triples.push_back(f);
  }
  if (with_triples.size() > 1) return attempt(with_triples);
  return {};
}

}  // namespace cutroute::geometry::detail
