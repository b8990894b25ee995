// Tests of io/sampling_report.h: the text and JSON of a sampling report whose gaps, duplicates
// and quantization step are known by construction, the JSON and the file read back, and the
// durations it prints (common/number_text.h duration_text).
#include "io/sampling_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/units.h"
#include "test_support.h"

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

// --- reading back (sampling_report_from_json, read_sampling_report_json) -------------------------

/// Bit-identical doubles (+0 and −0 differ; NaN equals NaN of the same bits).
::testing::AssertionResult same_bits(double a, double b) {
  if (std::memcmp(&a, &b, sizeof a) == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << std::hexfloat << a << " vs " << b;
}

::testing::AssertionResult same_bits(const std::optional<double>& a,
                                     const std::optional<double>& b) {
  if (a.has_value() != b.has_value()) {
    return ::testing::AssertionFailure()
           << (a ? "value" : "nullopt") << " vs " << (b ? "value" : "nullopt");
  }
  return a ? same_bits(*a, *b) : ::testing::AssertionSuccess();
}

::testing::AssertionResult same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) {
    return ::testing::AssertionFailure() << a.size() << " vs " << b.size() << " values";
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!same_bits(a[i], b[i])) return same_bits(a[i], b[i]) << " at [" << i << "]";
  }
  return ::testing::AssertionSuccess();
}

void expect_same_location(const std::optional<SampleLocation>& a,
                          const std::optional<SampleLocation>& b) {
  ASSERT_EQ(a.has_value(), b.has_value());
  if (!a) return;
  EXPECT_EQ(a->index, b->index);
  EXPECT_EQ(a->line, b->line);
}

/// Every field of two reports equal, doubles bit for bit.
void expect_same_report(const SamplingReport& a, const SamplingReport& b) {
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.non_finite_dropped, b.non_finite_dropped);
  EXPECT_EQ(a.rows_dropped, b.rows_dropped);
  const TimingReport& t = a.timing;
  const TimingReport& u = b.timing;
  EXPECT_EQ(t.has_timestamps, u.has_timestamps);
  EXPECT_TRUE(same_bits(t.rate_hz, u.rate_hz));
  EXPECT_TRUE(same_bits(t.median_interval_s, u.median_interval_s));
  EXPECT_TRUE(same_bits(t.mean_interval_s, u.mean_interval_s));
  EXPECT_TRUE(same_bits(t.sample_period_s, u.sample_period_s));
  EXPECT_EQ(t.period_from_mean, u.period_from_mean);
  EXPECT_TRUE(same_bits(t.duration_s, u.duration_s));
  EXPECT_TRUE(same_bits(t.mean_rate_hz, u.mean_rate_hz));
  EXPECT_EQ(t.gap_count, u.gap_count);
  EXPECT_TRUE(same_bits(t.longest_gap_s, u.longest_gap_s));
  EXPECT_EQ(t.missing_samples, u.missing_samples);
  expect_same_location(t.first_gap, u.first_gap);
  EXPECT_EQ(t.non_monotonic_count, u.non_monotonic_count);
  expect_same_location(t.first_non_monotonic, u.first_non_monotonic);
  EXPECT_EQ(t.duplicate_count, u.duplicate_count);
  expect_same_location(t.first_duplicate, u.first_duplicate);
  EXPECT_TRUE(same_bits(t.jitter_rms_s, u.jitter_rms_s));
  EXPECT_TRUE(same_bits(t.jitter_max_s, u.jitter_max_s));
  EXPECT_TRUE(same_bits(t.interval_histogram.bin_low_s, u.interval_histogram.bin_low_s));
  EXPECT_TRUE(same_bits(t.interval_histogram.bin_high_s, u.interval_histogram.bin_high_s));
  EXPECT_EQ(t.interval_histogram.counts, u.interval_histogram.counts);
  ASSERT_EQ(t.gaps.size(), u.gaps.size());
  for (std::size_t i = 0; i < t.gaps.size(); ++i) {
    EXPECT_EQ(t.gaps[i].after.index, u.gaps[i].after.index);
    EXPECT_EQ(t.gaps[i].after.line, u.gaps[i].after.line);
    EXPECT_TRUE(same_bits(t.gaps[i].start_s, u.gaps[i].start_s));
    EXPECT_TRUE(same_bits(t.gaps[i].length_s, u.gaps[i].length_s));
  }
  ASSERT_EQ(a.channels.size(), b.channels.size());
  for (std::size_t i = 0; i < a.channels.size(); ++i) {
    const ChannelReport& c = a.channels[i];
    const ChannelReport& d = b.channels[i];
    SCOPED_TRACE(c.name);
    EXPECT_EQ(c.name, d.name);
    EXPECT_EQ(c.unit, d.unit);
    EXPECT_TRUE(same_bits(c.min, d.min));
    EXPECT_TRUE(same_bits(c.max, d.max));
    EXPECT_TRUE(same_bits(c.mean, d.mean));
    EXPECT_TRUE(same_bits(c.std_dev, d.std_dev));
    EXPECT_EQ(c.constant, d.constant);
    EXPECT_EQ(c.saturation_runs, d.saturation_runs);
    EXPECT_EQ(c.saturated_samples, d.saturated_samples);
    EXPECT_EQ(c.longest_saturation_run, d.longest_saturation_run);
    expect_same_location(c.first_saturation, d.first_saturation);
    EXPECT_TRUE(same_bits(c.full_scale, d.full_scale));
    EXPECT_EQ(c.beyond_full_scale, d.beyond_full_scale);
    expect_same_location(c.first_beyond_full_scale, d.first_beyond_full_scale);
    EXPECT_TRUE(same_bits(c.lsb, d.lsb));
  }
}

