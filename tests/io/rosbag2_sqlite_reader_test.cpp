// The rosbag2 sqlite3 reader (io/rosbag2_sqlite_reader.h) on .db3 files in rosbag2's layout
// (Jazzy's and Foxy's) holding the CDR bytes of @foxglove/rosmsg2-serialization
// (tests/fixtures/write_rosbag2_fixtures.py): every sample, both time sources, the topic
// listing and its errors, and files that are not rosbag2 databases.
#include "io/rosbag2_sqlite_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/errors.h"
#include "robotics_log_fixtures.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

fs::path db3(const std::string& name) { return test::fixture_dir("db3") / name; }

TEST(Rosbag2SqliteReader, ReadsEverySampleOfBothLayoutsWithBothTimeSources) {
  IMUNOISE_REQUIRE_FIXTURE(csv, "node", "db3", "imu.csv");
  const auto expected = test::read_fixture_samples(csv);
  ASSERT_EQ(expected.size(), 1200u);
  for (const char* name : {"imu.db3", "imu_foxy.db3"}) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(is_sqlite_file(db3(name).string()));
    const pipeline::Recording recording = read_rosbag2_sqlite_imu(db3(name).string(), {});
    test::expect_fixture_samples(recording, expected, false);
    EXPECT_EQ(recording.channels[4].source_column, "/imu/data.linear_acceleration.y");
    LogReadOptions log;
    log.time_source = TimeSource::kLog;
    test::expect_fixture_samples(read_rosbag2_sqlite_imu(db3(name).string(), log), expected, true);
  }
}

TEST(Rosbag2SqliteReader, ListsTopicsAndTheTopicErrorsListThem) {
  IMUNOISE_REQUIRE_FIXTURE(file, "node", "db3", "imu.db3");
  const auto topics = list_rosbag2_sqlite_topics(file.string());
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].name, "/imu/data");
  EXPECT_EQ(topics[0].type, "sensor_msgs/msg/Imu");
  EXPECT_EQ(topics[0].message_count, 1200);
  EXPECT_TRUE(topics[0].is_imu);
  EXPECT_EQ(topics[1].name, "/status");
  EXPECT_EQ(topics[1].message_count, 120);
  LogReadOptions options;
  options.topic = "/status";
  EXPECT_THAT(test::error_of([&] { (void)read_rosbag2_sqlite_imu(file.string(), options); }),
              HasSubstr(file.string() + ": topic '/status' is of type 'std_msgs/msg/String', "
                                        "which imunoise does not read as an IMU; give --topic "
                                        "NAME; the rosbag2 database holds '/imu/data' "
                                        "(sensor_msgs/msg/Imu, 1200 messages), '/status' "
                                        "(std_msgs/msg/String, 120 messages)"));
}

TEST(Rosbag2SqliteReader, FilesThatAreNotRosbag2DatabasesAreErrors) {
  IMUNOISE_REQUIRE_FIXTURE(file, "node", "db3", "imu.db3");
  const fs::path dir = test::make_temp_dir("db3");
  const std::string bytes = test::read_file_bytes(file);
  const fs::path text = test::write_fixture_bytes(dir, "text.db3", "time,gyro\n");
  EXPECT_THAT(test::error_of([&] { (void)list_rosbag2_sqlite_topics(text.string()); }),
              HasSubstr("not a rosbag2 .db3 file"));
  // Cut: SQLite finds the database image malformed (or the tables missing).
  const fs::path cut = test::write_fixture_bytes(dir, "cut.db3", bytes.substr(0, 3000));
  EXPECT_THAT(test::error_of([&] { (void)read_rosbag2_sqlite_imu(cut.string(), {}); }),
              HasSubstr(cut.string() + ": "));
}

}  // namespace
}  // namespace imunoise::io
