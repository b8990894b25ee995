/// @file
/// @brief IEEE-952 Annex C graphical read-off of the five noise coefficients from an ADEV
/// curve (theory.md §4.1 table, §4.2). Reported for traceability with the reference study;
/// it is inconsistent when terms overlap (§4.2), so the estimator is fit_noise_model().
#pragma once

#include <cstddef>
#include <span>

#include "common/noise_term.h"

namespace imunoise::analysis {

/// Read-off of one term.
struct SlopeReadoffTerm {
  double value = 0.0;       ///< coefficient read off (Q, N, B, K or R, SI); 0 if not found
  bool found = false;       ///< a region with the term's slope exists
  double tau_low_s = 0.0;   ///< first τ of the region [s]
  double tau_high_s = 0.0;  ///< last τ of the region [s]
  std::size_t points = 0;   ///< number of curve points in the region
};

/// Read-off of all five terms, per NoiseTerm.
using SlopeReadoff = PerTerm<SlopeReadoffTerm>;

/// Tolerance on the local log-log slope for a point to belong to a term's region. For a curve
/// made of a term of slope s_i plus one of a neighbouring slope s_i ± 1/2, the local slope is
/// the variance-weighted mean of the two, so |slope − s_i| ≤ 0.1 means the term carries at
/// least 80 % of the AVAR there.
inline constexpr double kSlopeTolerance = 0.1;

/// Slope read-off (theory.md §4.1, §4.2): local slope d ln σ/d ln τ by central differences
/// (one-sided at the ends); the region of a term is the longest run of at least 2 contiguous
/// points whose slope is within kSlopeTolerance of −1, −1/2, 0, +1/2, +1 (Q, N, B, K, R). On
/// it the fixed-slope line ln σ = a + s·ln τ is fitted (a = mean of ln σ − s·ln τ) and read at
/// τ = √3, 1, 3, √2 s for Q, N, K, R (σ(√3) = Q, σ(1) = N, σ(3) = K, σ(√2) = R). B is the
/// minimum ADEV of its region divided by √(2 ln2/π) = 0.6643 (the IEEE "floor" read-off,
/// which N and K lift: it overestimates B, §4.2).
/// @param[in] tau_s averaging times [s], strictly increasing, > 0, at least 3
/// @param[in] adev  ADEV at those τ [rate unit], > 0
/// @throws AnalysisError on fewer than 3 points or values out of range (a curve the data gave);
///   ContractViolation on sizes that differ or τ not increasing.
SlopeReadoff slope_readoff(std::span<const double> tau_s, std::span<const double> adev);

}  // namespace imunoise::analysis
