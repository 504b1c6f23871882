#include "io/curve_fit.hpp"

#include <algorithm>
#include <array>
#include <initializer_list>
#include <cmath>
#include <numbers>
#include <optional>

namespace cutroute::io::detail {

namespace {

constexpr double kPi = std::numbers::pi;

// Parameter intervals are not split below this fraction of the whole curve's range: 2^-40 of the
// range is far below any drawing resolution, and it bounds the recursion depth.
constexpr int kMaxSplitDepth = 40;
// Curve samples per fitted piece for the deviation check (both directions).
constexpr int kSamples = 16;
// A biarc half whose tangent-to-chord angle exceeds this is rejected and the piece split: such
// arcs are nearly full circles and their fit is ill-conditioned [rad].
constexpr double kMaxHalfSweep = 0.9 * kPi;

double signed_angle(Vec2 from, Vec2 to) { return std::atan2(geometry::cross(from, to), geometry::dot(from, to)); }

double len(Vec2 v) { return std::sqrt(v.x * v.x + v.y * v.y); }

double distance2_to_line(Vec2 a, Vec2 b, Vec2 p) {
  const Vec2 ab = b - a;
  const double l2 = geometry::norm2(ab);
  const Vec2 ap = p - a;
  if (l2 <= 0) return geometry::norm2(ap);
  const double t = std::clamp(geometry::dot(ap, ab) / l2, 0.0, 1.0);
  return geometry::norm2(ap - ab * t);
}

double distance_to_line(Vec2 a, Vec2 b, Vec2 p) { return std::sqrt(distance2_to_line(a, b, p)); }

// Distance from p to the polyline pts, searching outward from segment `guess` (at most `window`
// segments each way) and stopping once a segment is closer than `good`. A nearest segment
// outside the window only overestimates the distance, which makes the fit more careful.
double distance_to_polyline(const std::vector<Vec2>& pts, Vec2 p, std::size_t guess, double good,
                            std::size_t window) {
  const std::size_t nseg = pts.size() - 1;
  guess = std::min(guess, nseg - 1);
  const double good2 = good * good;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < std::min(nseg, 2 * window + 1); ++k) {
    // guess, guess+1, guess-1, guess+2, ...
    const std::size_t off = (k + 1) / 2;
    std::size_t j;
    if (k % 2 == 1) {
      if (guess + off >= nseg) continue;
      j = guess + off;
    } else {
      if (off > guess) continue;
      j = guess - off;
    }
    best = std::min(best, distance2_to_line(pts[j], pts[j + 1], p));
    if (best <= good2) break;
  }
  return std::sqrt(best);
}

// An arc prepared for repeated distance queries, without trigonometry per query: the nearest
// circle point lies on the arc iff it is on the arc midpoint's side of the chord.
struct ArcGeom {
  bool line = false;
  Vec2 a, b, c, r0, mid;
  double r = 0, sweep = 0, mid_side = 0;
  explicit ArcGeom(const ArcSeg& s) : a(s.a), b(s.b) {
    if (std::abs(s.bulge) < 1e-12) {
      line = true;
      return;
    }
    c = arc_center(s);
    r0 = s.a - c;
    r = len(r0);
    sweep = 4 * std::atan(s.bulge);
    // The arc midpoint: the chord midpoint moved by the sagitta, to the right of a->b for
    // a counter-clockwise arc (positive bulge).
    const Vec2 chord = b - a;
    mid = (a + b) * 0.5 - geometry::perp(chord) * (s.bulge / 2);
    mid_side = geometry::cross(chord, mid - a);
  }
  double distance(Vec2 p) const {
    if (line) return distance_to_line(a, b, p);
    const Vec2 rp = p - c;
    const double d = len(rp);
    if (d <= 0) return r;
    const Vec2 q = c + rp * (r / d);
    if (geometry::cross(b - a, q - a) * mid_side >= 0) return std::abs(d - r);
    return std::min(len(p - a), len(p - b));
  }
  // n + 1 points evenly spaced along the arc, by repeated rotation.
  template <class F>
  void for_points(int n, F&& f) const {
    if (line) {
      for (int i = 1; i < n; ++i) f(a + (b - a) * (double(i) / n));
      return;
    }
    const double step = sweep / n;
    const double cs = std::cos(step), sn = std::sin(step);
    Vec2 v = r0;
    for (int i = 1; i < n; ++i) {
      v = {v.x * cs - v.y * sn, v.x * sn + v.y * cs};
      f(c + v);
    }
  }
};

// Two arcs P0 -> joint -> P1 with tangent t0 at P0, t1 at P1 and a common tangent at the joint
// (equal tangent-leg lengths d, the classic choice): returns false when no sensible biarc exists.
bool make_biarc(Vec2 p0, Vec2 t0, Vec2 p1, Vec2 t1, ArcSeg& first, ArcSeg& second) {
  const Vec2 v = p1 - p0;
  const double vv = geometry::norm2(v);
  if (vv <= 0) return false;
  const Vec2 t = t0 + t1;
  const double vt = geometry::dot(v, t);
  const double c = geometry::dot(t0, t1);
  const double disc = vt * vt + 2.0 * (1.0 - c) * vv;
  if (disc < 0) return false;
  const double denom = vt + std::sqrt(disc);
  if (!(denom > 1e-300)) return false;
  const double d = vv / denom;
  if (!(d > 0) || !std::isfinite(d)) return false;
  const Vec2 joint = (p0 + t0 * d + p1 - t1 * d) * 0.5;
  const double phi1 = signed_angle(t0, joint - p0);
  const double phi2 = signed_angle(p1 - joint, t1);
  if (std::abs(phi1) > kMaxHalfSweep || std::abs(phi2) > kMaxHalfSweep) return false;
  first = {p0, joint, std::tan(phi1 / 2)};
  second = {joint, p1, std::tan(phi2 / 2)};
  return true;
}

struct Piece {
  double a;
  double b;
  int depth;
};

}  // namespace

