#include <cutroute/model/demo_nest.hpp>

#include <cmath>
#include <numbers>

namespace cutroute::model {
namespace {

using geometry::Contour;
using geometry::Vec2;
using geometry::Vertex;

const double kQuarterBulge = std::tan(std::numbers::pi / 8);  // 90° arc

Contour circle(Vec2 c, double r, bool ccw) {
  const double b = ccw ? 1.0 : -1.0;
  return Contour{{Vertex{{c.x - r, c.y}, b}, Vertex{{c.x + r, c.y}, b}}, true};
}

// Counter-clockwise rectangle with corner radius r at (x, y) lower-left.
Contour rounded_rect(double x, double y, double w, double h, double r) {
  const double q = kQuarterBulge;
  return Contour{{Vertex{{x + r, y}, 0},       Vertex{{x + w - r, y}, q}, Vertex{{x + w, y + r}, 0},
                  Vertex{{x + w, y + h - r}, q}, Vertex{{x + w - r, y + h}, 0}, Vertex{{x + r, y + h}, q},
                  Vertex{{x, y + h - r}, 0},     Vertex{{x, y + r}, q}},
                 true};
}

// Counter-clockwise L-bracket 250 × 300 mm, arms 90 mm wide, inner corner filleted with R20.
Contour l_bracket(double x, double y) {
  const double w = 250, h = 300, arm = 90, r = 20;
  return Contour{{Vertex{{x, y}, 0}, Vertex{{x + w, y}, 0}, Vertex{{x + w, y + arm}, 0},
                  Vertex{{x + arm + r, y + arm}, -kQuarterBulge},  // concave corner: clockwise arc
                  Vertex{{x + arm, y + arm + r}, 0}, Vertex{{x + arm, y + h}, 0}, Vertex{{x, y + h}, 0}},
                 true};
}

SourceContour cut(Contour c) { return SourceContour{std::move(c), "CUT", {}, {}, {}}; }

}  // namespace

std::vector<SourceContour> make_demo_sheet() {
  std::vector<SourceContour> out;
  out.push_back(SourceContour{Contour{{Vertex{{0, 0}, 0}, Vertex{{kDemoSheetWidthMm, 0}, 0},
                                       Vertex{{kDemoSheetWidthMm, kDemoSheetHeightMm}, 0},
                                       Vertex{{0, kDemoSheetHeightMm}, 0}},
                                      true},
                              "SHEET", {}, {}, {}});
  for (double x : {30.0, 460.0, 890.0, 1320.0}) {
    out.push_back(cut(rounded_rect(x, 30, 400, 250, 15)));
    out.push_back(cut(circle({x + 200, 155}, 40, false)));
  }
  for (double cx : {200.0, 540.0, 880.0}) {
    out.push_back(cut(circle({cx, 480}, 150, true)));
    out.push_back(cut(circle({cx, 480}, 50, false)));
  }
  const double gap = kDemoChainGapMm, y = 670;
  for (double x : {30.0, 580.0, 1130.0}) {  // three pairs, 5 mm apart: chainable
    out.push_back(cut(l_bracket(x, y)));
    out.push_back(cut(l_bracket(x + 250 + gap, y)));
  }
  out.push_back(cut(l_bracket(1680, y)));
  return out;
}

}  // namespace cutroute::model
