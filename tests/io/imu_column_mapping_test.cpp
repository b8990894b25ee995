// Tests of read_recording (io/csv_reader.h, io/imu_column_mapping.cpp) and pipeline/recording.h:
// column mapping, SI conversion of every unit, increments, fixed rate, exact ns stamps, progress,
// and the mapping errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.h"
#include "common/units.h"
#include "io/csv_reader.h"
#include "pipeline/recording.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr char kSimulateHeader[] =
    "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,accel_x_m_per_s2,"
    "accel_y_m_per_s2,accel_z_m_per_s2\n";

std::string fixture(const std::string& name, const std::string& text) {
  const auto path = test::make_temp_dir("rec") / name;
  test::write_text(path, text);
  return path.string();
}

using test::error_of;

const pipeline::Channel& channel(const pipeline::Recording& rec, const std::string& name) {
  const pipeline::Channel* c = rec.find_channel(name);
  if (c == nullptr) throw std::runtime_error("no channel " + name);
  return *c;
}

TEST(ReadRecording, RecognisesSimulateColumnNames) {
  const auto path = fixture("sim.csv", std::string(kSimulateHeader) +
                                           "0.00,1,2,3,4,5,6\n"
                                           "0.01,1,2,3,4,5,6\n"
                                           "0.02,1,2,3,4,5,6\n");
  const pipeline::Recording rec = read_recording(path, {});
  ASSERT_EQ(rec.channels.size(), 6u);
  EXPECT_EQ(rec.channels[0].name, "gyro_x");
  EXPECT_EQ(rec.channels[5].name, "accel_z");
  EXPECT_EQ(channel(rec, "gyro_y").unit(), "rad/s");
  EXPECT_EQ(channel(rec, "accel_x").unit(), "m/s^2");
  EXPECT_EQ(channel(rec, "gyro_z").source_column, "gyro_z_rad_per_s");
  EXPECT_THAT(channel(rec, "accel_y").values, ElementsAre(5.0, 5.0, 5.0));
  EXPECT_NEAR(rec.sample_period_s, 0.01, 1e-15);
  EXPECT_NEAR(rec.report.timing.rate_hz, 100.0, 1e-9);
  EXPECT_EQ(rec.sample_count(), 3u);
  EXPECT_EQ(rec.time_s.size(), 3u);
}

TEST(ReadRecording, HeaderlessPositionalMappingInDegPerSAndG) {
  const auto path = fixture("raw.txt", "0.0 1 -2 0.5 1 0 -1\n0.5 1 -2 0.5 1 0 -1\n");
  InputConfig config;
  config.time_column = "1";
  config.gyro_columns = {"2", "3", "4"};
  config.gyro_unit = GyroUnit::kDegPerS;
  config.accel_columns = {"5", "6", "7"};
  config.accel_unit = AccelUnit::kG;
  const pipeline::Recording rec = read_recording(path, config);
  EXPECT_DOUBLE_EQ(channel(rec, "gyro_x").values[0], 0.017453292519943295);  // π/180
  EXPECT_DOUBLE_EQ(channel(rec, "gyro_y").values[0], -2.0 * 0.017453292519943295);
  EXPECT_DOUBLE_EQ(channel(rec, "accel_x").values[0], 9.80665);
  EXPECT_DOUBLE_EQ(channel(rec, "accel_z").values[1], -9.80665);
  EXPECT_EQ(channel(rec, "gyro_x").source_column, "column 2");
  EXPECT_EQ(channel(rec, "gyro_x").source_unit, "deg/s");
  EXPECT_FALSE(channel(rec, "gyro_x").from_increments);
  EXPECT_DOUBLE_EQ(rec.sample_period_s, 0.5);
}

TEST(ReadRecording, DegPerHourAndMilliGFactorsByValue) {
  const auto path = fixture("u.csv", "t,g,a\n0,1,1\n1,1,1\n2,1,1\n");
  InputConfig config;
  config.time_column = "t";
  config.gyro_columns = {"g"};
  config.gyro_unit = GyroUnit::kDegPerHour;
  config.accel_columns = {"a"};
  config.accel_unit = AccelUnit::kMilliG;
  const pipeline::Recording rec = read_recording(path, config);
  EXPECT_NEAR(channel(rec, "gyro_x").values[0], 4.848137e-6, 5e-13);  // theory.md §1.3
  EXPECT_NEAR(channel(rec, "accel_x").values[0], 9.80665e-3, 1e-15);
  ASSERT_EQ(rec.channels.size(), 2u);  // one axis each
}