Vec2 arc_center(const ArcSeg& s) {
  const Vec2 mid = (s.a + s.b) * 0.5;
  const double b = s.bulge;
  return mid + geometry::perp(s.b - s.a) * ((1 - b * b) / (4 * b));
}

double arc_length(const ArcSeg& s) {
  const double chord = geometry::distance(s.a, s.b);
  const double b = std::abs(s.bulge);
  if (b < 1e-12) return chord;
  const double sweep = 4 * std::atan(b);
  const double r = chord * (1 + b * b) / (4 * b);
  return r * sweep;
}

Vec2 arc_point(const ArcSeg& s, double t) {
  if (std::abs(s.bulge) < 1e-12) return s.a + (s.b - s.a) * t;
  const Vec2 c = arc_center(s);
  const double ang = 4 * std::atan(s.bulge) * t;
  const Vec2 r = s.a - c;
  return c + Vec2{r.x * std::cos(ang) - r.y * std::sin(ang), r.x * std::sin(ang) + r.y * std::cos(ang)};
}

double distance_to_arc(const ArcSeg& s, Vec2 p) {
  if (std::abs(s.bulge) < 1e-12) return distance_to_line(s.a, s.b, p);
  const Vec2 c = arc_center(s);
  const double r = geometry::distance(c, s.a);
  const double sweep = 4 * std::atan(s.bulge);
  const double a0 = std::atan2(s.a.y - c.y, s.a.x - c.x);
  const double ap = std::atan2(p.y - c.y, p.x - c.x);
  double delta = sweep > 0 ? ap - a0 : a0 - ap;
  delta = std::fmod(delta + 4 * kPi, 2 * kPi);
  if (delta <= std::abs(sweep)) return std::abs(geometry::distance(c, p) - r);
  return std::min(geometry::distance(s.a, p), geometry::distance(s.b, p));
}

bool Affine::is_similarity() const {
  // Columns orthogonal and of equal length.
  const double c0 = m00 * m00 + m10 * m10;
  const double c1 = m01 * m01 + m11 * m11;
  const double scale = std::max(c0, c1);
  if (!(scale > 0)) return false;
  return std::abs(c0 - c1) <= 1e-12 * scale && std::abs(m00 * m01 + m10 * m11) <= 1e-12 * scale;
}