/// A report with gaps, duplicates, a backward step, file lines, an interval histogram, and
/// channels with and without LSB, full scale and saturation.
SamplingReport full_report() {
  std::vector<double> t = uniform_stamps(3000, 0.0025);  // 400 Hz
  std::mt19937_64 rng(17);
  std::normal_distribution<double> jitter(0.0, 2e-5);
  for (double& x : t) x += jitter(rng);
  t.erase(t.begin() + 1000, t.begin() + 1003);  // a gap of 4 intervals
  t.erase(t.begin() + 2000, t.begin() + 2010);  // a gap of 11 intervals
  t.insert(t.begin() + 500, t[499]);            // a duplicate stamp
  t.insert(t.begin() + 700, t[699] - 1e-4);     // a backward step
  SamplingOptions options;
  options.line_of_sample = [](std::size_t i) { return static_cast<std::int64_t>(i) + 2; };
  SamplingReport report;
  report.timing = analyze_timing(t, options);
  report.samples = static_cast<std::int64_t>(t.size());
  report.non_finite_dropped = 3;
  report.rows_dropped = 2;
  std::vector<double> gyro = quantized_walk(t.size(), 250.0 / 32768.0 * units::kDegPerS);
  std::fill(gyro.begin() + 40, gyro.begin() + 50, *std::max_element(gyro.begin(), gyro.end()));
  std::normal_distribution<double> noise(9.81, 0.02);
  std::vector<double> accel(t.size());
  for (double& x : accel) x = noise(rng);
  const std::vector<double> constant(t.size(), -0.0);
  report.channels.push_back(analyze_channel({"gyro_x", "rad/s", gyro, 1e-3}, options));
  report.channels.push_back(analyze_channel({"accel_z", "m/s^2", accel, std::nullopt}, options));
  report.channels.push_back(analyze_channel({"temp", "", constant, 0.0}, options));
  return report;
}

TEST(SamplingReportJson, RoundTripsEveryField) {
  const SamplingReport report = full_report();
  // What the test covers, by construction.
  ASSERT_EQ(report.timing.gap_count, 2);
  ASSERT_EQ(report.timing.duplicate_count, 1);
  ASSERT_EQ(report.timing.non_monotonic_count, 1);
  ASSERT_EQ(report.timing.interval_histogram.counts.size(),
            static_cast<std::size_t>(kIntervalHistogramBins));
  ASSERT_TRUE(report.channels[0].lsb && report.channels[0].full_scale);
  ASSERT_GT(report.channels[0].saturation_runs, 0);
  ASSERT_TRUE(report.channels[0].first_beyond_full_scale);
  ASSERT_FALSE(report.channels[1].lsb || report.channels[1].full_scale);
  ASSERT_TRUE(report.channels[2].constant);
  // As `imunoise analyze` writes it: dump(2), parsed back.
  const std::string text = sampling_report_to_json(report, "rec.csv").dump(2) + "\n";
  const SamplingReport back =
      sampling_report_from_json(nlohmann::ordered_json::parse(text), "sampling_report.json");
  expect_same_report(report, back);
}

