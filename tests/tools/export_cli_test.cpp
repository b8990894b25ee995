/// @file
/// @brief End-to-end tests of `imunoise export` (tools/cmd_export.cpp): stdout and -o output,
/// `--to all`, the gnss-ins-sim file and the GTSAM Python snippet executed by a real Python
/// interpreter (with stand-in modules), the GTSAM C++ snippet compiled, the YAML and JSON
/// files read back by PyYAML and Python's json, upper bounds for terms not identified (and
/// `--strict`), and clean failures (unknown format, options that do not apply, bad model
/// files) with no output.
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
  EXPECT_EQ(files, 18);
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

/// kModel as a 30-min recording gives it: K not identified, with an upper bound only.
std::string short_recording_model() {
  std::string m = kModel;
  m.replace(m.find("random_walk_rad_per_s_sqrt_s: {value: 6.80678e-6}"), 49,
            "random_walk_rad_per_s_sqrt_s: {value: 0, ci_high: 2e-5, identified: false}");
  m.replace(m.find("random_walk_m_per_s2_sqrt_s: {value: 1e-4}"), 42,
            "random_walk_m_per_s2_sqrt_s: {value: 0, ci_high: 3e-4, identified: false}");
  return m;
}

TEST(ExportCli, TermNotIdentifiedUsesItsUpperBoundUnlessStrict) {
  const auto dir = make_temp_dir("export-upper-bound");
  const auto model = write_model(dir, short_recording_model());
  // Kalibr used to refuse here; now the upper bound is written, named in the header and on
  // stderr, and the exit code is 0.
  auto r = run_imunoise("export " + model.string() + " --to kalibr");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(yaml_number(r.out, "gyroscope_random_walk"), 2e-5, 0.0);
  EXPECT_NEAR(yaml_number(r.out, "accelerometer_random_walk"), 3e-4, 0.0);
  EXPECT_NE(r.out.find("# upper bound: gyro_x random_walk (K) is not identified; its upper "
                       "bound 2.0e-05 rad/s^1.5 is used in its place"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.err.find("imunoise: warning: kalibr: upper bound: gyro_x random_walk (K)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("accel_x random_walk (K)"), std::string::npos) << r.err;
  // Every format yields a file.
  const auto out = dir / "all";
  r = run_imunoise("export " + model.string() + " --to all -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // --strict restores the refusal, naming the term and the axis; nothing is written.
  const auto file = dir / "kalibr.yaml";
  r = run_imunoise("export " + model.string() + " --to kalibr --strict -o " + file.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("kalibr: gyro_x random_walk (K) is not identified, and --strict refuses "
                       "to use its upper bound 2.0e-05 rad/s^1.5"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(file));
  // A format that does not carry K (KF-GINS: white noise + GM bias) is not refused.
  r = run_imunoise("export " + model.string() + " --to kf-gins --strict");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(ExportCli, PythonReadsTheYamlAndJsonFilesAndRunsTheGtsamSnippet) {
  if (std::system("python3 -c 'import yaml, json' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3 with PyYAML (python3-yaml) not installed";
  const auto dir = make_temp_dir("export-python-yaml");
  const auto model = write_model(dir, kModel);
  const auto out = dir / "configs";
  ASSERT_EQ(run_imunoise("export " + model.string() + " --to all -o " + out.string()).exit_code, 0);
  // Stand-ins record what the snippet passes (no gtsam or numpy needed).
  const auto stub = dir / "stub";
  std::filesystem::create_directories(stub);
  std::ofstream(stub / "numpy.py") << "def diag(v):\n    return ('diag', list(v))\n"
                                      "def eye(n):\n    return Eye()\n"
                                      "class Eye:\n    def __mul__(self, s):\n"
                                      "        return ('eye', s)\n";
  std::ofstream(stub / "gtsam.py")
      << "calls = {}\nclass _P:\n    def __getattr__(self, name):\n"
         "        return lambda v: calls.__setitem__(name, v)\n"
         "class PreintegrationCombinedParams:\n    @staticmethod\n"
         "    def MakeSharedU(g):\n        calls['g'] = g\n        return _P()\n";
  // Independent conversions of kModel (N_g 1.16355e-4, K_g 6.80678e-6 at 200 Hz, N_a
  // 1.471e-3, K_a 1e-4): densities for LIO-SAM, Basalt; squared for GTSAM; N^2*rate for
  // FAST-LIO; the header lines of Basalt an array of strings.
  const std::string script = R"(import json, sys, yaml
d = sys.argv[1]
def close(a, b):
    assert abs(a - b) <= 5e-6 * abs(b), (a, b)
lio = yaml.safe_load(open(d + '/lio_sam_params.yaml'))['lio_sam']
close(lio['imuGyrNoise'], 1.16355e-4); close(lio['imuAccBiasN'], 1e-4)
fl = yaml.safe_load(open(d + '/fast_lio_mapping.yaml'))['mapping']
close(fl['gyr_cov'], 1.16355e-4 ** 2 * 200); close(fl['b_acc_cov'], 1e-4 ** 2 * 200)
g = yaml.safe_load(open(d + '/gtsam_preintegration.yaml'))
close(g['gyroscopeCovariance'][1][1], 1.16355e-4 ** 2); assert g['gyroscopeCovariance'][0][1] == 0
close(g['biasOmegaCovariance'][2][2], 6.80678e-6 ** 2)
b = json.load(open(d + '/basalt_imu_calib.json'))
assert list(b)[0] == 'value0'
close(b['value0']['accel_noise_std'][2], 1.471e-3); close(b['value0']['imu_update_rate'], 200)
assert all(isinstance(l, str) for l in b['imunoise_header'])
for f in ('kalibr_imu.yaml', 'kf-gins_imunoise.yaml', 'robot_localization_ekf.yaml'):
    yaml.safe_load(open(d + '/' + f))
lines = open(d + '/gtsam_preintegration.yaml').read().split('\n')
py = lines[lines.index('# Python (gtsam): the same numbers') + 1:]
exec('\n'.join(l[2:] for l in py if l.startswith('# ')))
import gtsam
c = gtsam.calls
close(c['g'], 9.80665)
assert c['setGyroscopeCovariance'][0] == 'diag'
close(c['setGyroscopeCovariance'][1][0], 1.16355e-4 ** 2)
close(c['setBiasAccCovariance'][1][2], 1e-4 ** 2)
assert c['setIntegrationCovariance'] == ('eye', 1e-8)
print('python read every file')
)";
  std::ofstream(dir / "check.py") << script;
  const std::string command = "cd " + dir.string() + " && PYTHONPATH=" + stub.string() +
                              " python3 check.py " + out.string() + " > py.txt 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(dir / "py.txt");
  EXPECT_NE(read_text(dir / "py.txt").find("python read every file"), std::string::npos);
}

TEST(ExportCli, GtsamCppSnippetCompiles) {
  if (std::system("command -v c++ >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "no C++ compiler to compile the GTSAM snippet";
  const auto dir = make_temp_dir("export-gtsam-cpp");
  const auto model = write_model(dir, kModel);
  const auto r = run_imunoise("export " + model.string() + " --to gtsam");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // A stand-in for GTSAM's header with the members and factories the snippet uses.
  std::filesystem::create_directories(dir / "gtsam" / "navigation");
  std::ofstream(dir / "gtsam" / "navigation" / "CombinedImuFactor.h")
      << "#include <array>\n#include <memory>\nnamespace gtsam {\n"
         "struct Matrix3 { std::array<double, 9> m{}; };\n"
         "inline Matrix3 operator*(Matrix3 a, double s) { for (auto& x : a.m) x *= s; return a; }\n"
         "inline const Matrix3 I_3x3{{1, 0, 0, 0, 1, 0, 0, 0, 1}};\n"
         "struct Vector3 { double x, y, z; Vector3(double a, double b, double c) : x(a), y(b), "
         "z(c) {}\n  Matrix3 asDiagonal() const { Matrix3 r; r.m[0] = x; r.m[4] = y; r.m[8] = z; "
         "return r; } };\n"
         "struct PreintegrationCombinedParams { double g = 0; Matrix3 accelerometerCovariance, "
         "gyroscopeCovariance, integrationCovariance, biasAccCovariance, biasOmegaCovariance;\n"
         "  static std::shared_ptr<PreintegrationCombinedParams> MakeSharedU(double g) {\n"
         "    auto p = std::make_shared<PreintegrationCombinedParams>(); p->g = g; return p; } };\n"
         "}\n";
  // The snippet's lines, uncommented, inside main().
  std::istringstream lines(r.out);
  std::string line, include, body;
  bool in_cpp = false;
  while (std::getline(lines, line)) {
    if (line.rfind("# C++ (GTSAM", 0) == 0) {
      in_cpp = true;
      continue;
    }
    if (!in_cpp) continue;
    if (line.rfind("# ", 0) != 0) break;
    (line.rfind("# #include", 0) == 0 ? include : body) += line.substr(2) + "\n";
  }
  ASSERT_FALSE(include.empty());
  std::ofstream(dir / "main.cpp")
      << "#include <cstdio>\n"
      << include << "int main() {\n"
      << body
      << "  std::printf(\"%.6g %.6g %.6g %.6g\\n\", p->g, p->gyroscopeCovariance.m[4], "
         "p->biasAccCovariance.m[8], p->integrationCovariance.m[0]);\n}\n";
  const std::string command = "cd " + dir.string() +
                              " && c++ -std=c++17 -I. main.cpp -o snippet > cc.txt 2>&1 && "
                              "./snippet > run.txt 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(dir / "cc.txt");
  // N_g^2 = (1.16355e-4)^2, K_a^2 = (1e-4)^2.
  EXPECT_EQ(read_text(dir / "run.txt"), "9.80665 1.35385e-08 1e-08 1e-08\n");
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
