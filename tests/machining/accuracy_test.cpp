// MACHINING.md 7.1 (U10-U12) and 7.2 (A1-A5 and the property tests): quantile, Simpson, ρ moments.
#include <gtest/gtest.h>

#include <cmath>

#include <cutroute/core/random.hpp>
#include <cutroute/machining/accuracy.hpp>
#include <cutroute/machining/models.hpp>

#include "examples.hpp"

namespace cutroute::machining {
namespace {

TEST(MachiningAccuracy, U10NormalQuantile) {
  EXPECT_NEAR(z_two_sided(0.9973), 2.999977, 5e-7);
  EXPECT_NEAR(z_two_sided(0.99), 2.575829, 5e-7);
  EXPECT_NEAR(z_two_sided(0.95), 1.959964, 5e-7);
  // Accurate far beyond the printed digits: P(|Z| <= z) recomputed with erf.
  for (double P : {0.5, 0.9, 0.95, 0.99, 0.9973, 0.999999}) {
    const double z = z_two_sided(P);
    EXPECT_NEAR(std::erf(z / std::sqrt(2.0)), P, 1e-14) << P;
  }
}

TEST(MachiningAccuracy, U11SimpsonExp) {
  const double v = simpson_2d([](double x, double y) { return std::exp(x + y); }, 0, 1, 0, 1, 4, 4);
  EXPECT_NEAR(v, 2.9526196, 5e-8);
  EXPECT_NEAR((std::exp(1.0) - 1) * (std::exp(1.0) - 1), 2.9524924, 5e-8);
}

TEST(MachiningAccuracy, U12SimpsonExactForCubics) {
  EXPECT_NEAR(simpson_2d([](double x, double y) { return x * x * y * y; }, 0, 1, 0, 1, 2, 2), 1.0 / 9.0,
              1e-16);
  EXPECT_NEAR(simpson_2d([](double x, double y) { return x * x * x * y * y * y; }, 0, 1, 0, 2, 2, 2), 1.0,
              1e-15);
}

struct AVector {
  const char* id;
  double sigma, phi;
  int mn;
  double mean_dev, sd;
  double mean_abs_tol;  // for the zero mean of A1
};

TEST(MachiningAccuracy, A1ToA5RadiusVectorMoments) {
  const AVector vs[] = {
      {"A1", 0.003, 0, 64, 0.0, 2.999994e-3, 1e-12},      {"A2", 0.003, 45, 64, 1.124995e-7, 2.121316e-3, 0},
      {"A3", 0.003, 90, 64, 2.249991e-7, 3.181987e-7, 0}, {"A4", 0.5, 90, 128, 6.247073e-3, 8.830570e-3, 0},
      {"A5", 2.0, 45, 128, 5.0554852e-2, 1.4054356, 0},
  };
  for (const auto& v : vs) {
    CubatureParams p;
    p.m = p.n = v.mn;
    const RhoMoments m = rho_moments(20.0, v.sigma, v.phi, p);
    if (v.mean_abs_tol > 0) {
      EXPECT_LT(std::abs(m.mean_dev), v.mean_abs_tol) << v.id;
    } else {
      // Printed to 7-8 digits: compare at the printed precision (about 5e-7 relative).
      EXPECT_NEAR(m.mean_dev / v.mean_dev, 1.0, 1e-6) << v.id << " E-r = " << m.mean_dev;
    }
    EXPECT_NEAR(std::sqrt(m.var) / v.sd, 1.0, 1e-6) << v.id << " sd = " << std::sqrt(m.var);
    EXPECT_NEAR(m.mean - 20.0, m.mean_dev, 1e-14) << v.id;  // r + d rounds at 20·2^-52
  }
  // A1 exact 3e-3; A3 ≈ σ²/(√2·r); A5 converged at m = n = 256.
  CubatureParams p256;
  p256.m = p256.n = 256;
  EXPECT_NEAR(std::sqrt(rho_moments(20.0, 2.0, 45, p256).var), 1.40543573, 2e-8);
  EXPECT_NEAR(3.181987e-7 / (0.003 * 0.003 / (std::sqrt(2.0) * 20.0)), 1.0, 1e-4);
}

TEST(MachiningAccuracy, PropertySecondMomentIsExact) {
  for (double sigma : {0.003, 0.05, 0.5, 2.0}) {
    for (double phi = 0; phi < 360; phi += 22.5) {
      CubatureParams p;
      p.m = p.n = 128;
      const RhoMoments m = rho_moments(20.0, sigma, phi, p);
      // E[ρ²] − r² = σ_A² for every φ (accumulated as 2r·E[d] + E[d²], no cancellation).
      EXPECT_NEAR((m.mean_sq - 400.0) / (sigma * sigma), 1.0, 1e-5) << sigma << " " << phi;
    }
  }
}

TEST(MachiningAccuracy, PropertyPhiZeroAndMaximumVariance) {
  const double sigma = 0.01;
  const RhoMoments m0 = rho_moments(20.0, sigma, 0.0);
  EXPECT_LT(std::abs(m0.mean_dev), 1e-13);
  EXPECT_NEAR(std::sqrt(m0.var) / sigma, 1.0, 5e-6);
  double vmax = 0.0;
  for (int j = 0; j < 36; ++j) vmax = std::max(vmax, rho_moments(20.0, sigma, 10.0 * j).var);
  EXPECT_DOUBLE_EQ(vmax, std::max(m0.var, rho_moments(20.0, sigma, 180.0).var));
  EXPECT_DOUBLE_EQ(max_rho_variance(20.0, sigma, 36), vmax);
  for (int j = 0; j < 36; ++j) EXPECT_LE(rho_moments(20.0, sigma, 10.0 * j).var, sigma * sigma * (1 + 1e-12));
}

TEST(MachiningAccuracy, NaiveVarianceFailsA1) {
  // Pitfall 2, regression guard: E[ρ²] − E[ρ]² loses every digit when σ_A ≪ r.
  const RhoMoments naive = rho_moments_naive(20.0, 0.003, 0.0);
  const RhoMoments good = rho_moments(20.0, 0.003, 0.0);
  EXPECT_NEAR(std::sqrt(good.var), 2.999994e-3, 5e-9);
  EXPECT_GT(std::abs(std::sqrt(naive.var) - 3e-3), 1e-4) << "naive sd = " << std::sqrt(naive.var);
}

TEST(MachiningAccuracy, RayleighFactors) {
  // Pitfall 4: σ_A is the Rayleigh parameter, not the standard deviation.
  EXPECT_NEAR(kRayleighSdFactor, std::sqrt(2.0 - kPi / 2.0), 1e-15);
  EXPECT_NEAR(kRayleighMeanFactor, std::sqrt(kPi / 2.0), 1e-15);
  EXPECT_NEAR(kRayleighSdFactor, 0.655136, 5e-7);
}

TEST(MachiningAccuracy, PhaseIntegralAvoidsArcsineSingularity) {
  // Pitfall 3: E[y²] of the arcsine law is 1/2; integrating over the phase gets it to machine precision.
  const double ey2 =
      simpson_2d([](double, double th) { return std::cos(th) * std::cos(th); }, 0, 1, 0, kPi, 2, 64) / kPi;
  EXPECT_NEAR(ey2, 0.5, 1e-14);
}

TEST(MachiningAccuracy, ChainPieces) {
  EXPECT_NEAR(eccentricity_sigma(0.4, 0.4), 0.4 / 6.0, 1e-15);
  EXPECT_NEAR(scatter_field(3.0, 0.0, 1.0), 6.0, 1e-15);
  EXPECT_NEAR(error_copying(0.9, 100.0, 1.5, 1000.0), 0.06, 1e-15);
}

}  // namespace
}  // namespace cutroute::machining