TEST(ReadRecording, TimeUnits) {
  for (const auto& [unit, stamps, period] :
       {std::tuple{TimeUnit::kMillisecond, "0\n5\n10\n", 0.005},
        std::tuple{TimeUnit::kMicrosecond, "0\n2500\n5000\n", 0.0025},
        std::tuple{TimeUnit::kNanosecond, "0\n1000000\n2000000\n", 0.001},
        std::tuple{TimeUnit::kSecond, "10\n10.25\n10.5\n", 0.25}}) {
    std::string text = "t,g\n";
    std::string rest = stamps;
    for (std::size_t pos = 0; pos < rest.size();) {
      const auto nl = rest.find('\n', pos);
      text += rest.substr(pos, nl - pos) + ",0\n";
      pos = nl + 1;
    }
    InputConfig config;
    config.time_column = "t";
    config.time_unit = unit;
    config.gyro_columns = {"g"};
    const pipeline::Recording rec = read_recording(fixture("t.csv", text), config);
    EXPECT_NEAR(rec.sample_period_s, period, period * 1e-12) << to_string(unit);
    EXPECT_EQ(rec.time_s.front(), 0.0);  // time is relative to the first sample
  }
}

TEST(ReadRecording, AngleAndVelocityIncrementsAreDividedByThePeriod) {
  // 200 Hz; 0.001 rad per sample = 0.2 rad/s; 0.5 deg per sample = 100 deg/s;
  // 0.05 m/s per sample = 10 m/s².
  const auto path = fixture("inc.csv",
                            "time_s,dth,dthd,dv\n0.000,0.001,0.5,0.05\n0.005,0.001,0.5,0.05\n"
                            "0.010,0.001,0.5,0.05\n");
  InputConfig config;
  config.gyro_columns = {"dth"};
  config.gyro_unit = GyroUnit::kRadIncrement;
  config.accel_columns = {"dv"};
  config.accel_unit = AccelUnit::kMPerSIncrement;
  const pipeline::Recording rec = read_recording(path, config);
  EXPECT_NEAR(channel(rec, "gyro_x").values[0], 0.2, 1e-12);
  EXPECT_TRUE(channel(rec, "gyro_x").from_increments);
  EXPECT_EQ(channel(rec, "gyro_x").source_unit, "rad");
  EXPECT_NEAR(channel(rec, "accel_x").values[2], 10.0, 1e-12);
  EXPECT_TRUE(channel(rec, "accel_x").from_increments);

  config.gyro_columns = {"dthd"};
  config.gyro_unit = GyroUnit::kDegIncrement;
  const pipeline::Recording deg = read_recording(path, config);
  EXPECT_NEAR(channel(deg, "gyro_x").values[1], 100.0 * units::kDegPerS, 1e-12);
}

TEST(ReadRecording, FixedRateReplacesTimeColumn) {
  const auto path =
      fixture("r.csv", std::string(kSimulateHeader) + "0,1,2,3,4,5,6\n9,1,2,3,4,5,6\n");
  InputConfig config;
  config.rate_hz = 50.0;
  const pipeline::Recording rec = read_recording(path, config);
  EXPECT_TRUE(rec.time_s.empty());
  EXPECT_DOUBLE_EQ(rec.sample_period_s, 0.02);
  EXPECT_FALSE(rec.report.timing.has_timestamps);
  EXPECT_DOUBLE_EQ(rec.report.timing.rate_hz, 50.0);
  EXPECT_EQ(rec.channels.size(), 6u);
}

TEST(ReadRecording, NanosecondStampsStayExact) {
  // EuRoC-style integer ns stamps at 200 Hz: as doubles they would show ~100 ns fake jitter.
  std::string text = "time_ns,gyro_x_deg_per_s,gyro_y_deg_per_s,gyro_z_deg_per_s\n";
  for (long long i = 0; i < 100; ++i) {
    text += std::to_string(1403636579758555392LL + i * 5000000LL) + ",1,2,3\n";
  }
  const pipeline::Recording rec = read_recording(fixture("ns.csv", text), {});
  EXPECT_NEAR(rec.sample_period_s, 0.005, 1e-15);
  EXPECT_LT(rec.report.timing.jitter_max_s, 1e-15);  // parsed as doubles: ~1e-7 s
  EXPECT_DOUBLE_EQ(rec.start_time_s, 1403636579.758555392);
  EXPECT_DOUBLE_EQ(channel(rec, "gyro_z").values[0], 3.0 * units::kDegPerS);
}