Affine Affine::then_after(const Affine& o) const {
  Affine r;
  r.m00 = m00 * o.m00 + m01 * o.m10;
  r.m01 = m00 * o.m01 + m01 * o.m11;
  r.m10 = m10 * o.m00 + m11 * o.m10;
  r.m11 = m10 * o.m01 + m11 * o.m11;
  r.t = apply(o.t);
  return r;
}

Affine Affine::translate(Vec2 v) {
  Affine r;
  r.t = v;
  return r;
}

Affine Affine::scale(double sx, double sy) {
  Affine r;
  r.m00 = sx;
  r.m11 = sy;
  return r;
}

Affine Affine::rotate(double radians) {
  Affine r;
  const double c = std::cos(radians);
  const double s = std::sin(radians);
  r.m00 = c;
  r.m01 = -s;
  r.m10 = s;
  r.m11 = c;
  return r;
}

double fit_biarcs(const ParamCurve& curve, double tol_mm, std::vector<Vertex>& out, std::size_t max_vertices) {
  double max_dev = 0.0;
  const double range = curve.t1 - curve.t0;
  if (!(range > 0)) return 0.0;
  // Depth-first, left to right, so vertices come out in curve order.
  std::vector<Piece> stack{{curve.t0, curve.t1, 0}};
  std::vector<Vec2> samples(kSamples + 1);
  bool overflow = false;
  auto sample = [&](const Piece& pc, int i) {
    const Vec2 q = curve.point(pc.a + (pc.b - pc.a) * i / kSamples);
    if (!geometry::is_finite(q)) overflow = true;
    return q;
  };
  while (!stack.empty()) {
    const Piece piece = stack.back();
    stack.pop_back();
    const bool can_split = piece.depth < kMaxSplitDepth && out.size() + stack.size() < max_vertices;
    auto split = [&] {
      const double m = 0.5 * (piece.a + piece.b);
      stack.push_back({m, piece.b, piece.depth + 1});
      stack.push_back({piece.a, m, piece.depth + 1});
    };
    const Vec2 p0 = curve.point(piece.a);
    const Vec2 p1 = curve.point(piece.b);
    // Overflowing input (weights, scales, ratios near 1e308) gives no curve to follow; splitting
    // would only multiply the work.
    if (!geometry::is_finite(p0) || !geometry::is_finite(p1)) return std::numeric_limits<double>::infinity();
    const Vec2 chord = p1 - p0;
    const double chord_len = len(chord);
    if (chord_len <= 1e-12) {
      // A closed or vanishing piece: split unless the whole piece is one point.
      double spread = 0;
      for (int i = 1; i < kSamples; ++i) spread = std::max(spread, len(sample(piece, i) - p0));
      if (overflow) return std::numeric_limits<double>::infinity();
      if (spread > tol_mm && can_split) {
        split();
        continue;
      }
      max_dev = std::max(max_dev, spread);
      continue;  // nothing to draw
    }
    // Candidate arcs for this piece.
    ArcSeg arcs[2];
    int narcs = 0;
    Vec2 t0 = geometry::normalized(curve.derivative(piece.a));
    Vec2 t1 = geometry::normalized(curve.derivative(piece.b));
    if (t0 == Vec2{}) t0 = geometry::normalized(sample(piece, 1) - p0);
    if (t1 == Vec2{}) t1 = geometry::normalized(p1 - sample(piece, kSamples - 1));
    const Vec2 u = chord / chord_len;
    if (std::abs(geometry::cross(t0, u)) < 1e-12 && std::abs(geometry::cross(t1, u)) < 1e-12 &&
        geometry::dot(t0, u) > 0 && geometry::dot(t1, u) > 0) {
      arcs[narcs++] = {p0, p1, 0.0};
    } else if (make_biarc(p0, t0, p1, t1, arcs[0], arcs[1])) {
      narcs = 2;
    }
    if (narcs == 0) {
      if (can_split) {
        split();
        continue;
      }
      arcs[narcs++] = {p0, p1, 0.0};
    }
    ArcGeom g0(arcs[0]);
    std::optional<ArcGeom> g1;
    if (narcs > 1) g1.emplace(arcs[1]);
    auto dist = [&](Vec2 q) { return g1 ? std::min(g0.distance(q), g1->distance(q)) : g0.distance(q); };
    // Most pieces that fail, fail grossly: test the quarter points first.
    double dev = 0;
    bool early_fail = false;
    for (int i : {kSamples / 2, kSamples / 4, 3 * kSamples / 4}) {
      samples[static_cast<std::size_t>(i)] = sample(piece, i);
      dev = std::max(dev, dist(samples[static_cast<std::size_t>(i)]));
      if (dev > tol_mm && can_split) {
        early_fail = true;
        break;
      }
    }
    if (overflow) return std::numeric_limits<double>::infinity();
    if (early_fail) {
      split();
      continue;
    }
    // Deviation both ways: curve samples to arcs, arc samples to the sampled curve.
    samples[0] = p0;
    samples[kSamples] = p1;
    for (int i = 1; i < kSamples; ++i) {
      if (i % (kSamples / 4) == 0) continue;  // done above
      samples[static_cast<std::size_t>(i)] = sample(piece, i);
      dev = std::max(dev, dist(samples[static_cast<std::size_t>(i)]));
    }
    if (dev <= tol_mm) {
      for (int k = 0; k < narcs; ++k) {
        const ArcGeom& g = k == 0 ? g0 : *g1;
        int i = 0;
        g.for_points(kSamples / 4, [&](Vec2 q) {
          ++i;
          const double frac = (k + double(i) / (kSamples / 4)) / narcs;
          const auto guess = static_cast<std::size_t>(frac * kSamples);
          dev = std::max(dev, distance_to_polyline(samples, q, guess, 0.5 * tol_mm, 2));
        });
      }
    }
    if (overflow) return std::numeric_limits<double>::infinity();
    if (dev > tol_mm && can_split) {
      split();
      continue;
    }
    max_dev = std::max(max_dev, dev);
    for (int k = 0; k < narcs; ++k) {
      const ArcSeg& a = arcs[k];
      if (len(a.b - a.a) <= 1e-12) continue;
      out.push_back({a.a, std::abs(a.bulge) < 1e-12 ? 0.0 : a.bulge});
    }
  }
  return max_dev;
}

