#include <cutroute/machining/accuracy.hpp>

#include <algorithm>
#include <cmath>

#include <cutroute/machining/models.hpp>

namespace cutroute::machining {

namespace {

// Rayleigh density (x/σ²)·exp(−x²/(2σ²)).
double rayleigh_pdf(double x, double s) { return x / (s * s) * std::exp(-x * x / (2.0 * s * s)); }

// Integrates g(A, y) against Rayleigh(σ_A) × arcsine(y) over the phase θ (y = cos θ, density 1/π):
// integrating over y directly would meet the infinite density at ±1 (pitfall 3).
template <class G>
double expect(G&& g, double sigma_A, const CubatureParams& p) {
  return simpson_2d([&](double a, double th) { return g(a, std::cos(th)) * rayleigh_pdf(a, sigma_A); }, 0.0,
                    p.a_mult * sigma_A, 0.0, kPi, p.m, p.n) /
         kPi;
}

}  // namespace

RhoMoments rho_moments(double r, double sigma_A, double phi_deg, const CubatureParams& p) {
  RhoMoments out;
  if (sigma_A <= 0.0) {
    out.mean = r;
    out.mean_sq = r * r;
    return out;
  }
  const double c = std::cos(phi_deg * kPi / 180.0);
  // One pass accumulating E[d] and E[d²] together.
  const double h = p.a_mult * sigma_A / p.m;
  const double k = kPi / p.n;
  double s1 = 0.0, s2 = 0.0;
  for (int i = 0; i <= p.m; ++i) {
    const double a = h * i;
    const double wa = simpson_weight(i, p.m) * rayleigh_pdf(a, sigma_A);
    if (wa == 0.0) continue;
    double r1 = 0.0, r2 = 0.0;
    for (int j = 0; j <= p.n; ++j) {
      const double y = std::cos(k * j);
      const double ay = a * y;
      const double num = ay * ay + 2.0 * r * ay * c;
      const double rho = std::sqrt(r * r + num);
      const double d = num / (rho + r);
      const double w = simpson_weight(j, p.n);
      r1 += w * d;
      r2 += w * d * d;
    }
    s1 += wa * r1;
    s2 += wa * r2;
  }
  const double scale = h * k / 9.0 / kPi;
  const double ed = s1 * scale;
  const double ed2 = s2 * scale;
  out.mean_dev = ed;
  out.mean = r + ed;
  out.var = std::max(0.0, ed2 - ed * ed);
  out.mean_sq = r * r + 2.0 * r * ed + ed2;
  return out;
}

RhoMoments rho_moments_naive(double r, double sigma_A, double phi_deg, const CubatureParams& p) {
  const double c = std::cos(phi_deg * kPi / 180.0);
  const auto rho = [&](double a, double y) { return std::sqrt(r * r + 2.0 * r * a * y * c + a * a * y * y); };
  RhoMoments out;
  out.mean = expect(rho, sigma_A, p);
  out.mean_sq = expect(
      [&](double a, double y) {
        const double q = rho(a, y);
        return q * q;
      },
      sigma_A, p);
  out.mean_dev = out.mean - r;
  out.var = std::max(0.0, out.mean_sq - out.mean * out.mean);
  return out;
}

double max_rho_variance(double r, double sigma_A, int n_phi, const CubatureParams& p) {
  double best = 0.0;
  for (int j = 0; j < n_phi; ++j) {
    best = std::max(best, rho_moments(r, sigma_A, 360.0 * j / n_phi, p).var);
  }
  return best;
}

double z_two_sided(double P) {
  // Inverse of Φ at q = (1 + P)/2 (upper half, q >= 0.5), Acklam's rational approximation.
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01, -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  const double q = 0.5 * (1.0 + P);
  const double tail = 0.5 * (1.0 - P);  // 1 − q, computed without cancellation
  double x = 0.0;
  if (tail > 0.02425) {
    const double u = q - 0.5;
    const double t = u * u;
    x = (((((a[0] * t + a[1]) * t + a[2]) * t + a[3]) * t + a[4]) * t + a[5]) * u /
        (((((b[0] * t + b[1]) * t + b[2]) * t + b[3]) * t + b[4]) * t + 1.0);
  } else {
    const double u = std::sqrt(-2.0 * std::log(tail));
    x = -(((((c[0] * u + c[1]) * u + c[2]) * u + c[3]) * u + c[4]) * u + c[5]) /
        ((((d[0] * u + d[1]) * u + d[2]) * u + d[3]) * u + 1.0);
  }
  // One Halley step on the upper tail 0.5·erfc(x/√2) − tail brings 1e-9 to machine precision.
  const double e = 0.5 * std::erfc(x / std::sqrt(2.0)) - tail;
  const double pdf = std::exp(-0.5 * x * x) / std::sqrt(2.0 * kPi);
  const double step = -e / pdf;
  x = x - step / (1.0 + 0.5 * x * step);
  return x;
}

double eccentricity_sigma(double TA, double TB) {
  const double a = TA / 6.0;
  const double b = TB / 6.0;
  return std::sqrt((a * a + b * b) / 2.0);
}
double error_copying(double x_r, double F_r, double ap, double k) { return x_r * F_r / (ap * k); }
double scatter_field(double z_p, double max_var, double sigma_r) {
  return 2.0 * z_p * std::sqrt(max_var + sigma_r * sigma_r);
}

}  // namespace cutroute::machining