TEST(ReadRecording, ExtraColumnsKeepTheirValues) {
  const auto path = fixture("x.csv", "time_s,gx,temp\n0,0.1,25.5\n1,0.2,25.6\n");
  InputConfig config;
  config.gyro_columns = {"gx"};
  config.extra_columns = {{"temperature_degc", "temp"}};
  const pipeline::Recording rec = read_recording(path, config);
  EXPECT_THAT(channel(rec, "temperature_degc").values, ElementsAre(25.5, 25.6));
  EXPECT_EQ(channel(rec, "temperature_degc").unit(), "");
}

TEST(ReadRecording, ReportNamesFileLinesOfTimingAnomalies) {
  const auto path = fixture("dup.csv",
                            "# logger v1\n"
                            "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s\n"
                            "0.00,0,0,0\n"
                            "0.01,0,0,0\n"
                            "# resync\n"
                            "0.01,0,0,0\n"  // line 6: duplicate
                            "0.02,0,0,0\n"
                            "0.015,0,0,0\n"  // line 8: goes back
                            "0.03,0,0,0\n"
                            "0.04,0,0,0\n");
  const pipeline::Recording rec = read_recording(path, {});
  const pipeline::TimingReport& t = rec.report.timing;
  EXPECT_EQ(t.duplicate_count, 1);
  ASSERT_TRUE(t.first_duplicate.has_value());
  EXPECT_EQ(t.first_duplicate->index, 2);
  EXPECT_EQ(t.first_duplicate->line, 6);
  EXPECT_EQ(t.non_monotonic_count, 1);
  EXPECT_EQ(t.first_non_monotonic->line, 8);
}

TEST(ReadRecording, DroppedNonFiniteRowsAreCounted) {
  const auto path = fixture("nan.csv", std::string(kSimulateHeader) +
                                           "0,1,2,3,4,5,6\n0.1,nan,2,inf,4,5,6\n0.2,1,2,3,4,5,6\n"
                                           "0.3,1,2,3,4,5,6\n0.4,1,2,3,4,5,6\n");
  EXPECT_THAT(error_of([&] { read_recording(path, {}); }),
              HasSubstr("nan.csv:3:5: non-finite value 'nan' in 'gyro_x_rad_per_s' (column 2)"));
  InputConfig config;
  config.drop_non_finite = true;
  const pipeline::Recording rec = read_recording(path, config);
  EXPECT_EQ(rec.sample_count(), 4u);
  EXPECT_EQ(rec.report.rows_dropped, 1);
  EXPECT_EQ(rec.report.non_finite_dropped, 2);
  // The dropped row looks like a gap of one sample.
  EXPECT_EQ(rec.report.timing.gap_count, 1);
}

// --- mapping errors ---------------------------------------------------------------------------

TEST(ReadRecordingErrors, NoTimeColumn) {
  InputConfig config;
  config.gyro_columns = {"1"};
  EXPECT_THAT(error_of([&] { read_recording(fixture("nt.txt", "1\n2\n"), config); }),
              HasSubstr("nt.txt: no time column: give --time-col COL [--time-unit s|ms|us|ns] or "
                        "--rate HZ"));
}

TEST(ReadRecordingErrors, NoImuColumnsListsAvailable) {
  EXPECT_THAT(error_of([&] { read_recording(fixture("ni.csv", "time_s,a,b\n0,1,2\n"), {}); }),
              HasSubstr("ni.csv:1: no gyro or accel columns: map them with --gyro-cols / "
                        "--accel-cols"));
  EXPECT_THAT(error_of([&] { read_recording(fixture("ni.csv", "time_s,a,b\n0,1,2\n"), {}); }),
              HasSubstr("available columns: time_s, a, b"));
}

TEST(ReadRecordingErrors, UnknownMappedColumn) {
  InputConfig config;
  config.gyro_columns = {"gx", "gy", "gz"};
  EXPECT_THAT(error_of([&] { read_recording(fixture("uc.csv", "time_s,gx,gy\n0,1,2\n"), config); }),
              HasSubstr("uc.csv:1: unknown column 'gz' (available columns: time_s, gx, gy)"));
}

TEST(ReadRecordingErrors, UnitContradictsColumnName) {
  InputConfig config;
  config.gyro_unit = GyroUnit::kDegPerS;
  const auto path =
      fixture("c.csv", std::string(kSimulateHeader) + "0,1,2,3,4,5,6\n1,1,2,3,4,5,6\n");
  EXPECT_THAT(error_of([&] { read_recording(path, config); }),
              HasSubstr("column 'gyro_x_rad_per_s' is in rad/s but gyro unit deg/s was given"));
}

