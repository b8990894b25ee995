/// @file
/// @brief Internal to the sampling checks (pipeline/sampling_timing.cpp, channel_checks.cpp,
/// lsb_estimate.cpp): the vector lanes of their streaming kernels, the run-time pick of the
/// AVX2 instances, and where a sample is. Not part of the public API
/// (pipeline/sampling_checks.h).
///
/// A 24 h recording at 1 kHz holds 86.4 M samples per channel, far beyond the caches, so the
/// checks cost what they read and the instructions they spend per sample: each pass reads its
/// array once and works in vector registers. Sample i of a pass goes to lane i mod kLanes
/// (independent accumulators: no add-latency chain), and sums are combined in the fixed tree of
/// lane_sum, so they do not depend on the vector width. The vectors are GCC vector types
/// (plain double arrays get vectorised for some of these loops only); each kernel is a
/// template on the vector type, instantiated for SSE2 (2 doubles, the x86-64 baseline) and for
/// AVX2 (4 doubles), picked at run time by the CPU. Both do the same IEEE operations on the
/// same lanes (AVX2 without FMA: no contraction), so the results are bit-identical. Elsewhere
/// than on x86-64 the 2-wide instance serves (GCC and clang map it to NEON and the like).
///
/// The exact scalar code of a check (first locations, runs, gaps) runs only on the blocks of
/// kBlock samples where a vector test finds something for it to do. Each test is conservative:
/// it may send a block to the exact code for nothing, never skip one that matters, so counts
/// and first locations are those of the plain left-to-right scan. The hot loops are small
/// kernels that return at such a block: with no call inside, their lanes stay in registers.
///
/// A 32-byte vector returned by value changes the ABI of a function compiled without AVX
/// (-Wpsabi). The functions that return one are all inlined, their D4 instances into AVX2
/// functions, so the warning says nothing about this code. GCC 12 reports it at three kinds of
/// places: the definition of such a function and a call to one in a kernel template (inside the
/// push / pop regions around the helpers below and around the kernels of each file), and, for
/// the bodies it compiles after parsing, the last token of the file: the `#pragma GCC
/// diagnostic ignored` just before that token in each file covers it, with nothing after it.
/// clang reports the calls only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "pipeline/sampling_checks.h"

namespace imunoise::pipeline::detail {

/// The 0-based INDEX, with its file line when OPTIONS can map it.
inline SampleLocation locate(std::size_t index, const SamplingOptions& options) {
  SampleLocation loc;
  loc.index = static_cast<std::int64_t>(index);
  if (options.line_of_sample) loc.line = options.line_of_sample(index);
  return loc;
}

inline constexpr std::size_t kLanes = 8;  // lanes of a pass
/// Samples per block: the vector test of a block is made before its sums, and one branch per
/// 32 samples costs little (a branch on loaded data every 8 samples slows a pass by ~40 %).
inline constexpr std::size_t kBlock = 4 * kLanes;
inline constexpr double kInf = std::numeric_limits<double>::infinity();

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

using D2 = double __attribute__((vector_size(16)));  // SSE2
using D4 = double __attribute__((vector_size(32)));  // AVX2
using I2 = int __attribute__((vector_size(8)));      // as many ints
using I4 = int __attribute__((vector_size(16)));
template <class D>
struct IntsOf;
template <>
struct IntsOf<D2> {
  using type = I2;
};
template <>
struct IntsOf<D4> {
  using type = I4;
};
template <class D>
inline constexpr std::size_t kWidth = sizeof(D) / sizeof(double);
template <class D>
inline constexpr std::size_t kGroups = kLanes / kWidth<D>;  // vectors per set of lanes
/// Comparison results: per double 0 or −1 (all bits set).
template <class D>
using MaskOf = decltype(D{} < D{});

template <class D>
[[gnu::always_inline]] inline D load(const double* p) {
  D v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// |x|, bit for bit as std::fabs (clears the sign, also of −0).
template <class D>
[[gnu::always_inline]] inline D vabs(const D& x) {
  return (D)((MaskOf<D>)x & std::numeric_limits<std::int64_t>::max());
}

template <class M>
[[gnu::always_inline]] inline bool any(const M& m) {
  std::int64_t bits = 0;
  for (std::size_t j = 0; j < sizeof(M) / sizeof(std::int64_t); ++j) bits |= m[j];
  return bits != 0;
}

/// M ? A : B per lane, as bit operations: GCC lowers a vector ?: whose condition is not a
/// plain comparison to a branch per element on SSE2.
template <class D>
[[gnu::always_inline]] inline D select(const MaskOf<D>& m, const D& a, const D& b) {
  return (D)(((MaskOf<D>)a & m) | ((MaskOf<D>)b & ~m));
}

#pragma GCC diagnostic pop

/// Σ of the lanes in a fixed tree: ((0+4) + (2+6)) + ((1+5) + (3+7)).
inline double lane_sum(const double (&l)[kLanes]) {
  return ((l[0] + l[4]) + (l[2] + l[6])) + ((l[1] + l[5]) + (l[3] + l[7]));
}

// --- Dispatch: the AVX2 instances on CPUs that have it ----------------------------------------

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define IMUNOISE_SAMPLING_AVX2 1

inline bool have_avx2() {
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
}
#endif

}  // namespace imunoise::pipeline::detail
