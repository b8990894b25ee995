/// @file
/// @brief The time-stamp checks (analyze_timing, fixed_rate_timing): the median interval (sampled
/// on long records), gaps, order, jitter and the interval histogram, in vector kernels and their
/// AVX2 instances (pipeline/sampling_checks_internal.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include "common/errors.h"
#include "common/sampling_gap.h"
#include "pipeline/sampling_checks.h"
#include "pipeline/sampling_checks_internal.h"

namespace imunoise::pipeline {

using namespace detail;  // the lanes and locate

namespace {

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

/// Intervals of at least this many stamps take their median from sampled_median.
constexpr std::size_t kSampledMedianMin = std::size_t{1} << 16;

/// Σ(d − median)² of the regular intervals (0 < d ≤ gap limit; interval i in lane i mod
/// kLanes), and the smallest and largest of them. max |d − median| is not kept: d − median
/// rounds monotonically in d, so the largest |d − median| is that of the smallest or the
/// largest d.
struct JitterSums {
  double sum_sq[kLanes] = {};
  double sum_dev[kLanes] = {};  ///< Σ (interval − median), for the mean regular interval
  double lo = kInf, hi = -kInf;
};

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

// --- Vector kernels ---------------------------------------------------------------------------

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // see sampling_checks_internal.h

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

/// The whole blocks from I (a multiple of kLanes) on whose intervals are all regular, into
/// SUMS. Returns the start of the first block with another interval (not added), or the first
/// i with i + kBlock > m.
template <class D>
[[gnu::always_inline]] inline std::size_t regular_blocks_of(const double* t, std::size_t i,
                                                            std::size_t m, double median,
                                                            double gap_limit, JitterSums& sums) {
  D sum[kGroups<D>], sum_dev[kGroups<D>], lo[2] = {(D{} + sums.lo), (D{} + sums.lo)},
                                          hi[2] = {(D{} + sums.hi), (D{} + sums.hi)};
  std::memcpy(sum, sums.sum_sq, sizeof sum);
  std::memcpy(sum_dev, sums.sum_dev, sizeof sum_dev);
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
        sum_dev[g] += dev;
        lo[g % 2] = d < lo[g % 2] ? d : lo[g % 2];
        hi[g % 2] = hi[g % 2] < d ? d : hi[g % 2];
      }
    }
  }
  std::memcpy(sums.sum_sq, sum, sizeof sum);
  std::memcpy(sums.sum_dev, sum_dev, sizeof sum_dev);
  for (std::size_t j = 0; j < 2 * kWidth<D>; ++j) {
    sums.lo = std::min(sums.lo, lo[j / kWidth<D>][j % kWidth<D>]);
    sums.hi = std::max(sums.hi, hi[j / kWidth<D>][j % kWidth<D>]);
  }
  return i;
}

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

#ifdef IMUNOISE_SAMPLING_AVX2
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

#pragma GCC diagnostic pop

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

/// 10^d for the grid digits.
constexpr double kPow10[kMaxGridDigits + 1] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};

/// The median of the intervals of T (sampled on long records), of the positive ones when it is
/// not positive.
double median_interval(std::span<const double> time_s) {
  const std::size_t m = time_s.size() - 1;
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
  return median;
}

}  // namespace

