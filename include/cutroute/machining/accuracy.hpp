// Radius-vector statistics of a bored hole (MACHINING.md 3.8): 2-D composite Simpson cubature,
// moments of ρ(φ), the two-sided normal quantile z_p and the error-copying accuracy chain.
#pragma once

#include <cassert>
#include <cstddef>

namespace cutroute::machining {

// Composite Simpson weight 1, 4, 2, 4, ..., 2, 4, 1 of node i out of 0..n (n even).
constexpr double simpson_weight(int i, int n) {
  if (i == 0 || i == n) return 1.0;
  return (i % 2 == 1) ? 4.0 : 2.0;
}

// ∬ fn(x, y) over [x0, x1] × [y0, y1] with m intervals in x and n in y (both even, >= 2); the node
// weight is w_i·w_j·h·k/9. Exact for bicubic integrands.
template <class Fn>
double simpson_2d(Fn&& fn, double x0, double x1, double y0, double y1, int m, int n) {
  assert(m >= 2 && n >= 2 && m % 2 == 0 && n % 2 == 0);
  const double h = (x1 - x0) / m;
  const double k = (y1 - y0) / n;
  double sum = 0.0;
  for (int i = 0; i <= m; ++i) {
    const double x = x0 + h * i;
    double row = 0.0;
    for (int j = 0; j <= n; ++j) row += simpson_weight(j, n) * fn(x, y0 + k * j);
    sum += simpson_weight(i, m) * row;
  }
  return sum * h * k / 9.0;
}

// Mean and variance of ρ = √(r² + 2·r·A·y·cosφ + A²·y²), A ~ Rayleigh(σ_A), y = cos θ, θ ~ U[0, π].
struct RhoMoments {
  double mean = 0.0;      // E[ρ] [mm]
  double var = 0.0;       // Var[ρ] [mm²]
  double mean_dev = 0.0;  // E[ρ] − r, accumulated directly (no cancellation) [mm]
  double mean_sq = 0.0;   // E[ρ²] [mm²]
};
struct CubatureParams {
  int m = 64;           // Simpson intervals over A ∈ [0, a_mult·σ_A] (even)
  int n = 64;           // Simpson intervals over the phase θ ∈ [0, π] (even)
  double a_mult = 8.0;  // truncation of the Rayleigh density, in σ_A [-]
};
// Accumulates the deviation d = ρ − r = (A²y² + 2rAy·cosφ)/(ρ + r), so that σ_A ≪ r keeps its digits.
RhoMoments rho_moments(double r_mm, double sigma_A_mm, double phi_deg, const CubatureParams& p = {});
// The naive E[ρ²] − E[ρ]² form, kept only as a regression guard (it loses everything when σ_A ≪ r).
RhoMoments rho_moments_naive(double r_mm, double sigma_A_mm, double phi_deg, const CubatureParams& p = {});
// max over φ_j = j·360/n_phi of Var[ρ(φ_j)] by cubature [mm²]; exact value is σ_A².
double max_rho_variance(double r_mm, double sigma_A_mm, int n_phi, const CubatureParams& p = {});

// Two-sided standard-normal quantile: z with P(|Z| <= z) = P, 0 < P < 1 (Acklam + one Halley step,
// absolute error below 1e-12).
double z_two_sided(double P);

// Rayleigh parameter of the pre-hole eccentricity from the tolerance fields (T = 6σ) [mm]. [recon]
double eccentricity_sigma(double TA_mm, double TB_mm);
// Error-copying coefficient ε = x_r·F_r/(ap·k) = (dF_r/dap)/k [-]. [recon]
double error_copying(double x_r, double F_r_n, double ap_mm, double k_n_mm);
// Scatter field of the radius vector V_ρ = 2·z_p·√(max_φ var + σ_r²) [mm].
double scatter_field(double z_p, double max_var_mm2, double sigma_r_mm);

// Rayleigh facts (pitfall 4): sd(A) = √(2 − π/2)·σ_A, mean(A) = √(π/2)·σ_A.
inline constexpr double kRayleighSdFactor = 0.6551363775620335;
inline constexpr double kRayleighMeanFactor = 1.2533141373155001;

}  // namespace cutroute::machining
