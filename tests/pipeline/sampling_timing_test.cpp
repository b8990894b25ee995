// Tests of the time-stamp checks (analyze_timing, fixed_rate_timing; pipeline/sampling_timing.cpp)
// on constructed series whose gaps, jitter and duplicates are known by construction, and against
// the plain scan (sampling_reference_scans.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "pipeline/sampling_checks.h"
#include "pipeline/sampling_reference_scans.h"

namespace imunoise::pipeline {
namespace {

using namespace sampling_test;  // the plain scans, the comparisons and the shared inputs

std::vector<double> uniform_stamps(std::size_t n, double dt) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = static_cast<double>(i) * dt;
  return t;
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

TEST(AnalyzeTiming, AlternatingStampsGiveTheMeanIntervalAsThePeriod) {
  // Stamped alternately 0.10 and 0.11 s after the previous one — a 10 Hz clock that slips — and
  // two 0.10 per 0.11 so the median is 0.10: the true period is the mean, (2·0.10 + 0.11)/3.
  std::vector<double> t{0.0};
  for (int i = 0; i < 3000; ++i) t.push_back(t.back() + (i % 3 == 2 ? 0.11 : 0.10));
  const TimingReport r = analyze_timing(t);
  EXPECT_NEAR(r.median_interval_s, 0.10, 1e-12);
  EXPECT_TRUE(r.period_from_mean);
  EXPECT_NEAR(r.mean_interval_s, 0.31 / 3.0, 1e-12);
  EXPECT_NEAR(r.sample_period_s, 0.31 / 3.0, 1e-12);
  EXPECT_NEAR(r.rate_hz, 3.0 / 0.31, 1e-9);
}

TEST(AnalyzeTiming, SymmetricJitterAndGapsKeepTheMedian) {
  // Gaussian jitter of 1 % and three gaps: the mean regular interval stays within ~0.01 %/√n of
  // the median, far inside the 0.1 % threshold; the gaps are not regular intervals.
  std::mt19937_64 rng(4);
  std::normal_distribution<double> jitter(0.0, 0.01 * 0.0025);
  std::vector<double> t{0.0};
  for (int i = 0; i < 20000; ++i) {
    const double gap = (i == 5000 || i == 9000 || i == 15000) ? 0.5 : 0.0;
    t.push_back(t.back() + 0.0025 + jitter(rng) + gap);
  }
  const TimingReport r = analyze_timing(t);
  EXPECT_FALSE(r.period_from_mean);
  EXPECT_EQ(r.gap_count, 3);
  EXPECT_EQ(r.sample_period_s, r.median_interval_s);
  EXPECT_NEAR(r.mean_interval_s / 0.0025, 1.0, 4.0 * 0.01 / std::sqrt(20000.0));
}

TEST(AnalyzeTiming, TooFewStampsGiveNoRate) {
  EXPECT_EQ(analyze_timing(std::vector<double>{1.0}).rate_hz, 0.0);
  EXPECT_EQ(analyze_timing(std::vector<double>{}).rate_hz, 0.0);
}

// --- exact rates -------------------------------------------------------------------------------

TEST(AnalyzeTiming, DecimalStampsGiveTheirRateExactly) {
  // k / 400 s, as simulate writes and reads back: the intervals in double scatter by ulps and
  // their median was 0.0025000000000545697 s (399.99999999126885 Hz) on 2 h of stamps.
  for (const std::size_t n : {std::size_t{1000}, std::size_t{2880000}}) {
    std::vector<double> t(n);
    for (std::size_t k = 0; k < n; ++k) t[k] = static_cast<double>(k) / 400.0;
    const TimingReport r = analyze_timing(t);
    EXPECT_EQ(r.rate_hz, 400.0) << n;
    EXPECT_EQ(r.median_interval_s, 0.0025) << n;
    EXPECT_EQ(r.sample_period_s, 0.0025) << n;
    EXPECT_FALSE(r.period_from_mean);
  }
  // Whole µs with jitter of whole µs: the median on the µs grid; 1e6 / 2501 exactly.
  std::vector<double> t;
  for (int k = 0; k < 101; ++k) t.push_back((k * 2501 + (k % 2)) * 1e-6);
  const TimingReport r = analyze_timing(t);
  EXPECT_EQ(r.median_interval_s, 2501e-6);
  EXPECT_EQ(r.rate_hz, 1e6 / 2501.0);
}

TEST(AnalyzeTiming, StampsOffEveryGridKeepTheirDoubleMedian) {
  std::vector<double> t;
  for (int k = 0; k < 50; ++k) t.push_back(k * 0.0025 + 1e-11 * (k % 3));
  EXPECT_EQ(decimal_grid_digits(t), std::nullopt);
  const TimingReport r = analyze_timing(t);
  std::vector<double> d;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) d.push_back(t[i + 1] - t[i]);
  std::nth_element(d.begin(), d.begin() + 24, d.end());
  EXPECT_EQ(r.median_interval_s, d[24]);  // 49 intervals: the 25th smallest
}

TEST(DecimalGrid, FewestDecimalsAndTheToleranceOfRounding) {
  EXPECT_EQ(decimal_grid_digits(std::vector<double>{0.0, 0.5, 1.0, 1.5}), 1);
  EXPECT_EQ(decimal_grid_digits(std::vector<double>{0.0, 1.0, 7.0}), 0);
  EXPECT_EQ(decimal_grid_digits(std::vector<double>{0.0, 0.0025, 0.005, 7199.9975}), 4);
  EXPECT_EQ(decimal_grid_digits(std::vector<double>{0.0, 1.0 / 3.0}), std::nullopt);
  EXPECT_TRUE(on_decimal_grid(0.1 + 0.2, 1));     // 0.30000000000000004: 1 ulp off 0.3
  EXPECT_FALSE(on_decimal_grid(0.3 + 1e-12, 1));  // far beyond rounding
  // 1.7e9 s (epoch) has ulps of 2.4e-7 s: a ns grid cannot be told from rounding there.
  EXPECT_FALSE(on_decimal_grid(1.7e9, 9));
  EXPECT_TRUE(on_decimal_grid(1.7e9, 0));
  EXPECT_EQ(snap_to_decimal_grid(0.0025000000000545697, 4), 0.0025);
  EXPECT_EQ(snap_to_decimal_grid(0.00150000000001, 3), 0.0015);  // half a step: even count
}

TEST(ExactTickMedian, IntegerNanosecondsGiveTheirRateHoweverLong) {
  // 200 Hz ns stamps about 4e15 ns (46 days) from the first: in seconds the ns grid is lost
  // (ulps of 4e6 s are 9e-10 s), and the median of double intervals is not 5 ms.
  std::vector<double> ticks;
  constexpr double kBase = 4e15;
  ticks.push_back(0.0);
  for (int k = 0; k < 2001; ++k) ticks.push_back(kBase + k * 5e6 + (k % 7 == 0 ? 37.0 : 0.0));
  const std::optional<ExactMedianInterval> exact = exact_tick_median(ticks, 1e9);
  ASSERT_TRUE(exact.has_value());
  EXPECT_EQ(exact->twice_ticks, 1e7);
  EXPECT_EQ(exact->rate_hz(), 200.0);
  EXPECT_EQ(exact->seconds(), 0.005);
  std::vector<double> seconds = ticks;
  for (double& v : seconds) v *= 1e-9;
  const TimingReport plain = analyze_timing(seconds);
  EXPECT_NE(plain.rate_hz, 200.0);  // what the double median gives
  const TimingReport r = analyze_timing(seconds, {}, exact);
  EXPECT_EQ(r.rate_hz, 200.0);
  EXPECT_EQ(r.median_interval_s, 0.005);
  EXPECT_EQ(r.sample_period_s, 0.005);
  EXPECT_EQ(r.gap_count, 1);  // the jump to kBase
  // An even count of intervals: the mean of the two middle ones, a half tick.
  EXPECT_EQ(exact_tick_median(std::vector<double>{0, 3, 7}, 1e9)->twice_ticks, 7.0);
  // Not whole numbers, or no positive interval: no exact median.
  EXPECT_EQ(exact_tick_median(std::vector<double>{0, 0.5, 1}, 1e9), std::nullopt);
  EXPECT_EQ(exact_tick_median(std::vector<double>{5, 5, 5}, 1e9), std::nullopt);
  EXPECT_EQ(exact_tick_median(std::vector<double>{0, 1e16}, 1e9), std::nullopt);  // > 2^53
}

TEST(FixedRateTiming, KnowsRateAndDuration) {
  const TimingReport r = fixed_rate_timing(200.0, 401);
  EXPECT_FALSE(r.has_timestamps);
  EXPECT_DOUBLE_EQ(r.median_interval_s, 0.005);
  EXPECT_DOUBLE_EQ(r.duration_s, 2.0);
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
