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

/// Removes the least-squares quadratic a + b·t + c·t² in place. The basis 1, u, u² on
/// u ∈ [−1, 1] is orthogonalised (Gram–Schmidt) against the actual samples, so the fit is
/// well conditioned for any length and any offset of the data.
/// Returns the residual energy Σz² after the fit, for the noiseless-input test.
double remove_quadratic(std::vector<double>& z) {
  const std::size_t n = z.size();
  const double half = 0.5 * static_cast<double>(n - 1);
  std::vector<std::vector<double>> basis;
  for (int degree = 0; degree <= 2; ++degree) {
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double u = half > 0.0 ? (static_cast<double>(i) - half) / half : 0.0;
      v[i] = degree == 0 ? 1.0 : (degree == 1 ? u : u * u);
    }
    for (const auto& b : basis) {
      double dot = 0.0;
      for (std::size_t i = 0; i < n; ++i) dot += v[i] * b[i];
      for (std::size_t i = 0; i < n; ++i) v[i] -= dot * b[i];
    }
    double norm = 0.0;
    for (const double value : v) norm += value * value;
    norm = std::sqrt(norm);
    if (norm == 0.0) continue;  // n < 3: fewer independent basis vectors
    for (double& value : v) value /= norm;
    basis.push_back(std::move(v));
  }
  for (const auto& b : basis) {
    double dot = 0.0;
    for (std::size_t i = 0; i < n; ++i) dot += z[i] * b[i];
    for (std::size_t i = 0; i < n; ++i) z[i] -= dot * b[i];
  }
  double energy = 0.0;
  for (const double v : z) energy += v * v;
  return energy;
}

/// Lag-1 autocorrelation r₁ = Σ(z_i − z̄)(z_{i+1} − z̄) / Σ(z_i − z̄)², [RG04] eq. (2);
/// std::nullopt when the denominator is zero.
std::optional<double> lag1_autocorrelation(const std::vector<double>& z) {
  double mean = 0.0;
  for (const double v : z) mean += v;
  mean /= static_cast<double>(z.size());
  double num = 0.0;
  double den = 0.0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double a = z[i] - mean;
    den += a * a;
    if (i + 1 < z.size()) num += a * (z[i + 1] - mean);
  }
  if (!(den > 0.0) || !std::isfinite(den)) return std::nullopt;
  return num / den;
}

}  // namespace

std::optional<int> lag1_noise_alpha(std::span<const double> phase, std::int64_t m, int d_max) {
  IMUNOISE_CHECK(m >= 1, AnalysisError,
                 "lag1_noise_alpha: m must be >= 1 (got " + std::to_string(m) + ")");
  IMUNOISE_CHECK(d_max >= 0 && d_max <= 3, AnalysisError,
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
  for (const double v : z) energy += v * v;
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
      return {-4, 2};  // d = 3: alpha + 6 > 1
    case DeviationType::adev:
    case DeviationType::oadev:
    case DeviationType::mdev:
    case DeviationType::tdev:
    case DeviationType::totdev:
      break;
  }
  return {-2, 2};  // d = 2: alpha + 4 > 1
}

int noise_alpha_for(DeviationType type, std::span<const double> phase, std::int64_t m) {
  IMUNOISE_CHECK(m >= 1, AnalysisError,
                 "noise_alpha_for: m must be >= 1 (got " + std::to_string(m) + ")");
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
