#include "pipeline/sampling_checks.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <limits>

#include "common/parallel_for.h"
#include "common/sampling_gap.h"
#include "common/units.h"

namespace imunoise::pipeline {

namespace {

SampleLocation locate(std::size_t index, const SamplingOptions& options) {
  SampleLocation loc;
  loc.index = static_cast<std::int64_t>(index);
  if (options.line_of_sample) loc.line = options.line_of_sample(index);
  return loc;
}

/// The median of V, reordering V (nth_element): callers that need the order keep their own.
double median_in_place(std::vector<double>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  // Even count: mean of the two middle values; the lower one is the max of the left half.
  const double upper = *mid;
  const double lower = *std::max_element(v.begin(), mid);
  return 0.5 * (lower + upper);
}

/// Euclid's algorithm on reals with a relative tolerance: stops when the remainder is within
/// 10 % of the divisor, which absorbs decimal printing and float rounding of scaled codes.
double approximate_gcd(double a, double b) {
  if (a < b) std::swap(a, b);
  for (int i = 0; i < 64 && b > 0.0; ++i) {
    const double r = std::fabs(a - b * std::nearbyint(a / b));
    if (r <= 0.1 * b) return b;
    a = b;
    b = r;
  }
  return 0.0;
}

// --- Streaming kernels ------------------------------------------------------------------------
//
// A 24 h recording at 1 kHz holds 86.4 M samples per channel, far beyond the caches, so the
// checks cost what they read and the instructions they spend per sample: each pass below reads
// its array once and works in vector registers. Sample i of a pass goes to lane i mod kLanes
// (independent accumulators: no add-latency chain), and sums are combined in the fixed tree of
// lane_sum, so they do not depend on the vector width. The vectors are GCC vector types
// (plain double arrays get vectorised for some of these loops only); each kernel is a
// template on the vector type, instantiated for SSE2 (2 doubles, the x86-64 baseline) and for
// AVX2 (4 doubles), picked at run time by the CPU. Both do the same IEEE operations on the
// same lanes (AVX2 without FMA: no contraction), so the results are bit-identical. Elsewhere
// than on x86-64 the 2-wide instance serves (GCC and clang map it to NEON and the like).
//
// The exact scalar code of a check (first locations, runs, gaps) runs only on the blocks of
// kBlock samples where a vector test finds something for it to do. Each test is conservative:
// it may send a block to the exact code for nothing, never skip one that matters, so counts
// and first locations are those of the plain left-to-right scan. The hot loops are small
// kernels that return at such a block: with no call inside, their lanes stay in registers.

constexpr std::size_t kLanes = 8;  // lanes of a pass
/// Samples per block: the vector test of a block is made before its sums, and one branch per
/// 32 samples costs little (a branch on loaded data every 8 samples slows a pass by ~40 %).
constexpr std::size_t kBlock = 4 * kLanes;
constexpr double kInf = std::numeric_limits<double>::infinity();
/// x + kRoundMagic − kRoundMagic rounds x to an integer (to nearest, ties to even, like
/// std::nearbyint in the default rounding mode) for 0 ≤ x < 2^51, without SSE4.1.
constexpr double kRoundMagic = 0x1.8p52;

// A 32-byte vector passed by value changes the ABI of a function compiled without AVX
// (-Wpsabi). The kernels taking them are all inlined, their D4 instances into AVX2 functions;
// GCC instantiates templates at the end of the file, so the warning is off from here on.
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
constexpr std::size_t kWidth = sizeof(D) / sizeof(double);
template <class D>
constexpr std::size_t kGroups = kLanes / kWidth<D>;  // vectors per set of lanes
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

/// Σ of the lanes in a fixed tree: ((0+4) + (2+6)) + ((1+5) + (3+7)).
double lane_sum(const double (&l)[kLanes]) {
  return ((l[0] + l[4]) + (l[2] + l[6])) + ((l[1] + l[5]) + (l[3] + l[7]));
}

/// The smallest step |v[i] − v[i−1]| above a floor, and how many steps are above it.
struct StepStats {
  double q0 = kInf;
  std::int64_t steps = 0;

  void add(double d, double floor) {
    if (d > floor) {
      q0 = std::min(q0, d);
      ++steps;
    }
  }
};

/// Vector accumulators of StepStats. A minimum and a count do not depend on the order, so
/// fewer accumulators than lanes do (registers are scarce: 16 of them).
template <class D>
struct StepLanes {
  D q0[2] = {(D{} + kInf), (D{} + kInf)};
  MaskOf<D> steps = {};