namespace {

// Non-zero B-spline basis functions of degree p at u in knot span `span` (The NURBS Book, A2.2).
void basis(const std::vector<double>& U, std::size_t span, double u, int p, double* N) {
  std::array<double, 32> left{}, right{};
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[static_cast<std::size_t>(j)] = u - U[span + 1 - static_cast<std::size_t>(j)];
    right[static_cast<std::size_t>(j)] = U[span + static_cast<std::size_t>(j)] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double den = right[static_cast<std::size_t>(r + 1)] + left[static_cast<std::size_t>(j - r)];
      const double temp = den != 0 ? N[r] / den : 0.0;
      N[r] = saved + right[static_cast<std::size_t>(r + 1)] * temp;
      saved = left[static_cast<std::size_t>(j - r)] * temp;
    }
    N[j] = saved;
  }
}

}  // namespace

Vec2 nurbs_point(const Nurbs& s, std::size_t span, double u, Vec2* derivative) {
  const int p = s.degree;
  std::array<double, 32> N{}, Nd{};
  basis(s.knots, span, u, p, N.data());
  if (p >= 1) basis(s.knots, span, u, p - 1, Nd.data());
  Vec2 A, dA;
  double W = 0, dW = 0;
  const auto& U = s.knots;
  for (int j = 0; j <= p; ++j) {
    const std::size_t i = span - static_cast<std::size_t>(p) + static_cast<std::size_t>(j);
    const double w = s.weights.empty() ? 1.0 : s.weights[i];
    double dn = 0;
    if (j >= 1) {
      const double den = U[i + static_cast<std::size_t>(p)] - U[i];
      if (den != 0) dn += p * Nd[static_cast<std::size_t>(j - 1)] / den;
    }
    if (j <= p - 1) {
      const double den = U[i + static_cast<std::size_t>(p) + 1] - U[i + 1];
      if (den != 0) dn -= p * Nd[static_cast<std::size_t>(j)] / den;
    }
    A += s.control[i] * (N[static_cast<std::size_t>(j)] * w);
    W += N[static_cast<std::size_t>(j)] * w;
    dA += s.control[i] * (dn * w);
    dW += dn * w;
  }
  const Vec2 c = A / W;
  if (derivative) *derivative = (dA - c * dW) / W;
  return c;
}


