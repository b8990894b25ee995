#include "analysis/difference_sums.h"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "analysis/kernel_support.h"
#include "common/errors.h"

// The kernels are compiled three times on x86-64 GCC/clang: for the baseline ISA, x86-64-v3
// (AVX2 + FMA) and x86-64-v4 (AVX-512), picked at load time by the CPU. On one machine every
// call takes the same clone, so results do not depend on thread counts; across machines they
// may differ in the last bits (FMA contraction), well inside every tolerance of theory.md §2.
// The v4 clone gave the same sums as v3 on the bench machine and took 0.6–1.0× its time
// (86.4 M samples, log:10 grid; noisy shared VM).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define IMUNOISE_KERNEL_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define IMUNOISE_KERNEL_CLONES
#endif

namespace imunoise::analysis::detail {

namespace {

template <int Order>
[[gnu::always_inline]] inline double difference(const double* x, std::int64_t k, std::int64_t m) {
  if constexpr (Order == 2) {
    return x[k + 2 * m] - 2.0 * x[k + m] + x[k];
  } else {
    return x[k + 3 * m] - 3.0 * x[k + 2 * m] + 3.0 * x[k + m] - x[k];
  }
}

/// Σ_{k=begin}^{end−1} difference², in 16 interleaved partial sums (lane (k−begin) mod 16):
/// independent add chains hide the FMA latency (4 AVX2 registers of 4 lanes, or 8 SSE2 ones);
/// the lanes are combined in a fixed tree, so the result does not depend on the vector width.
template <int Order>
[[gnu::always_inline]] inline double block_sum(const double* x, std::int64_t m, std::int64_t begin,
                                               std::int64_t end) {
  constexpr int kLanes = 16;
  double lane[kLanes] = {};
  std::int64_t k = begin;
  for (; k + kLanes <= end; k += kLanes) {
    for (int l = 0; l < kLanes; ++l) {
      const double d = difference<Order>(x, k + l, m);
      lane[l] += d * d;
    }
  }
  double tail = 0.0;
  for (; k < end; ++k) {
    const double d = difference<Order>(x, k, m);
    tail += d * d;
  }
  for (int width = kLanes / 2; width >= 1; width /= 2) {
    for (int l = 0; l < width; ++l) lane[l] += lane[l + width];
  }
  return lane[0] + tail;
}

/// The sums of FACTORS (ascending) over one pass: block by block, every factor in turn.
/// Inlined into each clone below, so that the whole loop nest gets that clone's ISA.
template <int Order>
[[gnu::always_inline]] inline void shared_pass(const double* x, std::int64_t M,
                                               const std::int64_t* factors, std::size_t count,
                                               CompensatedSum* totals) {
  const std::int64_t longest = M - Order * factors[0];  // terms of the smallest factor
  for (std::int64_t begin = 0; begin < longest; begin += kDifferenceBlock) {
    for (std::size_t i = 0; i < count; ++i) {
      const std::int64_t n = M - Order * factors[i];
      if (begin >= n) break;  // ascending factors: the rest have fewer terms still
      totals[i].add(block_sum<Order>(x, factors[i], begin, std::min(n, begin + kDifferenceBlock)));
    }
  }
}

/// Both block sums of one block at factor m, bit for bit block_sum<2> and block_sum<3>: the
/// same difference expressions, lanes and reduction tree, but x_k, x_{k+m} and x_{k+2m} are
/// loaded once for the two orders (4 streams instead of 7).
[[gnu::always_inline]] inline void joint_block_sum(const double* x, std::int64_t m,
                                                   std::int64_t begin, std::int64_t end,
                                                   double& sum2, double& sum3) {
  constexpr int kLanes = 16;
  double lane2[kLanes] = {};
  double lane3[kLanes] = {};
  std::int64_t k = begin;
  for (; k + kLanes <= end; k += kLanes) {
    for (int l = 0; l < kLanes; ++l) {
      const double d2 = difference<2>(x, k + l, m);
      const double d3 = difference<3>(x, k + l, m);
      lane2[l] += d2 * d2;
      lane3[l] += d3 * d3;
    }
  }
  double tail2 = 0.0;
  double tail3 = 0.0;
  for (; k < end; ++k) {
    const double d2 = difference<2>(x, k, m);
    const double d3 = difference<3>(x, k, m);
    tail2 += d2 * d2;
    tail3 += d3 * d3;
  }
  for (int width = kLanes / 2; width >= 1; width /= 2) {
    for (int l = 0; l < width; ++l) {
      lane2[l] += lane2[l + width];
      lane3[l] += lane3[l + width];
    }
  }
  sum2 = lane2[0] + tail2;
  sum3 = lane3[0] + tail3;
}

/// shared_pass for both orders at once. A block both orders cover in full goes through
/// joint_block_sum; the last blocks of a factor (where the order-3 range ends first) go
/// through the single-order block sums, so every block sum, and so every total, is the one
/// shared_pass<2> and shared_pass<3> give.
[[gnu::always_inline]] inline void joint_shared_pass(const double* x, std::int64_t M,
                                                     const std::int64_t* factors, std::size_t count,
                                                     CompensatedSum* totals2,
                                                     CompensatedSum* totals3) {
  const std::int64_t longest = M - 2 * factors[0];
  for (std::int64_t begin = 0; begin < longest; begin += kDifferenceBlock) {
    for (std::size_t i = 0; i < count; ++i) {
      const std::int64_t m = factors[i];
      const std::int64_t n2 = M - 2 * m;
      if (begin >= n2) break;  // ascending factors: the rest have fewer terms still
      const std::int64_t n3 = M - 3 * m;
      const std::int64_t end2 = std::min(n2, begin + kDifferenceBlock);
      if (end2 <= n3) {
        double sum2 = 0.0;
        double sum3 = 0.0;
        joint_block_sum(x, m, begin, end2, sum2, sum3);
        totals2[i].add(sum2);
        totals3[i].add(sum3);
        continue;
      }
      totals2[i].add(block_sum<2>(x, m, begin, end2));
      if (begin < n3) totals3[i].add(block_sum<3>(x, m, begin, std::min(n3, end2)));
    }
  }
}

IMUNOISE_KERNEL_CLONES
void joint_shared_pass_clone(const double* x, std::int64_t M, const std::int64_t* factors,
                             std::size_t count, CompensatedSum* totals2, CompensatedSum* totals3) {
  joint_shared_pass(x, M, factors, count, totals2, totals3);
}

IMUNOISE_KERNEL_CLONES
void shared_pass_clone(const double* x, std::int64_t M, int order, const std::int64_t* factors,
                       std::size_t count, CompensatedSum* totals) {
  if (order == 2) {
    shared_pass<2>(x, M, factors, count, totals);
  } else {
    shared_pass<3>(x, M, factors, count, totals);
  }
}

/// FACTORS (ascending) of M_VALUES, and where each came from: factors[i] = m_values[from[i]].
/// Duplicates are computed once each (cheap, and keeps the code plain).
struct AscendingFactors {
  std::vector<std::size_t> from;
  std::vector<std::int64_t> factors;
};

AscendingFactors ascending_factors(std::span<const std::int64_t> m_values) {
  AscendingFactors out{ascending_order(m_values), std::vector<std::int64_t>(m_values.size())};
  for (std::size_t i = 0; i < out.from.size(); ++i) out.factors[i] = m_values[out.from[i]];
  return out;
}

/// Calls PASS(first, count) once per pass over memory for FACTORS (ascending): one pass for
/// every factor whose difference span SPAN_ORDER·m fits kSharedPassSpan (they stay in cache
/// together), then one per run of at most GROUP larger factors: their spans exceed the cache,
/// so each still reads its own streams, but x_k is read once for the run and the far streams
/// of neighbouring factors are fetched together (difference_sums.h). The fixed blocks make
/// the grouping invisible in the sums.
template <class Pass>
void for_each_pass(const std::vector<std::int64_t>& factors, int span_order, std::size_t group,
                   Pass&& pass) {
  const auto shared = static_cast<std::size_t>(
      std::upper_bound(factors.begin(), factors.end(), kSharedPassSpan / span_order) -
      factors.begin());
  if (shared > 0) pass(std::size_t{0}, shared);
  for (std::size_t i = shared; i < factors.size(); i += group) {
    pass(i, std::min(group, factors.size() - i));
  }
}

}  // namespace

void overlapping_difference_sums(std::span<const double> x, int order,
                                 std::span<const std::int64_t> m_values, std::span<double> sums) {
  IMUNOISE_EXPECT(order == 2 || order == 3, "difference order must be 2 or 3");
  IMUNOISE_EXPECT(sums.size() == m_values.size(), "one sum per factor");
  const auto M = static_cast<std::int64_t>(x.size());
  for (std::int64_t m : m_values) {
    IMUNOISE_EXPECT(m >= 1 && M - order * m >= 1, "factor without a term");
  }
  const AscendingFactors sorted = ascending_factors(m_values);
  std::vector<CompensatedSum> totals(sorted.factors.size());
  for_each_pass(sorted.factors, order, kLargePassFactors, [&](std::size_t i, std::size_t count) {
    shared_pass_clone(x.data(), M, order, &sorted.factors[i], count, &totals[i]);
  });
  for (std::size_t i = 0; i < sorted.from.size(); ++i) sums[sorted.from[i]] = totals[i].value();
}

void allan_hadamard_difference_sums(std::span<const double> x,
                                    std::span<const std::int64_t> m_values,
                                    std::span<double> oavar_sums, std::span<double> ohvar_sums) {
  IMUNOISE_EXPECT(oavar_sums.size() == m_values.size() && ohvar_sums.size() == m_values.size(),
                  "one sum of each order per factor");
  const auto M = static_cast<std::int64_t>(x.size());
  for (std::int64_t m : m_values) {
    IMUNOISE_EXPECT(m >= 1 && M - 3 * m >= 1, "factor without a third difference");
  }
  const AscendingFactors sorted = ascending_factors(m_values);
  std::vector<CompensatedSum> totals2(sorted.factors.size());
  std::vector<CompensatedSum> totals3(sorted.factors.size());
  // The third difference spans 3m: that decides which factors stay in cache together.
  for_each_pass(sorted.factors, 3, kLargeJointPassFactors, [&](std::size_t i, std::size_t count) {
    joint_shared_pass_clone(x.data(), M, &sorted.factors[i], count, &totals2[i], &totals3[i]);
  });
  for (std::size_t i = 0; i < sorted.from.size(); ++i) {
    oavar_sums[sorted.from[i]] = totals2[i].value();
    ohvar_sums[sorted.from[i]] = totals3[i].value();
  }
}

}  // namespace imunoise::analysis::detail
