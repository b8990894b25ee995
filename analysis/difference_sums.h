/// @file
/// @brief Internal kernel of the overlapping Allan and Hadamard variances: the sums of squared
/// second / third differences of phase data at many averaging factors, computed so that the
/// small factors share one cache-resident pass over memory (theory.md §2, "Numerics").
/// Not part of the public analysis API; deviation.cpp is its user, and the estimators whose
/// value at m = 1 is OAVAR or OHVAR (PDEV, HTOTDEV) call lag_one_overlapping_variance.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace imunoise::analysis::detail {

/// Block length of every difference sum: each sum is Σ over blocks [j·kDifferenceBlock,
/// (j+1)·kDifferenceBlock) of a plain (vectorised) block sum, the blocks added in order with
/// Neumaier compensation. The blocking is fixed, so a sum does not depend on which other
/// factors were computed with it, nor on the thread that computed it.
inline constexpr std::int64_t kDifferenceBlock = 2048;

/// S(m) = Σ_{k=0}^{M−order·m−1} (Δ^order_m x)_k² for ORDER 2 (x_{k+2m} − 2x_{k+m} + x_k, the
/// OAVAR sum) or 3 (x_{k+3m} − 3x_{k+2m} + 3x_{k+m} − x_k, the OHVAR sum), for every m of
/// M_VALUES (each with M − order·m ≥ 1), written to SUMS (same size). The factors whose
/// differences span at most kSharedPassSpan samples are evaluated together, block by block,
/// while the block and its span stay in cache: the array is read from memory once for all of
/// them. The larger factors take one pass per kLargePassFactors consecutive factors.
/// @throws ContractViolation for another ORDER, sizes that differ or a factor without a term.
void overlapping_difference_sums(std::span<const double> x, int order,
                                 std::span<const std::int64_t> m_values, std::span<double> sums);

/// Samples a difference of the shared pass may span (order·m): 768 KiB of float64, which
/// stays in a core's L2 cache (1 MiB here) together with one block. Chosen by
/// bench/deviation_bench.cpp: 256 KiB and 1 MiB spans were 10–30 % slower (bench/RESULTS.md).
inline constexpr std::int64_t kSharedPassSpan = 98304;

/// Factors beyond the shared span evaluated together in one block-by-block pass. Their
/// differences reach past the cache, so every factor still streams its own x_{k+m}, x_{k+2m}
/// (…), but the group reads x_k once and the passes over memory are shared: on 86.4 M samples
/// (24 h at 1 kHz), one pass per factor took 3.5–3.9 s for the 27 large OAVAR factors of the
/// log:10 grid; groups of 4 / 8 / 12 / 16 took 0.72 / 0.64 / 0.61 / 0.68 of that, and 0.71 /
/// 0.68 / 0.69 / 0.70 for the 28 OHVAR factors (bench/RESULTS.md).
inline constexpr std::size_t kLargePassFactors = 8;

/// The OAVAR and OHVAR sums at the same factors, both from one pass: for every m of M_VALUES
/// (each with M − 3m ≥ 1), OAVAR_SUMS[i] = S(m) of order 2 and OHVAR_SUMS[i] = S(m) of order
/// 3, bit for bit what overlapping_difference_sums gives for each order (same blocks, lanes
/// and additions), but x_k … x_{k+3m} are read once for both: 4 streams instead of 7. The
/// factors with 3m ≤ kSharedPassSpan share one cache-resident pass, the larger ones take one
/// pass per kLargeJointPassFactors. @throws ContractViolation as overlapping_difference_sums().
void allan_hadamard_difference_sums(std::span<const double> x,
                                    std::span<const std::int64_t> m_values,
                                    std::span<double> oavar_sums, std::span<double> ohvar_sums);

/// Large factors per pass of allan_hadamard_difference_sums (3 own streams each).
inline constexpr std::size_t kLargeJointPassFactors = 8;

/// OAVAR (ORDER 2) or OHVAR (ORDER 3) from its difference sum SUM over N_TERMS terms at factor
/// M: SUM / (c·τ²·N_TERMS), c = 2 or 6, τ = m·τ0 (theory.md §2).
inline double overlapping_variance_of_sum(int order, double sum, std::int64_t n_terms,
                                          std::int64_t m, double tau0_s) {
  const double tau = static_cast<double>(m) * tau0_s;
  return sum / ((order == 2 ? 2.0 : 6.0) * tau * tau * static_cast<double>(n_terms));
}

/// OAVAR (ORDER 2) or OHVAR (ORDER 3) of X at m = 1 (M − ORDER terms, M − ORDER ≥ 1 and τ0
/// checked by the caller): bit for bit allan_family_variance(oadev / ohdev, X, 1, τ0).
inline double lag_one_overlapping_variance(std::span<const double> x, int order, double tau0_s) {
  const std::int64_t one = 1;
  double sum = 0.0;
  overlapping_difference_sums(x, order, std::span(&one, 1), std::span(&sum, 1));
  return overlapping_variance_of_sum(order, sum, static_cast<std::int64_t>(x.size()) - order, 1,
                                     tau0_s);
}

}  // namespace imunoise::analysis::detail
