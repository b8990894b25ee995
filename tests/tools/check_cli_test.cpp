// End-to-end tests of `imunoise check`: text and JSON reports, input flags and --config,
// flag-over-config precedence, and non-zero exits with FILE:LINE:COL on bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "common/units.h"
#include "test_support.h"

namespace imunoise {
namespace {

using ::testing::HasSubstr;

constexpr char kSimulateHeader[] =
    "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,accel_x_m_per_s2,"
    "accel_y_m_per_s2,accel_z_m_per_s2\n";

/// A 100 Hz simulate-style recording with one lost sample after row 50.
std::string simulate_csv() {
  std::string text = kSimulateHeader;
  for (int i = 0; i < 200; ++i) {
    if (i == 50) continue;
    text += std::to_string(i * 0.01) + ",0.001,-0.002,0.003," + std::to_string(0.01 * (i % 7)) +
            ",0,9.81\n";
  }
  return text;
}

std::string write_fixture(const std::string& name, const std::string& text) {
  const auto path = test::make_temp_dir("check") / name;
  test::write_text(path, text);
  return path.string();
}

TEST(CheckCli, TextReportForSimulateColumns) {
  const auto path = write_fixture("sim.csv", simulate_csv());
  const auto r = test::run_imunoise("check '" + path + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("samples:    199"));
  EXPECT_THAT(r.out, HasSubstr("rate:       100 Hz"));
  EXPECT_THAT(r.out, HasSubstr("gaps:       1 (longest 20 ms"));
  EXPECT_THAT(r.out, HasSubstr("(first at line 52)"));
  EXPECT_THAT(r.out, HasSubstr("gyro_x [rad/s]"));
  EXPECT_THAT(r.out, HasSubstr("accel_z [m/s^2]"));
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(CheckCli, JsonIsOneObjectWithUnitKeys) {
  const auto path = write_fixture("sim.csv", simulate_csv());
  const auto r = test::run_imunoise("check '" + path + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["rate_hz"].get<double>(), 100.0, 1e-6);
  EXPECT_EQ(j["gap_count"], 1);
  EXPECT_NEAR(j["longest_gap_s"].get<double>(), 0.02, 1e-9);
  EXPECT_TRUE(j.contains("jitter_rms_s"));
  ASSERT_EQ(j["channels"].size(), 6u);
  EXPECT_EQ(j["channels"][0]["name"], "gyro_x");
  EXPECT_EQ(j["channels"][0]["unit"], "rad/s");
  // accel_x cycles through 0.00 .. 0.06 in 0.01 steps: a clean code grid.
  EXPECT_NEAR(j["channels"][3]["lsb"].get<double>(), 0.01, 1e-9);
}

TEST(CheckCli, AlternatingStampsAreAnalysedAtTheirMeanInterval) {
  // Stamps 0.10, 0.10, 0.11 s apart (a 10 Hz clock that slips every third sample): the median
  // says 10 Hz; the 599 intervals (400 of 0.10 s, 199 of 0.11 s) average 0.103322 s.
  std::string text = kSimulateHeader;
  double t = 0.0;
  for (int i = 0; i < 600; ++i) {
    text += std::to_string(t) + ",0.001,-0.002,0.003,0.01,0,9.81\n";
    t += i % 3 == 2 ? 0.11 : 0.10;
  }
  const auto path = write_fixture("alternating.csv", text);
  const auto r = test::run_imunoise("check '" + path + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["median_interval_s"].get<double>(), 0.10, 1e-9);
  EXPECT_TRUE(j["period_from_mean"].get<bool>());
  const double mean_interval_s = (400 * 0.10 + 199 * 0.11) / 599;
  EXPECT_NEAR(j["sample_period_s"].get<double>(), mean_interval_s, 1e-9);
  EXPECT_NEAR(j["rate_hz"].get<double>(), 1.0 / mean_interval_s, 1e-7);
  const auto text_report = test::run_imunoise("check '" + path + "'");
  EXPECT_THAT(text_report.out, HasSubstr("from the mean regular interval"));
}

TEST(CheckCli, PositionalFlagsAndUnits) {
  const auto path = write_fixture("raw.txt", "0 1 2 3\n5 1 2 3\n10 1 2 3\n15 1 2 3\n");
  const auto r = test::run_imunoise("check '" + path +
                                    "' --time-col 1 --time-unit ms --gyro-cols 2,3,4 "
                                    "--gyro-unit deg/s --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["rate_hz"].get<double>(), 200.0, 1e-6);
  EXPECT_NEAR(j["channels"][0]["min"].get<double>(), units::kDegPerS, 1e-15);
  EXPECT_NEAR(j["channels"][2]["max"].get<double>(), 3.0 * units::kDegPerS, 1e-15);
}

TEST(CheckCli, FixedRateAndFullScale) {
  const auto path = write_fixture("r.txt", "100\n2500\n-2500\n3\n");
  const auto r = test::run_imunoise("check '" + path +
                                    "' --rate 400 --gyro-cols 1 --gyro-unit deg/s "
                                    "--full-scale-gyro 2000 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["has_timestamps"].get<bool>());
  EXPECT_DOUBLE_EQ(j["rate_hz"].get<double>(), 400.0);
  EXPECT_EQ(j["channels"][0]["beyond_full_scale"], 2);
  EXPECT_NEAR(j["channels"][0]["full_scale"].get<double>(), 2000.0 * units::kDegPerS, 1e-12);
}

TEST(CheckCli, FlagsOverrideConfigFile) {
  const auto dir = test::make_temp_dir("checkcfg");
  test::write_text(dir / "rec.csv", "t,g\n0,1\n1,1\n2,1\n");
  test::write_text(dir / "in.yaml", "time:\n  column: t\ngyro:\n  columns: [g]\n  unit: deg/h\n");
  const std::string base = "check '" + (dir / "rec.csv").string() + "' --config '" +
                           (dir / "in.yaml").string() + "' --json";
  const auto from_file = test::run_imunoise(base);
  ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
  EXPECT_NEAR(nlohmann::json::parse(from_file.out)["channels"][0]["min"].get<double>(),
              units::kDegPerHour, 1e-18);
  const auto overridden = test::run_imunoise(base + " --gyro-unit deg/s");
  ASSERT_EQ(overridden.exit_code, 0) << overridden.err;
  EXPECT_NEAR(nlohmann::json::parse(overridden.out)["channels"][0]["min"].get<double>(),
              units::kDegPerS, 1e-15);
}

TEST(CheckCli, DropNonFiniteIsCounted) {
  const auto path = write_fixture("nan.csv", std::string(kSimulateHeader) +
                                                 "0,1,1,1,0,0,9.8\n0.01,nan,1,1,0,0,9.8\n"
                                                 "0.02,1,1,1,0,0,9.8\n0.03,1,1,1,0,0,9.8\n");
  const auto failed = test::run_imunoise("check '" + path + "'");
  EXPECT_EQ(failed.exit_code, 2);
  EXPECT_THAT(failed.err, HasSubstr("nan.csv:3:6: non-finite value 'nan'"));
  const auto r = test::run_imunoise("check '" + path + "' --drop-non-finite --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["rows_dropped"], 1);
  EXPECT_EQ(j["non_finite_dropped"], 1);
  EXPECT_EQ(j["samples"], 3);
}

TEST(CheckCli, BadNumberExitsWithFileLineColumn) {
  const auto path = write_fixture(
      "bad.csv", std::string(kSimulateHeader) + "0,1,1,1,0,0,9.8\n0.01,1,1,1,0,x1,9.8\n");
  const auto r = test::run_imunoise("check '" + path + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("imunoise: error: " + path +
                               ":3:14: malformed number 'x1' in 'accel_y_m_per_s2' (column 6)"));
  EXPECT_TRUE(r.out.empty());
}

TEST(CheckCli, MissingFileAndBadConfig) {
  const auto missing = test::run_imunoise("check /nonexistent/rec.csv");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("/nonexistent/rec.csv: cannot open"));

  const auto dir = test::make_temp_dir("checkbad");
  test::write_text(dir / "rec.csv", simulate_csv());
  test::write_text(dir / "in.yaml", "gyro:\n  unit: dps\n");
  const auto bad = test::run_imunoise("check '" + (dir / "rec.csv").string() + "' --config '" +
                                      (dir / "in.yaml").string() + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("in.yaml:2:9: unknown unit 'dps' for 'gyro.unit'"));
}

TEST(CheckCli, BadFlagValuesAreUsageErrors) {
  const auto path = write_fixture("sim.csv", simulate_csv());
  const auto unit = test::run_imunoise("check '" + path + "' --gyro-unit dps");
  EXPECT_NE(unit.exit_code, 0);
  EXPECT_THAT(unit.err, HasSubstr("unknown value 'dps' (expected rad/s, deg/s, deg/h, rad, deg)"));
  const auto both = test::run_imunoise("check '" + path + "' --rate 100 --time-col 1");
  EXPECT_NE(both.exit_code, 0);
  EXPECT_THAT(both.err, HasSubstr("excludes"));
  const auto cols = test::run_imunoise("check '" + path + "' --gyro-cols 1,2,3,4");
  EXPECT_NE(cols.exit_code, 0);
  EXPECT_THAT(cols.err, HasSubstr("give 1 to 3 columns"));
}

TEST(CheckCli, HelpShowsExamplesAndInputFlags) {
  const auto r = test::run_imunoise("check --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("Examples:"));
  EXPECT_THAT(r.out, HasSubstr("imunoise check rec.csv"));
  EXPECT_THAT(r.out, HasSubstr("--gyro-cols"));
  EXPECT_THAT(r.out, HasSubstr("--full-scale-accel"));
  EXPECT_THAT(r.out, HasSubstr("--drop-non-finite"));
}

}  // namespace
}  // namespace imunoise
