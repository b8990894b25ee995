// Process-level tests of the CSV dialects (io/imu_header_mapping.cpp, docs/csv-dialects.md) and
// the exact rates (issue 22 items 2 and 5): the same samples written as imunoise's native CSV
// and as EuRoC, Kalibr, `rostopic echo -p`, a ROS 2 bag-to-CSV table (header.stamp.sec +
// nanosec), a semicolon + decimal-comma table and a single-axis file analyse with no mapping flag
// to the same model (coefficients equal to 1e-12 relative); the rate of integer-ns stamps and of
// a binary recording prints exactly.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/noise_model_yaml.h"
#include "models/noise_model.h"
#include "test_support.h"

namespace imunoise::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr std::int64_t kFirstStampNs = 1403636579758555392;  // EuRoC MH_01's first IMU stamp
constexpr std::int64_t kPeriodNs = 5000000;                  // 200 Hz
const std::string kAnalysisFlags = " -q --bootstrap 4 --seed 9";

/// The sample rows of simulate's CSV: the time text and the six value texts, as written.
struct Rows {
  std::vector<std::string> time;
  std::vector<std::vector<std::string>> values;  // gyro x y z (rad/s), accel x y z (m/s²)
};

Rows rows_of(const fs::path& csv) {
  Rows rows;
  std::ifstream in(csv);
  bool header = true;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line.front() == '#') continue;
    if (header) {  // time_s,gyro_x_rad_per_s,…
      header = false;
      continue;
    }
    std::vector<std::string> fields;
    std::stringstream split(line);
    for (std::string f; std::getline(split, f, ',');) fields.push_back(f);
    rows.time.push_back(fields[0]);
    rows.values.emplace_back(fields.begin() + 1, fields.end());
  }
  return rows;
}

std::string stamp(std::size_t k) {
  return std::to_string(kFirstStampNs + static_cast<std::int64_t>(k) * kPeriodNs);
}

std::string joined(const std::vector<std::string>& v, std::size_t from, std::size_t to) {
  std::string out;
  for (std::size_t i = from; i < to; ++i) {
    if (i > from) out += ',';
    out += v[i];
  }
  return out;
}

/// ROWS with integer ns stamps in one of the layouts below.
std::string written(const Rows& rows, const std::string& dialect) {
  std::string text;
  const auto zeros = [](int n) {
    std::string z;
    for (int i = 0; i < n; ++i) z += ",0";
    return z;
  };
  if (dialect == "native") {
    text =
        "time_ns,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,accel_x_m_per_s2,"
        "accel_y_m_per_s2,accel_z_m_per_s2\n";
  } else if (dialect == "euroc") {  // EuRoC MAV / TUM-VI mav0/imu0/data.csv
    text =
        "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
        "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  } else if (dialect == "kalibr") {  // Kalibr wiki, "Bag format": imu0.csv
    text = "timestamp,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z\n";
  } else if (dialect == "rostopic") {  // rostopic echo -p of sensor_msgs/Imu
    text =
        "%time,field.header.seq,field.header.stamp,field.header.frame_id,field.orientation.x,"
        "field.orientation.y,field.orientation.z,field.orientation.w";
    for (int i = 0; i < 9; ++i) text += ",field.orientation_covariance" + std::to_string(i);
    text += ",field.angular_velocity.x,field.angular_velocity.y,field.angular_velocity.z";
    for (int i = 0; i < 9; ++i) text += ",field.angular_velocity_covariance" + std::to_string(i);
    text +=
        ",field.linear_acceleration.x,field.linear_acceleration.y,"
        "field.linear_acceleration.z";
    for (int i = 0; i < 9; ++i) {
      text += ",field.linear_acceleration_covariance" + std::to_string(i);
    }
    text += "\n";
  } else if (dialect == "ros2") {  // rosbag2 to CSV (bag time, then the message's fields)
    text =
        "bag_time_ns,header.stamp.sec,header.stamp.nanosec,header.frame_id,"
        "angular_velocity.x,angular_velocity.y,angular_velocity.z,linear_acceleration.x,"
        "linear_acceleration.y,linear_acceleration.z\n";
  }
  for (std::size_t k = 0; k < rows.time.size(); ++k) {
    const std::vector<std::string>& v = rows.values[k];
    const std::string t = stamp(k);
    if (dialect == "rostopic") {
      // Receive time 0.3 ms after the stamp with its own jitter: header.stamp must win.
      const std::string received =
          std::to_string(kFirstStampNs + static_cast<std::int64_t>(k) * kPeriodNs + 300000 +
                         static_cast<std::int64_t>(k % 7) * 1000);
      text += received + "," + std::to_string(k) + "," + t + ",imu4,0,0,0,1" + zeros(9) + "," +
              joined(v, 0, 3) + zeros(9) + "," + joined(v, 3, 6) + zeros(9) + "\n";
    } else if (dialect == "ros2") {
      const std::int64_t ns = kFirstStampNs + static_cast<std::int64_t>(k) * kPeriodNs;
      text += std::to_string(ns + 70000) + "," + std::to_string(ns / 1000000000) + "," +
              std::to_string(ns % 1000000000) + ",imu_link," + joined(v, 0, 6) + "\n";
    } else {
      text += t + "," + joined(v, 0, 6) + "\n";
    }
  }
  return text;
}

