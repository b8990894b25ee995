// Tests of the CSV dialects (io/imu_header_mapping.cpp through io::read_recording, and the '#'
// header line and decimal comma of io/table_layout.cpp): each layout, written here from its
// documented header (docs/csv-dialects.md cites the sources), reads to the values, stamps and SI
// units it holds; the problems give located errors that list the columns.
#include "io/imu_header_mapping.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/units.h"
#include "io/csv_reader.h"
#include "pipeline/recording.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using test::error_of;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string fixture(const std::string& name, const std::string& text) {
  const auto path = test::make_temp_dir("dialect") / name;
  test::write_text(path, text);
  return path.string();
}

const pipeline::Channel& channel(const pipeline::Recording& rec, const std::string& name) {
  const pipeline::Channel* c = rec.find_channel(name);
  if (c == nullptr) throw std::runtime_error("no channel " + name);
  return *c;
}

std::vector<std::string> channel_names(const pipeline::Recording& rec) {
  std::vector<std::string> names;
  for (const pipeline::Channel& c : rec.channels) names.push_back(c.name);
  return names;
}

/// The mapping of a comma-separated HEADER (a row of zeros under it).
csv_detail::HeaderMapping mapping_of(const std::string& header) {
  std::string row = "0";
  for (char c : header) row += c == ',' ? ",0" : "";
  return csv_detail::map_imu_header(
      TableReader(fixture("h.csv", header + "\n" + row + "\n")).layout());
}

TEST(CsvDialect, EurocHeaderIsACommentWithBracketedUnitsAndNanosecondStamps) {
  const auto path = fixture("euroc.csv",
                            "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],"
                            "w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],"
                            "a_RS_S_z [m s^-2]\n"
                            "1403636579758555392,-0.099134701513277898,0.14730578886832138,"
                            "0.02722713633111154,8.1476917083333333,-0.37592158333333331,"
                            "-2.4026292499999999\n"
                            "1403636579763555584,-0.099134701513277898,0.14032447186034408,"
                            "0.029321531433504733,8.033280791666666,-0.40861041666666664,"
                            "-2.4026292499999999\n"
                            "1403636579768555520,-0.098436569812480182,0.12775810124598494,"
                            "0.037699111843077518,7.8861810416666662,-0.42495483333333334,"
                            "-2.3699404166666665\n");
  EXPECT_EQ(mapping_of("#timestamp [ns],w_RS_S_x [rad s^-1],a_RS_S_z [m s^-2]").dialect,
            "EuRoC/TUM-VI");
  const pipeline::Recording rec = read_recording(path, {});
  EXPECT_THAT(channel_names(rec),
              ElementsAre("gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"));
  EXPECT_EQ(channel(rec, "gyro_y").values[1], 0.14032447186034408);
  EXPECT_EQ(channel(rec, "accel_x").values[2], 7.8861810416666662);
  EXPECT_EQ(channel(rec, "gyro_x").source_unit, "rad/s");
  EXPECT_EQ(channel(rec, "accel_z").source_unit, "m/s^2");
  EXPECT_EQ(channel(rec, "accel_z").source_column, "a_RS_S_z [m s^-2]");
  // Stamps relative to the first, in exact integer ns: 5000192 and 10000128 ns.
  EXPECT_DOUBLE_EQ(rec.time_s[1], 5000192e-9);
  EXPECT_DOUBLE_EQ(rec.time_s[2], 10000128e-9);
  EXPECT_DOUBLE_EQ(rec.start_time_s, 1403636579.758555392);
  // The median of 5000192 and 4999936 ns: 4999936 + 128 = 5000064 ns.
  EXPECT_EQ(rec.report.timing.median_interval_s, 5000064e-9);
  EXPECT_EQ(rec.report.timing.rate_hz, 1e9 / 5000064.0);
}

