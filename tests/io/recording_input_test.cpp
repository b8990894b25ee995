// Tests of io/recording_input.h: the format of a file told by its first bytes and of an output
// by its name, the user LCM type mapped from an input config, and the read of each format
// with the settings that apply to it.
#include "io/recording_input.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/errors.h"
#include "io/binary_recording.h"
#include "io/csv_reader.h"
#include "io/recording_lcm_writer.h"
#include "robotics_log_fixtures.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

namespace fs = std::filesystem;

constexpr char kCsv[] =
    "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,accel_x_m_per_s2,"
    "accel_y_m_per_s2,accel_z_m_per_s2\n"
    "0,0.1,0.2,0.3,1,2,-9.8\n0.01,0.1,0.2,0.3,1,2,-9.8\n0.02,0.1,0.25,0.3,1,2,-9.8\n";

/// The same three samples as CSV, binary and LCM log in one temporary folder.
class RecordingInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::make_temp_dir("recording_input");
    test::write_text(csv(), kCsv);
    const pipeline::Recording rec = read_recording(csv(), InputConfig{});
    write_binary_recording(binary(), rec);
    write_recording_lcm(rec, log(), "IMU");
  }
  std::string csv() const { return (dir_ / "rec.csv").string(); }
  std::string binary() const { return (dir_ / "rec.imnb").string(); }
  std::string log() const { return (dir_ / "rec.lcmlog").string(); }

  fs::path dir_;
};

TEST_F(RecordingInput, FormatIsToldByContentNotName) {
  EXPECT_EQ(detect_recording_format(csv()), RecordingFormat::kTable);
  EXPECT_EQ(detect_recording_format(binary()), RecordingFormat::kBinary);
  EXPECT_EQ(detect_recording_format(log()), RecordingFormat::kLcmLog);
  EXPECT_TRUE(is_lcm_log_file(log()));
  EXPECT_FALSE(is_lcm_log_file(binary()));
  // A log under a CSV name is still a log; a missing file is a table (its reader says why).
  fs::copy_file(log(), dir_ / "log.csv");
  EXPECT_EQ(detect_recording_format((dir_ / "log.csv").string()), RecordingFormat::kLcmLog);
  EXPECT_EQ(detect_recording_format((dir_ / "none").string()), RecordingFormat::kTable);
}

TEST_F(RecordingInput, RoboticsLogsAreToldByTheirFirstBytes) {
  // The magic alone decides (the readers then check the rest).
  test::write_text(dir_ / "a.csv", "#ROSBAG V2.0\nxyz");
  EXPECT_EQ(detect_recording_format((dir_ / "a.csv").string()), RecordingFormat::kRosbag1);
  test::write_text(dir_ / "b.csv", "#ROSBAG V1.2\nxyz");
  EXPECT_EQ(detect_recording_format((dir_ / "b.csv").string()), RecordingFormat::kRosbag1);
  test::write_text(dir_ / "c.bag", std::string("\x89MCAP0\r\n\x01", 9));
  EXPECT_EQ(detect_recording_format((dir_ / "c.bag").string()), RecordingFormat::kMcap);
  test::write_text(dir_ / "d.mcap", std::string("SQLite format 3\0", 16));
  EXPECT_EQ(detect_recording_format((dir_ / "d.mcap").string()), RecordingFormat::kRosbag2Sqlite);
  for (const RecordingFormat f :
       {RecordingFormat::kRosbag1, RecordingFormat::kMcap, RecordingFormat::kRosbag2Sqlite}) {
    EXPECT_TRUE(is_robotics_log(f));
  }
  EXPECT_FALSE(is_robotics_log(RecordingFormat::kTable));
  EXPECT_EQ(recording_format_name(RecordingFormat::kMcap), "MCAP file");
}

TEST_F(RecordingInput, RoboticsLogsReadThroughTheOneEntryPoint) {
  IMUNOISE_REQUIRE_FIXTURE(bag, "rosbag1", "rosbag1", "imu_bz2.bag");
  const RecordingFormat format = detect_recording_format(bag.string());
  ASSERT_EQ(format, RecordingFormat::kRosbag1);
  EXPECT_EQ(list_log_topics(format, bag.string()).size(), 2u);
  EXPECT_EQ(read_recording_as(format, bag.string(), InputConfig{}, LcmImuSource{}).sample_count(),
            1200u);
  LogReadOptions options;
  options.topic = "/imu/data";
  EXPECT_EQ(read_robotics_log_as(format, bag.string(), options).sample_count(), 1200u);
}