TEST(ReadRecordingErrors, RateAndTimeColumnTogether) {
  InputConfig config;
  config.rate_hz = 100.0;
  config.time_column = "time_s";
  const auto path = fixture("b.csv", std::string(kSimulateHeader) + "0,1,2,3,4,5,6\n");
  EXPECT_THAT(error_of([&] { read_recording(path, config); }),
              HasSubstr("give either a time column or a rate, not both"));
}

TEST(ReadRecordingErrors, TimeColumnReusedAsChannel) {
  InputConfig config;
  config.time_column = "1";
  config.gyro_columns = {"1", "2"};
  EXPECT_THAT(error_of([&] { read_recording(fixture("tc.txt", "0 1\n1 2\n"), config); }),
              HasSubstr("tc.txt: column 1 is mapped both as the time column and as a channel"));
}

TEST(ReadRecordingErrors, TooFewSamplesAndStuckClock) {
  const auto one = fixture("one.csv", std::string(kSimulateHeader) + "0,1,2,3,4,5,6\n");
  EXPECT_THAT(error_of([&] { read_recording(one, {}); }),
              HasSubstr("one.csv: too few samples: 1 (need at least 2 for a sample rate from time "
                        "stamps)"));
  const auto stuck = fixture(
      "stuck.csv", std::string(kSimulateHeader) + "5,1,2,3,4,5,6\n5,1,2,3,4,5,6\n5,1,2,3,4,5,6\n");
  EXPECT_THAT(error_of([&] { read_recording(stuck, {}); }),
              HasSubstr("stuck.csv:2: cannot estimate the sample rate: the time stamps never "
                        "increase"));
}

TEST(RequireMinSamples, NamesFileCountAndPurpose) {
  pipeline::Recording rec;
  rec.source_path = "rec.csv";
  rec.channels.push_back({"gyro_x", SensorKind::gyro, {1.0, 2.0, 3.0}, "gx", "rad/s", false});
  EXPECT_NO_THROW(pipeline::require_min_samples(rec, 3, "Allan deviation"));
  EXPECT_THAT(error_of([&] { pipeline::require_min_samples(rec, 100, "Allan deviation"); }),
              HasSubstr("rec.csv: too few samples: 3 (need at least 100 for Allan deviation)"));
}

// --- fuzz regressions (fuzz/fuzz_csv_reader) ---------------------------------------------------

// Time stamps whose gaps are beyond int64 multiples of the median interval (found by
// fuzz_csv_reader as a UBSan signed overflow in the sampling report): read and reported, with
// the missing-sample count saturated.
TEST(ReadRecordingFuzzRegression, AbsurdGapsAreReportedWithoutOverflow) {
  const auto path = fixture("absurd_gaps.csv",
                            "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s\n"
                            "0,1,1,1\n1e-300,1,1,1\n2e-300,1,1,1\n3e-300,1,1,1\n"
                            "1e300,1,1,1\n2e300,1,1,1\n");
  const pipeline::Recording rec = read_recording(path, {});
  EXPECT_EQ(rec.report.timing.gap_count, 2);
  EXPECT_EQ(rec.report.timing.missing_samples, std::numeric_limits<std::int64_t>::max());
}

// The progress callback follows the bytes read, block by block, up to the file size, and the
// recording read with it is the same as without.
TEST(ReadRecording, ProgressFollowsTheBytesReadAndChangesNothing) {
  std::string text =
      "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,accel_x_m_per_s2,"
      "accel_y_m_per_s2,accel_z_m_per_s2\n";
  for (int i = 0; i < 60000; ++i) {
    text.append(std::to_string(0.01 * i));
    for (int c = 0; c < 6; ++c) text.append(",").append(std::to_string(1e-3 * ((i + c) % 97)));
    text.append("\n");
  }
  const std::string path = fixture("progress.csv", text);
  std::vector<std::int64_t> done_seen;
  std::int64_t total_seen = 0;
  const pipeline::Recording with = read_recording(
      path, InputConfig{}, [&](std::string_view stage, std::int64_t done, std::int64_t total) {
        EXPECT_EQ(stage, "reading");
        done_seen.push_back(done);
        total_seen = total;
      });
  const pipeline::Recording without = read_recording(path, InputConfig{});
  EXPECT_EQ(total_seen, static_cast<std::int64_t>(text.size()));
  ASSERT_GE(done_seen.size(), 2u) << "more than one 1 MiB block";
  EXPECT_TRUE(std::is_sorted(done_seen.begin(), done_seen.end()));
  EXPECT_EQ(done_seen.back(), total_seen);
  ASSERT_EQ(with.channels.size(), without.channels.size());
  EXPECT_EQ(with.channels[0].values, without.channels[0].values);
}

}  // namespace
}  // namespace imunoise::io