TEST(CsvDialect, KalibrImuCsvIsNanosecondsRadPerSecondAndMetresPerSecondSquared) {
  // Kalibr wiki, "Bag format": timestamps [ns], omega [rad/s], alpha [m/s^2].
  const auto path = fixture("imu0.csv",
                            "timestamp,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z\n"
                            "1385030208736607488,0.5,-0.2,-0.1,8.1,-1.9,-3.3\n"
                            "1385030208741607488,0.5,-0.1,-0.1,8.1,-1.9,-3.3\n"
                            "1385030208746607488,0.4,-0.1,-0.1,8.2,-1.9,-3.3\n");
  const pipeline::Recording rec = read_recording(path, {});
  EXPECT_EQ(mapping_of("timestamp,omega_x,alpha_x").dialect, "Kalibr");
  EXPECT_EQ(rec.channels.size(), 6u);
  EXPECT_THAT(channel(rec, "gyro_x").values, ElementsAre(0.5, 0.5, 0.4));
  EXPECT_THAT(channel(rec, "accel_x").values, ElementsAre(8.1, 8.1, 8.2));
  EXPECT_EQ(rec.report.timing.rate_hz, 200.0);
  EXPECT_EQ(rec.sample_period_s, 0.005);
  // omega / alpha without Kalibr's "timestamp": their units are not known.
  const csv_detail::HeaderMapping other = mapping_of("time_s,omega_x,alpha_x");
  ASSERT_TRUE(other.gyro.has_value());
  EXPECT_FALSE(other.gyro->unit.has_value());
}

TEST(CsvDialect, RostopicEchoTakesTheHeaderStampOverTheReceiveTime) {
  std::string text =
      "%time,field.header.seq,field.header.stamp,field.header.frame_id,field.orientation.x,"
      "field.orientation.y,field.orientation.z,field.orientation.w,field.angular_velocity.x,"
      "field.angular_velocity.y,field.angular_velocity.z,field.angular_velocity_covariance0,"
      "field.linear_acceleration.x,field.linear_acceleration.y,field.linear_acceleration.z\n";
  const long long t0 = 1570000000000000000LL;
  for (long long k = 0; k < 4; ++k) {
    text += std::to_string(t0 + k * 2500000 + 400000 + (k % 2) * 90000) + "," + std::to_string(k) +
            "," + std::to_string(t0 + k * 2500000) + ",imu,0.1,0.2,0.3,0.9,0.01,0.02," +
            std::to_string(0.03 * static_cast<double>(k)) + ",0,1.5,2.5,9.75\n";
  }
  const csv_detail::HeaderMapping m = mapping_of(text.substr(0, text.find('\n')));
  EXPECT_EQ(m.dialect, "rostopic echo -p");
  ASSERT_TRUE(m.time.has_value());
  EXPECT_EQ(m.time->column, 2u);
  const pipeline::Recording rec = read_recording(fixture("rt.csv", text), {});
  EXPECT_THAT(channel_names(rec),
              ElementsAre("gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"));
  EXPECT_THAT(channel(rec, "accel_z").values, ElementsAre(9.75, 9.75, 9.75, 9.75));
  EXPECT_EQ(channel(rec, "gyro_x").source_column, "field.angular_velocity.x");
  EXPECT_EQ(rec.report.timing.rate_hz, 400.0);  // the stamps; the receive times jitter
  EXPECT_DOUBLE_EQ(rec.time_s[1], 0.0025);
  EXPECT_DOUBLE_EQ(rec.time_s[3], 0.0075);
  EXPECT_DOUBLE_EQ(rec.start_time_s, 1570000000.0);
}