TEST_F(RecordingInput, EachFormatReadsTheSameSamples) {
  const InputConfig config;
  const LcmImuSource lcm{"IMU", std::nullopt};
  for (const auto& [format, path] :
       std::vector<std::pair<RecordingFormat, std::string>>{{RecordingFormat::kTable, csv()},
                                                            {RecordingFormat::kBinary, binary()},
                                                            {RecordingFormat::kLcmLog, log()}}) {
    const pipeline::Recording rec = read_recording_as(format, path, config, lcm);
    ASSERT_EQ(rec.channels.size(), 6u) << path;
    EXPECT_EQ(rec.channels[1].values, (std::vector<double>{0.2, 0.2, 0.25})) << path;
    EXPECT_EQ(rec.channels[5].values, (std::vector<double>{-9.8, -9.8, -9.8})) << path;
    EXPECT_EQ(rec.source_path, path);
  }
}

TEST_F(RecordingInput, BinaryReadTakesTheFullScaleOfTheConfig) {
  InputConfig config;
  config.gyro_full_scale_rad_per_s = 0.25;
  const pipeline::Recording rec =
      read_recording_as(RecordingFormat::kBinary, binary(), config, LcmImuSource{});
  ASSERT_EQ(rec.report.channels.size(), 6u);
  EXPECT_EQ(rec.report.channels[1].full_scale, 0.25);
  EXPECT_EQ(rec.report.channels[1].beyond_full_scale, 1);
  EXPECT_EQ(rec.report.channels[0].beyond_full_scale, 0);
}

TEST(RecordingFormatOfFileName, FollowsTheExtension) {
  EXPECT_EQ(recording_format_of_file_name("a.imnb"), RecordingFormat::kBinary);
  EXPECT_EQ(recording_format_of_file_name("a.csv"), RecordingFormat::kTable);
  EXPECT_EQ(recording_format_of_file_name("a.txt"), RecordingFormat::kTable);
  for (const char* name : {"a.lcm", "a.log", "a.lcmlog"}) {
    EXPECT_EQ(recording_format_of_file_name(name), RecordingFormat::kLcmLog) << name;
  }
  EXPECT_EQ(recording_format_of_file_name("a.dat"), std::nullopt);
  EXPECT_EQ(recording_format_of_file_name(".csv"), std::nullopt);
  EXPECT_EQ(recording_format_name(RecordingFormat::kTable), "CSV");
  EXPECT_EQ(recording_format_name(RecordingFormat::kBinary), "binary");
  EXPECT_EQ(recording_format_name(RecordingFormat::kLcmLog), "LCM log");
}

TEST(LcmUserTypeOfConfig, MapsColumnsAndUnitsToFieldsAndSiFactors) {
  InputConfig config;
  config.time_column = "stamp";
  config.time_unit = TimeUnit::kNanosecond;
  config.gyro_columns = {"gyro"};
  config.gyro_unit = GyroUnit::kDegPerS;
  config.accel_columns = {"ax", "ay", "az"};
  config.accel_unit = AccelUnit::kG;
  const LcmUserType t = lcm_user_type("imu.lcm", "pkg.imu_t", config);
  EXPECT_EQ(t.definition_path, "imu.lcm");
  EXPECT_EQ(t.type_name, "pkg.imu_t");
  EXPECT_EQ(t.time_field, "stamp");
  EXPECT_EQ(t.time_unit_s, 1e-9);
  EXPECT_EQ(t.gyro_fields, std::vector<std::string>{"gyro"});
  EXPECT_EQ(t.accel_fields, (std::vector<std::string>{"ax", "ay", "az"}));
  EXPECT_EQ(t.gyro_scale_to_si, si_factor(GyroUnit::kDegPerS));
  EXPECT_EQ(t.accel_scale_to_si, si_factor(AccelUnit::kG));
  EXPECT_FALSE(t.increments);
}

TEST(LcmUserTypeOfConfig, DefaultsToUtimeInMicrosecondsAndSiUnits) {
  InputConfig config;
  config.gyro_columns = {"g"};
  config.accel_columns = {"a"};
  const LcmUserType t = lcm_user_type("imu.lcm", "", config);
  EXPECT_EQ(t.time_field, "utime");
  EXPECT_EQ(t.time_unit_s, 1e-6);
  EXPECT_EQ(t.gyro_scale_to_si, 1.0);
  EXPECT_EQ(t.accel_scale_to_si, 1.0);
  config.gyro_unit = GyroUnit::kRadIncrement;
  config.accel_unit = AccelUnit::kMPerSIncrement;
  EXPECT_TRUE(lcm_user_type("imu.lcm", "", config).increments);
}

TEST(LcmUserTypeOfConfig, UncheckedMappingIsAContractViolation) {
  InputConfig config;
  config.gyro_columns = {"g"};
  EXPECT_THROW(lcm_user_type("imu.lcm", "", config), ContractViolation);  // no accel fields
  config.accel_columns = {"a"};
  config.gyro_unit = GyroUnit::kRadIncrement;  // increments with rates
  EXPECT_THROW(lcm_user_type("imu.lcm", "", config), ContractViolation);
}

}  // namespace
}  // namespace imunoise::io
