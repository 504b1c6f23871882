// Vec2: a 2D point or vector in millimetres, with the few operations everything else uses.
#pragma once

#include <cmath>

namespace cutroute::geometry {

struct Vec2 {
  double x = 0.0;  // [mm]
  double y = 0.0;  // [mm]

  friend constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
  friend constexpr Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
  friend constexpr Vec2 operator*(double s, Vec2 a) { return {a.x * s, a.y * s}; }
  friend constexpr Vec2 operator/(Vec2 a, double s) { return {a.x / s, a.y / s}; }
  Vec2& operator+=(Vec2 b) { x += b.x; y += b.y; return *this; }
  Vec2& operator-=(Vec2 b) { x -= b.x; y -= b.y; return *this; }
  friend constexpr bool operator==(Vec2, Vec2) = default;
};

constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// Not std::hypot: it guards against overflow at coordinates (1e154 mm) no drawing reaches, and it was
// a ninth of planning the entries of 72 000 contours.
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }
constexpr double norm2(Vec2 a) { return dot(a, a); }
inline double distance(Vec2 a, Vec2 b) { return norm(b - a); }
constexpr Vec2 perp(Vec2 a) { return {-a.y, a.x}; }  // rotated +90° (counter-clockwise)
inline Vec2 normalized(Vec2 a) { const double n = norm(a); return n > 0 ? a / n : Vec2{}; }
inline bool is_finite(Vec2 a) { return std::isfinite(a.x) && std::isfinite(a.y); }

}  // namespace cutroute::geometry