TEST(CsvDialect, Ros2SecondsAndNanosecondsPairCrossesSecondBoundariesExactly) {
  const auto path = fixture("ros2.csv",
                            "bag_time_ns,header.stamp.sec,header.stamp.nanosec,header.frame_id,"
                            "angular_velocity.x,linear_acceleration.z\n"
                            "1700000010000000900,1700000009,995000000,imu,0.25,9.5\n"
                            "1700000010005000100,1700000010,0,imu,0.5,9.25\n"
                            "1700000010010000700,1700000010,5000000,imu,0.75,9.0\n"
                            "1700000010015000300,1700000010,10000000,imu,1.0,8.75\n");
  EXPECT_EQ(mapping_of("header.stamp.sec,header.stamp.nanosec,angular_velocity.x").dialect,
            "ROS 2 stamp");
  const pipeline::Recording rec = read_recording(path, {});
  EXPECT_THAT(channel_names(rec), ElementsAre("gyro_x", "accel_z"));
  EXPECT_THAT(channel(rec, "gyro_x").values, ElementsAre(0.25, 0.5, 0.75, 1.0));
  EXPECT_EQ(channel(rec, "accel_z").source_unit, "m/s^2");
  EXPECT_DOUBLE_EQ(rec.time_s[1], 0.005);
  EXPECT_DOUBLE_EQ(rec.time_s[3], 0.015);
  EXPECT_EQ(rec.report.timing.rate_hz, 200.0);
  EXPECT_DOUBLE_EQ(rec.start_time_s, 1700000009.995);
}

TEST(CsvDialect, SemicolonDecimalCommaWithUnitsInTheNames) {
  const auto path = fixture("de.csv",
                            "time (ms);GyroX (deg/s);acc_y [g]\n"
                            "0;1,5;-0,5\n"
                            "2,5;-2,25;1\n"
                            "5;0,125;0,75\n");
  const pipeline::Recording rec = read_recording(path, {});
  EXPECT_THAT(channel_names(rec), ElementsAre("gyro_x", "accel_y"));
  EXPECT_DOUBLE_EQ(channel(rec, "gyro_x").values[1], -2.25 * units::kDegPerS);
  EXPECT_DOUBLE_EQ(channel(rec, "accel_y").values[0], -0.5 * units::kG);
  EXPECT_EQ(channel(rec, "gyro_x").source_unit, "deg/s");
  EXPECT_EQ(rec.report.timing.rate_hz, 400.0);
  EXPECT_EQ(rec.sample_period_s, 0.0025);
}

TEST(CsvDialect, AnySubsetOfAxesKeepsItsAxisNames) {
  const pipeline::Recording z =
      read_recording(fixture("z.csv", "time_s,gyro_z_rad_per_s\n0,1\n0.01,2\n0.02,3\n"), {});
  EXPECT_THAT(channel_names(z), ElementsAre("gyro_z"));
  EXPECT_THAT(channel(z, "gyro_z").values, ElementsAre(1.0, 2.0, 3.0));
  const pipeline::Recording yz = read_recording(
      fixture("yz.csv", "t [s],gz [deg/s],ay [m/s^2],gy [deg/s]\n0,1,2,3\n0.5,1,2,3\n"), {});
  EXPECT_THAT(channel_names(yz), ElementsAre("gyro_y", "gyro_z", "accel_y"));
  EXPECT_DOUBLE_EQ(channel(yz, "gyro_y").values[0], 3.0 * units::kDegPerS);
  // Plain names take their units from the flags.
  InputConfig config;
  config.time_unit = TimeUnit::kMillisecond;
  config.gyro_unit = GyroUnit::kDegPerS;
  const pipeline::Recording bare =
      read_recording(fixture("bare.csv", "time,gyro_z\n0,1\n10,2\n20,3\n"), config);
  EXPECT_THAT(channel_names(bare), ElementsAre("gyro_z"));
  EXPECT_DOUBLE_EQ(channel(bare, "gyro_z").values[2], 3.0 * units::kDegPerS);
  EXPECT_EQ(bare.report.timing.rate_hz, 100.0);
}

