// The MCAP reader (io/mcap_reader.h) on files written by the MCAP project's own writer
// (@mcap/core, tests/fixtures/write_mcap_fixtures.mjs): every sample of each compression
// (none, zstd, lz4), chunked and not, with and without a summary, big-endian CDR, both time
// sources, the topic listing and its errors, and malformed files named by byte offset.
#include "io/mcap_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/errors.h"
#include "robotics_log_fixtures.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using test::expect_fixture_samples;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

fs::path mcap(const std::string& name) { return test::fixture_dir("mcap") / name; }

TEST(McapReader, ReadsEverySampleOfEachCompressionChunkedOrNotWithOrWithoutSummary) {
  IMUNOISE_REQUIRE_FIXTURE(csv, "node", "mcap", "imu.csv");
  const auto expected = test::read_fixture_samples(csv);
  ASSERT_EQ(expected.size(), 1200u);
  for (const char* name : {"imu_none.mcap", "imu_zstd.mcap", "imu_lz4.mcap", "imu_unchunked.mcap",
                           "imu_zstd_nosummary.mcap", "imu_be.mcap"}) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(is_mcap_file(mcap(name).string()));
    const pipeline::Recording recording = read_mcap_imu(mcap(name).string(), {});
    expect_fixture_samples(recording, expected, false);
    EXPECT_EQ(recording.channels[2].source_column, "/imu/data.angular_velocity.z");
    EXPECT_EQ(recording.channels[3].source_unit, "m/s^2");
    EXPECT_NEAR(recording.sample_period_s, 0.005, 1e-12);
  }
}

TEST(McapReader, LogTimeSourceTakesTheLogTime) {
  IMUNOISE_REQUIRE_FIXTURE(csv, "node", "mcap", "imu.csv");
  const auto expected = test::read_fixture_samples(csv);
  LogReadOptions options;
  options.time_source = TimeSource::kLog;
  for (const char* name : {"imu_lz4.mcap", "imu_zstd_nosummary.mcap"}) {
    SCOPED_TRACE(name);
    expect_fixture_samples(read_mcap_imu(mcap(name).string(), options), expected, true);
  }
}

TEST(McapReader, ListsTopicsWithTypesAndCountsWithAndWithoutSummary) {
  IMUNOISE_REQUIRE_FIXTURE(file, "node", "mcap", "imu_zstd.mcap");
  for (const char* name : {"imu_zstd.mcap", "imu_zstd_nosummary.mcap", "imu_unchunked.mcap"}) {
    SCOPED_TRACE(name);
    const auto topics = list_mcap_topics(mcap(name).string());
    ASSERT_EQ(topics.size(), 2u);
    EXPECT_EQ(topics[0].name, "/imu/data");
    EXPECT_EQ(topics[0].type, "sensor_msgs/msg/Imu");
    EXPECT_EQ(topics[0].message_count, 1200);
    EXPECT_TRUE(topics[0].is_imu);
    EXPECT_EQ(topics[1].name, "/status");
    EXPECT_EQ(topics[1].type, "std_msgs/msg/String");
    EXPECT_EQ(topics[1].message_count, 120);
    EXPECT_FALSE(topics[1].is_imu);
  }
}

TEST(McapReader, TopicErrorsListTheTopicsTypesAndCounts) {
  IMUNOISE_REQUIRE_FIXTURE(two, "node", "mcap", "two_imus.mcap");
  const std::string path = two.string();
  // /imu/empty (no messages) is no candidate; the other two are.
  EXPECT_THAT(test::error_of([&] { (void)read_mcap_imu(path, {}); }),
              HasSubstr(path + ": 2 IMU topics, which one?; give --topic NAME; the MCAP file "
                               "holds '/imu/data' (sensor_msgs/msg/Imu, 100 messages), "
                               "'/imu2/data' (sensor_msgs/msg/Imu, 50 messages), '/imu/empty' "
                               "(sensor_msgs/msg/Imu, 0 messages)"));
  LogReadOptions options;
  options.topic = "/imu2/data";
  EXPECT_EQ(read_mcap_imu(path, options).sample_count(), 50u);
  options.topic = "/imu/empty";
  EXPECT_THAT(test::error_of([&] { (void)read_mcap_imu(path, options); }),
              HasSubstr("topic '/imu/empty' has no messages"));
  for (const char* name : {"imu_zstd.mcap", "imu_zstd_nosummary.mcap"}) {
    SCOPED_TRACE(name);
    const std::string p = mcap(name).string();
    options.topic = "/status";
    EXPECT_THAT(test::error_of([&] { (void)read_mcap_imu(p, options); }),
                HasSubstr("topic '/status' is of type 'std_msgs/msg/String', which imunoise does "
                          "not read as an IMU; give --topic NAME; the MCAP file holds "
                          "'/imu/data' (sensor_msgs/msg/Imu, 1200 messages), '/status' "
                          "(std_msgs/msg/String, 120 messages)"));
    options.topic = "/imu";
    EXPECT_THAT(test::error_of([&] { (void)read_mcap_imu(p, options); }),
                HasSubstr("topic '/imu' not found"));
  }
}

