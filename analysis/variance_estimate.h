/// @file
/// @brief One Allan-family variance at one averaging factor with its number of terms: what
/// every estimator kernel (analysis/deviation, total_family, extra_deviations) returns.
#pragma once

#include <cstdint>

namespace imunoise::analysis {

/// Variance estimate at one averaging factor, with the number of terms summed (Stable32 "#").
struct VarianceEstimate {
  double variance = 0.0;     ///< σ²(τ) in (phase unit / s)², i.e. rate unit squared
  std::int64_t n_terms = 0;  ///< number of differences in the sum
};

}  // namespace imunoise::analysis