  /// The steps into X (samples) from P (their predecessors); G alternates the minima.
  [[gnu::always_inline]] void add(const D& x, const D& p, double floor, std::size_t g) {
    const D d = vabs(x - p);
    const MaskOf<D> take = d > floor;
    const D candidate = d + (D)(~take & (MaskOf<D>)(D{} + kInf));  // d, or inf
    q0[g % 2] = candidate < q0[g % 2] ? candidate : q0[g % 2];
    steps -= take;
  }
  /// Adds the lanes to S.
  [[gnu::always_inline]] void add_to(StepStats& s) const {
    for (const D& m : q0) {
      for (std::size_t j = 0; j < kWidth<D>; ++j) s.q0 = std::min(s.q0, m[j]);
    }
    for (std::size_t j = 0; j < kWidth<D>; ++j) s.steps += steps[j];
  }
};

/// The steps of V above FLOOR (a pass of their own: see steps_above).
StepStats step_stats(std::span<const double> v, double floor) {
  const std::size_t n = v.size();
  StepLanes<D2> lanes;
  std::size_t i = 1;
  for (; i + kLanes <= n; i += kLanes) {
    for (std::size_t g = 0; g < kGroups<D2>; ++g) {
      const double* x = &v[i + g * kWidth<D2>];
      lanes.add(load<D2>(x), load<D2>(x - 1), floor, g);
    }
  }
  StepStats s;
  for (; i < n; ++i) s.add(std::fabs(v[i] - v[i - 1]), floor);
  lanes.add_to(s);
  return s;
}

/// Pass 1 over a channel's samples: the extremes, the sum and the nonzero steps.
struct Extremes {
  double lo = 0.0, hi = 0.0, sum = 0.0;
  StepStats nonzero_steps;
};

/// lo and hi are what a left-to-right std::min / std::max fold from v[0] gives: the first of
/// equal extremes, which only the sign of a zero can tell apart (a NaN in v[0] would stay;
/// later NaNs are skipped). sum: sample i in lane i mod kLanes, then lane_sum. V is not empty.
template <class D>
[[gnu::always_inline]] inline Extremes extremes_of(std::span<const double> v) {
  constexpr std::size_t W = kWidth<D>;
  const std::size_t n = v.size();
  Extremes e;
  e.lo = e.hi = v[0];
  double sum[kLanes] = {};
  const auto scalar = [&](std::size_t i) {
    e.lo = std::min(e.lo, v[i]);
    e.hi = std::max(e.hi, v[i]);
    sum[i % kLanes] += v[i];
    if (i > 0) e.nonzero_steps.add(std::fabs(v[i] - v[i - 1]), 0.0);
  };
  std::size_t i = 0;
  for (; i < std::min(n, kLanes); ++i) scalar(i);  // v[0] has no predecessor
  if (i + kLanes <= n) {
    D lo[2] = {(D{} + v[0]), (D{} + v[0])}, hi[2] = {lo[0], lo[0]}, s[kGroups<D>];
    std::memcpy(s, sum, sizeof s);
    StepLanes<D> steps;
    for (; i + kLanes <= n; i += kLanes) {
      for (std::size_t g = 0; g < kGroups<D>; ++g) {
        const double* p = &v[i + g * W];
        const D x = load<D>(p);
        lo[g % 2] = x < lo[g % 2] ? x : lo[g % 2];
        hi[g % 2] = hi[g % 2] < x ? x : hi[g % 2];
        s[g] += x;
        steps.add(x, load<D>(p - 1), 0.0, g);
      }
    }
    for (std::size_t j = 0; j < 2 * W; ++j) {
      e.lo = std::min(e.lo, lo[j / W][j % W]);
      e.hi = std::max(e.hi, hi[j / W][j % W]);
    }
    std::memcpy(sum, s, sizeof s);
    steps.add_to(e.nonzero_steps);
  }
  for (; i < n; ++i) scalar(i);
  // The lanes lose which of +0 and −0 came first; the fold keeps the first zero.
  if (e.lo == 0.0) e.lo = *std::find(v.begin(), v.end(), 0.0);
  if (e.hi == 0.0) e.hi = *std::find(v.begin(), v.end(), 0.0);
  e.sum = lane_sum(sum);
  return e;
}

/// The steps above NOISE_FLOOR: those of pass 1 when its smallest nonzero step is above the
/// floor (the usual case: the floor is 1e-12 of the scale), else a pass of their own.
StepStats steps_above(std::span<const double> v, const Extremes& e, double noise_floor) {
  return e.nonzero_steps.q0 > noise_floor ? e.nonzero_steps : step_stats(v, noise_floor);
}

// --- Quantization step (estimate_lsb) ---------------------------------------------------------

constexpr double kMaxLevels = 16777216.0;  // 2^24: no IMU ADC has a finer code grid
constexpr double kTolerance = 0.1;         // |step − k·q| allowed, as a fraction of q
constexpr std::size_t kMaxSmallSteps = 4096;

/// What the LSB search takes from the extremes.
struct LsbBounds {
  double range = 0.0;
  double noise_floor = 0.0;  ///< steps below this are float rounding of equal codes
  bool usable = false;       ///< a positive, finite range
};

LsbBounds lsb_bounds(double lo, double hi) {
  LsbBounds b;
  b.range = hi - lo;
  b.usable = b.range > 0.0 && std::isfinite(b.range);
  b.noise_floor = std::max(std::fabs(lo), std::fabs(hi)) * 1e-12;
  return b;
}

/// The first kMaxSmallSteps steps in (noise_floor, limit], in order. Blocks without one are
/// skipped by a vector test: with unquantised data few steps qualify, and the scan reads the
/// whole array.
std::vector<double> small_steps(std::span<const double> v, double noise_floor, double limit) {
  const std::size_t n = v.size();
  std::vector<double> small;
  const auto exact = [&](std::size_t i) {
    const double d = std::fabs(v[i] - v[i - 1]);
    if (d > noise_floor && d <= limit) small.push_back(d);
  };
  std::size_t i = 1;
  for (; i + kLanes <= n && small.size() < kMaxSmallSteps; i += kLanes) {
    MaskOf<D2> hit = {};
    for (std::size_t g = 0; g < kGroups<D2>; ++g) {
      const double* x = &v[i + g * kWidth<D2>];
      const D2 d = vabs(load<D2>(x) - load<D2>(x - 1));
      hit |= (d > noise_floor) & (d <= limit);
    }
    if (!any(hit)) continue;
    for (std::size_t j = i; j < i + kLanes && small.size() < kMaxSmallSteps; ++j) exact(j);
  }
  for (; i < n && small.size() < kMaxSmallSteps; ++i) exact(i);
  return small;
}

bool is_multiple(double d, double q) {
  const double k = std::nearbyint(d / q);
  return k >= 1.0 && std::fabs(d - k * q) <= kTolerance * q;
}

/// The step into sample I if it is above the noise floor and not a multiple of Q, else 0.
double offending_step(std::span<const double> v, std::size_t i, double noise_floor, double q) {
  const double d = std::fabs(v[i] - v[i - 1]);
  return d > noise_floor && !is_multiple(d, q) ? d : 0.0;
}

/// The vector test of the steps against a grid q: a step passes when k = round(d · (1/q)) ≥ 1
/// and |d − k·q| ≤ 0.09·q. A pass implies is_multiple: |d/q − k| ≤ 0.09 + 2^-13 (the rounding
/// of k·q for k < 2^40), so nearbyint(d / q) is the same k and |d − k·q| is within 10 % of q.
/// Steps that fail it go through is_multiple itself.
struct GridTest {
  double noise_floor, q, inv, tolerance;
};

/// The test for Q, or empty where it does not hold: every step is at most RANGE, so every
/// d·(1/q) < 2^40 (where kRoundMagic rounds exactly).
std::optional<GridTest> grid_test(double noise_floor, double q, double range) {
  const double inv = 1.0 / q;
  if (!(std::isfinite(inv) && range * inv < 0x1p40)) return std::nullopt;
  return GridTest{noise_floor, q, inv, 0.09 * q};
}

/// The steps D (|v[i] − v[i−1]|) above the noise floor that fail the test.
template <class D>
[[gnu::always_inline]] inline MaskOf<D> off_grid(const D& d, const GridTest& t) {
  const D k = (d * t.inv + kRoundMagic) - kRoundMagic;
  const MaskOf<D> fits = (k >= 1.0) & (vabs(d - k * t.q) <= t.tolerance);
  return (d > t.noise_floor) & ~fits;
}

/// The first step above the noise floor that is not a multiple of Q (is_multiple), or 0.
/// Blocks whose steps all pass GridTest are skipped.
template <class D>
[[gnu::always_inline]] inline double first_offender_of(std::span<const double> v,
                                                       double noise_floor, double q, double range) {
  const std::size_t n = v.size();
  const std::optional<GridTest> test = grid_test(noise_floor, q, range);
  std::size_t i = 1;
  for (; i + kBlock <= n; i += kBlock) {
    if (test) {
      MaskOf<D> bad = {};
      for (std::size_t j = i; j < i + kBlock; j += kWidth<D>) {
        bad |= off_grid(vabs(load<D>(&v[j]) - load<D>(&v[j - 1])), *test);
      }
      if (!any(bad)) continue;
    }
    for (std::size_t j = i; j < i + kBlock; ++j) {
      if (const double d = offending_step(v, j, noise_floor, q); d != 0.0) return d;
    }
  }
  for (; i < n; ++i) {
    if (const double d = offending_step(v, i, noise_floor, q); d != 0.0) return d;
  }
  return 0.0;
}

// --- Channel pass 2 (analyze_channel) ---------------------------------------------------------

/// What pass 2 compares the samples with. A sample outside (quiet_lo, quiet_hi) makes its
/// block "loud": the run and full-scale scan has work there (see analyze_channel).
struct ChannelMarks {
  double mean, quiet_lo, quiet_hi;
};

/// Pass 2 over the whole blocks from I (a multiple of kLanes, ≥ kLanes) on: adds Σ(v − mean)²
/// of them to the lanes SUM_SQ, up to the first loud block (not added). Returns that block's
/// start, or the first i with i + kBlock > n. With kGrid, a step that fails GRID also makes its
/// block loud: the offender scan of estimate_lsb rides along.
template <class D, bool kGrid>
[[gnu::always_inline]] inline std::size_t channel_blocks_of(const double* v, std::size_t i,
                                                            std::size_t n, const ChannelMarks& k,
                                                            const GridTest* grid,
                                                            double (&sum_sq)[kLanes]) {
  D sum[kGroups<D>];
  std::memcpy(sum, sum_sq, sizeof sum);
  const double mean = k.mean, quiet_lo = k.quiet_lo, quiet_hi = k.quiet_hi;
  for (; i + kBlock <= n; i += kBlock) {
    MaskOf<D> quiet = ~MaskOf<D>{};
    for (std::size_t j = i; j < i + kBlock; j += kWidth<D>) {
      const D x = load<D>(v + j);
      quiet &= (x > quiet_lo) & (x < quiet_hi);
      if (kGrid) quiet &= ~off_grid(vabs(x - load<D>(v + j - 1)), *grid);
    }
    if (any(~quiet)) break;
    for (std::size_t j = i; j < i + kBlock; j += kLanes) {
      for (std::size_t g = 0; g < kGroups<D>; ++g) {
        const D dev = load<D>(v + j + g * kWidth<D>) - mean;
        sum[g] += dev * dev;
      }
    }
  }
  std::memcpy(sum_sq, sum, sizeof sum);
  return i;
}

// --- Time stamps (analyze_timing) -------------------------------------------------------------

/// Intervals of at least this many stamps take their median from sampled_median.
constexpr std::size_t kSampledMedianMin = std::size_t{1} << 16;

/// The counting pass of sampled_median: how many of the M intervals of T are < a, ≤ a, < b and
/// ≤ b (COUNTS), and the ones strictly between a and b (into BETWEEN, KEPT of them). False
/// when they would not fit in CAPACITY.
template <class D>
[[gnu::always_inline]] inline bool bracket_pass_of(const double* t, std::size_t m, double a,
                                                   double b, double* between, std::size_t capacity,
                                                   std::size_t& kept, std::size_t (&counts)[4]) {
  using M = MaskOf<D>;
  M lt_a = {}, le_a = {}, le_b = {};  // counts: the order does not matter
  std::size_t n_kept = 0;
  std::size_t i = 0;
  for (; i + kBlock <= m; i += kBlock) {
    M any_inside = {};
    for (std::size_t j = i; j < i + kBlock; j += kWidth<D>) {
      const D d = load<D>(t + j + 1) - load<D>(t + j);
      lt_a -= d < a;
      le_a -= d <= a;
      le_b -= d <= b;
      any_inside |= (d > a) & (d < b);
    }
    if (!any(any_inside)) continue;
    if (n_kept + kBlock > capacity) return false;
    for (std::size_t j = i; j < i + kBlock; j += kLanes) {  // the kept ones are few
      D d[kGroups<D>];
      M inside[kGroups<D>], some = {};
      for (std::size_t g = 0; g < kGroups<D>; ++g) {
        const double* p = t + j + g * kWidth<D>;
        d[g] = load<D>(p + 1) - load<D>(p);
        inside[g] = (d[g] > a) & (d[g] < b);
        some |= inside[g];
      }
      if (!any(some)) continue;
      for (std::size_t l = 0; l < kLanes; ++l) {  // without branches
        between[n_kept] = d[l / kWidth<D>][l % kWidth<D>];
        n_kept += inside[l / kWidth<D>][l % kWidth<D>] != 0;
      }
    }
  }
  std::size_t below_a = 0, upto_a = 0, upto_b = 0;
  for (; i < m; ++i) {
    const double d = t[i + 1] - t[i];
    below_a += d < a;
    upto_a += d <= a;
    upto_b += d <= b;
    if (!(a < d && d < b)) continue;
    if (n_kept == capacity) return false;
    between[n_kept++] = d;
  }
  for (std::size_t j = 0; j < kWidth<D>; ++j) {
    below_a += static_cast<std::size_t>(lt_a[j]);
    upto_a += static_cast<std::size_t>(le_a[j]);
    upto_b += static_cast<std::size_t>(le_b[j]);
  }
  counts[0] = below_a;
  counts[1] = upto_a;
  counts[2] = a < b ? upto_a + n_kept : below_a;  // below b: ≤ a, or strictly between
  counts[3] = upto_b;
  kept = n_kept;
  return true;
}

/// Σ(d − median)² of the regular intervals (0 < d ≤ gap limit; interval i in lane i mod
/// kLanes), and the smallest and largest of them. max |d − median| is not kept: d − median
/// rounds monotonically in d, so the largest |d − median| is that of the smallest or the
/// largest d.
struct JitterSums {
  double sum_sq[kLanes] = {};
  double lo = kInf, hi = -kInf;
};

/// The whole blocks from I (a multiple of kLanes) on whose intervals are all regular, into
/// SUMS. Returns the start of the first block with another interval (not added), or the first
/// i with i + kBlock > m.
template <class D>
[[gnu::always_inline]] inline std::size_t regular_blocks_of(const double* t, std::size_t i,
                                                            std::size_t m, double median,
                                                            double gap_limit, JitterSums& sums) {
  D sum[kGroups<D>], lo[2] = {(D{} + sums.lo), (D{} + sums.lo)},
                     hi[2] = {(D{} + sums.hi), (D{} + sums.hi)};
  std::memcpy(sum, sums.sum_sq, sizeof sum);
  for (; i + kBlock <= m; i += kBlock) {
    MaskOf<D> regular = ~MaskOf<D>{};
    for (std::size_t j = i; j < i + kBlock; j += kWidth<D>) {
      const D d = load<D>(t + j + 1) - load<D>(t + j);
      regular &= (d > 0.0) & (d <= gap_limit);
    }
    if (any(~regular)) break;
    for (std::size_t j = i; j < i + kBlock; j += kLanes) {
      for (std::size_t g = 0; g < kGroups<D>; ++g) {
        const double* p = t + j + g * kWidth<D>;
        const D d = load<D>(p + 1) - load<D>(p);
        const D dev = d - median;
        sum[g] += dev * dev;
        lo[g % 2] = d < lo[g % 2] ? d : lo[g % 2];
        hi[g % 2] = hi[g % 2] < d ? d : hi[g % 2];
      }
    }
  }
  std::memcpy(sums.sum_sq, sum, sizeof sum);
  for (std::size_t j = 0; j < 2 * kWidth<D>; ++j) {
    sums.lo = std::min(sums.lo, lo[j / kWidth<D>][j % kWidth<D>]);
    sums.hi = std::max(sums.hi, hi[j / kWidth<D>][j % kWidth<D>]);
  }
  return i;
}

/// The bin of a regular interval D, as the histogram has always computed it.
int exact_bin(double d, double lo, double width) {
  constexpr int bins = kIntervalHistogramBins;
  // Clamped as a double: with stamps near the double range an interval is inf and the
  // bin position NaN, which no integer conversion may see.
  const double x = std::floor((d - lo) / width);
  return !(x > 0.0) ? 0 : x >= bins - 1 ? bins - 1 : static_cast<int>(x);
}

/// Counts of the histogram bins, and of the intervals that are not regular (the last one).
/// Four copies: consecutive intervals mostly fall in the same bin, and one counter would make
/// each increment wait for the previous one.
using BinCounts = std::int64_t[4][kIntervalHistogramBins + 1];

/// Adds the whole blocks of intervals from I on to COUNTS by bin, up to the first block that
/// needs the division (not added). Returns that block's start, or the first i with
/// i + kBlock > m. INV = 1/width, finite and positive; LO finite.
///
/// The bin floor((d − lo) / width) comes from the product y = (d − lo)·inv: y and the quotient
/// differ by < 1e-13 for y < 41 (d ≤ hi), so the bin is floor(min(y, 40.5)) unless that is
/// within 1e-9 of an integer, where exact_bin divides.
template <class D>
[[gnu::always_inline]] inline std::size_t bin_intervals_of(const double* t, std::size_t i,
                                                           std::size_t m, double gap_limit,
                                                           double lo, double inv,
                                                           BinCounts& counts) {
  constexpr int bins = kIntervalHistogramBins;
  using I = typename IntsOf<D>::type;
  for (; i + kBlock <= m; i += kBlock) {
    int bin[kBlock];
    MaskOf<D> unsure = {};
    for (std::size_t j = 0; j < kBlock; j += kWidth<D>) {
      const D d = load<D>(t + i + j + 1) - load<D>(t + i + j);
      const MaskOf<D> regular = (d > 0.0) & (d <= gap_limit);
      const D y = (d - lo) * inv;
      const D capped = y < bins - 0.5 ? y : (D{} + bins - 0.5);
      // The other intervals go to bin `bins` (41.5 truncates to it, and is no integer).
      const D position = select(regular, capped, (D{} + bins + 0.5));
      const I b = __builtin_convertvector(position, I);  // truncation = floor (≥ 0)
      const D fraction = position - __builtin_convertvector(b, D);
      unsure |= regular & ((fraction < 1e-9) | (fraction > 1.0 - 1e-9));
      std::memcpy(&bin[j], &b, sizeof b);
    }
    if (any(unsure)) break;
    for (std::size_t j = 0; j < kBlock; ++j) ++counts[j % 4][bin[j]];
  }
  return i;
}

// --- Dispatch: the AVX2 instances on CPUs that have it ----------------------------------------

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define IMUNOISE_SAMPLING_AVX2 1

bool have_avx2() {
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
}

__attribute__((target("avx2"))) Extremes extremes_avx2(std::span<const double> v) {
  return extremes_of<D4>(v);
}
__attribute__((target("avx2"))) double first_offender_avx2(std::span<const double> v,
                                                           double noise_floor, double q,
                                                           double range) {
  return first_offender_of<D4>(v, noise_floor, q, range);
}
__attribute__((target("avx2"))) std::size_t channel_blocks_avx2(const double* v, std::size_t i,
                                                                std::size_t n,
                                                                const ChannelMarks& k,
                                                                const GridTest* grid,
                                                                double (&sum_sq)[kLanes]) {
  return grid ? channel_blocks_of<D4, true>(v, i, n, k, grid, sum_sq)
              : channel_blocks_of<D4, false>(v, i, n, k, grid, sum_sq);
}
__attribute__((target("avx2"))) bool bracket_pass_avx2(const double* t, std::size_t m, double a,
                                                       double b, double* between,
                                                       std::size_t capacity, std::size_t& kept,
                                                       std::size_t (&counts)[4]) {
  return bracket_pass_of<D4>(t, m, a, b, between, capacity, kept, counts);
}
__attribute__((target("avx2"))) std::size_t regular_blocks_avx2(const double* t, std::size_t i,
                                                                std::size_t m, double median,
                                                                double gap_limit,
                                                                JitterSums& sums) {
  return regular_blocks_of<D4>(t, i, m, median, gap_limit, sums);
}
__attribute__((target("avx2"))) std::size_t bin_intervals_avx2(const double* t, std::size_t i,
                                                               std::size_t m, double gap_limit,
                                                               double lo, double inv,
                                                               BinCounts& counts) {
  return bin_intervals_of<D4>(t, i, m, gap_limit, lo, inv, counts);
}
#endif

Extremes extremes(std::span<const double> v) {
#ifdef IMUNOISE_SAMPLING_AVX2
  if (have_avx2()) return extremes_avx2(v);
#endif
  return extremes_of<D2>(v);
}

double first_offender(std::span<const double> v, double noise_floor, double q, double range) {
#ifdef IMUNOISE_SAMPLING_AVX2
  if (have_avx2()) return first_offender_avx2(v, noise_floor, q, range);
#endif
  return first_offender_of<D2>(v, noise_floor, q, range);
}

std::size_t channel_blocks(const double* v, std::size_t i, std::size_t n, const ChannelMarks& k,
                           const GridTest* grid, double (&sum_sq)[kLanes]) {
#ifdef IMUNOISE_SAMPLING_AVX2
  if (have_avx2()) return channel_blocks_avx2(v, i, n, k, grid, sum_sq);
#endif
  return grid ? channel_blocks_of<D2, true>(v, i, n, k, grid, sum_sq)
              : channel_blocks_of<D2, false>(v, i, n, k, grid, sum_sq);
}

bool bracket_pass(const double* t, std::size_t m, double a, double b, double* between,
                  std::size_t capacity, std::size_t& kept, std::size_t (&counts)[4]) {
#ifdef IMUNOISE_SAMPLING_AVX2
  if (have_avx2()) return bracket_pass_avx2(t, m, a, b, between, capacity, kept, counts);
#endif
  return bracket_pass_of<D2>(t, m, a, b, between, capacity, kept, counts);
}

std::size_t regular_blocks(const double* t, std::size_t i, std::size_t m, double median,
                           double gap_limit, JitterSums& sums) {
#ifdef IMUNOISE_SAMPLING_AVX2
  if (have_avx2()) return regular_blocks_avx2(t, i, m, median, gap_limit, sums);
#endif
  return regular_blocks_of<D2>(t, i, m, median, gap_limit, sums);
}

void bin_intervals(const double* t, std::size_t m, double gap_limit, double lo, double width,
                   BinCounts& counts) {
  const double inv = 1.0 / width;
  // Absurd stamps (infinite extremes, a zero or infinite width) take the division throughout.
  const bool products = std::isfinite(lo) && std::isfinite(inv) && inv > 0.0;
  std::size_t i = 0;
  while (i < m) {
    if (products) {
#ifdef IMUNOISE_SAMPLING_AVX2
      if (have_avx2()) {
        i = bin_intervals_avx2(t, i, m, gap_limit, lo, inv, counts);
      } else
#endif
      {
        i = bin_intervals_of<D2>(t, i, m, gap_limit, lo, inv, counts);
      }
    }
    // The block the products could not bin, or the tail.
    for (const std::size_t end = products ? std::min(m, i + kBlock) : m; i < end; ++i) {
      const double d = t[i + 1] - t[i];
      if (d > 0.0 && d <= gap_limit) ++counts[0][exact_bin(d, lo, width)];
    }
  }
}

// --- The searches over the passes -------------------------------------------------------------

/// estimate_lsb after its passes over the extremes and the steps, split where it needs the
/// first step of all that is off a grid q (a full scan): analyze_channel makes that scan
/// within its second pass. Usage: while (pending()) resume(first offender of *pending()).
class LsbSearch {
 public:
  LsbSearch(std::span<const double> values, const LsbBounds& bounds, const StepStats& stats)
      : range_(bounds.range), noise_floor_(bounds.noise_floor), q_(stats.q0) {
    if (values.size() < 3 || !bounds.usable || stats.steps < 8) return;
    // The first round's range test (q0 > noise_floor by construction), made before the small
    // steps are collected: for unquantised data q0 is tiny and the answer is already known.
    if (range_ / q_ > kMaxLevels) return;
    // The common divisor is searched among small steps (≤ 64 smallest steps): Euclid on a
    // large step would multiply q's rounding error by the step's multiple.
    small_ = small_steps(values, noise_floor_, 64.0 * q_);
    advance();
  }

