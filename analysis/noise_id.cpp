/// @file
/// @brief Lag-1 autocorrelation noise identification (see noise_id.h).
/// [RG04] W. J. Riley, C. A. Greenhall, "Power law noise identification using the lag 1
/// autocorrelation", EFTF 2004 — eqs. for r₁ and δ = r₁/(1+r₁), and the differencing loop.
#include "analysis/noise_id.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::analysis {
namespace {

/// Removes the least-squares quadratic a + b·t + c·t² in place and returns the residual
/// energy Σz². Uses the discrete orthogonal (Gram) polynomials of the uniform grid,
/// 1, s, s² − (n² − 1)/12 with s = i − (n−1)/2, so the fit is well conditioned for any length
/// and offset and needs no storage beyond z (records can have ~1e7 points).
double remove_quadratic(std::vector<double>& z) {
  const std::size_t n = z.size();
  const double centre = 0.5 * static_cast<double>(n - 1);
  const double shift = (static_cast<double>(n) * static_cast<double>(n) - 1.0) / 12.0;
  auto basis = [&](std::size_t i, double& p1, double& p2) {
    p1 = static_cast<double>(i) - centre;
    p2 = p1 * p1 - shift;
  };
  double dot0 = 0.0, dot1 = 0.0, dot2 = 0.0, norm1 = 0.0, norm2 = 0.0;
#pragma omp simd reduction(+ : dot0, dot1, dot2, norm1, norm2)
  for (std::size_t i = 0; i < n; ++i) {
    double p1 = 0.0, p2 = 0.0;
    basis(i, p1, p2);
    dot0 += z[i];
    dot1 += z[i] * p1;
    dot2 += z[i] * p2;
    norm1 += p1 * p1;
    norm2 += p2 * p2;
  }
  const double c0 = dot0 / static_cast<double>(n);
  const double c1 = norm1 > 0.0 ? dot1 / norm1 : 0.0;
  const double c2 = norm2 > 0.0 ? dot2 / norm2 : 0.0;
  double energy = 0.0;
#pragma omp simd reduction(+ : energy)
  for (std::size_t i = 0; i < n; ++i) {
    double p1 = 0.0, p2 = 0.0;
    basis(i, p1, p2);
    z[i] -= c0 + c1 * p1 + c2 * p2;
    energy += z[i] * z[i];
  }
  return energy;
}

/// Lag-1 autocorrelation r₁ = Σ(z_i − z̄)(z_{i+1} − z̄) / Σ(z_i − z̄)², [RG04] eq. (2);
/// std::nullopt when the denominator is zero.
std::optional<double> lag1_autocorrelation(const std::vector<double>& z) {
  const std::size_t n = z.size();
  if (n < 2) return std::nullopt;
  double mean = 0.0;
#pragma omp simd reduction(+ : mean)
  for (std::size_t i = 0; i < n; ++i) mean += z[i];
  mean /= static_cast<double>(n);
  double num = 0.0;
  double den = 0.0;
#pragma omp simd reduction(+ : num, den)
  for (std::size_t i = 0; i < n - 1; ++i) {
    const double a = z[i] - mean;
    den += a * a;
    num += a * (z[i + 1] - mean);
  }
  den += (z[n - 1] - mean) * (z[n - 1] - mean);
  if (!(den > 0.0) || !std::isfinite(den)) return std::nullopt;
  return num / den;
}

}  // namespace

std::optional<int> lag1_noise_alpha(std::span<const double> phase, std::int64_t m, int d_max) {
  IMUNOISE_EXPECT(m >= 1, "lag1_noise_alpha: m must be >= 1 (got " + std::to_string(m) + ")");
  IMUNOISE_EXPECT(d_max >= 0 && d_max <= 3,
                  "lag1_noise_alpha: d_max must be in 0..3 (got " + std::to_string(d_max) + ")");
  if (phase.empty()) return std::nullopt;
  const auto count = static_cast<std::int64_t>(phase.size() - 1) / m + 1;
  if (count < kMinNoiseIdPoints) return std::nullopt;

  // Decimate (not average): the phase at τ-spaced epochs is the θ of theory.md §1.1.
  std::vector<double> z(static_cast<std::size_t>(count));
  for (std::int64_t i = 0; i < count; ++i) {
    z[static_cast<std::size_t>(i)] = phase[static_cast<std::size_t>(i * m)];
  }
  // A quadratic in phase is a frequency offset plus a linear drift: not noise.
  double energy = 0.0;
#pragma omp simd reduction(+ : energy)
  for (std::size_t i = 0; i < z.size(); ++i) energy += z[i] * z[i];
  const double residual = remove_quadratic(z);
  // Residual RMS below 1e-13 of the data RMS is round-off of an exact quadratic (~1e-16),
  // not noise; real records sit orders of magnitude above it.
  if (!(residual > 1e-26 * energy)) return std::nullopt;

  for (int d = 0;; ++d) {
    const std::optional<double> r1 = lag1_autocorrelation(z);
    if (!r1) return std::nullopt;
    // δ ≈ −β/2 for stationary noise with S_z ∝ f^β [RG04]; r₁ ≥ −1 always, the max only
    // guards the division for degenerate inputs.
    const double delta = *r1 / std::max(1.0 + *r1, 1e-12);
    if (delta < 0.25 || d >= d_max) {
      // Phase PSD exponent after d differences is β + 2d = −2δ, and alpha = β + 2.
      return 2 - 2 * d - static_cast<int>(std::lround(2.0 * delta));
    }
    for (std::size_t i = 0; i + 1 < z.size(); ++i) z[i] = z[i + 1] - z[i];
    z.pop_back();
  }
}

AlphaRange supported_alpha_range(DeviationType type) {
  switch (type) {
    case DeviationType::hdev:
    case DeviationType::ohdev:
    case DeviationType::htotdev:
      return {-4, 2};  // d = 3: alpha + 6 > 1
    case DeviationType::adev:
    case DeviationType::oadev:
    case DeviationType::mdev:
    case DeviationType::tdev:
    case DeviationType::totdev:
    case DeviationType::mtotdev:
    case DeviationType::ttotdev:
    case DeviationType::theo1:
      break;
  }
  return {-2, 2};  // d = 2: alpha + 4 > 1
}

int noise_alpha_for(DeviationType type, std::span<const double> phase, std::int64_t m) {
  IMUNOISE_EXPECT(m >= 1, "noise_alpha_for: m must be >= 1 (got " + std::to_string(m) + ")");
  const AlphaRange range = supported_alpha_range(type);
  const int d_max = range.min == -4 ? 3 : 2;
  std::optional<int> alpha = lag1_noise_alpha(phase, m, d_max);
  if (!alpha && !phase.empty()) {
    // Too few points at m: use the largest factor that still has kMinNoiseIdPoints points.
    const auto m_fallback = static_cast<std::int64_t>(phase.size() - 1) / (kMinNoiseIdPoints - 1);
    if (m_fallback >= 1 && m_fallback < m) alpha = lag1_noise_alpha(phase, m_fallback, d_max);
  }
  return std::clamp(alpha.value_or(0), range.min, range.max);
}

}  // namespace imunoise::analysis
