/// @file
/// @brief Internal kernel of the overlapping Allan and Hadamard variances: the sums of squared
/// second / third differences of phase data at many averaging factors, computed so that the
/// small factors share one cache-resident pass over memory (theory.md §2, "Numerics").
/// Not part of the public analysis API; deviation.cpp is its user.
#pragma once

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
/// them. The larger factors each take their own pass.
void overlapping_difference_sums(std::span<const double> x, int order,
                                 std::span<const std::int64_t> m_values, std::span<double> sums);

/// Samples a difference of the shared pass may span (order·m): 768 KiB of float64, which
/// stays in a core's L2 cache (1 MiB here) together with one block. Chosen by
/// bench/deviation_bench.cpp: 256 KiB and 1 MiB spans were 10–30 % slower (bench/RESULTS.md).
inline constexpr std::int64_t kSharedPassSpan = 98304;

}  // namespace imunoise::analysis::detail
