/// @file
/// @brief End-to-end tests of `imunoise simulate` (tools/cmd_simulate.cpp): columns, rows,
/// reproducibility, unit conversion of the flags, and clean failures with no output file.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "test_support.h"

namespace imunoise::test {
namespace {

constexpr const char* kColumns =
    "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,accel_x_m_per_s2,"
    "accel_y_m_per_s2,accel_z_m_per_s2";

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A parsed simulate output: '#' comment lines, the column line, numeric rows.
struct Csv {
  std::vector<std::string> comments;
  std::string columns;
  std::vector<std::vector<double>> rows;
};

Csv read_csv(const std::filesystem::path& path) {
  Csv csv;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.starts_with("#")) {
      EXPECT_TRUE(csv.columns.empty()) << "comment after the column line";
      csv.comments.push_back(line);
    } else if (csv.columns.empty()) {
      csv.columns = line;
    } else {
      std::vector<double> row;
      const char* p = line.data();
      const char* end = line.data() + line.size();
      while (p <= end) {
        double value = 0.0;
        const auto [next, ec] = std::from_chars(p, end, value);
        EXPECT_EQ(ec, std::errc()) << "bad number in: " << line;
        row.push_back(value);
        p = next + 1;  // skip ','
        if (next == end) break;
      }
      csv.rows.push_back(row);
    }
  }
  return csv;
}

std::string demo_model() { return std::string(IMUNOISE_SOURCE_DIR) + "/configs/demo_imu.yaml"; }

