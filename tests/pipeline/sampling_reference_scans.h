/// @file
/// @brief Test helpers of the sampling checks (tests/pipeline/sampling_timing_test.cpp,
/// channel_checks_test.cpp, lsb_estimate_test.cpp): the plain left-to-right scans the vector
/// checks of pipeline/sampling_checks.h are compared with, the comparisons, and the inputs the
/// tests share.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "pipeline/sampling_checks.h"

namespace imunoise::pipeline::sampling_test {

/// Integer codes of a random walk ±1 or ±2 codes per step (fixed seed), times `lsb`.
inline std::vector<double> quantized_walk(std::size_t n, double lsb, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> step(-2, 2);
  std::vector<double> v(n);
  long code = 1000;
  for (std::size_t i = 0; i < n; ++i) {
    code += step(rng);
    v[i] = static_cast<double>(code) * lsb;
  }
  return v;
}

// --- equality with the plain scans --------------------------------------------------------------
//
// analyze_channel, estimate_lsb and analyze_timing scan in vector blocks and take the exact code
// only where a block needs it. These tests compare them with the plain left-to-right algorithms
// (the implementation before the block scans, kept here written simply) on generated inputs:
// every count, location, extreme, step and histogram must be identical; the sums (mean,
// std_dev, jitter_rms_s) may differ by summation order, so they are checked against long
// double sums.

namespace plain {

inline SampleLocation locate(std::size_t index, const SamplingOptions& options) {
  SampleLocation loc;
  loc.index = static_cast<std::int64_t>(index);
  if (options.line_of_sample) loc.line = options.line_of_sample(index);
  return loc;
}

inline double median(
    std::vector<double> v) {  // of the sorted values, as nth_element would pick them
  std::sort(v.begin(), v.end());
  const std::size_t mid = v.size() / 2;
  return v.size() % 2 == 1 ? v[mid] : 0.5 * (v[mid - 1] + v[mid]);
}

inline double approximate_gcd(double a, double b) {
  if (a < b) std::swap(a, b);
  for (int i = 0; i < 64 && b > 0.0; ++i) {
    const double r = std::fabs(a - b * std::nearbyint(a / b));
    if (r <= 0.1 * b) return b;
    a = b;
    b = r;
  }
  return 0.0;
}

inline std::optional<double> estimate_lsb(const std::vector<double>& v) {
  const std::size_t n = v.size();
  if (n < 3) return std::nullopt;
  double lo = v[0], hi = v[0];
  for (double x : v) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const double range = hi - lo;
  const double noise_floor = std::max(std::fabs(lo), std::fabs(hi)) * 1e-12;
  if (!(range > 0.0) || !std::isfinite(range)) return std::nullopt;
  std::vector<double> steps;  // above the noise floor, in order
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double d = std::fabs(v[i + 1] - v[i]);
    if (d > noise_floor) steps.push_back(d);
  }
  if (steps.size() < 8) return std::nullopt;
  const double q0 = *std::min_element(steps.begin(), steps.end());
  std::vector<double> small;
  for (double d : steps) {
    if (small.size() < 4096 && d <= 64.0 * q0) small.push_back(d);
  }
  const auto is_multiple = [](double d, double q) {
    const double k = std::nearbyint(d / q);
    return k >= 1.0 && std::fabs(d - k * q) <= 0.1 * q;
  };
  double q = q0;
  for (int round = 0; round < 16; ++round) {
    if (!(q > noise_floor) || range / q > 16777216.0) return std::nullopt;
    const auto bad =
        std::find_if_not(small.begin(), small.end(), [&](double d) { return is_multiple(d, q); });
    if (bad != small.end()) {
      q = approximate_gcd(q, *bad);
      continue;
    }
    double sum_d = 0.0, sum_k = 0.0;
    for (double d : small) {
      if (!is_multiple(d, q)) continue;
      sum_d += d;
      sum_k += std::nearbyint(d / q);
    }
    if (sum_k > 0.0) q = sum_d / sum_k;
    const auto offender =
        std::find_if_not(steps.begin(), steps.end(), [&](double d) { return is_multiple(d, q); });
    if (offender == steps.end()) return q;
    q = approximate_gcd(q, *offender);
  }
  return std::nullopt;
}

struct Channel {
  ChannelReport report;  // mean and std_dev from the long double sums below
  long double mean = 0, std_dev = 0, mean_abs = 0;
};

inline Channel analyze_channel(const std::vector<double>& v, std::optional<double> full_scale,
                               const SamplingOptions& options) {
  Channel c;
  ChannelReport& r = c.report;
  r.full_scale = full_scale;
  const std::size_t n = v.size();
  if (n == 0) return c;
  r.min = r.max = v[0];
  for (double x : v) {
    r.min = std::min(r.min, x);
    r.max = std::max(r.max, x);
    c.mean += x;
    c.mean_abs += std::fabs(x);
  }
  c.mean /= static_cast<long double>(n);
  c.mean_abs /= static_cast<long double>(n);
  for (double x : v) c.std_dev += (x - c.mean) * (x - c.mean);
  c.std_dev = n > 1 ? std::sqrt(c.std_dev / static_cast<long double>(n - 1)) : 0.0L;
  r.constant = r.min == r.max;
  for (std::size_t start = 0; start < n;) {  // one run of equal samples per step
    std::size_t end = start + 1;
    while (end < n && v[end] == v[start]) ++end;
    const auto len = static_cast<std::int64_t>(end - start);
    if (!r.constant && len >= options.saturation_min_run &&
        (v[start] == r.min || v[start] == r.max)) {
      if (r.saturation_runs++ == 0) r.first_saturation = locate(start, options);
      r.saturated_samples += len;
      r.longest_saturation_run = std::max(r.longest_saturation_run, len);
    }
    start = end;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (full_scale && std::fabs(v[i]) >= *full_scale) {
      if (r.beyond_full_scale++ == 0) r.first_beyond_full_scale = locate(i, options);
    }
  }
  r.lsb = estimate_lsb(v);
  return c;
}

struct Timing {
  TimingReport report;  // jitter_rms_s from the long double sum below
  long double jitter_rms = 0;
};

inline Timing analyze_timing(const std::vector<double>& t, const SamplingOptions& options) {
  Timing out;
  TimingReport& r = out.report;
  long double sum_dev = 0;
  r.has_timestamps = true;
  const std::size_t n = t.size();
  if (n < 2) return out;
  std::vector<double> intervals, positive;
  for (std::size_t i = 0; i + 1 < n; ++i) intervals.push_back(t[i + 1] - t[i]);
  for (double d : intervals) {
    if (d > 0.0) positive.push_back(d);
  }
  double median = plain::median(intervals);
  if (!(median > 0.0)) median = positive.empty() ? 0.0 : plain::median(positive);
  // The decimal grid (sampling_checks.h): the fewest decimals d <= 9 with every stamp within
  // 4 ulp of a whole number of 10^-d s (that tolerance below 1/64 step); the median is then the
  // nearest half step, the rate 10^d / steps.
  std::optional<double> grid_scale;
  for (int d = 0; d <= 9 && !grid_scale; ++d) {
    const double scale = std::pow(10.0, d);
    const bool all = std::all_of(t.begin(), t.end(), [scale](double s) {
      const double x = s * scale;
      const double tolerance = 4.0 * std::numeric_limits<double>::epsilon() * std::fabs(x);
      return std::isfinite(x) && tolerance <= 1.0 / 64.0 &&
             std::fabs(x - std::round(x)) <= tolerance;
    });
    if (all) grid_scale = scale;
  }
  double twice_steps = 0.0;
  if (grid_scale && median > 0.0) {
    twice_steps = std::round(2.0 * median * *grid_scale);
    if (twice_steps > 0.0) median = twice_steps / (2.0 * *grid_scale);
  }
  r.median_interval_s = median;
  r.rate_hz = twice_steps > 0.0 ? 2.0 * *grid_scale / twice_steps
              : median > 0.0    ? 1.0 / median
                                : 0.0;
  r.duration_s = t[n - 1] - t[0];
  r.mean_rate_hz = r.duration_s > 0.0 ? static_cast<double>(n - 1) / r.duration_s : 0.0;
  const double gap_limit = options.gap_factor * median;
  std::vector<double> regular;
  std::int64_t jitter_count = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double d = intervals[i];
    if (d > 0.0 && d <= gap_limit) regular.push_back(d);
    if (d < 0.0) {
      if (r.non_monotonic_count++ == 0) r.first_non_monotonic = locate(i + 1, options);
    } else if (d == 0.0) {
      if (r.duplicate_count++ == 0) r.first_duplicate = locate(i + 1, options);
    } else if (median > 0.0 && d > gap_limit) {
      if (r.gap_count++ == 0) r.first_gap = locate(i + 1, options);
      if (r.gaps.size() < kMaxListedGaps) {
        r.gaps.push_back(GapRecord{locate(i + 1, options), t[i] - t[0], d});
      }
      r.longest_gap_s = std::max(r.longest_gap_s, d);
      const double missing = std::round(d / median) - 1.0;
      const std::int64_t add = !(missing > 0.0)    ? 0
                               : missing >= 0x1p63 ? std::numeric_limits<std::int64_t>::max()
                                                   : static_cast<std::int64_t>(missing);
      if (__builtin_add_overflow(r.missing_samples, add, &r.missing_samples)) {
        r.missing_samples = std::numeric_limits<std::int64_t>::max();
      }
    } else {
      const long double dev = d - median;
      out.jitter_rms += dev * dev;
      sum_dev += dev;
      r.jitter_max_s = std::max(r.jitter_max_s, std::fabs(d - median));
      ++jitter_count;
    }
  }
  r.sample_period_s = median;
  if (jitter_count > 0 && median > 0.0) {
    r.mean_interval_s =
        static_cast<double>(median + sum_dev / static_cast<long double>(jitter_count));
    if (std::isfinite(r.mean_interval_s) && r.mean_interval_s > 0.0 &&
        std::fabs(r.mean_interval_s - median) > kPeriodFromMeanThreshold * median) {
      r.sample_period_s = r.mean_interval_s;
      r.period_from_mean = true;
      r.rate_hz = 1.0 / r.sample_period_s;
    }
  }
  if (jitter_count == 0) return out;
  out.jitter_rms = std::sqrt(out.jitter_rms / static_cast<long double>(jitter_count));
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double d : regular) {
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  IntervalHistogram& h = r.interval_histogram;
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
  for (double d : regular) {
    const double x = one_bin ? 0.0 : std::floor((d - lo) / width);
    const int b = !(x > 0.0) ? 0 : x >= bins - 1 ? bins - 1 : static_cast<int>(x);
    ++h.counts[static_cast<std::size_t>(b)];
  }
  return out;
}

}  // namespace plain

