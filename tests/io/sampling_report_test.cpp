// Tests of io/sampling_report.h: the text and JSON of a sampling report whose gaps, duplicates
// and quantization step are known by construction; the durations it prints
// (common/number_text.h duration_text).
#include "io/sampling_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "common/number_text.h"

namespace imunoise::io {
namespace {

using namespace imunoise::pipeline;
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

TEST(DurationText, PicksTheUnitByMagnitudeWithItsDigits) {
  EXPECT_EQ(duration_text(0.0), "0 s");
  EXPECT_EQ(duration_text(4.77e-8), "47.7 ns");
  EXPECT_EQ(duration_text(8.1234e-6), "8.12 us");
  EXPECT_EQ(duration_text(0.0081256), "8.126 ms");
  EXPECT_EQ(duration_text(310.123456), "310.123 s");
  EXPECT_EQ(duration_text(-0.02), "-20 ms");  // the unit from |s|
  EXPECT_EQ(duration_text(1e-3), "1 ms");
  EXPECT_EQ(duration_text(1.0), "1 s");
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

}  // namespace
}  // namespace imunoise::io
