/// @file
/// @brief Internal helpers shared by the deviation kernels (deviation.cpp, total_family.cpp,
/// extra_deviations.cpp): compensated summation and the sample-period check. Not part of
/// the public analysis API.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <span>
#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::analysis::detail {

/// Neumaier (improved Kahan) accumulator: the running error term keeps the sum exact to
/// about one rounding of the result however many values are added (theory.md §2 "Numerics").
struct CompensatedSum {
  double sum = 0.0;
  double carry = 0.0;
  void add(double v) {
    const double t = sum + v;
    carry += std::abs(sum) >= std::abs(v) ? (sum - t) + v : (v - t) + sum;
    sum = t;
  }
  double value() const { return sum + carry; }
};

/// Σ_{k<n} term(k): plain (vectorisable) sums over short blocks, blocks added with
/// compensation. Error ≈ kBlock·ε relative instead of n·ε: full precision at 10^8 terms.
template <class Term>
double blocked_sum(std::int64_t n, Term&& term) {
  constexpr std::int64_t kBlock = 2048;
  CompensatedSum total;
  for (std::int64_t start = 0; start < n; start += kBlock) {
    const std::int64_t end = std::min(n, start + kBlock);
    double block = 0.0;
#pragma omp simd reduction(+ : block)
    for (std::int64_t k = start; k < end; ++k) block += term(k);
    total.add(block);
  }
  return total.value();
}

/// Indices of VALUES in ascending order of value, equal values in their given order (the
/// order the difference-sum kernels visit averaging factors in).
inline std::vector<std::size_t> ascending_order(std::span<const std::int64_t> values) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  return order;
}

/// Throws ContractViolation "<where>sample period tau0 must be positive and finite, got …" (the
/// callers validated τ0: the recording's period, `allan --tau0`).
inline void check_sample_period(double tau0_s, const std::string& where = "") {
  IMUNOISE_EXPECT(
      tau0_s > 0.0 && std::isfinite(tau0_s),
      where + "sample period tau0 must be positive and finite, got " + std::to_string(tau0_s));
}

}  // namespace imunoise::analysis::detail