namespace {

// One knot span as three polynomials in s in [0, 1] (homogeneous x*w, y*w, w): evaluating them
// by Horner is several times cheaper than the basis-function recurrence, which matters for
// drawings made of thousands of spline spans.
struct SpanPoly {
  int degree = 0;
  double cx[16] = {}, cy[16] = {}, cw[16] = {};

  Vec2 point(double s, Vec2* d) const {
    double x = 0, y = 0, w = 0, dx = 0, dy = 0, dw = 0;
    for (int k = degree; k >= 0; --k) {
      dx = dx * s + x;
      dy = dy * s + y;
      dw = dw * s + w;
      x = x * s + cx[k];
      y = y * s + cy[k];
      w = w * s + cw[k];
    }
    const Vec2 c{x / w, y / w};
    if (d) *d = Vec2{(dx - c.x * dw) / w, (dy - c.y * dw) / w};
    return c;
  }
};

// Homogeneous point of span `span` at parameter u.
void homogeneous(const Nurbs& s, std::size_t span, double u, double& X, double& Y, double& W) {
  const int p = s.degree;
  std::array<double, 32> N{};
  basis(s.knots, span, u, p, N.data());
  X = Y = W = 0;
  for (int j = 0; j <= p; ++j) {
    const std::size_t i = span - static_cast<std::size_t>(p) + static_cast<std::size_t>(j);
    const double w = s.weights.empty() ? 1.0 : s.weights[i];
    const double nw = N[static_cast<std::size_t>(j)] * w;
    X += nw * s.control[i].x;
    Y += nw * s.control[i].y;
    W += nw;
  }
}

// Power-basis coefficients through p + 1 samples (Vandermonde system, Gaussian elimination with
// partial pivoting; p is small).
bool span_poly(const Nurbs& s, std::size_t span, SpanPoly& out) {
  const int p = s.degree;
  if (p > 15) return false;
  const double a = s.knots[span], b = s.knots[span + 1];
  const int n = p + 1;
  double A[16][19];
  for (int r = 0; r < n; ++r) {
    const double t = p == 0 ? 0.0 : double(r) / p;
    double X, Y, W;
    homogeneous(s, span, a + (b - a) * t, X, Y, W);
    double tp = 1;
    for (int c = 0; c < n; ++c) {
      A[r][c] = tp;
      tp *= t;
    }
    A[r][n] = X;
    A[r][n + 1] = Y;
    A[r][n + 2] = W;
  }
  for (int c = 0; c < n; ++c) {
    int piv = c;
    for (int r = c + 1; r < n; ++r) {
      if (std::abs(A[r][c]) > std::abs(A[piv][c])) piv = r;
    }
    if (A[piv][c] == 0) return false;
    if (piv != c) {
      for (int k = 0; k < n + 3; ++k) std::swap(A[c][k], A[piv][k]);
    }
    for (int r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = A[r][c] / A[c][c];
      if (f == 0) continue;
      for (int k = c; k < n + 3; ++k) A[r][k] -= f * A[c][k];
    }
  }
  out.degree = p;
  for (int c = 0; c < n; ++c) {
    out.cx[c] = A[c][n] / A[c][c];
    out.cy[c] = A[c][n + 1] / A[c][c];
    out.cw[c] = A[c][n + 2] / A[c][c];
  }
  return true;
}

}  // namespace

