// Tests of io/sampling_report.h on constructed series whose gaps, jitter, duplicates,
// saturation runs and quantization step are known by construction.
#include "io/sampling_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "common/units.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;

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

TEST(SamplingReportJson, KeysCarryUnits) {
  SamplingReport report;
  report.samples = 8;
  report.timing = analyze_timing(std::vector<double>{0.0, 1.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0});
  const std::vector<double> v{1, 2, 3, 4, 5, 6, 7, 8};
  report.channels.push_back(analyze_channel({"gyro_x", "rad/s", v, std::nullopt}));
  const auto j = sampling_report_to_json(report, "rec.csv");
  EXPECT_EQ(j["file"], "rec.csv");
  EXPECT_DOUBLE_EQ(j["rate_hz"].get<double>(), 1.0);
  EXPECT_TRUE(j.contains("longest_gap_s"));
  EXPECT_TRUE(j.contains("jitter_rms_s"));
  EXPECT_TRUE(j.contains("jitter_max_s"));
  EXPECT_EQ(j["duplicate_count"], 1);
  EXPECT_EQ(j["first_duplicate"]["index"], 2);
  EXPECT_TRUE(j["first_duplicate"]["line"].is_null());
  EXPECT_TRUE(j["first_gap"].is_null());
  EXPECT_EQ(j["channels"][0]["unit"], "rad/s");
  EXPECT_TRUE(j["channels"][0]["lsb"].is_null());  // 7 steps: too few to tell
  EXPECT_TRUE(j["channels"][0]["full_scale"].is_null());
}

TEST(SamplingReportText, ReadableSummary) {
  SamplingReport report;
  std::vector<double> t = uniform_stamps(100, 0.01);
  t.erase(t.begin() + 10);
  report.timing = analyze_timing(t);
  report.samples = static_cast<std::int64_t>(t.size());
  const std::vector<double> v = quantized_walk(t.size(), 0.001);
  report.channels.push_back(analyze_channel({"gyro_x", "rad/s", v, std::nullopt}));
  const std::string text = format_sampling_report(report, "rec.csv");
  EXPECT_THAT(text, HasSubstr("file:       rec.csv"));
  EXPECT_THAT(text, HasSubstr("rate:       100 Hz"));
  EXPECT_THAT(text, HasSubstr("gaps:       1 (longest 20 ms, about 1 samples missing) (first at "
                              "sample 10)"));
  EXPECT_THAT(text, HasSubstr("LSB:        0.001 rad/s (0.0573 deg/s)"));
}

TEST(IntervalHistogram, BinsEveryRegularIntervalAndListsTheGaps) {
  // 10 ms steps with ±0.2 ms alternating jitter, one 55 ms gap after sample 500.
  std::vector<double> t{0.0};
  for (int i = 1; i < 1000; ++i) {
    const double step = i == 501 ? 0.055 : 0.010 + (i % 2 == 0 ? 2e-4 : -2e-4);
    t.push_back(t.back() + step);
  }
  const TimingReport r = analyze_timing(t);
  const IntervalHistogram& h = r.interval_histogram;
  ASSERT_EQ(h.counts.size(), static_cast<std::size_t>(kIntervalHistogramBins));
  std::int64_t total = 0;
  for (auto c : h.counts) total += c;
  EXPECT_EQ(total, 998);  // 999 intervals, one of them the gap
  EXPECT_NEAR(h.bin_low_s.front(), 0.0098, 1e-12);
  EXPECT_NEAR(h.bin_high_s.back(), 0.0102, 1e-12);
  // Two clusters: the shortest and the longest interval fill the first and last bins.
  EXPECT_EQ(h.counts.front() + h.counts.back(), 998);
  ASSERT_EQ(r.gaps.size(), 1u);
  EXPECT_EQ(r.gaps[0].after.index, 501);
  EXPECT_NEAR(r.gaps[0].start_s, t[500], 1e-12);
  EXPECT_NEAR(r.gaps[0].length_s, 0.055, 1e-12);
  const auto j = sampling_report_to_json(SamplingReport{1000, r, {}, 0, 0}, "x.csv");
  EXPECT_EQ(j["interval_histogram"]["counts"].size(), h.counts.size());
  EXPECT_EQ(j["gaps"][0]["after"]["index"], 501);
  EXPECT_DOUBLE_EQ(j["gaps"][0]["length_s"].get<double>(), r.gaps[0].length_s);
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

}  // namespace
}  // namespace imunoise::io
