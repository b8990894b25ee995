/// @file
/// @brief Chi-square distribution with real (non-integer) degrees of freedom: CDF, survival
/// function and their inverses, as needed for the confidence intervals of theory.md §3.1.
///
/// χ²_ν is the gamma distribution with shape a = ν/2 and scale 2, so
/// CDF(x; ν) = P(ν/2, x/2), the regularized lower incomplete gamma function.
#pragma once

namespace imunoise::analysis {

/// @name Distribution functions
/// @{

/// Regularized lower incomplete gamma function P(a, x) = γ(a, x)/Γ(a).
/// @param[in] a shape, > 0 (any real value)
/// @param[in] x argument, ≥ 0
/// @throws AnalysisError when a ≤ 0, x < 0 or either is not finite.
double regularized_gamma_p(double a, double x);

/// Regularized upper incomplete gamma function Q(a, x) = 1 − P(a, x), accurate even when
/// Q is far below machine epsilon. Same arguments and errors as regularized_gamma_p().
double regularized_gamma_q(double a, double x);

/// Chi-square CDF, Pr(χ²_dof ≤ x) = P(dof/2, x/2); dof may be non-integer (an EDF).
/// @throws AnalysisError when dof ≤ 0, x < 0 or either is not finite.
double chi_square_cdf(double x, double dof);

/// Chi-square survival function, Pr(χ²_dof > x) = Q(dof/2, x/2), accurate in the far tail.
double chi_square_sf(double x, double dof);

/// @}
/// @name Quantiles (relative accuracy ~1e-12 over dof 1e-2 … 1e9)
/// @{

/// Inverse of chi_square_cdf(): the x with Pr(χ²_dof ≤ x) = probability. Returns 0 when the
/// true quantile is below the smallest positive double (tiny dof with small probability).
/// @param[in] probability in (0, 1)
/// @param[in] dof degrees of freedom, > 0
/// @throws AnalysisError when dof is outside its range (an EDF the data gave), ContractViolation
///   when the probability is.
double chi_square_quantile(double probability, double dof);

/// Inverse of chi_square_sf(): the x with Pr(χ²_dof > x) = tail. Use it for upper
/// quantiles close to 1, where 1 − tail would lose digits.
/// @param[in] tail upper-tail probability in (0, 1)
/// @param[in] dof degrees of freedom, > 0
/// @throws as chi_square_quantile().
double chi_square_upper_quantile(double tail, double dof);

/// @}

}  // namespace imunoise::analysis
