// Tests of pipeline/sampling_checks.h on constructed series whose gaps, jitter, duplicates,
// saturation runs and quantization step are known by construction.
#include "pipeline/sampling_checks.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "common/units.h"

namespace imunoise::pipeline {
namespace {

std::vector<double> uniform_stamps(std::size_t n, double dt) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = static_cast<double>(i) * dt;
  return t;
}

/// Integer codes of a random walk ±1 or ±2 codes per step (fixed seed), times `lsb`.
std::vector<double> quantized_walk(std::size_t n, double lsb, unsigned seed = 7) {
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

TEST(AnalyzeTiming, CountsAGapAndTheMissingSamples) {
  std::vector<double> t = uniform_stamps(1000, 0.01);
  t.erase(t.begin() + 500, t.begin() + 504);  // 4 samples lost: one 0.05 s interval
  const TimingReport r = analyze_timing(t);
  EXPECT_NEAR(r.rate_hz, 100.0, 1e-9);
  EXPECT_EQ(r.gap_count, 1);
  EXPECT_NEAR(r.longest_gap_s, 0.05, 1e-12);
  EXPECT_EQ(r.missing_samples, 4);
  ASSERT_TRUE(r.first_gap.has_value());
  EXPECT_EQ(r.first_gap->index, 500);
  EXPECT_FALSE(r.first_gap->line.has_value());  // no line mapper given
  EXPECT_EQ(r.duplicate_count, 0);
  EXPECT_EQ(r.non_monotonic_count, 0);
  EXPECT_NEAR(r.duration_s, 9.99, 1e-9);
}

TEST(AnalyzeTiming, JitterIsDeviationFromTheMedianInterval) {
  // Odd samples late by 0.1 ms: intervals alternate 10.1 ms and 9.9 ms around 10 ms.
  std::vector<double> t = uniform_stamps(1001, 0.01);
  for (std::size_t i = 1; i < t.size(); i += 2) t[i] += 1e-4;
  const TimingReport r = analyze_timing(t);
  EXPECT_NEAR(r.median_interval_s, 0.01, 1e-12);
  EXPECT_NEAR(r.jitter_rms_s, 1e-4, 1e-12);
  EXPECT_NEAR(r.jitter_max_s, 1e-4, 1e-12);
  EXPECT_EQ(r.gap_count, 0);
}

TEST(AnalyzeTiming, GapsDoNotInflateJitter) {
  std::vector<double> t = uniform_stamps(100, 0.5);
  for (std::size_t i = 50; i < t.size(); ++i) t[i] += 10.0;  // one 10.5 s interval
  const TimingReport r = analyze_timing(t);
  EXPECT_EQ(r.gap_count, 1);
  EXPECT_NEAR(r.longest_gap_s, 10.5, 1e-12);
  EXPECT_EQ(r.missing_samples, 20);
  EXPECT_LT(r.jitter_max_s, 1e-12);
}

TEST(AnalyzeTiming, DuplicatesAndBackwardStepsWithLines) {
  const std::vector<double> t{0.0, 1.0, 1.0, 2.0, 1.5, 3.0, 4.0, 4.0};
  SamplingOptions options;
  options.line_of_sample = [](std::size_t i) { return static_cast<std::int64_t>(i) + 10; };
  const TimingReport r = analyze_timing(t, options);
  EXPECT_EQ(r.duplicate_count, 2);
  EXPECT_EQ(r.first_duplicate->index, 2);
  EXPECT_EQ(r.first_duplicate->line, 12);
  EXPECT_EQ(r.non_monotonic_count, 1);
  EXPECT_EQ(r.first_non_monotonic->index, 4);
  EXPECT_EQ(r.first_non_monotonic->line, 14);
}

TEST(AnalyzeTiming, TooFewStampsGiveNoRate) {
  EXPECT_EQ(analyze_timing(std::vector<double>{1.0}).rate_hz, 0.0);
  EXPECT_EQ(analyze_timing(std::vector<double>{}).rate_hz, 0.0);
}

TEST(FixedRateTiming, KnowsRateAndDuration) {
  const TimingReport r = fixed_rate_timing(200.0, 401);
  EXPECT_FALSE(r.has_timestamps);
  EXPECT_DOUBLE_EQ(r.median_interval_s, 0.005);
  EXPECT_DOUBLE_EQ(r.duration_s, 2.0);
}

TEST(AnalyzeChannel, SaturationRunsAtMinAndMax) {
  std::vector<double> v = quantized_walk(200, 1.0);
  // Clamp-like runs at the extremes: 6 at +1e4 and 5 at −1e4; a run of 4 does not count.
  std::fill(v.begin() + 20, v.begin() + 26, 1e4);
  std::fill(v.begin() + 100, v.begin() + 105, -1e4);
  std::fill(v.begin() + 150, v.begin() + 154, 1e4);
  const ChannelReport r = analyze_channel({"gyro_x", "rad/s", v, std::nullopt});
  EXPECT_EQ(r.max, 1e4);
  EXPECT_EQ(r.min, -1e4);
  EXPECT_EQ(r.saturation_runs, 2);
  EXPECT_EQ(r.saturated_samples, 11);
  EXPECT_EQ(r.longest_saturation_run, 6);
  EXPECT_EQ(r.first_saturation->index, 20);
  EXPECT_FALSE(r.constant);
}

TEST(AnalyzeChannel, FullScaleLimitCountsSamplesAtOrBeyond) {
  const std::vector<double> v{0.1, 34.9, -35.0, 35.2, 0.0, -1.0};
  const ChannelReport r = analyze_channel({"gyro_z", "rad/s", v, 35.0});
  EXPECT_EQ(r.beyond_full_scale, 2);
  EXPECT_EQ(r.first_beyond_full_scale->index, 2);
  EXPECT_EQ(r.full_scale, 35.0);
}

TEST(AnalyzeChannel, ConstantChannelIsNotSaturation) {
  const std::vector<double> v(50, 0.0);
  const ChannelReport r = analyze_channel({"accel_x", "m/s^2", v, std::nullopt});
  EXPECT_TRUE(r.constant);
  EXPECT_EQ(r.saturation_runs, 0);
  EXPECT_FALSE(r.lsb.has_value());
}

TEST(AnalyzeChannel, MeanAndStd) {
  const std::vector<double> v{1.0, 2.0, 3.0, 4.0};
  const ChannelReport r = analyze_channel({"x", "", v, std::nullopt});
  EXPECT_DOUBLE_EQ(r.mean, 2.5);
  EXPECT_DOUBLE_EQ(r.std_dev, std::sqrt(5.0 / 3.0));
}

TEST(EstimateLsb, BinaryStep) { EXPECT_EQ(estimate_lsb(quantized_walk(5000, 0.0625)), 0.0625); }

TEST(EstimateLsb, ScaledAdcCodesInSi) {
  // 16-bit gyro at ±250 deg/s: 250/32768 deg/s per code, stored in rad/s.
  const double lsb = 250.0 / 32768.0 * units::kDegPerS;
  const auto q = estimate_lsb(quantized_walk(20000, lsb));
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(*q, lsb, lsb * 1e-9);
}

TEST(EstimateLsb, SmallestSeenStepIsTwoCodes) {
  // Steps of 2 and 3 codes only: the code grid is still 1 LSB (common divisor).
  std::vector<double> v{0.0};
  std::mt19937 rng(3);
  for (int i = 0; i < 1000; ++i) v.push_back(v.back() + ((rng() & 1) ? 2.0 : -3.0) * 0.01);
  const auto q = estimate_lsb(v);
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(*q, 0.01, 1e-9);
}

TEST(EstimateLsb, DecimalPrintingOfCodes) {
  // Codes printed with 6 decimals: each value carries up to 5e-7 of rounding.
  const double lsb = 0.00762939453125;
  std::vector<double> v = quantized_walk(5000, lsb);
  for (double& x : v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6f", x);
    x = std::strtod(text, nullptr);
  }
  const auto q = estimate_lsb(v);
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(*q, lsb, 1e-6);
}

TEST(EstimateLsb, PrintResolutionOfWideNoiseNearAnOffset) {
  // Accelerometer-like 9.8 ± 0.02 m/s² printed with 6 decimals: the file's own step is 1e-6,
  // though the smallest step between neighbours is usually several of them.
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(9.8, 0.02);
  std::vector<double> v(5000);
  for (double& x : v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6f", noise(rng));
    x = std::strtod(text, nullptr);
  }
  const auto q = estimate_lsb(v);
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(*q, 1e-6, 1e-12);
}

TEST(EstimateLsb, NoneForNineSignificantDigits) {
  // "%.9g" keeps relative, not absolute, resolution: no code grid.
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::vector<double> v(5000);
  for (double& x : v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", noise(rng));
    x = std::strtod(text, nullptr);
  }
  EXPECT_FALSE(estimate_lsb(v).has_value());
}

TEST(EstimateLsb, NoneForContinuousNoise) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::vector<double> v(10000);
  for (double& x : v) x = noise(rng);
  EXPECT_FALSE(estimate_lsb(v).has_value());
}

TEST(EstimateLsb, NoneWithTooFewSteps) {
  EXPECT_FALSE(estimate_lsb(std::vector<double>{1.0, 2.0, 3.0}).has_value());
}

TEST(IntervalHistogram, EqualIntervalsGiveOneBinAtTheMedian) {
  std::vector<double> t;
  for (int i = 0; i < 500; ++i) t.push_back(i * 0.02);  // decimal steps: ~1e-17 s rounding
  const TimingReport r = analyze_timing(t);
  ASSERT_EQ(r.interval_histogram.counts.size(), 1u);
  EXPECT_EQ(r.interval_histogram.counts[0], 499);
  EXPECT_LT(r.interval_histogram.bin_low_s[0], r.median_interval_s);
  EXPECT_GT(r.interval_histogram.bin_high_s[0], r.median_interval_s);
  EXPECT_TRUE(r.gaps.empty());
}

TEST(IntervalHistogram, GapListIsCappedButEveryGapIsCounted) {
  std::vector<double> t{0.0};
  const std::size_t gaps = kMaxListedGaps + 5;
  for (std::size_t g = 0; g < gaps; ++g) {
    t.push_back(t.back() + 1.0);
    t.push_back(t.back() + 1.0);
    t.push_back(t.back() + 5.0);  // a gap of 5 median intervals
  }
  const TimingReport r = analyze_timing(t);
  EXPECT_EQ(r.gap_count, static_cast<std::int64_t>(gaps));
  EXPECT_EQ(r.gaps.size(), kMaxListedGaps);
  EXPECT_EQ(r.missing_samples, static_cast<std::int64_t>(4 * gaps));
}

// --- fuzz regressions (fuzz/fuzz_csv_reader) ---------------------------------------------------

// Stamps near the double range: gap / median beyond int64 made llround's result undefined and
// the sum of missing samples a signed overflow (wrapped to -2 here); an infinite interval put a
// NaN bin position through an integer conversion. Both were UBSan aborts in the fuzz build.
TEST(TimingFuzzRegression, MissingSamplesOfAbsurdGapsSaturate) {
  const TimingReport r =
      analyze_timing(std::vector<double>{0, 1e-300, 2e-300, 3e-300, 1e300, 2e300});
  EXPECT_EQ(r.gap_count, 2);
  EXPECT_EQ(r.missing_samples, std::numeric_limits<std::int64_t>::max());
}

TEST(TimingFuzzRegression, InfiniteIntervalLandsInAHistogramBin) {
  const TimingReport r = analyze_timing(std::vector<double>{-1.7e308, 1.7e308, 1.7e308, 1.7e308});
  std::int64_t counted = 0;
  for (const auto c : r.interval_histogram.counts) counted += c;
  EXPECT_EQ(counted, 1);  // the infinite interval; the two 0-s intervals are duplicates
  EXPECT_EQ(r.duplicate_count, 2);
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

SampleLocation locate(std::size_t index, const SamplingOptions& options) {
  SampleLocation loc;
  loc.index = static_cast<std::int64_t>(index);
  if (options.line_of_sample) loc.line = options.line_of_sample(index);
  return loc;
}

double median(std::vector<double> v) {  // of the sorted values, as nth_element would pick them
  std::sort(v.begin(), v.end());
  const std::size_t mid = v.size() / 2;
  return v.size() % 2 == 1 ? v[mid] : 0.5 * (v[mid - 1] + v[mid]);
}

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

std::optional<double> estimate_lsb(const std::vector<double>& v) {
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

Channel analyze_channel(const std::vector<double>& v, std::optional<double> full_scale,
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

Timing analyze_timing(const std::vector<double>& t, const SamplingOptions& options) {
  Timing out;
  TimingReport& r = out.report;
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
  r.median_interval_s = median;
  r.rate_hz = median > 0.0 ? 1.0 / median : 0.0;
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
      r.jitter_max_s = std::max(r.jitter_max_s, std::fabs(d - median));
      ++jitter_count;
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
::testing::AssertionResult same(double a, double b) {
  if (std::memcmp(&a, &b, sizeof a) == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << std::hexfloat << a << " vs " << b;
}

::testing::AssertionResult same(const std::optional<double>& a, const std::optional<double>& b) {
  if (a.has_value() != b.has_value()) {
    return ::testing::AssertionFailure()
           << (a ? "value" : "nullopt") << " vs " << (b ? "value" : "nullopt");
  }
  return a ? same(*a, *b) : ::testing::AssertionSuccess();
}

void expect_same_location(const std::optional<SampleLocation>& a,
                          const std::optional<SampleLocation>& b) {
  ASSERT_EQ(a.has_value(), b.has_value());
  if (!a) return;
  EXPECT_EQ(a->index, b->index);
  EXPECT_EQ(a->line, b->line);
}

/// Within 1e-12 of a long double reference, relative to SCALE (the size of the data: sums of
/// values that cancel have no relative accuracy of their own).
::testing::AssertionResult close(double value, long double reference, long double scale) {
  const long double error = std::fabs(static_cast<long double>(value) - reference);
  if (error <= 1e-12L * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << std::setprecision(17) << value << " vs " << static_cast<double>(reference) << ", error "
         << static_cast<double>(error / scale) << " of the scale";
}

void expect_channel_matches(const std::vector<double>& v, std::optional<double> full_scale,
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

void expect_timing_matches(const std::vector<double>& t, const SamplingOptions& options) {
  const TimingReport r = analyze_timing(t, options);
  const plain::Timing p = plain::analyze_timing(t, options);
  const TimingReport& e = p.report;
  EXPECT_EQ(r.has_timestamps, e.has_timestamps);
  EXPECT_TRUE(same(r.rate_hz, e.rate_hz));
  EXPECT_TRUE(same(r.median_interval_s, e.median_interval_s));
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
constexpr std::size_t kSizes[] = {0,  1,  2,  3,  7,  8,  9,  15, 16, 17, 31,   32,
                                  33, 39, 40, 41, 63, 64, 65, 71, 72, 73, 1000, 100003};

std::string printed(double x, const char* format) {
  char text[48];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

/// Channel values of kind KIND (0 … kChannelKinds − 1), N samples.
constexpr int kChannelKinds = 17;
std::vector<double> channel_values(int kind, std::size_t n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> v(n);
  const double lsbs[] = {1e-3, 0.0078125, 1.0 / 3.0 * 1e-4};
  const double offsets[] = {0.0, 9.80665, -123.4};
  const double q = lsbs[static_cast<std::size_t>(kind) % 3];
  const double offset = offsets[static_cast<std::size_t>(kind / 3) % 3];
  switch (kind) {
    case 0:
    case 1:
    case 2:
    case 3:
    case 4:
    case 5:
    case 6:
    case 7:
    case 8: {
      // Codes q·k + offset, σ of 0.3 to 30 codes: from mostly equal neighbours to none.
      const double sigma = std::array{0.3, 3.0, 30.0}[rng() % 3];
      for (double& x : v) x = offset + q * std::nearbyint(sigma * normal(rng));
      break;
    }
    case 9:  // codes printed with 6 decimals
      for (double& x : v) {
        x = std::strtod(printed(9.8 + 0.0078125 * std::nearbyint(5 * normal(rng)), "%.6f").c_str(),
                        nullptr);
      }
      break;
    case 10:  // unquantised noise
      for (double& x : v) x = 1e-3 * normal(rng);
      break;
    case 11: {  // constant (also ±0)
      const double c = std::array{0.0, -0.0, 1.5, -2.25}[rng() % 4];
      std::fill(v.begin(), v.end(), c);
      break;
    }
    case 12:  // codes with a glitch off the grid now and then
      for (double& x : v) x = 1e-3 * std::nearbyint(4 * normal(rng));
      for (std::size_t i = 0; i < n; i += 1 + rng() % 5000) v[i] += 0.37e-3;
      break;
    case 13:  // a few values only, zeros of both signs among them
      for (double& x : v) x = std::array{0.0, -0.0, 1.0, -1.0, 0.5}[rng() % 5];
      break;
    case 14:  // zero is the minimum, +0 and −0 both present (which comes first is the min)
      for (double& x : v) x = std::array{0.0, -0.0, 0.25, 1.0}[rng() % 4];
      break;
    case 15:  // zero is the maximum
      for (double& x : v) x = std::array{-0.0, 0.0, -0.25, -1.0}[rng() % 4];
      break;
    case 16:  // codes near 1000 whose equal values differ by float rounding (below the floor)
      for (double& x : v) {
        x = 1000.0 + 1e-3 * std::nearbyint(3 * normal(rng));
        if (rng() % 4 == 0) x = std::nextafter(x, 2000.0);
      }
      break;
  }
  return v;
}

/// Clips V at both ends in runs of the given lengths, at the very start and end, across the
/// block edges of the scans (8 + 32·k) and at random places.
void add_saturation(std::vector<double>& v, std::mt19937_64& rng) {
  const std::size_t n = v.size();
  if (n == 0) return;
  double lo = *std::min_element(v.begin(), v.end());
  double hi = *std::max_element(v.begin(), v.end());
  if (rng() % 2) {  // clip beyond the data: new extremes
    hi += 1.0;
    lo -= 1.0;
  }
  const std::size_t lengths[] = {1, 2, 3, 4, 5, 6, 10, 17};
  const auto run = [&](std::size_t start, std::size_t len, double value) {
    for (std::size_t i = start; i < std::min(n, start + len); ++i) v[i] = value;
  };
  run(0, lengths[rng() % 8], rng() % 2 ? lo : hi);
  const std::size_t tail = lengths[rng() % 8];
  run(n - std::min(n, tail), tail, rng() % 2 ? lo : hi);
  for (int k = 0; k < 6; ++k) {
    const std::size_t len = lengths[rng() % 8];
    std::size_t start = rng() % n;
    if (k % 2 == 0) {  // across or up to a block edge
      const std::size_t edge = 8 + 32 * (rng() % (n / 32 + 1));
      start = edge - std::min(edge, static_cast<std::size_t>(rng() % (len + 1)));
    }
    if (start < n) run(start, len, rng() % 2 ? lo : hi);
  }
}

TEST(SamplingReferenceEquality, ChannelMatchesPlainScan) {
  std::mt19937_64 rng(2024);
  int cases = 0;
  for (std::size_t n : kSizes) {
    for (int kind = 0; kind < kChannelKinds; ++kind) {
      for (int variant = 0; variant < 4; ++variant) {
        std::vector<double> v = channel_values(kind, n, rng);
        if (variant >= 2) add_saturation(v, rng);
        std::optional<double> full_scale;
        if (variant % 2 == 1 && n > 0) {  // at, between and beyond some of the samples
          const double top = std::fabs(v[rng() % n]);
          full_scale = std::array{top, 0.5 * top, 1e300, 0.0}[rng() % 4];
        }
        SamplingOptions options;
        options.saturation_min_run = std::array<std::int64_t, 5>{5, 1, 2, 3, 0}[rng() % 5];
        if (rng() % 2) {
          options.line_of_sample = [](std::size_t i) { return static_cast<std::int64_t>(i) + 2; };
        }
        SCOPED_TRACE(::testing::Message() << "n " << n << ", kind " << kind << ", variant "
                                          << variant << ", min run " << options.saturation_min_run);
        expect_channel_matches(v, full_scale, options);
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, static_cast<int>(std::size(kSizes)) * kChannelKinds * 4);
}

TEST(SamplingReferenceEquality, SaturationRunAtEveryPositionAndLength) {
  // An 80-sample walk with one clipped run [start, start + len) at its maximum, for every start
  // and length: every alignment of a run to the blocks of the scan (edges at 8, 40 and 72).
  SamplingOptions options;
  options.saturation_min_run = 3;
  for (std::size_t len = 1; len <= 12; ++len) {
    for (std::size_t start = 0; start + len <= 80; ++start) {
      std::vector<double> v = quantized_walk(80, 1.0, static_cast<unsigned>(len));
      const double top = *std::max_element(v.begin(), v.end()) + 1.0;
      std::fill(v.begin() + static_cast<std::ptrdiff_t>(start),
                v.begin() + static_cast<std::ptrdiff_t>(start + len), top);
      SCOPED_TRACE(::testing::Message() << "run [" << start << ", " << start + len << ")");
      expect_channel_matches(v, top, options);
    }
  }
}

TEST(SamplingReferenceEquality, ZeroExtremeKeepsTheSignOfTheFirstZero) {
  // min = 0 (or max = 0) with +0 and −0 both present, the first of them anywhere: the
  // extreme is the first zero, as a left-to-right std::min / std::max fold finds it.
  for (std::size_t n : {9, 16, 40, 1000}) {
    for (std::size_t first = 0; first + 1 < n; first += 3) {
      for (double sign : {1.0, -1.0}) {
        std::vector<double> v(n, sign);  // all ±1, zeros later
        v[first] = std::copysign(0.0, -sign);
        v[first + 1 + (first * 7) % (n - first - 1)] = std::copysign(0.0, sign);
        SCOPED_TRACE(::testing::Message() << "n " << n << ", first zero " << first);
        expect_channel_matches(v, std::nullopt, {});
      }
    }
  }
}

TEST(SamplingReferenceEquality, EstimateLsbOnLongPrintedRecords) {
  // The exact offender scan behind the vector test: decimal printing puts every step a little
  // off the grid; "%.9g" keeps no absolute grid at all.
  std::mt19937_64 rng(77);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const char* format : {"%.6f", "%.5f", "%.9g", "%.4f"}) {
    std::vector<double> v(200000);
    for (double& x : v) {
      x = std::strtod(printed(9.8 + 0.02 * normal(rng), format).c_str(), nullptr);
    }
    SCOPED_TRACE(format);
    EXPECT_TRUE(same(estimate_lsb(v), plain::estimate_lsb(v)));
  }
}

TEST(SamplingReferenceEquality, EstimateLsbFindsTheFirstOffGridStepLate) {
  // Codes whose first off-grid step comes after the small steps were collected, so the full
  // scan (in analyze_channel: within its second pass) must find it: just outside the 10 %
  // tolerance, well outside, and just inside.
  for (double off : {0.105, 0.15, 0.25, 0.45, 0.095}) {
    for (std::size_t at : {60000, 60001, 60007, 99990}) {
      std::vector<double> v = quantized_walk(100003, 1e-3, static_cast<unsigned>(at));
      v[at] += off * 1e-3;
      v[at + 5] += 0.3 * 1e-3;
      SCOPED_TRACE(::testing::Message() << "off " << off << " at " << at);
      expect_channel_matches(v, std::nullopt, {});  // analyze_channel and estimate_lsb
    }
  }
}

/// Time stamps of kind KIND (0 … kTimingKinds − 1), N of them.
constexpr int kTimingKinds = 12;
std::vector<double> time_stamps(int kind, std::size_t n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> t(n);
  const double dt = std::array{1e-3, 0.01, 1.0 / 400.0}[static_cast<std::size_t>(kind) % 3];
  for (std::size_t i = 0; i < n; ++i) t[i] = static_cast<double>(i) * dt;
  switch (kind) {
    case 0:
    case 1:
    case 2:  // regular, decimal rounding only
      break;
    case 3:
    case 4:
    case 5:  // jitter
      for (double& x : t) x += 0.05 * dt * normal(rng);
      break;
    case 6:  // jitter, duplicates, backward steps and gaps of 1.2 to 50 intervals
      for (std::size_t i = 0; i < n; ++i) {
        t[i] += 0.02 * dt * normal(rng);
        if (i > 0 && uniform(rng) < 0.01) t[i] = t[i - 1];
        if (i > 0 && uniform(rng) < 0.005) t[i] = t[i - 1] - 0.3 * dt;
      }
      for (std::size_t i = 1; i < n; ++i) {
        if (uniform(rng) < 0.003) {
          const double gap = dt * (0.2 + 50.0 * uniform(rng));
          for (std::size_t j = i; j < n; ++j) t[j] += gap;
        }
      }
      break;
    case 7:  // epoch seconds at 1 kHz: intervals quantised to 2^-22 s, few distinct values
      for (std::size_t i = 0; i < n; ++i) t[i] = 1.7e9 + static_cast<double>(i) * 1e-3;
      break;
    case 8:  // mostly duplicates (median 0: the positive intervals give it)
      for (std::size_t i = 0; i < n; ++i) t[i] = std::floor(static_cast<double>(i) / 3.0) * dt;
      break;
    case 9:  // one stamp repeated
      std::fill(t.begin(), t.end(), 5.0);
      break;
    case 10:  // integer microseconds, jittered by whole microseconds
      for (std::size_t i = 0; i < n; ++i) {
        t[i] = (static_cast<double>(i) * 1000.0 + std::nearbyint(3.0 * normal(rng))) * 1e-6;
      }
      break;
    case 11:  // random order within bursts
      for (std::size_t i = 0; i < n; ++i)
        t[i] = std::floor(static_cast<double>(i) / 4.0) * 4.0 * dt + dt * uniform(rng) * 4.0;
      break;
  }
  return t;
}

TEST(SamplingReferenceEquality, TimingMatchesPlainScan) {
  std::mt19937_64 rng(99);
  int cases = 0;
  for (std::size_t n : kSizes) {
    for (int kind = 0; kind < kTimingKinds; ++kind) {
      for (double gap_factor : {1.5, 1.0, 0.5, 4.0}) {
        std::vector<double> t = time_stamps(kind, n, rng);
        SamplingOptions options;
        options.gap_factor = gap_factor;
        if (rng() % 2) {
          options.line_of_sample = [](std::size_t i) { return static_cast<std::int64_t>(i) + 1; };
        }
        SCOPED_TRACE(::testing::Message()
                     << "n " << n << ", kind " << kind << ", gap factor " << gap_factor);
        expect_timing_matches(t, options);
        ++cases;
      }
    }
  }
  // Even and odd interval counts through the sampled median.
  for (std::size_t n : {65537, 65538, 100004}) {
    for (int kind : {3, 6, 7, 10}) {
      SCOPED_TRACE(::testing::Message() << "n " << n << ", kind " << kind);
      expect_timing_matches(time_stamps(kind, n, rng), {});
      ++cases;
    }
  }
  EXPECT_EQ(cases, static_cast<int>(std::size(kSizes)) * kTimingKinds * 4 + 12);
}

TEST(SamplingReferenceEquality, MedianRankAtTheEdgeOfTiedIntervals) {
  // Intervals tied at two values with distinct ones between, shuffled: the middle rank(s) sit
  // exactly at the first or last of a tie, where the sampled median's bracket has its edges.
  // Multiples of 2^-10 keep the stamps exact, so the intervals are these values exactly.
  std::mt19937_64 rng(5);
  for (std::size_t m : {100000, 100001}) {
    for (double low_share : {0.4, 0.45, 0.5, 0.55}) {
      for (double between_share : {0.0, 0.02, 0.1}) {
        std::vector<double> d(m);
        for (std::size_t i = 0; i < m; ++i) {
          const double u = static_cast<double>(i) / static_cast<double>(m);
          d[i] = u < low_share ? 1.0
                 : u < low_share + between_share
                     ? 1.0 + std::ldexp(static_cast<double>(1 + rng() % 511), -10)
                     : 2.0;
        }
        std::shuffle(d.begin(), d.end(), rng);
        std::vector<double> t{0.0};
        for (double x : d) t.push_back(t.back() + x);
        SamplingOptions options;
        options.gap_factor = 3.0;
        SCOPED_TRACE(::testing::Message() << m << " intervals, " << low_share << " low, "
                                          << between_share << " between");
        expect_timing_matches(t, options);
      }
    }
  }
}

TEST(SamplingReferenceEquality, HistogramBinEdgeWhereTheProductRoundsDown) {
  // Integer stamps (exact intervals) whose bin positions (d − lo) / width are whole numbers
  // that d·(1/width) misses by one rounding: the binning must divide there, as the plain code.
  bool found = false;
  for (int stride = 3; stride < 400 && !found; ++stride) {
    std::vector<double> steps;
    for (int j = 0; j <= kIntervalHistogramBins; ++j) steps.push_back(1000.0 + stride * j);
    const double lo = steps.front(), width = (steps.back() - lo) / kIntervalHistogramBins;
    for (double d : steps) {
      found = found || std::floor((d - lo) * (1.0 / width)) != std::floor((d - lo) / width);
    }
    if (!found) continue;
    std::mt19937_64 rng(static_cast<unsigned>(stride));
    std::vector<double> t{0.0};
    for (int i = 0; i < 100000; ++i) t.push_back(t.back() + steps[rng() % steps.size()]);
    SamplingOptions options;
    options.gap_factor = 2.0;
    SCOPED_TRACE(::testing::Message() << "stride " << stride);
    expect_timing_matches(t, options);
    const TimingReport r = analyze_timing(t, options);
    EXPECT_EQ(r.interval_histogram.counts.size(), std::size_t{kIntervalHistogramBins});
  }
  EXPECT_TRUE(found) << "no stride where the product and the quotient floor differently";
}

}  // namespace
}  // namespace imunoise::pipeline
