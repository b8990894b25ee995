// Tests of io/imu_sample_message.h: imu_sample_t bytes → the live window's samples, and the
// window's snapshot of decoded messages equal, column for column, to what append_imu_sample
// (the LCM log reader's path) makes of the same messages — so live and analyze on a log of
// the same messages see the same numbers.
#include "io/imu_sample_message.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "io/lcm_messages.h"
#include "lcm_test_support.h"
#include "pipeline/live_window.h"

namespace imunoise::io {
namespace {

imunoise::imu_sample_t message(std::int64_t k, bool increments, bool temperature) {
  imunoise::imu_sample_t m{};
  m.utime = 1'000 + 10'000 * k;
  m.has_increments = increments;
  for (int a = 0; a < 3; ++a) {
    m.angular_rate_rad_per_s[a] = 0.1 * static_cast<double>(k) + a;
    m.specific_force_m_per_s2[a] = -9.8 + 0.01 * static_cast<double>(k) + a;
    m.delta_angle_rad[a] = 1e-3 * static_cast<double>(k) + a;
    m.delta_velocity_m_per_s[a] = -0.098 + 1e-4 * static_cast<double>(k) + a;
  }
  m.has_temperature = temperature;
  m.temperature_degc = 25.0 + 0.5 * static_cast<double>(k);
  return m;
}

void expect_same_columns(const pipeline::ImuSampleColumns& a, const pipeline::ImuSampleColumns& b) {
  EXPECT_EQ(a.utime_us, b.utime_us);
  EXPECT_EQ(a.increments, b.increments);
  for (std::size_t c = 0; c < 6; ++c) EXPECT_EQ(a.values[c], b.values[c]) << c;
  EXPECT_EQ(a.temperature_degc, b.temperature_degc);
  EXPECT_EQ(a.source_fields, b.source_fields);
  EXPECT_EQ(a.source_units, b.source_units);
  EXPECT_EQ(a.temperature_field, b.temperature_field);
}

TEST(ImuSampleMessage, WindowSnapshotEqualsTheLogReadersColumns) {
  for (const bool increments : {false, true}) {
    for (const bool temperature : {false, true}) {
      pipeline::LiveWindow window({3600.0, 1000, 1.0}, imu_sample_fields());
      pipeline::ImuSampleColumns reference;
      for (std::int64_t k = 0; k < 20; ++k) {
        const imunoise::imu_sample_t m = message(k, increments, temperature);
        const test::LcmBytes bytes = test::lcm_encode(m);
        const std::optional<pipeline::ImuSample> s = decode_imu_sample(bytes.data(), bytes.size());
        ASSERT_TRUE(s.has_value());
        window.add(*s);
        append_imu_sample(m, reference);
      }
      expect_same_columns(window.snapshot(), reference);
    }
  }
}

TEST(ImuSampleMessage, WindowAndLogReaderStopTheTemperatureAtTheSameSample) {
  // One rule (pipeline::append_sample_temperature) for both: message 7 carries none, so the
  // temperature column stops there on both paths though later messages carry one again.
  pipeline::LiveWindow window({3600.0, 1000, 1.0}, imu_sample_fields());
  pipeline::ImuSampleColumns reference;
  for (std::int64_t k = 0; k < 20; ++k) {
    const imunoise::imu_sample_t m = message(k, false, k != 7);
    const test::LcmBytes bytes = test::lcm_encode(m);
    const std::optional<pipeline::ImuSample> s = decode_imu_sample(bytes.data(), bytes.size());
    ASSERT_TRUE(s.has_value());
    window.add(*s);
    append_imu_sample(m, reference);
  }
  EXPECT_EQ(reference.temperature_degc.size(), 7u);
  expect_same_columns(window.snapshot(), reference);
}

TEST(ImuSampleMessage, KeepsTheUsedFieldsOnly) {
  const pipeline::ImuSample rates = imu_sample_of(message(3, false, false));
  EXPECT_FALSE(rates.increments);
  EXPECT_EQ(rates.values[1], 0.1 * 3 + 1);
  EXPECT_EQ(rates.values[5], -9.8 + 0.01 * 3 + 2);
  EXPECT_FALSE(rates.temperature_degc.has_value());
  const pipeline::ImuSample increments = imu_sample_of(message(3, true, true));
  EXPECT_TRUE(increments.increments);
  EXPECT_EQ(increments.values[0], 1e-3 * 3);
  EXPECT_EQ(increments.values[4], -0.098 + 1e-4 * 3 + 1);
  EXPECT_EQ(increments.temperature_degc, 25.0 + 0.5 * 3);
}

TEST(ImuSampleMessage, TruncatedOrForeignBytesDoNotDecode) {
  test::LcmBytes bytes = test::lcm_encode(message(0, false, false));
  bytes.resize(bytes.size() / 2);
  EXPECT_FALSE(decode_imu_sample(bytes.data(), bytes.size()).has_value());
  const test::LcmBytes other = test::lcm_encode(noise_model_message(models::NoiseModel{}, 0));
  EXPECT_FALSE(decode_imu_sample(other.data(), other.size()).has_value());
  const test::LcmBytes longer = [] {
    test::LcmBytes b = test::lcm_encode(message(0, false, false));
    b.push_back(0);
    return b;
  }();
  EXPECT_FALSE(decode_imu_sample(longer.data(), longer.size()).has_value());
}

TEST(ImuSampleMessage, FieldNamesAreTheLogReaders) {
  const pipeline::ImuSampleFields f = imu_sample_fields();
  EXPECT_EQ(f.rate_fields[0], "angular_rate_rad_per_s[0]");
  EXPECT_EQ(f.rate_units[3], "m/s^2");
  EXPECT_EQ(f.increment_fields[5], "delta_velocity_m_per_s[2]");
  EXPECT_EQ(f.increment_units[1], "rad");
  EXPECT_EQ(f.temperature_field, "temperature_degc");
}

}  // namespace
}  // namespace imunoise::io