std::vector<Vertex> nurbs_to_arcs(const Nurbs& s, double tol_mm, double* max_dev) {
  std::vector<Vertex> out;
  double dev = 0;
  const int p = s.degree;
  const std::size_t n = s.control.size();
  if (p < 1 || p > kMaxSplineDegree || n < static_cast<std::size_t>(p) + 1 || s.knots.size() != n + static_cast<std::size_t>(p) + 1) return out;
  if (!s.weights.empty() && s.weights.size() != n) return out;
  Vec2 prev_end;
  bool have_prev = false;
  for (std::size_t k = static_cast<std::size_t>(p); k < n; ++k) {
    const double a = s.knots[k];
    const double b = s.knots[k + 1];
    if (!(b > a)) continue;
    ParamCurve c;
    SpanPoly poly;
    if (span_poly(s, k, poly)) {
      // Span ends exactly as the recurrence gives them (clamped ends are control points).
      const Vec2 pa = nurbs_point(s, k, a, nullptr), pb = nurbs_point(s, k, b, nullptr);
      c.point = [poly, pa, pb](double t) { return t == 0 ? pa : t == 1 ? pb : poly.point(t, nullptr); };
      c.derivative = [poly](double t) {
        Vec2 d;
        poly.point(t, &d);
        return d;
      };
      c.t0 = 0;
      c.t1 = 1;
    } else {
      c.point = [&s, k](double u) { return nurbs_point(s, k, u, nullptr); };
      c.derivative = [&s, k](double u) {
        Vec2 d;
        nurbs_point(s, k, u, &d);
        return d;
      };
      c.t0 = a;
      c.t1 = b;
    }
    // A jump between spans (a knot of multiplicity degree + 1) becomes a straight segment.
    const Vec2 start = c.point(c.t0);
    if (have_prev && len(prev_end - start) > 1e-9) out.push_back({prev_end, 0.0});
    dev = std::max(dev, fit_biarcs(c, tol_mm, out));
    prev_end = c.point(c.t1);
    have_prev = true;
  }
  if (have_prev) out.push_back({prev_end, 0.0});
  if (max_dev) *max_dev = dev;
  return out;
}

namespace {

// Solves a (possibly cyclic) tridiagonal system a[i] x[i-1] + b[i] x[i] + c[i] x[i+1] = d[i]
// (with a[0] and c[n-1] the corner entries when cyclic) for two right-hand sides at once.
bool solve_tridiagonal(std::vector<double> a, std::vector<double> b, std::vector<double> c, std::vector<Vec2> d,
                       bool cyclic, std::vector<Vec2>& x) {
  const std::size_t n = b.size();
  x.assign(n, Vec2{});
  if (n == 0) return true;
  auto thomas = [&](std::vector<double> aa, std::vector<double> bb, std::vector<double> cc, std::vector<Vec2> dd,
                    std::vector<Vec2>& xx) {
    xx.assign(n, Vec2{});
    for (std::size_t i = 1; i < n; ++i) {
      if (bb[i - 1] == 0) return false;
      const double m = aa[i] / bb[i - 1];
      bb[i] -= m * cc[i - 1];
      dd[i] -= dd[i - 1] * m;
    }
    if (bb[n - 1] == 0) return false;
    xx[n - 1] = dd[n - 1] / bb[n - 1];
    for (std::size_t i = n - 1; i-- > 0;) xx[i] = (dd[i] - xx[i + 1] * cc[i]) / bb[i];
    return true;
  };
  if (!cyclic || n < 3) return thomas(a, b, c, d, x);
  // Sherman–Morrison: A = T + u v^T with the corners moved into u, v.
  const double alpha = c[n - 1];  // A[n-1][0]
  const double beta = a[0];       // A[0][n-1]
  const double gamma = -b[0];
  std::vector<double> bb = b;
  bb[0] -= gamma;
  bb[n - 1] -= alpha * beta / gamma;
  std::vector<Vec2> y, z;
  std::vector<double> aa = a, cc = c;
  aa[0] = 0;
  cc[n - 1] = 0;
  if (!thomas(aa, bb, cc, d, y)) return false;
  std::vector<Vec2> uvec(n, Vec2{});
  uvec[0] = {gamma, gamma};
  uvec[n - 1] = {alpha, alpha};
  if (!thomas(aa, bb, cc, uvec, z)) return false;
  const double vz_x = z[0].x + beta / gamma * z[n - 1].x;
  const double vy_x = y[0].x + beta / gamma * y[n - 1].x;
  const double vy_y = y[0].y + beta / gamma * y[n - 1].y;
  const double fx = vy_x / (1 + vz_x);
  const double fy = vy_y / (1 + vz_x);
  for (std::size_t i = 0; i < n; ++i) x[i] = {y[i].x - fx * z[i].x, y[i].y - fy * z[i].x};
  return true;
}

}  // namespace

