/// @file
/// @brief Power-law noise identification by the lag-1 autocorrelation method of Riley &
/// Greenhall [RG04] (theory.md §3.4), used to choose the EDF model at each averaging factor.
///
/// alpha is the exponent of S_y(f) ∝ f^alpha: 2 white PM (gyro: angle quantization Q),
/// 1 flicker PM, 0 white FM (ARW N), −1 flicker FM (bias instability B), −2 random-walk FM
/// (rate random walk K), −3 flicker-walk FM, −4 random-run FM.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "analysis/deviation_type.h"

namespace imunoise::analysis {

/// Smallest number of decimated points the lag-1 method is trusted with [RG04].
inline constexpr std::int64_t kMinNoiseIdPoints = 30;

/// Lag-1 ACF noise identification on phase data at averaging factor m [RG04]: decimate to
/// z_i = x_{i·m}, remove a least-squares quadratic, then difference until
/// δ = r₁/(1 + r₁) < 0.25 or d = d_max, and return alpha = 2 − 2d − round(2δ) (the "+2" is the
/// phase-data offset). The result can exceed 2 or fall below −2·d_max for data that are not
/// power-law noise; callers clamp.
/// @param[in] phase M phase samples x_k (angle for a gyro, τ0-spaced)
/// @param[in] m     averaging factor ≥ 1
/// @param[in] d_max maximum number of differences, 0 … 3 (2 for Allan, 3 for Hadamard types)
/// @return std::nullopt when fewer than kMinNoiseIdPoints decimated points exist or the
///         detrended data have no variance (e.g. noiseless input).
/// @throws ContractViolation for m < 1 or d_max outside 0 … 3.
std::optional<int> lag1_noise_alpha(std::span<const double> phase, std::int64_t m, int d_max);

/// Range of alpha for which the EDF of a statistic is defined (GR03 needs alpha + 2d > 1):
/// [−2, 2] for the Allan types and TOTDEV, [−4, 2] for HDEV and OHDEV.
struct AlphaRange {
  int min;  ///< most divergent noise supported
  int max;  ///< always 2 (white PM)
};
AlphaRange supported_alpha_range(DeviationType type);

/// The alpha imunoise uses for the EDF of TYPE at averaging factor m: lag1_noise_alpha() with
/// d_max = 2 (Allan types, TOTDEV) or 3 (HDEV, OHDEV), clamped to supported_alpha_range().
/// Fallback when the decimated series has fewer than 30 points (m > (M−1)/29): the alpha
/// identified at the largest averaging factor that still has 30 points, m_f = ⌊(M−1)/29⌋ —
/// the "last identified alpha" of an increasing τ grid, computed directly so the result does
/// not depend on the grid. (Stable32 switches to the B1/R(n) ratio tests there; with fewer
/// than 30 averages their variance is large, and IMU records are long enough that the
/// fallback only covers the last factor ~7 of τ below the stop ratio.) If even m = 1 has
/// fewer than 30 points, or the data have no variance, returns 0 (white FM: ARW, the
/// dominant IMU term at short τ). Never throws for valid m ≥ 1.
int noise_alpha_for(DeviationType type, std::span<const double> phase, std::int64_t m);

}  // namespace imunoise::analysis