TEST(McapReader, MalformedFilesAreErrorsAtTheByteOffset) {
  IMUNOISE_REQUIRE_FIXTURE(source, "node", "mcap", "imu_zstd.mcap");
  const fs::path dir = test::make_temp_dir("mcap");
  const std::string bytes = test::read_file_bytes(source);
  // Cut short: no footer, the data section is scanned and its last record is cut.
  for (const std::size_t size : {bytes.size() / 2, std::size_t{60}}) {
    SCOPED_TRACE(size);
    const fs::path cut = test::write_fixture_bytes(dir, "cut.mcap", bytes.substr(0, size));
    const std::string error = test::error_of([&] { (void)read_mcap_imu(cut.string(), {}); });
    EXPECT_THAT(error, HasSubstr(cut.string() + ": byte offset "));
    EXPECT_THAT(error, HasSubstr("truncated"));
  }
  // Cut inside the summary: the data section, complete up to its data end record, still reads.
  const fs::path summary_cut =
      test::write_fixture_bytes(dir, "summary_cut.mcap", bytes.substr(0, bytes.size() - 100));
  EXPECT_EQ(read_mcap_imu(summary_cut.string(), {}).sample_count(), 1200u);
  // The first chunk: its compression string (uint32 4, "zstd") is 37 bytes into the record
  // (opcode, length, start and end times, uncompressed size, CRC).
  const std::size_t compression = bytes.find(std::string("\x04\x00\x00\x00zstd", 8));
  ASSERT_NE(compression, std::string::npos);
  const std::size_t chunk_at = compression - 37;
  ASSERT_EQ(bytes[chunk_at], '\x06');
  std::string unknown = bytes;
  unknown.replace(compression + 4, 4, "zzzz");
  const fs::path u = test::write_fixture_bytes(dir, "unknown.mcap", unknown);
  EXPECT_THAT(test::error_of([&] { (void)read_mcap_imu(u.string(), {}); }),
              HasSubstr("byte offset " + std::to_string(chunk_at) +
                        ": unknown chunk compression 'zzzz' (MCAP chunks are \"\", zstd or lz4)"));
  std::string huge = bytes;
  huge.replace(chunk_at + 1, 8, std::string("\x00\x00\x00\x00\x00\x00\x00\x40", 8));  // 2^62
  const fs::path h = test::write_fixture_bytes(dir, "huge.mcap", huge);
  EXPECT_THAT(test::error_of([&] { (void)read_mcap_imu(h.string(), {}); }),
              HasSubstr("byte offset " + std::to_string(chunk_at) +
                        ": truncated record (opcode 0x06): its content needs 4611686018427387904 "
                        "bytes"));
  const fs::path text = test::write_fixture_bytes(dir, "text.mcap", "time,gyro\n1,2\n");
  EXPECT_FALSE(is_mcap_file(text.string()));
  EXPECT_THAT(test::error_of([&] { (void)list_mcap_topics(text.string()); }),
              HasSubstr("byte offset 0: not an MCAP file"));
}

// Found by fuzz_mcap_reader: statistics claiming more messages than a vector holds made the
// reader reserve them (std::length_error); the counts now only bound the reservation by the
// file size.
TEST(McapReader, RegressionAStatisticsCountBeyondTheFileIsNoAllocation) {
  const fs::path input = fs::path(IMUNOISE_SOURCE_DIR) /
                         "fuzz/corpus/fuzz_mcap_reader/regression_statistics_count_reserve.mcap";
  try {
    (void)read_mcap_imu(input.string(), {});
  } catch (const InputError&) {
  } catch (const AnalysisError&) {
  }
}

}  // namespace
}  // namespace imunoise::io
