// The ROS 1 bag reader (io/rosbag1_reader.h) on bags written by ROS's own rosbag.Bag
// (tests/fixtures/write_rosbag1_fixtures.py): every sample of each compression, with and
// without the index, both time sources, the topic listing and its errors, and malformed bags
// (truncated, impossible lengths, unknown compression) named by byte offset.
#include "io/rosbag1_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "robotics_log_fixtures.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

using test::expect_fixture_samples;

std::string bytes_of(const fs::path& p) { return test::read_file_bytes(p); }

fs::path write_bytes(const fs::path& dir, const std::string& name, const std::string& bytes) {
  return test::write_fixture_bytes(dir, name, bytes);
}

TEST(Rosbag1Reader, ReadsEverySampleOfEachCompressionWithAndWithoutIndex) {
  IMUNOISE_REQUIRE_FIXTURE(csv, "rosbag1", "rosbag1", "imu.csv");
  const auto expected = test::read_fixture_samples(csv);
  ASSERT_EQ(expected.size(), 1200u);
  for (const char* name : {"imu_none.bag", "imu_bz2.bag", "imu_lz4.bag", "imu_lz4_unindexed.bag"}) {
    SCOPED_TRACE(name);
    const fs::path bag = test::fixture_dir("rosbag1") / name;
    EXPECT_TRUE(is_rosbag1_file(bag.string()));
    const pipeline::Recording recording = read_rosbag1_imu(bag.string(), {});
    expect_fixture_samples(recording, expected, false);
    EXPECT_EQ(recording.channels[0].name, "gyro_x");
    EXPECT_EQ(recording.channels[0].source_column, "/imu/data.angular_velocity.x");
    EXPECT_EQ(recording.channels[5].source_column, "/imu/data.linear_acceleration.z");
    EXPECT_EQ(recording.channels[5].source_unit, "m/s^2");
    EXPECT_NEAR(recording.sample_period_s, 0.005, 1e-12);
    EXPECT_EQ(recording.report.samples, 1200);
  }
}

TEST(Rosbag1Reader, LogTimeSourceTakesTheRecordTime) {
  IMUNOISE_REQUIRE_FIXTURE(csv, "rosbag1", "rosbag1", "imu.csv");
  const auto expected = test::read_fixture_samples(csv);
  LogReadOptions options;
  options.time_source = TimeSource::kLog;
  for (const char* name : {"imu_bz2.bag", "imu_lz4_unindexed.bag"}) {
    SCOPED_TRACE(name);
    expect_fixture_samples(
        read_rosbag1_imu((test::fixture_dir("rosbag1") / name).string(), options), expected, true);
  }
}

TEST(Rosbag1Reader, ListsTopicsWithTypesAndCountsWithAndWithoutIndex) {
  IMUNOISE_REQUIRE_FIXTURE(bag, "rosbag1", "rosbag1", "imu_lz4.bag");
  for (const char* name : {"imu_lz4.bag", "imu_lz4_unindexed.bag"}) {
    SCOPED_TRACE(name);
    const auto topics = list_rosbag1_topics((test::fixture_dir("rosbag1") / name).string());
    ASSERT_EQ(topics.size(), 2u);
    EXPECT_EQ(topics[0].name, "/imu/data");
    EXPECT_EQ(topics[0].type, "sensor_msgs/Imu");
    EXPECT_EQ(topics[0].message_count, 1200);
    EXPECT_TRUE(topics[0].is_imu);
    EXPECT_EQ(topics[1].name, "/status");
    EXPECT_EQ(topics[1].type, "std_msgs/String");
    EXPECT_EQ(topics[1].message_count, 120);
    EXPECT_FALSE(topics[1].is_imu);
  }
}

TEST(Rosbag1Reader, TopicErrorsListTheTopicsTypesAndCounts) {
  IMUNOISE_REQUIRE_FIXTURE(two, "rosbag1", "rosbag1", "two_imus.bag");
  const std::string path = two.string();
  const std::string ambiguous = test::error_of([&] { (void)read_rosbag1_imu(path, {}); });
  EXPECT_THAT(ambiguous, HasSubstr(path + ": 2 IMU topics, which one?; give --topic NAME; the bag "
                                          "holds '/imu/data' (sensor_msgs/Imu, 100 messages), "
                                          "'/imu2/data' (sensor_msgs/Imu, 50 messages)"));
  LogReadOptions options;
  options.topic = "/imu2/data";
  EXPECT_EQ(read_rosbag1_imu(path, options).sample_count(), 50u);

  const std::string bag = (test::fixture_dir("rosbag1") / "imu_none.bag").string();
  for (const char* name : {"imu_none.bag", "imu_lz4_unindexed.bag"}) {
    SCOPED_TRACE(name);
    const std::string p = (test::fixture_dir("rosbag1") / name).string();
    options.topic = "/imu";
    EXPECT_THAT(test::error_of([&] { (void)read_rosbag1_imu(p, options); }),
                HasSubstr("topic '/imu' not found; give --topic NAME; the bag holds '/imu/data' "
                          "(sensor_msgs/Imu, 1200 messages), '/status' (std_msgs/String, 120 "
                          "messages)"));
    options.topic = "/status";
    EXPECT_THAT(test::error_of([&] { (void)read_rosbag1_imu(p, options); }),
                HasSubstr("topic '/status' is of type 'std_msgs/String', which imunoise does not "
                          "read as an IMU"));
  }
}

