/// @file
/// @brief End-to-end tests of `imunoise export` (tools/cmd_export.cpp): stdout and -o output,
/// `--to all`, the gnss-ins-sim file executed by a real Python interpreter, and clean
/// failures (unknown format, options that do not apply, bad model files) with no output.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_support.h"

namespace imunoise::test {
namespace {

/// The shortest model.yaml the loader accepts (docs/model-yaml.md), theory.md §8 gyro values.
constexpr const char* kModel = R"(format: imunoise-noise-model
format_version: 1
sample_rate_hz: 200
axes:
  gyro_x:
    sensor: gyro
    quantization_rad: {value: 0}
    white_noise_rad_per_sqrt_s: {value: 1.16355e-4, ci_low: 1.1e-4, ci_high: 1.2e-4}
    bias_instability_rad_per_s: {value: 1.22173e-4}
    random_walk_rad_per_s_sqrt_s: {value: 6.80678e-6}
    ramp_rad_per_s2: {value: 0}
    fit: {tau_min_s: 0.005, tau_max_s: 3000, tau_of_min_adev_s: 29.6, note: ""}
  accel_x:
    sensor: accel
    quantization_m_per_s: {value: 0}
    white_noise_m_per_s_sqrt_s: {value: 1.471e-3}
    bias_instability_m_per_s2: {value: 4.9e-4}
    random_walk_m_per_s2_sqrt_s: {value: 1e-4}
    ramp_m_per_s3: {value: 0}
    fit: {tau_min_s: 0.005, tau_max_s: 3000, tau_of_min_adev_s: 20, note: ""}
)";

std::filesystem::path write_model(const std::filesystem::path& dir, const std::string& text) {
  const auto path = dir / "model.yaml";
  std::ofstream(path) << text;
  return path;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The number after "KEY: " at the start of a line (plain search: std::regex trips a GCC 12
/// false -Wmaybe-uninitialized in the sanitizer build).
double yaml_number(const std::string& text, const std::string& key) {
  const auto at = text.find("\n" + key + ": ");
  if (at == std::string::npos) {
    ADD_FAILURE() << "no key " << key;
    return 0.0;
  }
  return std::stod(text.substr(at + key.size() + 3));
}

TEST(ExportCli, KalibrToStdoutAndFile) {
  const auto dir = make_temp_dir("export-kalibr");
  const auto model = write_model(dir, kModel);
  const auto r = run_imunoise("export " + model.string() + " --to kalibr --rate 200");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(yaml_number(r.out, "gyroscope_noise_density"), 1.16355e-4, 1e-9);
  EXPECT_NEAR(yaml_number(r.out, "gyroscope_random_walk"), 6.80678e-6, 1e-11);
  EXPECT_NEAR(yaml_number(r.out, "update_rate"), 200.0, 0.0);
  EXPECT_NE(r.out.find("# command: imunoise export " + model.string() + " --to kalibr --rate 200"),
            std::string::npos);

  const auto out = dir / "imu.yaml";
  const auto w = run_imunoise("export " + model.string() + " --to kalibr -o " + out.string());
  ASSERT_EQ(w.exit_code, 0) << w.err;
  EXPECT_TRUE(w.out.empty());
  // Without --rate: the model's sample rate.
  EXPECT_NEAR(yaml_number(read_text(out), "update_rate"), 200.0, 0.0);
}

TEST(ExportCli, AllFormatsIntoADirectory) {
  const auto dir = make_temp_dir("export-all");
  const auto model = write_model(dir, kModel);
  const auto out = dir / "configs";
  const auto r = run_imunoise("export " + model.string() + " --to all -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    if (entry.path().filename() == "commands.txt") continue;  // the command, for reports
    EXPECT_GT(entry.file_size(), 200u) << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 11);
  // commands.txt: the directory, then the command that wrote it (shell-quoted).
  std::ifstream commands(out / "commands.txt");
  std::string cd, command;
  std::getline(commands, cd);
  std::getline(commands, command);
  EXPECT_EQ(cd.rfind("cd ", 0), 0u) << cd;
  EXPECT_EQ(command, "imunoise export " + model.string() + " --to all -o " + out.string());
}

TEST(ExportCli, GnssInsSimFileRunsInPython) {
  if (std::system("command -v python3 >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3 not installed: the gnss-ins-sim file cannot be executed here";
  const auto dir = make_temp_dir("export-python");
  const auto model = write_model(dir, kModel);
  const auto file = dir / "imu_err.py";
  ASSERT_EQ(
      run_imunoise("export " + model.string() + " --to gnss-ins-sim -o " + file.string()).exit_code,
      0);
  // numpy is not needed to check the dict: a stand-in module with array() = list().
  const auto stub = dir / "stub";
  std::filesystem::create_directories(stub);
  std::ofstream(stub / "numpy.py") << "def array(values):\n    return list(values)\n";
  const std::string script =
      "import runpy; d = runpy.run_path('" + file.string() +
      "')['imu_err']; print(sorted(d)); print(d['gyro_arw'][0], d['gyro_b_corr'][0])";
  const std::string command = "cd " + dir.string() + " && PYTHONPATH=" + stub.string() +
                              " python3 -c \"" + script + "\" > out.txt 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(dir / "out.txt");
  const auto out = read_text(dir / "out.txt");
  EXPECT_NE(out.find("['accel_b', 'accel_b_corr', 'accel_b_stability', 'accel_vrw', 'gyro_arw', "
                     "'gyro_b', 'gyro_b_corr', 'gyro_b_stability']"),
            std::string::npos)
      << out;
  // 1.16355e-4 rad/√s = 0.399999 deg/√h; T_c of (b) = 29.6/1.892618 = 15.6397 s.
  EXPECT_NE(out.find("0.399999 15.6397"), std::string::npos) << out;
}

TEST(ExportCli, CleanFailures) {
  const auto dir = make_temp_dir("export-fail");
  const auto model = write_model(dir, kModel);
  auto r = run_imunoise("export " + model.string() + " --to nosuch");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown format 'nosuch'; choose one of native, kalibr"), std::string::npos)
      << r.err;
  r = run_imunoise("export " + model.string() + " --to native --axis x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--axis does not apply to --to native"), std::string::npos) << r.err;
  r = run_imunoise("export " + model.string() + " --to all");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("needs -o DIR"), std::string::npos) << r.err;

  // A bad model: the error names file, line and key; an existing output is left untouched.
  std::string bad = kModel;
  bad.replace(bad.find("value: 1.22173e-4"), 17, "value: -1");
  const auto bad_model = dir / "bad.yaml";
  std::ofstream(bad_model) << bad;
  const auto out = dir / "keep.yaml";
  std::ofstream(out) << "previous content\n";
  r = run_imunoise("export " + bad_model.string() + " --to kalibr -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.yaml:9:41:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("axes.gyro_x.bias_instability_rad_per_s.value"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(out), "previous content\n");
}

}  // namespace
}  // namespace imunoise::test
