// The PX4 ULog reader (io/ulog_reader.h) on files written by tests/fixtures/write_ulog_fixtures.mjs
// and read back there by @foxglove/ulog: sensor_combined, sensor_gyro + sensor_accel of two
// instances, the FIFO topics, both time sources, the topic listing and its errors, and
// malformed files named by byte offset.
#include "io/ulog_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/errors.h"
#include "io/ulog_format.h"
#include "robotics_log_fixtures.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

fs::path ulog(const std::string& name) { return test::fixture_dir("ulog") / name; }

TEST(UlogReader, ReadsSensorCombinedByDefault) {
  IMUNOISE_REQUIRE_FIXTURE(csv, "node", "ulog", "combined.csv");
  const auto expected = test::read_fixture_samples(csv);
  ASSERT_EQ(expected.size(), 1200u);
  EXPECT_TRUE(is_ulog_file(ulog("imu.ulg").string()));
  const pipeline::Recording recording = read_ulog_imu(ulog("imu.ulg").string(), {});
  test::expect_fixture_samples(recording, expected, false);
  EXPECT_EQ(recording.channels[0].source_column, "sensor_combined.gyro_rad[0]");
  EXPECT_EQ(recording.channels[5].source_column, "sensor_combined.accelerometer_m_s2[2]");
  EXPECT_NEAR(recording.sample_period_s, 0.005, 1e-12);
}

TEST(UlogReader, PairsSensorGyroWithSensorAccelOfEachInstance) {
  IMUNOISE_REQUIRE_FIXTURE(csv0, "node", "ulog", "imu0.csv");
  for (const int instance : {0, 1}) {
    SCOPED_TRACE(instance);
    const auto expected = test::read_fixture_samples(test::fixture_dir("ulog") /
                                                     ("imu" + std::to_string(instance) + ".csv"));
    for (const char* topic : {"sensor_gyro", "sensor_accel"}) {
      LogReadOptions options;
      options.topic = topic;
      options.instance = instance;
      const pipeline::Recording r = read_ulog_imu(ulog("imu.ulg").string(), options);
      test::expect_fixture_samples(r, expected, false);
      EXPECT_EQ(r.channels[1].source_column, "sensor_gyro.y");
      EXPECT_EQ(r.channels[4].source_column, "sensor_accel.y");
      options.time_source = TimeSource::kLog;
      test::expect_fixture_samples(read_ulog_imu(ulog("imu.ulg").string(), options), expected,
                                   true);
    }
  }
}

TEST(UlogReader, ExpandsTheFifoTopics) {
  IMUNOISE_REQUIRE_FIXTURE(csv, "node", "ulog", "fifo.csv");
  const auto expected = test::read_fixture_samples(csv);
  ASSERT_EQ(expected.size(), 800u);
  LogReadOptions options;
  options.topic = "sensor_gyro_fifo";
  const pipeline::Recording r = read_ulog_imu(ulog("imu.ulg").string(), options);
  test::expect_fixture_samples(r, expected, false);
  EXPECT_NEAR(r.sample_period_s, 625e-6, 1e-12);
  options.time_source = TimeSource::kLog;
  test::expect_fixture_samples(read_ulog_imu(ulog("imu.ulg").string(), options), expected, true);
}

