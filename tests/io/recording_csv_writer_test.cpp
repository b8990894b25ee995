// Tests of io/recording_csv_writer.h: the row formatter, the column names, the '#' header, and
// the round trip the CSV exists for — written, then read back by io::read_recording with
// default options, every value and stamp identical bit for bit (shortest round-trip text).
#include "io/recording_csv_writer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/csv_reader.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b,
                      const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a[i]), std::bit_cast<std::uint64_t>(b[i]))
        << what << " sample " << i << ": " << a[i] << " vs " << b[i];
  }
}

/// Six IMU channels of N samples: random values over many binades, plus the numbers whose
/// shortest text is longest or most awkward in the first rows.
pipeline::Recording imu_recording(std::size_t n) {
  pipeline::Recording rec;
  rec.source_path = "memory.csv";
  rec.sample_period_s = 0.0025;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> binade(-30, 30);
  const std::vector<double> awkward{-2.2250738585072014e-308,
                                    1.7976931348623157e308,
                                    0.1,
                                    1.0 / 3.0,
                                    -0.0,
                                    123456789.12345679,
                                    5e-324,
                                    -9.80665};
  for (std::size_t c = 0; c < 6; ++c) {
    pipeline::Channel ch;
    ch.name = pipeline::kImuChannelNames[c];
    ch.kind = pipeline::kImuChannelKinds[c];
    ch.source_column = csv_column_name(ch);
    for (std::size_t i = 0; i < n; ++i) {
      ch.values.push_back(i < awkward.size() ? awkward[(i + c) % awkward.size()]
                                             : std::ldexp(normal(rng), binade(rng)));
    }
    rec.channels.push_back(std::move(ch));
  }
  for (std::size_t i = 0; i < n; ++i) rec.time_s.push_back(static_cast<double>(i) / 400.0);
  return rec;
}

TEST(AppendCsvRow, WritesTheShortestRoundTripTextOfEveryNumber) {
  std::vector<char> buffer(4 * kCsvFieldChars);
  const std::vector<double> values{1.0, -2.5, -2.2250738585072014e-308};
  char* end = append_csv_row(buffer.data(), 0.1, values);
  EXPECT_EQ(std::string(buffer.data(), end), "0.1,1,-2.5,-2.2250738585072014e-308\n");
}

TEST(CsvColumnName, SiChannelsGetTheirUnitSuffixOthersTheirName) {
  pipeline::Channel gyro{"gyro_x", SensorKind::gyro, {}, "", "", false};
  pipeline::Channel accel{"accel_z", SensorKind::accel, {}, "", "", false};
  pipeline::Channel extra{"temperature", std::nullopt, {}, "temp", "", false};
  EXPECT_EQ(csv_column_name(gyro), "gyro_x_rad_per_s");
  EXPECT_EQ(csv_column_name(accel), "accel_z_m_per_s2");
  EXPECT_EQ(csv_column_name(extra), "temperature");
}

TEST(WriteRecordingCsv, ReadsBackWithDefaultOptionsBitForBit) {
  const pipeline::Recording rec = imu_recording(10'000);  // several blocks of 4096 rows
  const std::string path = (test::make_temp_dir("csv_writer") / "rec.csv").string();
  write_recording_csv(rec, path);
  const pipeline::Recording back = read_recording(path, InputConfig{});
  ASSERT_EQ(back.channels.size(), 6u);
  for (std::size_t c = 0; c < 6; ++c) {
    EXPECT_EQ(back.channels[c].name, rec.channels[c].name);
    EXPECT_EQ(back.channels[c].unit(), rec.channels[c].unit());
    expect_same_bits(back.channels[c].values, rec.channels[c].values, rec.channels[c].name);
  }
  expect_same_bits(back.time_s, rec.time_s, "time_s");
}

TEST(WriteRecordingCsv, FixedRateRecordingGetsStampsKOverRate) {
  pipeline::Recording rec = imu_recording(7);
  rec.time_s.clear();
  rec.sample_period_s = 1.0 / 3.0;
  rec.report.timing.rate_hz = 3.0;
  const std::string path = (test::make_temp_dir("csv_writer_rate") / "rec.csv").string();
  write_recording_csv(rec, path);
  const pipeline::Recording back = read_recording(path, InputConfig{});
  std::vector<double> expected;
  for (int k = 0; k < 7; ++k) expected.push_back(k / 3.0);
  expect_same_bits(back.time_s, expected, "time_s");
  for (std::size_t c = 0; c < 6; ++c) {
    expect_same_bits(back.channels[c].values, rec.channels[c].values, rec.channels[c].name);
  }
  const std::string text = test::read_file_bytes(path);
  EXPECT_THAT(text, HasSubstr("# time_s: k / 3 Hz (the input had a fixed rate)\n"));
}

TEST(WriteRecordingCsv, HeaderNamesTheSourceAndEveryChannelsProvenance) {
  pipeline::Recording rec = imu_recording(3);
  rec.start_time_s = 1700000000.5;
  rec.channels[0].source_column = "dtheta_x";
  rec.channels[0].source_unit = "rad";
  rec.channels[0].from_increments = true;
  pipeline::Channel temperature{"temperature", std::nullopt, {20.5, 20.25, 20.0},
                                "temp",        "",           false};
  rec.channels.push_back(temperature);
  const std::string path = (test::make_temp_dir("csv_writer_header") / "rec.csv").string();
  write_recording_csv(rec, path);
  const std::string text = test::read_file_bytes(path);
  EXPECT_THAT(text, StartsWith("# imunoise convert: memory.csv, SI units\n"
                               "# sample_period_s: 0.0025\n"
                               "# start_time_s: 1700000000.5\n"
                               "# samples: 3\n"
                               "# gyro_x: from dtheta_x [rad] (increments divided by the sample "
                               "period)\n"
                               "# gyro_y: from gyro_y_rad_per_s\n"));
  EXPECT_THAT(text, HasSubstr("# temperature: from temp\n"
                              "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,"
                              "accel_x_m_per_s2,accel_y_m_per_s2,accel_z_m_per_s2,temperature\n"
                              "0,"));
  EXPECT_THAT(text, HasSubstr(",20.25\n"));
}

TEST(WriteRecordingCsv, UnwritablePathIsAnInputErrorNamingIt) {
  const auto path = test::make_temp_dir("csv_writer_bad") / "missing" / "rec.csv";
  const std::string message =
      test::error_of([&] { write_recording_csv(imu_recording(2), path.string()); });
  EXPECT_THAT(message, HasSubstr(path.string()));
}

}  // namespace
}  // namespace imunoise::io
