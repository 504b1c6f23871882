#include <cutroute/machining/contours.hpp>

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace cutroute::machining {

namespace {

// A crossing lives on a grid edge: horizontal edge (i,j)-(i+1,j) or vertical edge (i,j)-(i,j+1).
std::int64_t edge_key(int vertical, int i, int j, int nx) {
  return (static_cast<std::int64_t>(j) * nx + i) * 2 + vertical;
}

}  // namespace

std::vector<IsoLine> iso_lines(const std::vector<double>& z, int nx, int ny, double level) {
  struct Seg {
    std::int64_t a, b;
  };
  std::vector<Seg> segs;
  std::unordered_map<std::int64_t, std::array<double, 2>> point;
  const auto at = [&](int i, int j) { return z[static_cast<std::size_t>(j) * nx + i]; };
  const auto crossing = [&](int vertical, int i, int j) {
    const std::int64_t key = edge_key(vertical, i, j, nx);
    if (!point.count(key)) {
      const double v0 = at(i, j);
      const double v1 = vertical ? at(i, j + 1) : at(i + 1, j);
      const double t = (level - v0) / (v1 - v0);
      point[key] =
          vertical ? std::array<double, 2>{double(i), j + t} : std::array<double, 2>{i + t, double(j)};
    }
    return key;
  };
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const double c[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      if (!(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && std::isfinite(c[3])))
        continue;
      int idx = 0;
      for (int q = 0; q < 4; ++q) idx |= (c[q] > level ? 1 : 0) << q;
      if (idx == 0 || idx == 15) continue;
      // Edges: e0 bottom (c0-c1), e1 right (c1-c2), e2 top (c3-c2), e3 left (c0-c3).
      const auto e = [&](int k) {
        switch (k) {
          case 0:
            return crossing(0, i, j);
          case 1:
            return crossing(1, i + 1, j);
          case 2:
            return crossing(0, i, j + 1);
          default:
            return crossing(1, i, j);
        }
      };
      const bool centre_above = (c[0] + c[1] + c[2] + c[3]) / 4.0 > level;
      if (idx == 5 || idx == 10) {
        const bool cut_c1_c3 = (idx == 5) == centre_above;
        if (cut_c1_c3) {
          segs.push_back({e(0), e(1)});
          segs.push_back({e(2), e(3)});
        } else {
          segs.push_back({e(0), e(3)});
          segs.push_back({e(1), e(2)});
        }
        continue;
      }
      // Exactly two edges change sign.
      const int b[4] = {idx & 1, (idx >> 1) & 1, (idx >> 2) & 1, (idx >> 3) & 1};
      int found[2];
      int nf = 0;
      if (b[0] != b[1]) found[nf++] = 0;
      if (b[1] != b[2]) found[nf++] = 1;
      if (b[3] != b[2]) found[nf++] = 2;
      if (b[0] != b[3]) found[nf++] = 3;
      if (nf == 2) segs.push_back({e(found[0]), e(found[1])});
    }
  }
  // Join segments through shared edge crossings (each crossing touches at most two segments).
  std::unordered_map<std::int64_t, std::vector<std::size_t>> touch;
  for (std::size_t s = 0; s < segs.size(); ++s) {
    touch[segs[s].a].push_back(s);
    touch[segs[s].b].push_back(s);
  }
  std::vector<char> used(segs.size(), 0);
  std::vector<IsoLine> out;
  const auto other_seg = [&](std::int64_t key, std::size_t s) -> std::ptrdiff_t {
    for (std::size_t t : touch[key]) {
      if (t != s && !used[t]) return static_cast<std::ptrdiff_t>(t);
    }
    return -1;
  };
  // Start at open ends first so open lines come out whole, then pick up closed loops.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t s0 = 0; s0 < segs.size(); ++s0) {
      if (used[s0]) continue;
      std::int64_t start = segs[s0].a;
      if (pass == 0) {
        if (touch[segs[s0].a].size() == 1)
          start = segs[s0].a;
        else if (touch[segs[s0].b].size() == 1)
          start = segs[s0].b;
        else
          continue;
      }
      IsoLine line;
      line.pts.push_back(point[start]);
      std::size_t s = s0;
      std::int64_t cur = start;
      while (true) {
        used[s] = 1;
        cur = segs[s].a == cur ? segs[s].b : segs[s].a;
        line.pts.push_back(point[cur]);
        const std::ptrdiff_t nxt = other_seg(cur, s);
        if (nxt < 0) break;
        s = static_cast<std::size_t>(nxt);
      }
      line.closed = pass == 1 && cur == start;
      out.push_back(std::move(line));
    }
  }
  return out;
}

}  // namespace cutroute::machining
