// The test nest where multi-segment cutting pays: a long frame between the start and parts at its far end.
#pragma once

#include <array>
#include <string>

#include "support/dxf_builder.hpp"

namespace cutroute::test {

struct Rect {
  double x, y, w, h;  // [mm]
};

// A 1500 x 80 mm frame from x = 50 to 1550 (contour 1), a 60 mm hole near its left end
// (contour 2) holding a 30 mm part (contour 3), and three 40 mm parts past its right end
// (contours 4-6). The machine starts and parks at (0, 0), left of the frame: cut whole, the frame
// leaves the head where it entered, and the route crosses its 1500 mm length twice by rapid (to
// the far parts and back); in two pieces (bottom and right edge out, top and left edge back) the
// head travels that length cutting both ways.
inline constexpr std::array<Rect, 6> kFrameNest{{{50, 100, 1500, 80},
                                                 {70, 110, 60, 60},
                                                 {85, 125, 30, 30},
                                                 {1600, 100, 40, 40},
                                                 {1660, 100, 40, 40},
                                                 {1600, 160, 40, 40}}};

inline std::string frame_nest_dxf() {
  DxfBuilder b;
  b.insunits(4);
  for (const auto& r : kFrameNest)
    b.lwpolyline({{{r.x, r.y}, 0}, {{r.x + r.w, r.y}, 0}, {{r.x + r.w, r.y + r.h}, 0}, {{r.x, r.y + r.h}, 0}}, true);
  return b.str();
}

}  // namespace cutroute::test
