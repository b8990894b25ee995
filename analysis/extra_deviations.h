/// @file
/// @brief Deviations outside the Allan family of deviation.h: Thêo1 (NIST SP 1065 §5.2.15),
/// the parabolic variance PVAR (Vernotte, Lenczner, Bourgeois & Rubiola 2016, as computed by
/// SigmaTheta) and the classical sample variance of non-overlapping m-averages (the SP 1065
/// test-suite "std dev" rows). Same phase convention as deviation.h: M phase samples x_k
/// (0-based, any unit), sample period τ0; results are in (phase unit / s)², i.e. rate unit².
#pragma once

#include <cstdint>
#include <span>

#include "analysis/deviation_type.h"
#include "analysis/variance_estimate.h"

namespace imunoise::analysis {

/// @name Thêo1
/// @{

/// Thêo1 variance at averaging factor m (SP 1065 eq. 30; D. A. Howe & T. K. Peppler 2003),
/// 0-based, with h = m/2:
///   Theo1(m) = 1/(0.75·(M−m)·(m·τ0)²) · Σ_{i=0}^{M−m−1} Σ_{j=1}^{h} (1/j)·
///              [(x_i − x_{i+j}) + (x_{i+m} − x_{i+m−j})]²
/// (j = m/2 − δ of the SP 1065 form). It estimates the Allan variance at the Thêo1 averaging
/// time τ = 0.75·m·τ0 (not m·τ0), unbiased for white rate noise.
///
/// With @p bias_corrected the SP 1065 Table (Thêo1 bias; Howe & Tasset EFTF 2004, Table 1)
/// correction is applied: AVAR/Theo1 = a + b/t^c with t = 0.75·m (τ in units of τ0) and
/// (a, b, c) = (0.09, 0.74, 0.40) α=+2, (0.14, 0.82, 0.30) α=+1, (1, 0, 0) α=0,
/// (1.87, −1.05, 0.79) α=−1, (2.70, −1.53, 0.85) α=−2; the returned variance is Theo1·that
/// ratio. Without it (default) the value is Stable32's "no bias correction" Thêo1.
///
/// n_terms = (M−m)·m/2, the number of squared brackets summed (Stable32's "Thêo1 #" column,
/// which the tables print in floating-point format but which is this integer).
///
/// Cost O((M−m)·m/2) per m: the inner sum couples x_{i+j} and x_{i+m−j} (an anti-diagonal
/// lag product with weights 1/j), which prefix sums of x and x² cannot reduce; see the .cpp.
/// @param[in] phase  M phase samples
/// @param[in] m      averaging factor, even, 2 ≤ m ≤ M−1 (SP 1065 recommends m ≥ 10)
/// @param[in] tau0_s sample period τ0 > 0 [s]
/// @param[in] bias_corrected apply the noise-type bias removal above
/// @param[in] alpha  power-law exponent of S_y(f) for the bias removal, −2..+2
/// @throws AnalysisError when m > M−1 or alpha is outside −2..+2; ContractViolation on an odd
///   m or m < 2 (the τ grids give even m) or τ0 ≤ 0.
VarianceEstimate theo1_variance(std::span<const double> phase, std::int64_t m, double tau0_s,
                                bool bias_corrected = false, int alpha = 0);

/// Equivalent degrees of freedom of Thêo1 (SP 1065 Table 12, Howe & Peppler 2003), with
/// t = 0.75·m and N = n_phase phase samples:
///   α=+2: 0.86(N+1)(N−4t/3)/(N−t) · t/(t+1.14)
///   α=+1: (4.798N² − 6.374Nt + 12.387t)/(√(t+36.6)·(N−t)) · t/(t+0.3)
///   α= 0: ((4.1N+0.8)/t − (3.1N+6.5)/N) · t^{3/2}/(t^{3/2}+5.2)
///   α=−1: (2N² − 1.3Nt − 3.5t)/(Nt) · t³/(t³+2.3)
///   α=−2: (4.4N−2)/(2.9t) · ((4.4N−1)² − 8.6t(4.4N−1) + 11.4t²)/(4.4N−3)²
/// @throws AnalysisError on alpha outside −2..+2, odd m, m < 2 or m ≥ n_phase, or a
/// non-positive result (the fits are not meant for that corner).
double theo1_edf(int alpha, std::int64_t m, std::int64_t n_phase);
/// @}

/// @name Parabolic and classical variances
/// @{

/// Parabolic variance PVAR (PDEV²), Vernotte et al., "The parabolic variance (PVAR): a
/// wavelet variance based on the least-square fit", IEEE T-UFFC 63(4) 2016, phase form as in
/// SigmaTheta / allantools: for m ≥ 2, with c_k = (m−1)/2 − k and n = M − 2m terms,
///   PVAR(τ) = 72/(n·m⁴·τ²) · Σ_{i=0}^{n−1} [ Σ_{k=0}^{m−1} c_k·(x_{i+k} − x_{i+k+m}) ]²,
/// τ = m·τ0; at m = 1 the weights vanish and PVAR is defined as the overlapping AVAR
/// (n = M − 2), as SigmaTheta does. O(M) per m (sliding-window recursion, see the .cpp).
/// @throws AnalysisError when M < 2m + 1; ContractViolation when m < 1 or τ0 ≤ 0.
VarianceEstimate parabolic_variance(std::span<const double> phase, std::int64_t m, double tau0_s);

/// Sample variance (N−1 normalisation) of the J = ⌊(M−1)/m⌋ non-overlapping m-averages of
/// the rate, ȳ_j = (x_{(j+1)m} − x_{jm})/(m·τ0) — the "standard deviation" rows of the
/// SP 1065 test suite. Not a stability measure (it diverges for flicker and random-walk
/// noise); provided to check against published tables. n_terms = J. O(J).
/// @throws AnalysisError when J < 2; ContractViolation when m < 1 or τ0 ≤ 0.
VarianceEstimate sample_variance_of_averages(std::span<const double> phase, std::int64_t m,
                                             double tau0_s);
/// @}

}  // namespace imunoise::analysis