  /// The grid whose first offender is needed next; empty once the search has ended.
  std::optional<double> pending() const { return pending_; }
  double range() const { return range_; }
  double noise_floor() const { return noise_floor_; }

  /// Goes on with the first offender of pending() (0 for none).
  void resume(double offender) {
    pending_.reset();
    if (offender == 0.0) {
      result_ = q_;
      return;
    }
    q_ = approximate_gcd(q_, offender);
    ++round_;
    advance();
  }

  std::optional<double> result() const { return result_; }

 private:
  /// Rounds until one needs a full scan (pending_) or the search fails.
  void advance() {
    for (; round_ < 16; ++round_) {
      if (!(q_ > noise_floor_) || range_ / q_ > kMaxLevels) return;
      // First make q divide every small step; q is then still a difference of data values,
      // accurate to their rounding, so refining it cannot pull it off the grid.
      const auto small_offender = std::find_if_not(small_.begin(), small_.end(),
                                                   [&](double d) { return is_multiple(d, q_); });
      if (small_offender != small_.end()) {
        q_ = approximate_gcd(q_, *small_offender);
        continue;
      }
      q_ = refine(q_);
      pending_ = q_;
      return;
    }
  }

  /// Least squares q = Σd / Σk over the small steps that fit the grid: averages the decimal
  /// printing error of each value down, so large steps are judged against an accurate q.
  double refine(double q) const {
    double sum_d = 0.0, sum_k = 0.0;
    for (double d : small_) {
      if (!is_multiple(d, q)) continue;
      sum_d += d;
      sum_k += std::nearbyint(d / q);
    }
    return sum_k > 0.0 ? sum_d / sum_k : q;
  }