TEST(SimulateCli, DemoModelWritesExpectedColumnsAndRows) {
  const auto dir = make_temp_dir("simulate-demo");
  const auto out = dir / "rec.csv";
  const CommandResult r =
      run_imunoise("simulate '" + demo_model() + "' --duration 10s --rate 100 --seed 3 -o '" +
                   out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Csv csv = read_csv(out);
  EXPECT_EQ(csv.columns, kColumns);
  ASSERT_EQ(csv.rows.size(), 1000U);
  bool has_seed = false;
  bool has_model = false;
  for (const std::string& c : csv.comments) {
    has_seed = has_seed || c == "# seed: 3";
    has_model = has_model || c.find("demo_imu.yaml") != std::string::npos;
  }
  EXPECT_TRUE(has_seed);
  EXPECT_TRUE(has_model);
  double accel_z_sum = 0.0;
  for (std::size_t k = 0; k < csv.rows.size(); ++k) {
    ASSERT_EQ(csv.rows[k].size(), 7U) << "row " << k;
    EXPECT_DOUBLE_EQ(csv.rows[k][0], static_cast<double>(k) / 100.0);
    accel_z_sum += csv.rows[k][6];
  }
  // Level FRD: −g₀ + 0.08 m/s² bias; the noise over 10 s is ≪ 0.01 m/s².
  EXPECT_NEAR(accel_z_sum / 1000.0, -9.80665 + 0.08, 0.01);
}

TEST(SimulateCli, SameSeedGivesIdenticalFilesAndOtherSeedDiffers) {
  const auto dir = make_temp_dir("simulate-seed");
  const auto run = [&](const std::string& name, int seed) {
    const auto path = dir / name;
    const CommandResult r =
        run_imunoise("simulate '" + demo_model() + "' --duration 2s --rate 200 --seed " +
                     std::to_string(seed) + " -o '" + path.string() + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_text(path);
  };
  const std::string a = run("a.csv", 5);
  const std::string b = run("b.csv", 5);
  const std::string c = run("c.csv", 6);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(SimulateCli, ArwFlagIsConvertedFromDegPerSqrtHour) {
  // N = 0.4 deg/√h = 1.16355e-4 rad/√s (theory.md §8.2); at 50 Hz σ_d = N·√50. Sample σ of
  // n = 3000 normals has relative standard error 1/√(2n) = 1.3 %; accept 5 × that.
  const auto dir = make_temp_dir("simulate-flags");
  const auto out = dir / "rec.csv";
  const CommandResult r = run_imunoise(
      "simulate --duration 1min --rate 50 --seed 9 --gyro-arw-deg-per-sqrt-h 0.4 "
      "--specific-force-m-per-s2 0,0,-9.80665 -o '" +
      out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Csv csv = read_csv(out);
  ASSERT_EQ(csv.rows.size(), 3000U);
  const double n = static_cast<double>(csv.rows.size());
  for (int column = 1; column <= 3; ++column) {
    double sum_sq = 0.0;
    for (const auto& row : csv.rows) sum_sq += row[column] * row[column];
    const double sigma = std::sqrt(sum_sq / n);
    EXPECT_NEAR(sigma / (1.16355e-4 * std::sqrt(50.0)), 1.0, 5.0 / std::sqrt(2.0 * n));
  }
  for (const auto& row : csv.rows) {
    EXPECT_EQ(row[4], 0.0);
    EXPECT_EQ(row[6], -9.80665);
  }
}

TEST(SimulateCli, DurationUnits) {
  const auto dir = make_temp_dir("simulate-duration");
  const struct {
    const char* duration;
    std::size_t rows;
  } cases[] = {{"0.02h", 72}, {"1.5min", 90}, {"30s", 30}, {"12", 12}};
  for (const auto& c : cases) {
    const auto out = dir / (std::string("d") + std::to_string(c.rows) + ".csv");
    const CommandResult r = run_imunoise("simulate --duration " + std::string(c.duration) +
                                         " --rate 1 -o '" + out.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << c.duration << ": " << r.err;
    EXPECT_EQ(read_csv(out).rows.size(), c.rows) << c.duration;
  }
}

/// Runs ARGS expecting failure: non-zero exit, stderr containing every FRAGMENT, no OUT file.
void expect_failure(const std::string& args, const std::filesystem::path& out,
                    const std::vector<std::string>& fragments) {
  const CommandResult r = run_imunoise(args + " -o '" + out.string() + "'");
  EXPECT_NE(r.exit_code, 0) << args;
  for (const std::string& fragment : fragments) {
    EXPECT_NE(r.err.find(fragment), std::string::npos)
        << "stderr lacks '" << fragment << "': " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out)) << args;
  // No temporary file left behind either.
  for (const auto& entry : std::filesystem::directory_iterator(out.parent_path())) {
    EXPECT_EQ(entry.path().filename().string().find("rec.csv"), std::string::npos) << entry.path();
  }
}

TEST(SimulateCli, BadFlagsFailWithoutOutput) {
  const auto dir = make_temp_dir("simulate-bad-flags");
  const auto out = dir / "rec.csv";
  expect_failure("simulate --duration 2hours --rate 100", out, {"--duration", "2hours"});
  expect_failure("simulate --duration=-5s --rate 100", out, {"--duration"});
  expect_failure("simulate --duration 10s", out, {"--rate"});
  expect_failure("simulate --duration 10s --rate 100 --gyro-arw-deg-per-sqrt-h -1", out,
                 {"--gyro-arw-deg-per-sqrt-h"});
  expect_failure("simulate --duration 10s --rate 100 --specific-force-m-per-s2 0,0", out,
                 {"--specific-force-m-per-s2"});
  expect_failure("simulate '" + (dir / "missing.yaml").string() + "' --duration 10s --rate 100",
                 out, {"missing.yaml"});
}

TEST(SimulateCli, BadModelFilesFailNamingFileLineAndKey) {
  const auto dir = make_temp_dir("simulate-bad-yaml");
  const auto out = dir / "rec.csv";
  struct Case {
    const char* yaml;
    std::vector<std::string> fragments;
  };
  const Case cases[] = {
      {"gyro:\n  arw_deg_per_sqrt_hr: 0.4\n",  // arw_deg_per_sqrt_h is a valid key
       {"bad.yaml:2:3", "gyro.arw_deg_per_sqrt_hr", "unknown key", "arw_rad_per_sqrt_s"}},
      {"gyro:\n  x:\n    arw_rad_per_sqrt_s: -1e-4\n",
       {"bad.yaml:3", "gyro.x.arw_rad_per_sqrt_s", ">= 0"}},
      {"accel:\n  vrw_m_per_s_sqrt_s: abc\n", {"accel.vrw_m_per_s_sqrt_s", "'abc'"}},
      {"gyro:\n  gauss_markov: [{sigma_rad_per_s: 1e-4}]\n", {"gyro.gauss_markov[0]", "tau_c_s"}},
      {"gyro:\n  gauss_markov: [{sigma_rad_per_s: 1e-4, tau_c_s: 0}]\n",
       {"gyro.gauss_markov[0].tau_c_s", "> 0"}},
      {"magnetometer: {}\n", {"magnetometer", "unknown key"}},
      {"gyro: [1, 2\n", {"bad.yaml", "YAML syntax"}},
  };
  for (const Case& c : cases) {
    const auto model = dir / "bad.yaml";
    write_text(model, c.yaml);
    expect_failure("simulate '" + model.string() + "' --duration 10s --rate 100", out, c.fragments);
  }
}

TEST(SimulateCli, HelpShowsAnExample) {
  const CommandResult r = run_imunoise("simulate --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("imunoise simulate configs/demo_imu.yaml"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--gyro-arw-deg-per-sqrt-h"), std::string::npos);
}

}  // namespace
}  // namespace imunoise::test