TEST(Rosbag1Reader, TruncatedBagsAreErrorsAtTheByteOffset) {
  IMUNOISE_REQUIRE_FIXTURE(source, "rosbag1", "rosbag1", "imu_lz4.bag");
  const fs::path dir = test::make_temp_dir("rosbag1");
  const std::string bytes = bytes_of(source);
  // Cut inside the chunks: the index is past the end, so the chunks are scanned, and the last
  // one is cut.
  for (const std::size_t size : {bytes.size() / 2, std::size_t{5000}, std::size_t{4200}}) {
    SCOPED_TRACE(size);
    const fs::path cut = write_bytes(dir, "cut.bag", bytes.substr(0, size));
    const std::string error = test::error_of([&] { (void)read_rosbag1_imu(cut.string(), {}); });
    EXPECT_THAT(error, HasSubstr(cut.string() + ": byte offset "));
    EXPECT_THAT(error, HasSubstr("truncated"));
  }
  // Cut inside the bag header record.
  const fs::path head = write_bytes(dir, "head.bag", bytes.substr(0, 30));
  EXPECT_THAT(
      test::error_of([&] { (void)read_rosbag1_imu(head.string(), {}); }),
      HasSubstr(head.string() + ": byte offset 13: truncated bag header record: its header of "));
  const fs::path other = write_bytes(dir, "v12.bag", "#ROSBAG V1.2\n" + bytes.substr(13));
  EXPECT_THAT(test::error_of([&] { (void)read_rosbag1_imu(other.string(), {}); }),
              HasSubstr("byte offset 0: bag format '1.2' is not supported (only 2.0)"));
}

TEST(Rosbag1Reader, ImpossibleLengthsAndUnknownCompressionAreErrorsAtTheByteOffset) {
  IMUNOISE_REQUIRE_FIXTURE(source, "rosbag1", "rosbag1", "imu_none.bag");
  const fs::path dir = test::make_temp_dir("rosbag1");
  const std::string bytes = bytes_of(source);
  const std::size_t compression = bytes.find("compression=none");
  ASSERT_NE(compression, std::string::npos);
  // The first chunk record: header length, the field "op=\x05" (4 + 4 bytes), then the field
  // "compression=none" (rosbag.Bag writes op first).
  const std::size_t chunk_at = compression - 4 - 8 - 4;
  std::string unknown = bytes;
  unknown.replace(compression, 16, "compression=zzzz");
  const fs::path u = write_bytes(dir, "unknown.bag", unknown);
  EXPECT_THAT(test::error_of([&] { (void)read_rosbag1_imu(u.string(), {}); }),
              HasSubstr("byte offset " + std::to_string(chunk_at) +
                        ": unknown chunk compression 'zzzz' (a bag 2.0 chunk is none, bz2 or "
                        "lz4)"));

  std::string huge = bytes;
  huge.replace(chunk_at, 4, std::string("\xf0\xff\xff\x7f", 4));  // header length 2^31 - 16
  const fs::path h = write_bytes(dir, "huge.bag", huge);
  EXPECT_THAT(
      test::error_of([&] { (void)read_rosbag1_imu(h.string(), {}); }),
      HasSubstr("byte offset " + std::to_string(chunk_at) +
                ": truncated chunk record: its header of 2147483632 bytes and data length need "
                "2147483640 bytes, the file has "));
}

// Found by fuzz_rosbag1_reader: a chunk info counting ~4·10^9 messages made the reader reserve
// that many samples (an out-of-memory); the index's counts now only bound the reservation by
// the file size.
TEST(Rosbag1Reader, RegressionAnIndexCountBeyondTheFileIsNoAllocation) {
  const fs::path input = fs::path(IMUNOISE_SOURCE_DIR) /
                         "fuzz/corpus/fuzz_rosbag1_reader/regression_index_count_oom.bag";
  try {
    (void)read_rosbag1_imu(input.string(), {});
  } catch (const InputError&) {
  } catch (const AnalysisError&) {
  }
}

TEST(Rosbag1Reader, NotABagIsAnError) {
  const fs::path dir = test::make_temp_dir("rosbag1");
  const fs::path p = write_bytes(dir, "text.bag", "time,gyro\n");
  EXPECT_FALSE(is_rosbag1_file(p.string()));
  EXPECT_THAT(test::error_of([&] { (void)list_rosbag1_topics(p.string()); }),
              HasSubstr("byte offset 0: not a ROS bag"));
}

}  // namespace
}  // namespace imunoise::io
