// route_to_svg(): the pierce numbers stand beside their pierce, never printed over each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
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

// 400 pierces in a 20 x 20 mm block (jittered) and a few far away, on a 900 mm picture.
// The positions must be those of the rule the picture states, checked here by brute force: numbers
// and marks sized by the nest (900 / 90 and 900 / 400 mm) but at most 0.8 and 0.25 of the median
// distance between a pierce and its nearest other; each number at the first place, of eight round
// its mark at three distances (beside it, then one and two number heights further), that stays in
// the picture and overlaps no mark and no earlier number; none free: left out.
TEST(RoutePicture, PierceNumbersStandBesideTheirPierceWithoutOverprinting) {
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

  std::vector<double> nearest;
  for (std::size_t i = 0; i < pierces.size(); ++i) {
    double d = 1e300;
    for (std::size_t j = 0; j < pierces.size(); ++j)
      if (j != i) d = std::min(d, std::hypot(pierces[i].x - pierces[j].x, pierces[i].y - pierces[j].y));
    nearest.push_back(d);
  }
  std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2), nearest.end());
  const double spacing = nearest[nearest.size() / 2];
  const double size = std::max(std::min(10.0, 0.8 * spacing), 0.5), mark = std::max(std::min(2.25, 0.25 * spacing), 0.2);
  ASSERT_NEAR(labels.begin()->second.size, size, 1e-3);
  ASSERT_LT(size, 1.0);  // the block sets the size, not the picture
  // The picture's frame: world box (0, 0)-(900, 900), margin 2 % of it + 1 mm, y pointing down.
  const double margin = 900.0 * 0.02 + 1.0, rise = 0.75 * size, gap = 1.5 * mark;
  struct B {
    double x0, y0, x1, y1;
  };
  std::vector<B> taken;
  for (const auto& p : pierces) taken.push_back({p.x - mark, p.y - mark, p.x + mark, p.y + mark});
  std::vector<geometry::Vec2> offsets;
  for (int ring = 0; ring < 3; ++ring) {
    const double d = gap + ring * size;
    for (const geometry::Vec2 o : {geometry::Vec2{d, d}, {d, -d - rise}, {-d, d}, {-d, -d - rise}, {d, -rise / 2}, {-d, -rise / 2},
                                   {0, d}, {0, -d - rise}})
      offsets.push_back(o);
  }
  int left_out = 0, moved_out = 0;
  for (std::size_t k = 0; k < pierces.size(); ++k) {
    const int number = static_cast<int>(k + 1);
    const double width = size * (0.7 * static_cast<double>(std::to_string(number).size()) + 0.1);
    std::optional<B> at;
    for (std::size_t o = 0; o < offsets.size() && !at; ++o) {
      const auto& off = offsets[o];
      const double x = off.x < 0 ? pierces[k].x + off.x - width : off.x == 0 ? pierces[k].x - width / 2 : pierces[k].x + off.x;
      const B box{x, pierces[k].y + off.y, x + width, pierces[k].y + off.y + rise};
      if (box.x0 < -margin || box.x1 > 900 + margin || box.y0 < -margin || box.y1 > 900 + margin) continue;
      bool free = true;
      for (const auto& t : taken) free = free && !(box.x0 < t.x1 && t.x0 < box.x1 && box.y0 < t.y1 && t.y0 < box.y1);
      if (!free) continue;
      at = box;
      moved_out += o >= 8;
    }
    if (!at) {
      ++left_out;
      EXPECT_FALSE(labels.count(number)) << number;
      continue;
    }
    taken.push_back(*at);
    ASSERT_TRUE(labels.count(number)) << number;
    EXPECT_NEAR(labels.at(number).x, at->x0 + margin, 1.5e-3) << number;
    EXPECT_NEAR(labels.at(number).y, 900.0 - at->y0 + margin, 1.5e-3) << number;
    // Never far from its own pierce: within the third ring.
    EXPECT_LT(std::hypot((at->x0 + at->x1) / 2 - pierces[k].x, (at->y0 + at->y1) / 2 - pierces[k].y), gap + 3 * size + width) << number;
  }
  EXPECT_EQ(labels.size(), pierces.size() - static_cast<std::size_t>(left_out));
  EXPECT_GT(moved_out, 20);  // the case is the crowded one,
  EXPECT_GT(left_out, 20);   // up to numbers left out
  for (int far : {401, 402, 403}) EXPECT_TRUE(labels.count(far)) << far;
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

