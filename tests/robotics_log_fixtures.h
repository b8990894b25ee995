/// @file
/// @brief The robotics-log fixtures of the io and tools tests (ROS 1 bags, MCAP, rosbag2 .db3,
/// ULog), written at test time by the other tools' own writers into IMUNOISE_FIXTURE_DIR
/// (tests/fixtures/write_fixtures.sh, the ctest fixture "robotics_logs"), and the samples each
/// writer was given, read back from the CSV it wrote beside them.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pipeline/recording.h"

namespace imunoise::test {

/// The folder of one writer's fixtures: IMUNOISE_FIXTURE_DIR/SUBDIR.
inline std::filesystem::path fixture_dir(const std::string& subdir) {
  return std::filesystem::path(IMUNOISE_FIXTURE_DIR) / subdir;
}

/// Why the fixtures of writer KIND ("rosbag1", "node") are missing, or "" when they are there.
inline std::string fixture_skip_reason(const std::string& kind) {
  std::ifstream skip(std::filesystem::path(IMUNOISE_FIXTURE_DIR) / (kind + ".skip"));
  if (!skip) return {};
  std::stringstream s;
  s << skip.rdbuf();
  return "the " + kind + " fixture writer could not run: " + s.str();
}

/// Skips the test when writer KIND could not run (its reason); fails it when the fixture file
/// SUBDIR/NAME is missing otherwise; else VAR is its path.
#define IMUNOISE_REQUIRE_FIXTURE(var, kind, subdir, name)                                          \
  if (const std::string reason_ = ::imunoise::test::fixture_skip_reason(kind); !reason_.empty()) { \
    GTEST_SKIP() << reason_;                                                                       \
  }                                                                                                \
  const std::filesystem::path var = ::imunoise::test::fixture_dir(subdir) / (name);                \
  if (!std::filesystem::exists(var)) {                                                             \
    GTEST_FAIL() << var                                                                            \
                 << " is missing: run the tests with ctest (its fixture "                          \
                    "RoboticsLogFixtures.Write writes it), or tests/fixtures/write_fixtures.sh";   \
  }

/// One sample as the fixture writer was given it.
struct FixtureSample {
  std::int64_t stamp_ns = 0;       ///< header.stamp / timestamp_sample [ns]
  std::int64_t log_ns = 0;         ///< the log / receive time [ns]
  std::array<double, 6> values{};  ///< gyro x y z [rad/s], accel x y z [m/s²]
};

/// The samples of a fixture CSV (time_ns, log_time_ns, six values; a header line first).
inline std::vector<FixtureSample> read_fixture_samples(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  std::vector<FixtureSample> out;
  while (std::getline(in, line)) {
    FixtureSample s;
    const char* p = line.c_str();
    char* end = nullptr;
    s.stamp_ns = std::strtoll(p, &end, 10);
    s.log_ns = std::strtoll(end + 1, &end, 10);
    for (double& v : s.values) v = std::strtod(end + 1, &end);
    out.push_back(s);
  }
  return out;
}

/// Checks every sample of RECORDING (values and stamps) against what the writer was given:
/// the stamps header.stamp (LOG_TIME false) or the log time.
inline void expect_fixture_samples(const pipeline::Recording& recording,
                                   const std::vector<FixtureSample>& expected, bool log_time) {
  ASSERT_EQ(recording.sample_count(), expected.size());
  ASSERT_EQ(recording.channels.size(), 6u);
  const auto stamp = [&](std::size_t i) {
    return log_time ? expected[i].log_ns : expected[i].stamp_ns;
  };
  EXPECT_DOUBLE_EQ(recording.start_time_s, static_cast<double>(stamp(0)) * 1e-9);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(recording.time_s[i], static_cast<double>(stamp(i) - stamp(0)) * 1e-9) << i;
    for (std::size_t c = 0; c < 6; ++c) {
      ASSERT_EQ(recording.channels[c].values[i], expected[i].values[c])
          << "sample " << i << " channel " << c;
    }
  }
}

/// BYTES written to DIR/NAME; returns the path.
inline std::filesystem::path write_fixture_bytes(const std::filesystem::path& dir,
                                                 const std::string& name,
                                                 const std::string& bytes) {
  const std::filesystem::path p = dir / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

}  // namespace imunoise::test