/// The coefficients of every axis of the model.yaml in DIR, each with its axis and term.
struct Coefficient {
  std::string axis;
  std::size_t term;
  double value, ci_low, ci_high;
};

std::vector<Coefficient> coefficients(const fs::path& dir) {
  const models::NoiseModel model = io::load_model_yaml((dir / "model.yaml").string());
  std::vector<Coefficient> out;
  for (const models::AxisModel& a : model.axes) {
    for (std::size_t t = 0; t < a.terms.size(); ++t) {
      out.push_back({a.name, t, a.terms[t].value, a.terms[t].ci_low, a.terms[t].ci_high});
    }
  }
  return out;
}

void expect_same_coefficients(const std::vector<Coefficient>& got,
                              const std::vector<Coefficient>& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  std::size_t nonzero = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].axis, want[i].axis) << what;
    for (const auto& [g, w] :
         {std::pair{got[i].value, want[i].value}, std::pair{got[i].ci_low, want[i].ci_low},
          std::pair{got[i].ci_high, want[i].ci_high}}) {
      EXPECT_LE(std::fabs(g - w), 1e-12 * std::fabs(w))
          << what << ": " << got[i].axis << " term " << got[i].term << ": " << g << " vs " << w;
      nonzero += w != 0.0;
    }
  }
  EXPECT_GT(nonzero, got.size());  // the comparison is not of zeros
}

/// simulate's 60 s at 200 Hz of the reference IMU (rec.csv), the same rows with integer ns
/// stamps in each layout, and the analysis of the native ones.
class CsvDialectsCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(make_temp_dir("csv_dialects_cli"));
    const std::string model =
        quoted_for_shell(fs::path(IMUNOISE_SOURCE_DIR) / "configs/reference-imu.yaml");
    const auto r = run_imunoise("simulate " + model + " --duration 60s --rate 200 --seed 5 -o " +
                                quoted_for_shell(*dir_ / "rec.csv"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    rows_ = new Rows(rows_of(*dir_ / "rec.csv"));
    ASSERT_EQ(rows_->time.size(), 12000U);
    for (const char* d : {"native", "euroc", "kalibr", "rostopic", "ros2"}) {
      write_text(*dir_ / (std::string(d) + ".csv"), written(*rows_, d));
    }
    for (const char* input : {"native.csv", "rec.csv"}) {
      const auto a = run_imunoise("analyze " + quoted_for_shell(*dir_ / input) + kAnalysisFlags +
                                  " -o " + quoted_for_shell(*dir_ / (std::string("a_") + input)));
      ASSERT_EQ(a.exit_code, 0) << a.err;
    }
  }
  static void TearDownTestSuite() {
    delete rows_;
    delete dir_;
  }
  static const fs::path& dir() { return *dir_; }
  static const Rows& rows() { return *rows_; }

  /// Analyses INPUT (in dir()) with FLAGS into a_INPUT; its coefficients.
  static std::vector<Coefficient> analysed(const std::string& input,
                                           const std::string& flags = "") {
    const auto r = run_imunoise("analyze " + quoted_for_shell(dir() / input) + kAnalysisFlags +
                                flags + " -o " + quoted_for_shell(dir() / ("a_" + input)));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return coefficients(dir() / ("a_" + input));
  }

 private:
  static inline fs::path* dir_ = nullptr;
  static inline Rows* rows_ = nullptr;
};