TimingReport analyze_timing(std::span<const double> time_s, const SamplingOptions& options,
                            const std::optional<ExactMedianInterval>& exact_median) {
  TimingReport t;
  t.has_timestamps = true;
  const std::size_t n = time_s.size();
  if (n < 2) return t;
  const std::size_t m = n - 1;  // intervals

  // Exact, on a decimal grid, or as the intervals give it. The first two are a whole or half
  // number of steps: the period and the rate are then one division of exact integers.
  std::optional<ExactMedianInterval> steps = exact_median;
  double median = steps ? steps->seconds() : median_interval(time_s);
  if (!steps && median > 0.0) {
    if (const std::optional<int> digits = decimal_grid_digits(time_s)) {
      const double twice = std::nearbyint(2.0 * median * kPow10[*digits]);
      if (twice > 0.0) steps = ExactMedianInterval{twice, 2.0 * kPow10[*digits]};
      median = snap_to_decimal_grid(median, *digits);
    }
  }
  t.median_interval_s = median;
  t.rate_hz = steps ? steps->rate_hz() : median > 0.0 ? 1.0 / median : 0.0;
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
      sums.sum_dev[i % kLanes] += dev;
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
  t.sample_period_s = median;
  if (jitter_count > 0 && median > 0.0) {
    t.mean_interval_s = median + lane_sum(sums.sum_dev) / static_cast<double>(jitter_count);
    // Finite and positive for any stamps: the regular intervals lie in (0, gap_factor·median].
    if (std::isfinite(t.mean_interval_s) && t.mean_interval_s > 0.0 &&
        std::fabs(t.mean_interval_s - median) > kPeriodFromMeanThreshold * median) {
      t.sample_period_s = t.mean_interval_s;
      t.period_from_mean = true;
      t.rate_hz = 1.0 / t.sample_period_s;
    }
  }
  if (jitter_count > 0) {
    t.jitter_rms_s = std::sqrt(lane_sum(sums.sum_sq) / static_cast<double>(jitter_count));
    t.interval_histogram = interval_histogram(time_s, median, gap_limit, std::min(sums.lo, lo),
                                              std::max(sums.hi, hi), regular);
  }
  return t;
}

bool on_decimal_grid(double stamp, int digits) {
  if (digits < 0 || digits > kMaxGridDigits || !std::isfinite(stamp)) return false;
  const double x = stamp * kPow10[digits];
  const double tolerance = 4.0 * std::numeric_limits<double>::epsilon() * std::fabs(x);
  if (tolerance > 1.0 / 64.0) return false;
  return std::fabs(x - std::nearbyint(x)) <= tolerance;
}

std::optional<int> decimal_grid_digits(std::span<const double> stamps) {
  for (int digits = 0; digits <= kMaxGridDigits; ++digits) {
    const bool all = std::all_of(stamps.begin(), stamps.end(),
                                 [digits](double s) { return on_decimal_grid(s, digits); });
    if (all) return digits;
  }
  return std::nullopt;
}

double snap_to_decimal_grid(double median, int digits) {
  IMUNOISE_EXPECT(digits >= 0 && digits <= kMaxGridDigits, "snap_to_decimal_grid: digits");
  if (!(median > 0.0)) return median;
  const double twice_steps = std::nearbyint(2.0 * median * kPow10[digits]);
  return twice_steps > 0.0 ? twice_steps / (2.0 * kPow10[digits]) : median;
}

std::optional<ExactMedianInterval> exact_tick_median(std::span<const double> ticks,
                                                     double ticks_per_second) {
  IMUNOISE_EXPECT(ticks_per_second > 0.0 && std::isfinite(ticks_per_second),
                  "exact_tick_median: ticks_per_second");
  if (ticks.size() < 2) return std::nullopt;
  constexpr double kExact = 9007199254740992.0;  // 2^53
  const bool whole = std::all_of(ticks.begin(), ticks.end(), [](double v) {
    return std::fabs(v) <= kExact && v == std::nearbyint(v);
  });
  if (!whole) return std::nullopt;
  // Whole-number intervals below 2^54 are exact; the median is one of them or the mean of two.
  const double median = median_interval(ticks);
  if (!(median > 0.0)) return std::nullopt;
  return ExactMedianInterval{2.0 * median, 2.0 * ticks_per_second};
}

TimingReport fixed_rate_timing(double rate_hz, std::int64_t samples) {
  TimingReport t;
  t.has_timestamps = false;
  t.rate_hz = rate_hz;
  t.mean_rate_hz = rate_hz;
  t.median_interval_s = rate_hz > 0.0 ? 1.0 / rate_hz : 0.0;
  t.sample_period_s = t.median_interval_s;
  t.mean_interval_s = t.median_interval_s;
  t.duration_s = samples > 1 ? static_cast<double>(samples - 1) * t.median_interval_s : 0.0;
  return t;
}

// GCC 12 reports -Wpsabi for the D4 functions it compiles after parsing at the last token of
// the file: off for that token only, nothing follows (see sampling_checks_internal.h).
#pragma GCC diagnostic ignored "-Wpsabi"
}  // namespace imunoise::pipeline