  double range_, noise_floor_, q_;
  std::vector<double> small_;
  int round_ = 0;
  std::optional<double> pending_, result_;
};

/// The whole search, each full scan a pass of its own.
std::optional<double> lsb_search(std::span<const double> values, const LsbBounds& bounds,
                                 const StepStats& stats) {
  LsbSearch search(values, bounds, stats);
  while (const std::optional<double> q = search.pending()) {
    search.resume(first_offender(values, search.noise_floor(), *q, search.range()));
  }
  return search.result();
}

/// The median of the intervals of T (as median_in_place computes it) without copying them,
/// or empty when the sample below was unlucky (the caller then takes median_in_place).
///
/// A pseudo-random sample of kSample intervals brackets the middle rank(s) between two of its
/// values a ≤ b, 4 σ of the sample quantile on each side; one pass counts the intervals < a,
/// ≤ a, < b and ≤ b and keeps those strictly between (about 1.6 % of them). When the middle
/// ranks fall inside [#(< a), #(≤ b)), the median is a, b or an order statistic of the kept
/// ones: exactly the value(s) nth_element would find. (Zeros may come back as −0 where the
/// full search would give +0: analyze_timing only uses a positive median.)
std::optional<double> sampled_median(std::span<const double> t) {
  constexpr std::size_t kChunks = 1024, kChunk = 64;  // consecutive intervals: cheap to read
  constexpr std::size_t kSample = kChunks * kChunk;
  constexpr double kMargin = 512.0;  // 4 × √(kSample · ½ · ½): ranks of the sample quantile
  const std::size_t m = t.size() - 1;
  std::vector<double> sample(kSample);
  std::uint64_t state = 0x243F6A8885A308D3;  // splitmix64, fixed seed: the same every call
  for (std::size_t c = 0; c < kChunks; ++c) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EB;
    const auto start = static_cast<std::size_t>((z ^ (z >> 31)) % (m - kChunk + 1));
    for (std::size_t j = 0; j < kChunk; ++j) {
      sample[c * kChunk + j] = t[start + j + 1] - t[start + j];
    }
  }
  const std::size_t k = m / 2;  // the upper middle rank; an even m also needs k − 1
  const double centre = static_cast<double>(k) / static_cast<double>(m) * kSample;
  const auto sample_rank = [&](double r) {
    return static_cast<std::ptrdiff_t>(std::clamp(r, 0.0, static_cast<double>(kSample - 1)));
  };
  const auto rank_a = sample.begin() + sample_rank(std::floor(centre - kMargin));
  const auto rank_b = sample.begin() + sample_rank(std::ceil(centre + kMargin));
  std::nth_element(sample.begin(), rank_a, sample.end());
  const double a = *rank_a;  // read before the next search reorders [rank_a, end)
  std::nth_element(rank_a, rank_b, sample.end());
  const double b = *rank_b;