TEST(UlogReader, ListsTopicsWithInstancesAndTheErrorsListThem) {
  IMUNOISE_REQUIRE_FIXTURE(file, "node", "ulog", "imu.ulg");
  const auto topics = list_ulog_topics(file.string());
  ASSERT_EQ(topics.size(), 7u);
  EXPECT_EQ(topics[0].name, "sensor_combined");
  EXPECT_EQ(topics[0].instance, 0);
  EXPECT_EQ(topics[0].message_count, 1200);
  EXPECT_TRUE(topics[0].is_imu);
  EXPECT_EQ(topics[2].name, "sensor_gyro");
  EXPECT_EQ(topics[2].instance, 1);
  EXPECT_FALSE(topics[3].is_imu);  // sensor_accel: read as the pair of sensor_gyro
  EXPECT_EQ(topics[5].name, "sensor_gyro_fifo");
  EXPECT_EQ(topics[5].message_count, 100);
  LogReadOptions options;
  options.topic = "sensor_gyro";
  EXPECT_THAT(test::error_of([&] { (void)read_ulog_imu(file.string(), options); }),
              HasSubstr(file.string() + ": topic 'sensor_gyro' has several instances, which "
                                        "one?; give --topic NAME (and --instance N); the ULog "
                                        "file holds 'sensor_combined' instance 0 "
                                        "(sensor_combined, 1200 messages), 'sensor_gyro' "
                                        "instance 0 (sensor_gyro, 1200 messages)"));
  options.instance = 3;
  EXPECT_THAT(test::error_of([&] { (void)read_ulog_imu(file.string(), options); }),
              HasSubstr("topic 'sensor_gyro' instance 3 not found"));
  const std::string gyro_only = ulog("gyro_only.ulg").string();
  EXPECT_THAT(test::error_of([&] { (void)read_ulog_imu(gyro_only, {}); }),
              HasSubstr("topic 'sensor_gyro' instance 0 has no sensor_accel of the same instance "
                        "with messages"));
}

TEST(UlogReader, MalformedFilesAreErrorsAtTheByteOffset) {
  IMUNOISE_REQUIRE_FIXTURE(file, "node", "ulog", "imu.ulg");
  const fs::path dir = test::make_temp_dir("ulog");
  const std::string bytes = test::read_file_bytes(file);
  const fs::path cut =
      test::write_fixture_bytes(dir, "cut.ulg", bytes.substr(0, bytes.size() / 2 + 1));
  const std::string error = test::error_of([&] { (void)read_ulog_imu(cut.string(), {}); });
  EXPECT_THAT(error, HasSubstr(cut.string() + ": byte offset "));
  EXPECT_THAT(error, HasSubstr("truncated message"));
  const fs::path head = test::write_fixture_bytes(dir, "head.ulg", bytes.substr(0, 10));
  EXPECT_THAT(test::error_of([&] { (void)list_ulog_topics(head.string()); }),
              HasSubstr("byte offset 0: truncated ULog header"));
  // A data message of a msg_id no subscription defines: the first 'D' message's id patched.
  const std::size_t data = bytes.find(std::string("D\x00\x00", 3), 16);
  ASSERT_NE(data, std::string::npos);
  std::string unknown = bytes;
  unknown[data + 1] = '\x63';
  const fs::path u = test::write_fixture_bytes(dir, "unknown.ulg", unknown);
  EXPECT_THAT(test::error_of([&] { (void)read_ulog_imu(u.string(), {}); }),
              HasSubstr("byte offset " + std::to_string(data - 2) +
                        ": data of msg_id 99, which no subscription defines"));
  const fs::path text = test::write_fixture_bytes(dir, "text.ulg", "time,gyro\n");
  EXPECT_THAT(test::error_of([&] { (void)list_ulog_topics(text.string()); }),
              HasSubstr("byte offset 0: not a ULog file"));
}

// Found by fuzz_ulog_reader: a second format message of a name already laid out freed the
// fields its reader pointed to (a heap use-after-free under ASan); a redefinition is now an
// error.
TEST(UlogReader, RegressionAFormatDefinedTwiceIsAnError) {
  const fs::path input =
      fs::path(IMUNOISE_SOURCE_DIR) /
      "fuzz/corpus/fuzz_ulog_reader/regression_format_redefined_use_after_free.ulg";
  try {
    (void)read_ulog_imu(input.string(), {});
  } catch (const InputError&) {
  } catch (const AnalysisError&) {
  }
  UlogFormats formats;
  EXPECT_EQ(formats.add("a:float x;"), "");
  EXPECT_EQ(formats.add("a:double x;"), "format 'a' is defined twice");
}

}  // namespace
}  // namespace imunoise::io