// What the picture must not hide: a tab (the head crossing a millimetre with the beam off, under
// a pierce mark of several), drawn as its own thick stretch with a small mark; drawn paths the
// program does not cut, dashed, with what they are; the legend; the page's step counter counts
// the segments (the park rapid is not one).
TEST(RoutePicture, TabsAndUncutContoursShow) {
  nc::Toolpath path;
  path.start = path.end = {0, 0};
  nc::CutSegment a, b;
  a.pierce = {10, 10};
  a.pieces.push_back({geometry::Contour{{{{10, 10}, 0}, {{200, 10}, 0}}, false}, nc::PieceRole::contour, 0});
  a.label = "part 1 outer";
  b.pierce = {201, 10};  // the cut resumes 1 mm on, past the tab
  b.pieces.push_back({geometry::Contour{{{{201, 10}, 0}, {{400, 10}, 0}}, false}, nc::PieceRole::contour, 0});
  b.after_tab = true;
  b.label = "part 1 outer after tab 1";
  path.segments = {a, b};
  RoutePictureOptions o;
  o.not_cut.emplace_back(geometry::Contour{{{{0, 50}, 0}, {{100, 60}, 0}}, false}, "not cut: open contour (line 7, layer 0)");
  const std::string svg = route_to_svg(model::Nest{}, path, o);
  std::size_t tabs = 0;
  for (auto at = svg.find("class=\"tab\""); at != std::string::npos; at = svg.find("class=\"tab\"", at + 1)) ++tabs;
  EXPECT_EQ(tabs, 1u);
  EXPECT_NE(svg.find("<title>not cut: open contour (line 7, layer 0)</title>"), std::string::npos);
  EXPECT_NE(svg.find("class=\"not-cut\""), std::string::npos);
  EXPECT_NE(svg.find("<desc>cut: red"), std::string::npos);
  // The tab's mark is the smaller one.
  std::vector<double> radii;
  for (auto at = svg.find("<circle "); at != std::string::npos; at = svg.find("<circle ", at + 1)) {
    const std::string el = svg.substr(at, svg.find('>', at) - at);
    if (el.find("fill=\"#f39c12\"") != std::string::npos) radii.push_back(std::stod(attribute(el, "r")));
  }
  ASSERT_EQ(radii.size(), 2u);
  EXPECT_LT(radii[1], 0.5 * radii[0]);
  const std::string html = route_to_html(model::Nest{}, path, {}, o);
  EXPECT_NE(html.find("const last=segs.length-1;"), std::string::npos);
  EXPECT_NE(html.find("id=\"legend\""), std::string::npos);
}

}  // namespace
}  // namespace cutroute::io

namespace cutroute::io {
namespace {

// The text elements of a picture: body -> baseline y (picture units, down) and font size.
std::map<std::string, Label> texts(const std::string& svg) {
  std::map<std::string, Label> out;
  for (auto at = svg.find("<text "); at != std::string::npos; at = svg.find("<text ", at + 1)) {
    const auto open_end = svg.find('>', at), close = svg.find("</text>", at);
    const std::string el = svg.substr(at, open_end - at);
    out[svg.substr(open_end + 1, close - open_end - 1)] = {std::stod(attribute(el, "x")), std::stod(attribute(el, "y")),
                                                           std::stod(attribute(el, "font-size"))};
  }
  return out;
}

// A standalone picture says what it shows: one line of the report's figures, below the drawing
// and the start's label (the start at the nest's lower left corner puts its label lowest), inside
// the page. The HTML page has its table instead.
TEST(RoutePicture, StandalonePictureHasACaption) {
  const nlohmann::json report = {{"material", "S235"},     {"thickness_mm", 3.0},         {"chosen", "chain"},
                                 {"pierces", 18},          {"cut_length_mm", 17564.44},   {"rapid_length_mm", 4336.36},
                                 {"t_cut_s", 245.614},     {"solver", {{"status", "optimal"}}}};
  const std::string caption = report_caption(report);
  EXPECT_EQ(caption, "S235 3 mm · chain cutting · 18 pierces · cut 17564.4 mm · rapid 4336.4 mm · T_cut 245.61 s (eq. 10) · route optimal");
  nc::Toolpath path;
  path.start = path.end = {0, 0};
  for (int k = 0; k < 20; ++k) {
    nc::CutSegment s;
    s.pierce = {100.0 * (k % 5), 50.0 * (k / 5)};
    path.segments.push_back(s);
  }
  RoutePictureOptions o;
  o.caption = caption;
  const std::string svg = route_to_svg(model::Nest{}, path, o);
  const auto t = texts(svg);
  ASSERT_TRUE(t.contains(caption));
  ASSERT_TRUE(t.contains("start"));
  const Label c = t.at(caption);
  // The caption's capitals (a font size above the baseline) clear every other text's descenders
  // (a quarter of its size below its baseline).
  for (const auto& [text, l] : t) {
    if (text == caption) continue;
    EXPECT_LT(l.y + 0.25 * l.size, c.y - c.size) << text;
  }
  const std::string view = svg.substr(svg.find("viewBox=\"") + 9);
  double x0 = 0, y0 = 0, w = 0, h = 0;
  ASSERT_EQ(std::sscanf(view.c_str(), "%lf %lf %lf %lf", &x0, &y0, &w, &h), 4);
  EXPECT_LT(c.y + 0.25 * c.size, h);
  EXPECT_EQ(route_to_svg(model::Nest{}, path, RoutePictureOptions{}).find(caption), std::string::npos);
  EXPECT_EQ(route_to_html(model::Nest{}, path, {}, o).find(caption), std::string::npos);
}

}  // namespace
}  // namespace cutroute::io