  const std::size_t capacity = m / 16 + kSample;
  std::vector<double> between(capacity);
  std::size_t kept = 0;
  std::size_t counts[4];
  if (!bracket_pass(t.data(), m, a, b, between.data(), capacity, kept, counts)) {
    return std::nullopt;
  }
  between.resize(kept);
  const std::size_t below_a = counts[0], upto_a = counts[1], below_b = counts[2],
                    upto_b = counts[3];
  // The value of rank R (0-based) among all intervals, if the bracket holds it.
  const auto at_rank = [&](std::size_t r) -> std::optional<double> {
    if (r < below_a || r >= upto_b) return std::nullopt;
    if (r < upto_a) return a;
    if (r >= below_b) return b;
    const auto nth = between.begin() + static_cast<std::ptrdiff_t>(r - upto_a);
    std::nth_element(between.begin(), nth, between.end());
    return *nth;
  };
  const std::optional<double> upper = at_rank(k);
  if (!upper) return std::nullopt;
  if (m % 2 == 1) return *upper;
  const std::optional<double> lower = at_rank(k - 1);
  if (!lower) return std::nullopt;
  return 0.5 * (*lower + *upper);
}

/// The histogram of the regular intervals (see IntervalHistogram), given their extremes LO, HI
/// and count REGULAR.
IntervalHistogram interval_histogram(std::span<const double> time_s, double median,
                                     double gap_limit, double lo, double hi, std::int64_t regular) {
  IntervalHistogram h;
  // Stamps parsed as decimal seconds differ from the true step by ~1e-14 s: not jitter.
  const bool one_bin = hi - lo <= 1e-9 * median;
  const int bins = one_bin ? 1 : kIntervalHistogramBins;
  const double width = one_bin ? 1e-6 * median : (hi - lo) / bins;
  const double first = one_bin ? median - 0.5 * width : lo;
  h.counts.assign(static_cast<std::size_t>(bins), 0);
  for (int b = 0; b < bins; ++b) {
    h.bin_low_s.push_back(first + b * width);
    h.bin_high_s.push_back(b + 1 == bins ? (one_bin ? first + width : hi)
                                         : first + (b + 1) * width);
  }
  if (one_bin) {
    h.counts[0] = regular;
    return h;
  }
  BinCounts counts = {};
  bin_intervals(time_s.data(), time_s.size() - 1, gap_limit, lo, width, counts);
  for (std::size_t b = 0; b < h.counts.size(); ++b) {
    for (const auto& copy : counts) h.counts[b] += copy[b];
  }
  return h;
}

}  // namespace

