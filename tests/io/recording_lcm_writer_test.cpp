// Tests of io/recording_lcm_writer.h: a Recording written as an LCM log of imu_sample_t reads
// back (io::read_lcm_imu_log) with the same values bit for bit, stamps in whole µs from the
// start time, the temperature when there is one; the events are what LCM's own reader
// (lcm::LogFile) decodes; a recording without the six IMU channels is refused.
#include "io/recording_lcm_writer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <imunoise/imu_sample_t.hpp>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "io/lcm_log.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;

pipeline::Recording recording(std::size_t n, bool with_temperature) {
  pipeline::Recording rec;
  rec.source_path = "memory.csv";
  rec.sample_period_s = 0.01;
  rec.start_time_s = 1700000000.25;
  for (std::size_t c = 0; c < 6; ++c) {
    pipeline::Channel ch;
    ch.name = pipeline::kImuChannelNames[c];
    ch.kind = pipeline::kImuChannelKinds[c];
    for (std::size_t i = 0; i < n; ++i) ch.values.push_back(0.001 * (c + 1) + 1e-7 * i * i);
    rec.channels.push_back(std::move(ch));
  }
  if (with_temperature) {
    pipeline::Channel t{"temperature", std::nullopt, {}, "temp", "", false};
    for (std::size_t i = 0; i < n; ++i) t.values.push_back(20.0 + 0.25 * i);
    rec.channels.push_back(std::move(t));
  }
  for (std::size_t i = 0; i < n; ++i) rec.time_s.push_back(0.01 * i);
  return rec;
}

TEST(WriteRecordingLcm, ReadsBackTheSameSamplesAndTemperature) {
  const pipeline::Recording rec = recording(50, true);
  const std::string path = (test::make_temp_dir("lcm_writer") / "rec.lcmlog").string();
  write_recording_lcm(rec, path, "IMU_A");
  const pipeline::Recording back = read_lcm_imu_log(path, "IMU_A");
  ASSERT_EQ(back.channels.size(), 7u);
  for (std::size_t c = 0; c < 7; ++c) {
    EXPECT_EQ(back.channels[c].name, rec.channels[c].name);
    ASSERT_EQ(back.channels[c].values.size(), 50u);
    for (std::size_t i = 0; i < 50; ++i) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(back.channels[c].values[i]),
                std::bit_cast<std::uint64_t>(rec.channels[c].values[i]))
          << rec.channels[c].name << " sample " << i;
    }
  }
  EXPECT_NEAR(back.sample_period_s, 0.01, 1e-15);  // whole µs stamps
}

TEST(WriteRecordingLcm, EventsAreImuSamplesStampedFromTheStartTime) {
  const pipeline::Recording rec = recording(3, false);
  const std::string path = (test::make_temp_dir("lcm_writer_events") / "rec.lcmlog").string();
  write_recording_lcm(rec, path, "IMU");
  lcm::LogFile log(path, "r");
  ASSERT_TRUE(log.good());
  for (std::int64_t i = 0; i < 3; ++i) {
    const lcm::LogEvent* event = log.readNextEvent();
    ASSERT_NE(event, nullptr);
    EXPECT_EQ(event->eventnum, i);
    EXPECT_EQ(event->channel, "IMU");
    imunoise::imu_sample_t m;
    ASSERT_GT(m.decode(event->data, 0, event->datalen), 0);
    EXPECT_EQ(m.utime, 1'700'000'000'250'000 + 10'000 * i);
    EXPECT_EQ(event->timestamp, m.utime);
    EXPECT_EQ(m.angular_rate_rad_per_s[1], rec.channels[1].values[i]);
    EXPECT_EQ(m.specific_force_m_per_s2[2], rec.channels[5].values[i]);
    EXPECT_FALSE(m.has_temperature);
    EXPECT_EQ(m.temperature_degc, 0.0);
  }
  EXPECT_EQ(log.readNextEvent(), nullptr);
}

TEST(WriteRecordingLcm, MissingImuChannelsAreAnInputErrorListingThem) {
  pipeline::Recording rec = recording(3, false);
  rec.channels.erase(rec.channels.begin() + 4, rec.channels.end());
  const std::string path = (test::make_temp_dir("lcm_writer_missing") / "rec.lcmlog").string();
  const std::string message = test::error_of([&] { write_recording_lcm(rec, path, "IMU"); });
  EXPECT_EQ(message,
            "memory.csv: an LCM log of imu_sample_t needs all six channels gyro_x ... accel_z; "
            "missing: accel_y, accel_z");
}

TEST(ImuSampleLogWriter, WritesOneEventPerSampleOnItsChannel) {
  std::ostringstream out;
  ImuSampleLogWriter writer(out, "CH");
  writer.write(5, {1, 2, 3}, {4, 5, 6}, 21.5);
  writer.write(7, {1, 2, 3}, {4, 5, 6});
  const std::string bytes = out.str();
  // Two events: header (28 bytes) + channel (2) + the encoded message each.
  imunoise::imu_sample_t m;
  EXPECT_EQ(bytes.size(), 2u * (28u + 2u + static_cast<std::size_t>(m.getEncodedSize())));
}

}  // namespace
}  // namespace imunoise::io