namespace cutroute::machining {
namespace {

TEST(MachiningAccuracy, MonteCarloCrossCheck) {
  // Independent truth for A4 and A5: seeded sampling of A ~ Rayleigh(σ) by inverse CDF and θ ~ U[0, 2π)
  // (pitfall 10: a Monte-Carlo check takes a seeded engine).
  const struct { double sigma, phi; } cases[] = {{0.5, 90}, {2.0, 45}};
  for (const auto& c : cases) {
    Rng rng(12345);
    const double r = 20.0, cphi = std::cos(c.phi * kPi / 180.0);
    const int n = 400000;
    double s1 = 0, s2 = 0;
    for (int k = 0; k < n; ++k) {
      const double a = c.sigma * std::sqrt(-2.0 * std::log(1.0 - rng.uniform01()));
      const double y = std::cos(2.0 * kPi * rng.uniform01());
      const double d = std::sqrt(r * r + 2 * r * a * y * cphi + a * a * y * y) - r;
      s1 += d;
      s2 += d * d;
    }
    const double mean = s1 / n, var = s2 / n - mean * mean;
    CubatureParams p;
    p.m = p.n = 128;
    const RhoMoments m = rho_moments(r, c.sigma, c.phi, p);
    // Standard errors: sd/√n for the mean, about sd²·√(2/n)·2 for the variance (heavy-ish tails).
    EXPECT_NEAR(m.mean_dev, mean, 5.0 * std::sqrt(var / n)) << c.sigma;
    EXPECT_NEAR(m.var / var, 1.0, 5.0 * 2.0 * std::sqrt(2.0 / n)) << c.sigma;
  }
}

}  // namespace
}  // namespace cutroute::machining