/// Bit-identical doubles (+0 and −0 differ).
inline ::testing::AssertionResult same(double a, double b) {
  if (std::memcmp(&a, &b, sizeof a) == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << std::hexfloat << a << " vs " << b;
}

inline ::testing::AssertionResult same(const std::optional<double>& a,
                                       const std::optional<double>& b) {
  if (a.has_value() != b.has_value()) {
    return ::testing::AssertionFailure()
           << (a ? "value" : "nullopt") << " vs " << (b ? "value" : "nullopt");
  }
  return a ? same(*a, *b) : ::testing::AssertionSuccess();
}

inline void expect_same_location(const std::optional<SampleLocation>& a,
                                 const std::optional<SampleLocation>& b) {
  ASSERT_EQ(a.has_value(), b.has_value());
  if (!a) return;
  EXPECT_EQ(a->index, b->index);
  EXPECT_EQ(a->line, b->line);
}

/// Within 1e-12 of a long double reference, relative to SCALE (the size of the data: sums of
/// values that cancel have no relative accuracy of their own).
inline ::testing::AssertionResult close(double value, long double reference, long double scale) {
  const long double error = std::fabs(static_cast<long double>(value) - reference);
  if (error <= 1e-12L * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << std::setprecision(17) << value << " vs " << static_cast<double>(reference) << ", error "
         << static_cast<double>(error / scale) << " of the scale";
}

inline void expect_channel_matches(const std::vector<double>& v, std::optional<double> full_scale,
                                   const SamplingOptions& options) {
  const ChannelReport r = analyze_channel({"ch", "rad/s", v, full_scale}, options);
  const plain::Channel p = plain::analyze_channel(v, full_scale, options);
  const ChannelReport& e = p.report;
  EXPECT_EQ(r.name, "ch");
  EXPECT_EQ(r.unit, "rad/s");
  EXPECT_TRUE(same(r.min, e.min));
  EXPECT_TRUE(same(r.max, e.max));
  EXPECT_EQ(r.constant, e.constant);
  EXPECT_EQ(r.saturation_runs, e.saturation_runs);
  EXPECT_EQ(r.saturated_samples, e.saturated_samples);
  EXPECT_EQ(r.longest_saturation_run, e.longest_saturation_run);
  expect_same_location(r.first_saturation, e.first_saturation);
  EXPECT_TRUE(same(r.full_scale, e.full_scale));
  EXPECT_EQ(r.beyond_full_scale, e.beyond_full_scale);
  expect_same_location(r.first_beyond_full_scale, e.first_beyond_full_scale);
  EXPECT_TRUE(same(r.lsb, e.lsb));
  EXPECT_TRUE(same(estimate_lsb(v), e.lsb));
  const long double scale = std::max(p.mean_abs, 1e-300L);
  EXPECT_TRUE(close(r.mean, p.mean, scale));
  EXPECT_TRUE(close(r.std_dev, p.std_dev, std::max(p.std_dev, scale * 1e-3L)));
}

inline void expect_timing_matches(const std::vector<double>& t, const SamplingOptions& options) {
  const TimingReport r = analyze_timing(t, options);
  const plain::Timing p = plain::analyze_timing(t, options);
  const TimingReport& e = p.report;
  EXPECT_EQ(r.has_timestamps, e.has_timestamps);
  EXPECT_TRUE(same(r.median_interval_s, e.median_interval_s));
  // The mean regular interval is a lane-wise sum of deviations against the plain long double
  // one: equal to rounding, and the rule that picks it agrees.
  EXPECT_EQ(r.period_from_mean, e.period_from_mean);
  EXPECT_TRUE(close(r.mean_interval_s, e.mean_interval_s,
                    std::max<long double>(e.median_interval_s, std::fabs(e.mean_interval_s))));
  if (e.period_from_mean) {
    EXPECT_TRUE(close(r.rate_hz, e.rate_hz, e.rate_hz));
    EXPECT_TRUE(close(r.sample_period_s, e.sample_period_s, e.sample_period_s));
  } else {
    EXPECT_TRUE(same(r.rate_hz, e.rate_hz));
    EXPECT_TRUE(same(r.sample_period_s, e.sample_period_s));
  }
  EXPECT_TRUE(same(r.duration_s, e.duration_s));
  EXPECT_TRUE(same(r.mean_rate_hz, e.mean_rate_hz));
  EXPECT_EQ(r.gap_count, e.gap_count);
  EXPECT_TRUE(same(r.longest_gap_s, e.longest_gap_s));
  EXPECT_EQ(r.missing_samples, e.missing_samples);
  expect_same_location(r.first_gap, e.first_gap);
  EXPECT_EQ(r.non_monotonic_count, e.non_monotonic_count);
  expect_same_location(r.first_non_monotonic, e.first_non_monotonic);
  EXPECT_EQ(r.duplicate_count, e.duplicate_count);
  expect_same_location(r.first_duplicate, e.first_duplicate);
  EXPECT_TRUE(same(r.jitter_max_s, e.jitter_max_s));
  EXPECT_TRUE(close(r.jitter_rms_s, p.jitter_rms, p.jitter_rms));
  EXPECT_EQ(r.interval_histogram.counts, e.interval_histogram.counts);
  EXPECT_EQ(r.interval_histogram.bin_low_s, e.interval_histogram.bin_low_s);
  EXPECT_EQ(r.interval_histogram.bin_high_s, e.interval_histogram.bin_high_s);
  ASSERT_EQ(r.gaps.size(), e.gaps.size());
  for (std::size_t i = 0; i < r.gaps.size(); ++i) {
    EXPECT_EQ(r.gaps[i].after.index, e.gaps[i].after.index);
    EXPECT_EQ(r.gaps[i].after.line, e.gaps[i].after.line);
    EXPECT_TRUE(same(r.gaps[i].start_s, e.gaps[i].start_s));
    EXPECT_TRUE(same(r.gaps[i].length_s, e.gaps[i].length_s));
  }
}

// Sizes around the block edges of the scans (8 lanes; blocks of 32 samples from sample 8 or
// from 0), and two long ones (the sampled median of analyze_timing starts at 65536 intervals).
inline constexpr std::size_t kSizes[] = {0,  1,  2,  3,  7,  8,  9,  15, 16, 17, 31,   32,
                                         33, 39, 40, 41, 63, 64, 65, 71, 72, 73, 1000, 100003};

inline std::string printed(double x, const char* format) {
  char text[48];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

}  // namespace imunoise::pipeline::sampling_test
