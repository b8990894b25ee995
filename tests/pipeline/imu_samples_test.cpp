// Tests of pipeline/imu_samples.h append_sample_temperature: the one rule for the temperature
// channel of message samples (the LCM log reader's io::append_imu_sample and the live window's
// snapshot both use it) — a channel only if every sample carries a temperature, the column
// stopping at the first sample without one — and what recording_from_imu_samples makes of it.
#include "pipeline/imu_samples.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::pipeline {
namespace {

/// Columns of rate samples 10 ms apart whose temperatures are TEMPERATURES (none = the sample
/// carried none), each appended as the readers do: stamp and values, then the temperature.
ImuSampleColumns columns_with(const std::vector<std::optional<double>>& temperatures) {
  ImuSampleColumns columns;
  columns.temperature_field = "temperature_degc";
  for (std::size_t k = 0; k < temperatures.size(); ++k) {
    columns.utime_us.push_back(static_cast<std::int64_t>(k) * 10'000);
    for (std::size_t c = 0; c < 6; ++c) columns.values[c].push_back(c == 5 ? -9.8 : 0.0);
    append_sample_temperature(columns, temperatures[k]);
  }
  return columns;
}

TEST(ImuSampleTemperature, EverySampleWithOneMakesAChannel) {
  const ImuSampleColumns columns = columns_with({20.0, 20.5, 21.0, 21.5});
  EXPECT_EQ(columns.temperature_degc, (std::vector<double>{20.0, 20.5, 21.0, 21.5}));
  const Recording rec = recording_from_imu_samples(columns, "lcm:IMU", "IMU");
  const Channel* temperature = rec.find_channel("temperature");
  ASSERT_NE(temperature, nullptr);
  EXPECT_EQ(temperature->values, (std::vector<double>{20.0, 20.5, 21.0, 21.5}));
  EXPECT_EQ(temperature->source_column, "IMU.temperature_degc");
}

TEST(ImuSampleTemperature, StopsAtTheFirstSampleWithoutOne) {
  // The samples after the gap carry one again: the column does not resume.
  const ImuSampleColumns columns = columns_with({20.0, 20.5, std::nullopt, 21.5, 22.0});
  EXPECT_EQ(columns.temperature_degc, (std::vector<double>{20.0, 20.5}));
  EXPECT_EQ(recording_from_imu_samples(columns, "lcm:IMU", "IMU").find_channel("temperature"),
            nullptr);
}

TEST(ImuSampleTemperature, FirstSampleWithoutOneMeansNoChannel) {
  const ImuSampleColumns columns = columns_with({std::nullopt, 20.0, 20.5});
  EXPECT_TRUE(columns.temperature_degc.empty());
  EXPECT_EQ(recording_from_imu_samples(columns, "lcm:IMU", "IMU").find_channel("temperature"),
            nullptr);
}

TEST(ImuSampleTemperature, NeedsTheSampleAppendedFirst) {
  ImuSampleColumns empty;
  test::expect_throw_containing<ContractViolation>(
      [&] { append_sample_temperature(empty, 20.0); },
      "append_sample_temperature: append the sample's stamp first");
  EXPECT_TRUE(empty.temperature_degc.empty());
}

}  // namespace
}  // namespace imunoise::pipeline