TimingReport analyze_timing(std::span<const double> time_s, const SamplingOptions& options) {
  TimingReport t;
  t.has_timestamps = true;
  const std::size_t n = time_s.size();
  if (n < 2) return t;
  const std::size_t m = n - 1;  // intervals

  std::optional<double> sampled;
  if (m >= kSampledMedianMin) sampled = sampled_median(time_s);
  double median = 0.0;
  if (sampled) {
    median = *sampled;
  } else {
    std::vector<double> intervals(m);
    for (std::size_t i = 0; i < m; ++i) intervals[i] = time_s[i + 1] - time_s[i];
    median = median_in_place(intervals);
  }
  if (!(median > 0.0)) {
    // Mostly duplicated stamps: the positive intervals still tell the step.
    std::vector<double> positive;
    for (std::size_t i = 0; i < m; ++i) {
      const double d = time_s[i + 1] - time_s[i];
      if (d > 0.0) positive.push_back(d);
    }
    median = positive.empty() ? 0.0 : median_in_place(positive);
  }
  t.median_interval_s = median;
  t.rate_hz = median > 0.0 ? 1.0 / median : 0.0;
  t.duration_s = time_s[n - 1] - time_s[0];
  t.mean_rate_hz = t.duration_s > 0.0 ? static_cast<double>(n - 1) / t.duration_s : 0.0;

  // One pass: blocks of regular intervals (0 < d ≤ gap limit) only add to the jitter sums;
  // the others take the exact scan of each interval. Σ(d − median)² is summed per lane
  // (interval i in lane i mod kLanes), then in lane_sum's tree.
  const double gap_limit = options.gap_factor * median;
  JitterSums sums;               // of regular_blocks
  double lo = kInf, hi = -kInf;  // of the regular intervals in the exact scan
  std::int64_t jitter_count = 0, regular = 0;
  const auto exact = [&](std::size_t i) {
    const double d = time_s[i + 1] - time_s[i];
    if (d > 0.0 && d <= gap_limit) {  // the histogram's intervals
      lo = std::min(lo, d);
      hi = std::max(hi, d);
      ++regular;
    }
    if (d < 0.0) {
      if (t.non_monotonic_count++ == 0) t.first_non_monotonic = locate(i + 1, options);
    } else if (d == 0.0) {
      if (t.duplicate_count++ == 0) t.first_duplicate = locate(i + 1, options);
    } else if (median > 0.0 && d > gap_limit) {
      if (t.gap_count++ == 0) t.first_gap = locate(i + 1, options);
      if (t.gaps.size() < kMaxListedGaps) {
        t.gaps.push_back(GapRecord{locate(i + 1, options), time_s[i] - time_s[0], d});
      }
      t.longest_gap_s = std::max(t.longest_gap_s, d);
      if (__builtin_add_overflow(t.missing_samples, missing_samples_in_gap(d, median),
                                 &t.missing_samples)) {
        t.missing_samples = std::numeric_limits<std::int64_t>::max();
      }
    } else {
      const double dev = d - median;
      sums.sum_sq[i % kLanes] += dev * dev;
      t.jitter_max_s = std::max(t.jitter_max_s, std::fabs(dev));
      ++jitter_count;
    }
  };
  std::size_t i = 0;
  while (i < m) {
    // All regular, hence median > 0: every interval of these blocks is jitter.
    const std::size_t stop = regular_blocks(time_s.data(), i, m, median, gap_limit, sums);
    jitter_count += static_cast<std::int64_t>(stop - i);
    regular += static_cast<std::int64_t>(stop - i);
    // The block with another interval, or the tail.
    for (i = stop; i < std::min(m, stop + kBlock); ++i) exact(i);
  }
  if (sums.lo <= sums.hi) {  // regular_blocks took some
    t.jitter_max_s =
        std::max({t.jitter_max_s, std::fabs(sums.lo - median), std::fabs(sums.hi - median)});
  }
  if (jitter_count > 0) {
    t.jitter_rms_s = std::sqrt(lane_sum(sums.sum_sq) / static_cast<double>(jitter_count));
    t.interval_histogram = interval_histogram(time_s, median, gap_limit, std::min(sums.lo, lo),
                                              std::max(sums.hi, hi), regular);
  }
  return t;
}