TEST(CsvDialect, NonImuVectorsAreNotTakenForGyroOrAccel) {
  const csv_detail::HeaderMapping m = mapping_of(
      "time_s,field.orientation.x,mag_x,position_x,gyro_bias_x,angular_acceleration_x,"
      "velocity_x,q_w,angular_velocity_covariance[0],gyro_x_raw");
  EXPECT_FALSE(m.gyro.has_value());
  EXPECT_FALSE(m.accel.has_value());
  ASSERT_TRUE(m.time.has_value());
  EXPECT_EQ(m.time->unit, TimeUnit::kSecond);
}

TEST(CsvDialect, ACommentIsAHeaderOnlyWhenItsNamesMatchTheRow) {
  // simulate's preamble style: comments, then no header, 3 columns; the last comment has 2
  // words, so it stays a comment.
  EXPECT_FALSE(TableReader(fixture("c.csv", "# seed: 5\n# gyro only\n0,1,2\n1,1,2\n"))
                   .layout()
                   .has_header());
  const TableLayout layout =
      TableReader(fixture("c2.csv", "# made by x\n#t,gx,gy\n0,1,2\n1,1,2\n")).layout();
  EXPECT_THAT(layout.column_names, ElementsAre("t", "gx", "gy"));
  EXPECT_EQ(layout.header_line, 2);
}

TEST(CsvDialectErrors, MissingUnitsNameFileLineColumnAndFlag) {
  EXPECT_THAT(error_of([&] {
                read_recording(fixture("nu.csv", "time_s,acc_x,acc_y\n0,1,2\n1,1,2\n"), {});
              }),
              HasSubstr("nu.csv:1: 'acc_x' (column 2) is an accel axis but the header states no "
                        "unit: give --accel-unit m/s^2|g|mg|m/s (or accel.unit in the config)"));
  // With the gyro mapped by the flags, named accel columns without a unit are left out.
  InputConfig config;
  config.gyro_columns = {"2"};
  const pipeline::Recording rec =
      read_recording(fixture("nu2.csv", "time_s,g,acc_x\n0,1,2\n1,1,2\n"), config);
  EXPECT_THAT(channel_names(rec), ElementsAre("gyro_x"));
}

TEST(CsvDialectErrors, AmbiguousAndUnknownUnitsListTheColumns) {
  EXPECT_THAT(
      error_of(
          [&] { read_recording(fixture("u.csv", "time_s,gyro_x [furlong/s]\n0,1\n1,1\n"), {}); }),
      HasSubstr("u.csv:1: 'gyro_x [furlong/s]' (column 2) states the unit 'furlong/s', which is "
                "not a gyro unit imunoise knows"));
  EXPECT_THAT(error_of([&] {
                read_recording(
                    fixture("d.csv", "time_s,gyro_x [deg/s],gyro_y [rad/s]\n0,1,1\n1,1,1\n"), {});
              }),
              HasSubstr("d.csv:1: 'gyro_x [deg/s]' (column 2) and 'gyro_y [rad/s]' (column 3) "
                        "state different gyro units (columns found: time_s, gyro_x [deg/s], "
                        "gyro_y [rad/s])"));
  EXPECT_THAT(
      error_of([&] {
        read_recording(fixture("t.csv", "time_s,timestamp [ns],gz [rad/s]\n0,0,1\n1,1,1\n"), {});
      }),
      HasSubstr("t.csv:1: two time columns: 'time_s' (column 1) and 'timestamp [ns]' (column 2); "
                "choose one with --time-col"));
  // The flag settles it.
  InputConfig config;
  config.time_column = "time_s";
  EXPECT_EQ(
      read_recording(fixture("t2.csv", "time_s,timestamp [ns],gz [rad/s]\n0,0,1\n1,1,1\n"), config)
          .sample_period_s,
      1.0);
  EXPECT_THAT(error_of([&] {
                read_recording(fixture("a.csv", "t [s],gyro_x [rad/s],Gyro X [rad/s]\n0,1,1\n"),
                               {});
              }),
              HasSubstr("two gyro x columns: 'gyro_x [rad/s]' (column 2) and 'Gyro X [rad/s]' "
                        "(column 3)"));
}

}  // namespace
}  // namespace imunoise::io