std::vector<Vertex> fit_points_to_arcs(const std::vector<Vec2>& in, bool closed, const Vec2* start_tangent,
                                       const Vec2* end_tangent, double tol_mm, double* max_dev) {
  std::vector<Vec2> pts;
  for (const Vec2& p : in) {
    if (pts.empty() || geometry::distance(pts.back(), p) > 1e-12) pts.push_back(p);
  }
  if (closed && pts.size() > 2 && geometry::distance(pts.front(), pts.back()) <= 1e-12) pts.pop_back();
  std::vector<Vertex> out;
  double dev = 0;
  if (pts.size() < 2) return out;
  if (closed && pts.size() < 3) closed = false;
  const std::size_t n = pts.size();
  const std::size_t segs = closed ? n : n - 1;
  std::vector<double> h(segs);
  for (std::size_t i = 0; i < segs; ++i) h[i] = geometry::distance(pts[i], pts[(i + 1) % n]);
  // Second derivatives M at the knots.
  std::vector<Vec2> M;
  const std::size_t m = closed ? n : n;
  std::vector<double> a(m, 0), b(m, 0), c(m, 0);
  std::vector<Vec2> d(m, Vec2{});
  for (std::size_t i = 0; i < m; ++i) {
    const bool first = i == 0, last = i == n - 1;
    if (closed || (!first && !last)) {
      const std::size_t ip = closed ? (i + n - 1) % n : i - 1;
      const double hp = h[closed ? (i + segs - 1) % segs : i - 1];
      const double hn = h[i % segs];
      a[i] = hp;
      b[i] = 2 * (hp + hn);
      c[i] = hn;
      d[i] = ((pts[(i + 1) % n] - pts[i]) / hn - (pts[i] - pts[ip]) / hp) * 6.0;
    } else if (first) {
      if (start_tangent) {
        b[i] = 2 * h[0];
        c[i] = h[0];
        d[i] = ((pts[1] - pts[0]) / h[0] - geometry::normalized(*start_tangent)) * 6.0;
      } else {
        b[i] = 1;
      }
    } else {
      if (end_tangent) {
        a[i] = h[segs - 1];
        b[i] = 2 * h[segs - 1];
        d[i] = (geometry::normalized(*end_tangent) - (pts[n - 1] - pts[n - 2]) / h[segs - 1]) * 6.0;
      } else {
        b[i] = 1;
      }
    }
  }
  if (!solve_tridiagonal(a, b, c, d, closed, M)) return out;
  for (std::size_t i = 0; i < segs; ++i) {
    const Vec2 y0 = pts[i], y1 = pts[(i + 1) % n];
    const Vec2 M0 = M[i], M1 = M[(i + 1) % n];
    const double hh = h[i];
    ParamCurve cv;
    cv.t0 = 0;
    cv.t1 = hh;
    cv.point = [=](double t) {
      const double s = hh - t;
      return M0 * (s * s * s / (6 * hh)) + M1 * (t * t * t / (6 * hh)) + (y0 / hh - M0 * (hh / 6)) * s +
             (y1 / hh - M1 * (hh / 6)) * t;
    };
    cv.derivative = [=](double t) {
      const double s = hh - t;
      return M0 * (-s * s / (2 * hh)) + M1 * (t * t / (2 * hh)) - (y0 / hh - M0 * (hh / 6)) + (y1 / hh - M1 * (hh / 6));
    };
    dev = std::max(dev, fit_biarcs(cv, tol_mm, out));
  }
  if (!closed) out.push_back({pts.back(), 0.0});
  if (max_dev) *max_dev = dev;
  return out;
}

}  // namespace cutroute::io::detail