TEST_F(CsvDialectsCli, RobotDatasetLayoutsAnalyseWithoutMappingFlagsToTheNativeModel) {
  const std::vector<Coefficient> native = coefficients(dir() / "a_native.csv");
  ASSERT_EQ(native.front().axis, "gyro_x");
  ASSERT_EQ(native.back().axis, "accel_z");
  for (const char* d : {"euroc", "kalibr", "rostopic", "ros2"}) {
    expect_same_coefficients(analysed(std::string(d) + ".csv"), native, d);
  }
}

TEST_F(CsvDialectsCli, IntegerNanosecondStampsPrintTheirRateExactly) {
  for (const char* d : {"euroc", "rostopic", "ros2"}) {
    const auto text = run_imunoise("check " + quoted_for_shell(dir() / (std::string(d) + ".csv")));
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_THAT(text.out, HasSubstr("\nrate:       200 Hz from the median interval 5 ms")) << d;
    const auto json =
        run_imunoise("check " + quoted_for_shell(dir() / (std::string(d) + ".csv")) + " --json");
    ASSERT_EQ(json.exit_code, 0) << json.err;
    EXPECT_THAT(json.out, HasSubstr("\"rate_hz\": 200.0,")) << d;
    EXPECT_THAT(json.out, HasSubstr("\"median_interval_s\": 0.005,")) << d;
  }
}

TEST_F(CsvDialectsCli, SemicolonAndDecimalCommaAnalyseToTheModelOfTheCommaFile) {
  // simulate's own rows (decimal seconds) with ';' and ',' for the point: the same numbers.
  std::string text =
      "time_s;gyro_x_rad_per_s;gyro_y_rad_per_s;gyro_z_rad_per_s;accel_x_m_per_s2;"
      "accel_y_m_per_s2;accel_z_m_per_s2\n";
  const auto comma = [](std::string s) {
    for (char& c : s) c = c == '.' ? ',' : c;
    return s;
  };
  for (std::size_t k = 0; k < rows().time.size(); ++k) {
    text += comma(rows().time[k]);
    for (const std::string& v : rows().values[k]) text.append(";").append(comma(v));
    text += "\n";
  }
  write_text(dir() / "decimal_comma.csv", text);
  expect_same_coefficients(analysed("decimal_comma.csv"), coefficients(dir() / "a_rec.csv"),
                           "decimal comma");
}

