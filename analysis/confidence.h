/// @file
/// @brief Chi-square confidence interval of a deviation from its equivalent degrees of
/// freedom (theory.md §3.1, NIST SP 1065 eq. 45).
#pragma once

namespace imunoise::analysis {

/// Two-sided interval [low, high] of a deviation σ (not of the variance σ²).
struct DeviationInterval {
  double low;   ///< lower bound, same unit as the deviation
  double high;  ///< upper bound, same unit as the deviation
};

/// Confidence interval of the true deviation given an estimate and its EDF ν: with
/// ν·σ̂²/σ² ~ χ²_ν, σ² ∈ [ν σ̂²/χ²_ν(1 − p/2), ν σ̂²/χ²_ν(p/2)] with p = 1 − confidence,
/// and the deviation bounds are the square roots (SP 1065 eq. 45).
/// @param[in] deviation  estimated deviation σ̂ ≥ 0 (any unit)
/// @param[in] edf        equivalent degrees of freedom ν > 0 (non-integer allowed)
/// @param[in] confidence two-sided coverage in (0, 1), e.g. 0.683 for "1 sigma"
/// @throws AnalysisError when the deviation or the EDF (numbers the data gave) is outside its
///   range, ContractViolation when the confidence (the caller's, validated by the CLI) is.
DeviationInterval deviation_interval(double deviation, double edf, double confidence);

}  // namespace imunoise::analysis