TEST(SamplingReportJson, ReadsTheFileBackWithItsSource) {
  const SamplingReport report = full_report();
  const auto path = test::make_temp_dir("sampling_report_json") / "sampling_report.json";
  test::write_text(path, sampling_report_to_json(report, "data/rec 1.csv").dump(2) + "\n");
  const SamplingReportFile file = read_sampling_report_json(path.string());
  EXPECT_EQ(file.source_path, "data/rec 1.csv");
  expect_same_report(report, file.report);
}

TEST(SamplingReportJson, WrittenFileReadsBackToTheSameReport) {
  const SamplingReport report = full_report();
  const auto dir = test::make_temp_dir("sampling_report_write");
  const auto path = dir / "sampling_report.json";
  write_sampling_report_json(path.string(), report, "data/rec 1.csv");
  const SamplingReportFile file = read_sampling_report_json(path.string());
  EXPECT_EQ(file.source_path, "data/rec 1.csv");
  expect_same_report(report, file.report);
  // The bytes `imunoise analyze` writes: the JSON with indent 2 and a final newline; no
  // temporary file is left beside it.
  EXPECT_EQ(test::read_file_bytes(path),
            sampling_report_to_json(report, "data/rec 1.csv").dump(2) + "\n");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(SamplingReportJson, PeriodFromTheMeanRoundTripsAndOlderFilesReadTheMedian) {
  std::vector<double> t{0.0};
  for (int i = 0; i < 300; ++i) t.push_back(t.back() + (i % 3 == 2 ? 0.11 : 0.10));
  SamplingReport report;
  report.samples = static_cast<std::int64_t>(t.size());
  report.timing = analyze_timing(t);
  ASSERT_TRUE(report.timing.period_from_mean);
  nlohmann::ordered_json j = sampling_report_to_json(report, "alt.csv");
  expect_same_report(report, sampling_report_from_json(j, "alt.json"));
  // A file written before the sample period could be the mean has none of the three keys: its
  // period is its median interval.
  j.erase("mean_interval_s");
  j.erase("sample_period_s");
  j.erase("period_from_mean");
  const TimingReport old = sampling_report_from_json(j, "old.json").timing;
  EXPECT_EQ(old.sample_period_s, report.timing.median_interval_s);
  EXPECT_FALSE(old.period_from_mean);
  // Text: the rate says where it came from.
  EXPECT_NE(format_sampling_report(report, "alt.csv").find("from the mean regular interval"),
            std::string::npos);
}

TEST(SamplingReportJson, FixedRateReportRoundTrips) {
  SamplingReport report;
  report.samples = 401;
  report.timing = fixed_rate_timing(200.0, 401);
  const SamplingReport back = sampling_report_from_json(
      nlohmann::ordered_json::parse(sampling_report_to_json(report, "x.csv").dump()), "x");
  expect_same_report(report, back);
  EXPECT_TRUE(back.timing.interval_histogram.counts.empty());
}

TEST(SamplingReportJson, WritesRoundTripDigits) {
  // nlohmann writes digits that read back to the same double (Grisu2, at most 17 significant):
  // every finite double, of any exponent and sign, subnormals included, survives the file bit
  // for bit.
  std::mt19937_64 rng(23);
  std::vector<double> values{0.0,
                             -0.0,
                             std::numeric_limits<double>::min(),
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::max(),
                             0.1,
                             1.0 / 3.0,
                             0.0025000000000000001};
  while (values.size() < 5000) {
    const std::uint64_t bits = rng();
    double x = 0.0;
    std::memcpy(&x, &bits, sizeof x);
    if (std::isfinite(x)) values.push_back(x);
  }
  SamplingReport report;
  report.timing.has_timestamps = true;
  report.timing.interval_histogram.bin_low_s = values;
  report.timing.interval_histogram.bin_high_s = values;
  report.timing.interval_histogram.counts.assign(values.size(), 1);
  report.timing.rate_hz = values[6];
  const SamplingReport back = sampling_report_from_json(
      nlohmann::ordered_json::parse(sampling_report_to_json(report, "x.csv").dump(2)), "x");
  EXPECT_TRUE(same_bits(back.timing.interval_histogram.bin_low_s, values));
  EXPECT_TRUE(same_bits(back.timing.interval_histogram.bin_high_s, values));
  expect_same_report(report, back);
}

TEST(SamplingReportJson, NonFiniteRealReadsBackAsNaN) {
  // JSON has no inf or NaN: nlohmann writes null, which the reader takes as NaN.
  SamplingReport report;
  report.timing.longest_gap_s = std::numeric_limits<double>::infinity();
  report.timing.jitter_rms_s = std::nan("");
  const std::string text = sampling_report_to_json(report, "x.csv").dump();
  EXPECT_NE(text.find("\"longest_gap_s\":null"), std::string::npos) << text;
  const SamplingReport back = sampling_report_from_json(nlohmann::ordered_json::parse(text), "x");
  EXPECT_TRUE(std::isnan(back.timing.longest_gap_s));
  EXPECT_TRUE(std::isnan(back.timing.jitter_rms_s));
}

TEST(SamplingReportJson, MissingOrMistypedKeyNamesThePathAndTheKey) {
  const nlohmann::ordered_json good = sampling_report_to_json(full_report(), "rec.csv");
  const auto error_with = [&](auto&& edit) {
    nlohmann::ordered_json j = good;
    edit(j);
    return test::error_of([&] { sampling_report_from_json(j, "out/sampling_report.json"); });
  };
  EXPECT_EQ(error_with([](auto& j) { j.erase("rate_hz"); }),
            "out/sampling_report.json: key 'rate_hz' missing");
  EXPECT_EQ(error_with([](auto& j) { j["rate_hz"] = "400"; }),
            "out/sampling_report.json: key 'rate_hz' not a number");
  EXPECT_EQ(error_with([](auto& j) { j["samples"] = 2.5; }),
            "out/sampling_report.json: key 'samples' not an integer");
  EXPECT_EQ(error_with([](auto& j) { j["file"] = 1; }),
            "out/sampling_report.json: key 'file' not a string");
  EXPECT_EQ(error_with([](auto& j) { j["has_timestamps"] = 1; }),
            "out/sampling_report.json: key 'has_timestamps' not a boolean");
  EXPECT_EQ(error_with([](auto& j) { j["channels"][1].erase("std"); }),
            "out/sampling_report.json: channels[1]: key 'std' missing");
  EXPECT_EQ(error_with([](auto& j) { j["channels"][0]["lsb"] = "small"; }),
            "out/sampling_report.json: channels[0]: key 'lsb' not a number or null");
  EXPECT_EQ(error_with([](auto& j) { j["first_gap"].erase("line"); }),
            "out/sampling_report.json: first_gap: key 'line' missing");
  EXPECT_EQ(error_with([](auto& j) { j["gaps"][1]["after"]["index"] = -1.5; }),
            "out/sampling_report.json: gaps[1].after: key 'index' not an integer");
  EXPECT_EQ(error_with([](auto& j) { j["interval_histogram"]["counts"].push_back(1); }),
            "out/sampling_report.json: interval_histogram: bin_low_s, bin_high_s and counts "
            "differ in length");
  EXPECT_EQ(error_with([](auto& j) { j["interval_histogram"]["bin_low_s"][0] = true; }),
            "out/sampling_report.json: interval_histogram: key 'bin_low_s' not a number");
  EXPECT_EQ(error_with([](auto& j) { j["missing_samples"] = 9223372036854775808u; }),
            "out/sampling_report.json: key 'missing_samples' not an integer");
  EXPECT_EQ(error_with([](auto& j) { j = nlohmann::ordered_json::array(); }),
            "out/sampling_report.json: not a JSON object");
}

TEST(SamplingReportJson, UnreadableFileIsAnInputError) {
  const auto dir = test::make_temp_dir("sampling_report_bad");
  EXPECT_EQ(test::error_of([&] { read_sampling_report_json((dir / "none.json").string()); }),
            (dir / "none.json").string() + ": cannot open for reading");
  test::write_text(dir / "bad.json", "{\"file\": ");
  test::expect_throw_containing<InputError>(
      [&] { read_sampling_report_json((dir / "bad.json").string()); },
      (dir / "bad.json").string() + ": not valid JSON (");
}

}  // namespace
}  // namespace imunoise::io