TEST_F(CsvDialectsCli, SingleAxisGyroFileAnalysesWithoutMappingFlags) {
  std::string text = "time_s,gyro_z [rad/s]\n";
  for (std::size_t k = 0; k < rows().time.size(); ++k) {
    text += rows().time[k] + "," + rows().values[k][2] + "\n";
  }
  write_text(dir() / "gyro_z.csv", text);
  const std::vector<Coefficient> got = analysed("gyro_z.csv");
  std::vector<Coefficient> want;
  for (const Coefficient& c : coefficients(dir() / "a_rec.csv")) {
    if (c.axis == "gyro_z") want.push_back(c);
  }
  expect_same_coefficients(got, want, "gyro_z only");

  // `time,gyro_z` names the columns but not their units: the error asks for the unit flags,
  // and with them (no column flag) it analyses to the same model.
  std::string bare = "time,gyro_z\n";
  for (std::size_t k = 0; k < rows().time.size(); ++k) {
    bare += rows().time[k] + "," + rows().values[k][2] + "\n";
  }
  write_text(dir() / "bare.csv", bare);
  const auto no_unit = run_imunoise("analyze " + quoted_for_shell(dir() / "bare.csv") + " -q -o " +
                                    quoted_for_shell(dir() / "a_bare_fails"));
  EXPECT_EQ(no_unit.exit_code, 2);
  EXPECT_THAT(no_unit.err, HasSubstr("bare.csv:1: 'time' (column 1) is the time stamp but the "
                                     "header states no unit: give --time-unit s|ms|us|ns"));
  const auto no_gyro_unit =
      run_imunoise("analyze " + quoted_for_shell(dir() / "bare.csv") + " -q --time-unit s -o " +
                   quoted_for_shell(dir() / "a_bare_fails"));
  EXPECT_EQ(no_gyro_unit.exit_code, 2);
  EXPECT_THAT(no_gyro_unit.err,
              HasSubstr("bare.csv:1: 'gyro_z' (column 2) is a gyro axis but the header states no "
                        "unit: give --gyro-unit rad/s|deg/s|deg/h|rad|deg"));
  expect_same_coefficients(analysed("bare.csv", " --time-unit s --gyro-unit rad/s"), want,
                           "time,gyro_z with unit flags");
}

TEST_F(CsvDialectsCli, AmbiguousOrUnknownHeadersListTheColumnsFound) {
  write_text(dir() / "two_imus.csv",
             "time_s,imu0/gyro_x [rad/s],imu1/gyro_x [rad/s]\n0,1,2\n0.01,1,2\n0.02,1,2\n");
  const auto two = run_imunoise("check " + quoted_for_shell(dir() / "two_imus.csv"));
  EXPECT_EQ(two.exit_code, 2);
  EXPECT_THAT(two.err, HasSubstr("two_imus.csv:1: two gyro sensors: 'imu0/gyro_x [rad/s]' "
                                 "(column 2) and 'imu1/gyro_x [rad/s]' (column 3); choose the "
                                 "columns with --gyro-cols (columns found: time_s, imu0/gyro_x "
                                 "[rad/s], imu1/gyro_x [rad/s])"));
  write_text(dir() / "unknown.csv", "stamp [ns],p,q,r\n0,1,2,3\n1000,1,2,3\n");
  const auto unknown = run_imunoise("check " + quoted_for_shell(dir() / "unknown.csv"));
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("unknown.csv:1: no gyro or accel columns"));
  EXPECT_THAT(unknown.err, HasSubstr("available columns: stamp [ns], p, q, r"));
}

TEST(ExactRateCli, BinaryRecordingReportsItsHeaderRate) {
  // Before: 400.0000000000796 Hz for this file (399.99999999126885 Hz for 2 h of it).
  const fs::path dir = make_temp_dir("exact_rate_cli");
  const std::string model =
      quoted_for_shell(fs::path(IMUNOISE_SOURCE_DIR) / "configs/reference-imu.yaml");
  const auto sim = run_imunoise("simulate " + model + " --duration 60s --rate 400 -q -o " +
                                quoted_for_shell(dir / "s.imnb"));
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto json = run_imunoise("check " + quoted_for_shell(dir / "s.imnb") + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_THAT(json.out, HasSubstr("\"rate_hz\": 400.0,"));
  EXPECT_THAT(json.out, HasSubstr("\"sample_period_s\": 0.0025,"));
  const auto text = run_imunoise("check " + quoted_for_shell(dir / "s.imnb"));
  EXPECT_THAT(text.out, HasSubstr("\nrate:       400 Hz from the median interval 2.5 ms"));
  const auto analyze = run_imunoise("analyze " + quoted_for_shell(dir / "s.imnb") +
                                    " -q --bootstrap 4 -o " + quoted_for_shell(dir / "a"));
  ASSERT_EQ(analyze.exit_code, 0) << analyze.err;
  EXPECT_THAT(read_file_bytes(dir / "a" / "model.yaml"), HasSubstr("\nsample_rate_hz: 400\n"));
}

}  // namespace
}  // namespace imunoise::test
