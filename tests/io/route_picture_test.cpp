// route_to_svg(): the pierce numbers of close pierces are stacked, never printed over each other.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <cutroute/core/random.hpp>
#include <cutroute/io/route_picture.hpp>

namespace cutroute::io {
namespace {

struct Label {
  double x, y, size;
};

// The value of attribute `name` in the element text `el` (empty when absent).
std::string attribute(const std::string& el, const std::string& name) {
  const auto at = el.find(" " + name + "=\"");
  if (at == std::string::npos) return {};
  const auto begin = at + name.size() + 3;
  return el.substr(begin, el.find('"', begin) - begin);
}

// The order numbers written (k -> position in picture units), with the "start" label left out.
std::map<int, Label> order_labels(const std::string& svg) {
  std::map<int, Label> out;
  for (auto at = svg.find("<text "); at != std::string::npos; at = svg.find("<text ", at + 1)) {
    const auto open_end = svg.find('>', at), close = svg.find("</text>", at);
    if (open_end == std::string::npos || close == std::string::npos) break;
    const std::string el = svg.substr(at, open_end - at), body = svg.substr(open_end + 1, close - open_end - 1);
    if (body.rfind("start", 0) == 0) continue;
    const int k = std::stoi(body);
    EXPECT_FALSE(out.count(k)) << "number " << k << " written twice";
    out[k] = {std::stod(attribute(el, "x")), std::stod(attribute(el, "y")), std::stod(attribute(el, "font-size"))};
  }
  return out;
}

// 400 pierces in a 20 x 20 mm block (jittered, so that labels straddle the picture's label columns)
// and a few far away: on a 900 mm picture the numbers are 10 mm tall, so most of the block's stack.
// The positions must be those of the rule the picture states, checked here by brute force: each
// number starts up and right of its pierce and moves up above every earlier number it would
// overlap (their spans across meet, each 0.7 sizes per digit plus 0.1 from its x, and they are
// closer than 0.9 sizes up or down), scanning them all until none does; a number pushed above the
// picture's top edge is left out. Numbers of 1 to 3 digits.
TEST(RoutePicture, PierceNumbersOfClosePiercesStackWithoutOverprinting) {
  nc::Toolpath path;
  path.start = path.end = {0, 0};
  Rng rng(5);
  std::vector<geometry::Vec2> pierces;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) pierces.push_back({300 + j + 0.9 * rng.uniform01(), 300 + i + 0.9 * rng.uniform01()});
  for (double x : {800.0, 850.0, 900.0}) pierces.push_back({x, 900});
  for (std::size_t k = 0; k < pierces.size(); ++k) {
    nc::CutSegment s;
    s.pierce = pierces[k];
    s.label = "hole " + std::to_string(k + 1);
    path.segments.push_back(s);
  }
  const std::string svg = route_to_svg(model::Nest{}, path, RoutePictureOptions{});
  const auto labels = order_labels(svg);
  ASSERT_FALSE(labels.empty());
  EXPECT_EQ(labels.begin()->first, 1);
  EXPECT_EQ(labels.rbegin()->first, static_cast<int>(pierces.size()));  // the far ones have room

  // The picture's frame: world box (0, 0)-(900, 900), margin 2 % of it + 1 mm, y pointing down.
  const double size = labels.begin()->second.size;  // [mm] 900 / 90
  ASSERT_NEAR(size, 10.0, 1e-9);
  const double mark = 900.0 / 400.0, margin = 900.0 * 0.02 + 1.0, top = 900.0 + margin;
  auto span = [size](int number) { return size * (0.7 * static_cast<double>(std::to_string(number).size()) + 0.1); };
  std::vector<std::pair<geometry::Vec2, double>> placed;  // position, span across
  int stacked = 0, left_out = 0;
  for (std::size_t k = 0; k < pierces.size(); ++k) {
    const int number = static_cast<int>(k + 1);
    geometry::Vec2 at = pierces[k] + geometry::Vec2{1.5 * mark, 1.5 * mark};
    for (bool moved = true; moved && at.y <= top;) {
      moved = false;
      for (const auto& [q, w] : placed)
        if (at.y <= top && q.x < at.x + span(number) && at.x < q.x + w && std::abs(q.y - at.y) < size * 0.9)
          at.y = q.y + size, moved = true;
    }
    if (at.y > top) {
      ++left_out;
      EXPECT_FALSE(labels.count(number)) << number;
      continue;
    }
    if (at.y > pierces[k].y + 1.5 * mark) ++stacked;
    placed.push_back({at, span(number)});
    ASSERT_TRUE(labels.count(number)) << number;
    const Label& got = labels.at(number);
    EXPECT_NEAR(got.x, at.x + margin, 1.5e-3) << number;
    EXPECT_NEAR(got.y, 900.0 - at.y + margin, 1.5e-3) << number;
  }
  EXPECT_EQ(labels.size(), pierces.size() - static_cast<std::size_t>(left_out));
  EXPECT_GT(stacked, 50);     // the case is the stacking one,
  EXPECT_GT(left_out, 200);   // up to the top and past it
  // And as written: no two numbers overlap (1 µm rounding allowed), their digits 0.7 sizes wide.
  for (auto a = labels.begin(); a != labels.end(); ++a)
    for (auto b = std::next(a); b != labels.end(); ++b) {
      const double wa = 0.7 * size * static_cast<double>(std::to_string(a->first).size());
      const double wb = 0.7 * size * static_cast<double>(std::to_string(b->first).size());
      const bool apart = a->second.x + wa <= b->second.x + 2e-3 || b->second.x + wb <= a->second.x + 2e-3 ||
                         std::abs(a->second.y - b->second.y) >= 0.9 * size - 2e-3;
      EXPECT_TRUE(apart) << a->first << " and " << b->first;
    }
}

// A nest drawn far from the machine's origin: the picture frames the nest, not the origin, so its
// pierce numbers have room (framing both, 9 of 139 numbers were written); the start is marked where
// its rapid comes into the picture, with its coordinates. Near the nest the start stays in frame.
TEST(RoutePicture, NestFarFromTheStartIsFramedAlone) {
  nc::Toolpath path;
  path.start = path.end = {0, 0};
  for (int k = 0; k < 139; ++k) {
    nc::CutSegment s;
    s.pierce = {10000.0 + 40 * (k % 12), 20000.0 + 40 * (k / 12)};
    path.segments.push_back(s);
  }
  const std::string svg = route_to_svg(model::Nest{}, path, RoutePictureOptions{});
  const auto labels = order_labels(svg);
  EXPECT_EQ(labels.size(), 139u);
  EXPECT_NE(svg.find(">start (0, 0)</text>"), std::string::npos);
  // Picture units: every number within the frame of the pierces (440 x 440 mm plus margins).
  for (const auto& [k, l] : labels) {
    EXPECT_GE(l.x, 0.0);
    EXPECT_LT(l.x, 520.0) << k;
  }
  // The same pierces 300 mm from the start: the start is drawn where it is, named "start".
  for (auto& s : path.segments) s.pierce = s.pierce - geometry::Vec2{9700, 19700};
  const std::string near = route_to_svg(model::Nest{}, path, RoutePictureOptions{});
  EXPECT_NE(near.find(">start</text>"), std::string::npos);
}

}  // namespace
}  // namespace cutroute::io