TimingReport fixed_rate_timing(double rate_hz, std::int64_t samples) {
  TimingReport t;
  t.has_timestamps = false;
  t.rate_hz = rate_hz;
  t.mean_rate_hz = rate_hz;
  t.median_interval_s = rate_hz > 0.0 ? 1.0 / rate_hz : 0.0;
  t.duration_s = samples > 1 ? static_cast<double>(samples - 1) * t.median_interval_s : 0.0;
  return t;
}

std::vector<ChannelReport> analyze_channels(std::span<const ChannelSamples> channels,
                                            const SamplingOptions& options, unsigned threads) {
  std::vector<ChannelReport> reports(channels.size());
  parallel_for(channels.size(), threads,
               [&](std::size_t i) { reports[i] = analyze_channel(channels[i], options); });
  return reports;
}

std::optional<double> estimate_lsb(std::span<const double> values) {
  if (values.size() < 3) return std::nullopt;
  const Extremes e = extremes(values);
  const LsbBounds bounds = lsb_bounds(e.lo, e.hi);
  if (!bounds.usable) return std::nullopt;
  return lsb_search(values, bounds, steps_above(values, e, bounds.noise_floor));
}

ChannelReport analyze_channel(const ChannelSamples& channel, const SamplingOptions& options) {
  ChannelReport r;
  r.name = std::string(channel.name);
  r.unit = std::string(channel.unit);
  r.full_scale = channel.full_scale;
  const auto v = channel.values;
  const std::size_t n = v.size();
  if (n == 0) return r;

  // Pass 1: extremes, Σ and the steps (see extremes).
  const Extremes e = extremes(v);
  const double lo = e.lo, hi = e.hi;
  r.min = lo;
  r.max = hi;
  r.mean = e.sum / static_cast<double>(n);
  r.constant = lo == hi;

  // The quantization step needs pass 1 only, up to its first scan of all steps for one off
  // the grid q it found (pending): that scan rides along in pass 2.
  std::optional<LsbSearch> lsb;
  if (n >= 3) {
    const LsbBounds bounds = lsb_bounds(lo, hi);
    if (bounds.usable) lsb.emplace(v, bounds, steps_above(v, e, bounds.noise_floor));
  }
  std::optional<GridTest> grid;
  if (lsb && lsb->pending()) grid = grid_test(lsb->noise_floor(), *lsb->pending(), lsb->range());
  bool searching = grid.has_value();
  double offender = 0.0;  // the first step off the grid
  const auto check_step = [&](std::size_t i) {
    if (!searching || i == 0) return;
    offender = offending_step(v, i, grid->noise_floor, grid->q);
    searching = offender == 0.0;
  };

  // Pass 2: Σ(v − mean)² (sample i in lane i mod kLanes, then lane_sum) and the scan for
  // saturation runs and full-scale samples.
  std::size_t run_start = 0;
  const auto close_run = [&](std::size_t end) {  // run is [run_start, end)
    const auto len = static_cast<std::int64_t>(end - run_start);
    const double value = v[run_start];
    if (!r.constant && len >= options.saturation_min_run && (value == lo || value == hi)) {
      if (r.saturation_runs++ == 0) r.first_saturation = locate(run_start, options);
      r.saturated_samples += len;
      r.longest_saturation_run = std::max(r.longest_saturation_run, len);
    }
  };
  const auto exact = [&](std::size_t i) {
    if (i > 0 && v[i] != v[run_start]) {
      close_run(i);
      run_start = i;
    }
    if (channel.full_scale && std::fabs(v[i]) >= *channel.full_scale) {
      if (r.beyond_full_scale++ == 0) r.first_beyond_full_scale = locate(i, options);
    }
  };
  // The scan has nothing to do at a "quiet" sample: one that is no extreme (runs count only
  // at the extremes, and none in a constant channel), so lo < x < hi, and below full scale,
  // so −fs < x < fs. A full scale that no sample can be below (≤ 0, NaN) leaves none quiet.
  ChannelMarks marks{r.mean, r.constant ? -kInf : lo, r.constant ? kInf : hi};
  if (channel.full_scale) {
    const double fs = *channel.full_scale;
    marks.quiet_lo = fs > 0.0 ? std::max(marks.quiet_lo, -fs) : kInf;
    marks.quiet_hi = std::min(marks.quiet_hi, fs);
  }
  double sum_sq[kLanes] = {};
  const auto exact_with_sum = [&](std::size_t i) {
    const double dev = v[i] - r.mean;
    sum_sq[i % kLanes] += dev * dev;
    exact(i);
    check_step(i);
  };
  std::size_t i = 0;
  for (; i < std::min(n, kLanes); ++i) exact_with_sum(i);  // as in pass 1
  while (i < n) {
    const std::size_t loud =
        channel_blocks(v.data(), i, n, marks, searching ? &*grid : nullptr, sum_sq);
    if (loud > i) {
      // Quiet blocks [i, loud): a run open at i that is at an extreme ends there; the run
      // open at loud − 1 is at no extreme, so where it started does not matter (it will not
      // count).
      close_run(i);
      run_start = loud - 1;
    }
    // The loud block, or the tail.
    for (i = loud; i < std::min(n, loud + kBlock); ++i) exact_with_sum(i);
  }
  close_run(n);
  r.std_dev = n > 1 ? std::sqrt(lane_sum(sum_sq) / static_cast<double>(n - 1)) : 0.0;
  if (lsb) {
    if (grid) lsb->resume(offender);
    while (const std::optional<double> q = lsb->pending()) {  // grids after the first
      lsb->resume(first_offender(v, lsb->noise_floor(), *q, lsb->range()));
    }
    r.lsb = lsb->result();
  }
  return r;
}

}  // namespace imunoise::pipeline
