// Process-level tests of the robotics-log inputs (ROS 1 bags, ...): `imunoise analyze` on a log
// written by the other tool's own writer gives the model of the CSV of the same samples (the
// same bytes but the source's name), with no mapping flag, and drift gives the same segments;
// check, allan and convert accept the logs; the topic errors list the topics (exit 2);
// --time-source; the flags that do not apply are refused, naming them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "robotics_log_fixtures.h"
#include "test_support.h"

namespace imunoise {
namespace {

using test::quoted_for_shell;
using test::read_file_bytes;
using test::run_imunoise;
using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    text.replace(at, from.size(), to);
    at += to.size();
  }
  return text;
}

/// analyze on LOG and on CSV (the same samples) into DIR; the model.yaml, allan.csv and psd.csv
/// must be the same bytes once the source names are swapped.
void expect_same_analysis(const fs::path& log, const fs::path& csv, const fs::path& dir,
                          const std::string& extra_flags = "") {
  const std::string flags = " -q --bootstrap 4 --seed 9";
  const auto a = run_imunoise("analyze " + quoted_for_shell(log) + flags + extra_flags + " -o " +
                              quoted_for_shell(dir / "log"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto b = run_imunoise("analyze " + quoted_for_shell(csv) + flags + " -o " +
                              quoted_for_shell(dir / "csv"));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  std::string model = read_file_bytes(dir / "log" / "model.yaml");
  model = replaced(model, log.string(), csv.string());
  model = replaced(model, log.filename().string(), csv.filename().string());
  const std::string model_csv = read_file_bytes(dir / "csv" / "model.yaml");
  ASSERT_FALSE(model_csv.empty());
  EXPECT_EQ(model, model_csv);
  EXPECT_EQ(read_file_bytes(dir / "log" / "allan.csv"), read_file_bytes(dir / "csv" / "allan.csv"));
  EXPECT_EQ(read_file_bytes(dir / "log" / "psd.csv"), read_file_bytes(dir / "csv" / "psd.csv"));
  // drift with that model: the same segments and envelope from the log and from the CSV.
  for (const auto& [input, out] : {std::pair{log, "drift_log"}, std::pair{csv, "drift_csv"}}) {
    const auto d = run_imunoise("drift " + quoted_for_shell(input) + extra_flags + " --model " +
                                quoted_for_shell(dir / "log" / "model.yaml") +
                                " --segment 2min --align 30s --monte-carlo 0 --heading 0 --force "
                                "-q -o " +
                                quoted_for_shell(dir / out));
    ASSERT_EQ(d.exit_code, 0) << d.err;
  }
  const std::string segments = read_file_bytes(dir / "drift_csv" / "drift_segments.csv");
  ASSERT_FALSE(segments.empty());
  EXPECT_EQ(read_file_bytes(dir / "drift_log" / "drift_segments.csv"), segments);
  EXPECT_EQ(read_file_bytes(dir / "drift_log" / "drift_envelope.csv"),
            read_file_bytes(dir / "drift_csv" / "drift_envelope.csv"));
}

TEST(RoboticsLogCli, AnalyzeOnARosbagGivesTheModelOfTheCsvOfTheSameSamples) {
  IMUNOISE_REQUIRE_FIXTURE(bag, "rosbag1", "rosbag1", "analyze.bag");
  expect_same_analysis(bag, test::fixture_dir("rosbag1") / "analyze.csv",
                       test::make_temp_dir("robotics_cli"));
}

TEST(RoboticsLogCli, AnalyzeOnAnMcapGivesTheModelOfTheCsvOfTheSameSamples) {
  IMUNOISE_REQUIRE_FIXTURE(file, "node", "mcap", "analyze.mcap");
  expect_same_analysis(file, test::fixture_dir("mcap") / "analyze.csv",
                       test::make_temp_dir("robotics_cli"));
}

TEST(RoboticsLogCli, AnalyzeOnARosbag2DatabaseGivesTheModelOfTheCsvOfTheSameSamples) {
  IMUNOISE_REQUIRE_FIXTURE(file, "node", "db3", "analyze.db3");
  expect_same_analysis(file, test::fixture_dir("db3") / "analyze.csv",
                       test::make_temp_dir("robotics_cli"));
}

TEST(RoboticsLogCli, AnalyzeOnAUlogGivesTheModelOfTheCsvOfTheSameSamples) {
  IMUNOISE_REQUIRE_FIXTURE(file, "node", "ulog", "analyze.ulg");
  expect_same_analysis(file, test::fixture_dir("ulog") / "analyze.csv",
                       test::make_temp_dir("robotics_cli"));
}

TEST(RoboticsLogCli, UlogInstanceSelectsTheImu) {
  IMUNOISE_REQUIRE_FIXTURE(file, "node", "ulog", "imu.ulg");
  const auto chosen =
      run_imunoise("check " + quoted_for_shell(file) + " --topic sensor_gyro --instance 1");
  ASSERT_EQ(chosen.exit_code, 0) << chosen.err;
  EXPECT_THAT(chosen.out, HasSubstr("samples:    1200"));
  const auto several = run_imunoise("check " + quoted_for_shell(file) + " --topic sensor_gyro");
  EXPECT_EQ(several.exit_code, 2);
  EXPECT_THAT(several.err, HasSubstr("has several instances, which one?"));
}

TEST(RoboticsLogCli, CheckAllanAndConvertReadABag) {
  IMUNOISE_REQUIRE_FIXTURE(bag, "rosbag1", "rosbag1", "imu_lz4.bag");
  const fs::path dir = test::make_temp_dir("robotics_cli");
  const auto check = run_imunoise("check " + quoted_for_shell(bag));
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("samples:    1200"));
  EXPECT_THAT(check.out, HasSubstr("rate:       200 Hz"));

  const auto allan = run_imunoise("allan " + quoted_for_shell(bag) + " --column gyro_z --json");
  ASSERT_EQ(allan.exit_code, 0) << allan.err;
  EXPECT_THAT(allan.out, HasSubstr("/imu/data.angular_velocity.z"));

  const auto convert = run_imunoise("convert " + quoted_for_shell(bag) + " -q -o " +
                                    quoted_for_shell(dir / "c.csv"));
  ASSERT_EQ(convert.exit_code, 0) << convert.err;
  EXPECT_THAT(convert.out, HasSubstr("wrote 1200 samples"));
  // The converted CSV reads back to the bag's samples.
  const auto back = run_imunoise("check " + quoted_for_shell(dir / "c.csv"));
  ASSERT_EQ(back.exit_code, 0) << back.err;
  EXPECT_THAT(back.out, HasSubstr("samples:    1200"));
}

TEST(RoboticsLogCli, LiveReplaysABagConvertedToAnLcmLog) {
  // live reads LCM; a bag reaches it through convert (the log holds the bag's samples at µs
  // stamps). One analysis at the end of the replay must give analyze's coefficients on the bag.
  IMUNOISE_REQUIRE_FIXTURE(bag, "rosbag1", "rosbag1", "analyze.bag");
  const fs::path dir = test::make_temp_dir("robotics_cli");
  const auto convert =
      run_imunoise("convert " + quoted_for_shell(bag) + " -q --lcm-channel IMU -o " +
                   quoted_for_shell(dir / "bag.lcmlog"));
  ASSERT_EQ(convert.exit_code, 0) << convert.err;
  const auto live = run_imunoise(
      "live --channel IMU --lcm-url " +
      quoted_for_shell("file://" + (dir / "bag.lcmlog").string() + "?speed=0") + " --publish-url " +
      quoted_for_shell("file://" + (dir / "out.lcmlog").string() + "?mode=w") +
      " --every 100000s --bootstrap 0 -o " + quoted_for_shell(dir / "live"));
  ASSERT_EQ(live.exit_code, 0) << live.err;
  EXPECT_THAT(live.out, HasSubstr("received 60000, accepted 60000"));
  const auto analyze = run_imunoise("analyze " + quoted_for_shell(bag) + " -q --bootstrap 0 -o " +
                                    quoted_for_shell(dir / "analyze"));
  ASSERT_EQ(analyze.exit_code, 0) << analyze.err;
  // The coefficient lines (value, interval ends) of the two models.
  const auto coefficients = [](const std::string& yaml) {
    std::string lines;
    std::size_t start = 0;
    while (start < yaml.size()) {
      std::size_t end = yaml.find('\n', start);
      if (end == std::string::npos) end = yaml.size();
      const std::string line = yaml.substr(start, end - start);
      if (line.find("value:") != std::string::npos || line.find("ci_") != std::string::npos) {
        lines += line + "\n";
      }
      start = end + 1;
    }
    return lines;
  };
  const std::string expected = coefficients(read_file_bytes(dir / "analyze" / "model.yaml"));
  ASSERT_THAT(expected, HasSubstr("value:"));
  EXPECT_EQ(coefficients(read_file_bytes(dir / "live" / "model.yaml")), expected);
}

TEST(RoboticsLogCli, TopicErrorsListTopicsTypesAndCounts) {
  IMUNOISE_REQUIRE_FIXTURE(two, "rosbag1", "rosbag1", "two_imus.bag");
  const auto ambiguous = run_imunoise("check " + quoted_for_shell(two));
  EXPECT_EQ(ambiguous.exit_code, 2);
  EXPECT_THAT(ambiguous.err,
              HasSubstr("2 IMU topics, which one?; give --topic NAME; the bag holds '/imu/data' "
                        "(sensor_msgs/Imu, 100 messages), '/imu2/data' (sensor_msgs/Imu, 50 "
                        "messages)"));
  const auto chosen = run_imunoise("check " + quoted_for_shell(two) + " --topic /imu2/data");
  ASSERT_EQ(chosen.exit_code, 0) << chosen.err;
  EXPECT_THAT(chosen.out, HasSubstr("samples:    50"));
  const auto wrong = run_imunoise("check " + quoted_for_shell(two) + " --topic /cam");
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_THAT(wrong.err, HasSubstr("topic '/cam' not found; give --topic NAME; the bag holds"));
}

TEST(RoboticsLogCli, TimeSourceAndFlagsThatDoNotApply) {
  IMUNOISE_REQUIRE_FIXTURE(bag, "rosbag1", "rosbag1", "imu_none.bag");
  const auto log_time = run_imunoise("check " + quoted_for_shell(bag) + " --time-source log");
  ASSERT_EQ(log_time.exit_code, 0) << log_time.err;
  // The record times carry a 0–0.4 ms jitter (the fixture writer's), the header stamps none.
  EXPECT_THAT(log_time.out, Not(HasSubstr("jitter:     RMS 0 ")));
  const auto bad_source = run_imunoise("check " + quoted_for_shell(bag) + " --time-source rx");
  EXPECT_EQ(bad_source.exit_code, 2);
  EXPECT_THAT(bad_source.err, HasSubstr("--time-source 'rx': expected header or log"));
  const auto rate = run_imunoise("check " + quoted_for_shell(bag) + " --rate 100");
  EXPECT_EQ(rate.exit_code, 2);
  EXPECT_THAT(rate.err, HasSubstr("--rate does not apply to this ROS 1 bag"));
  const auto channel = run_imunoise("check " + quoted_for_shell(bag) + " --channel IMU");
  EXPECT_EQ(channel.exit_code, 2);
  EXPECT_THAT(channel.err, HasSubstr("--channel does not apply to this ROS 1 bag"));
  const auto csv = run_imunoise(
      "check " + quoted_for_shell(test::fixture_dir("rosbag1") / "imu.csv") + " --topic /imu");
  EXPECT_EQ(csv.exit_code, 2);
  EXPECT_THAT(csv.err, HasSubstr("--topic applies to robotics logs"));
}

}  // namespace
}  // namespace imunoise
