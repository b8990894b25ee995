// Tests of io/filter_export.h: every conversion against the hand-computed values of
// theory.md §8 (the worked example), the key sets of ../shared/docs/filter-formats.md, a real
// parser for each file (yaml-cpp for YAML; OpenCV's FileStorage — the parser OpenVINS, VINS,
// ORB-SLAM3 and OKVIS use — where it is installed), golden files, and the errors.
//
// Golden files: tests/io/golden/export_<format>.txt. After an intended change of the output,
// regenerate with IMUNOISE_UPDATE_GOLDEN=1 and review the diff by hand.
#include "io/filter_export.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "common/errors.h"
#include "common/units.h"
#include "io/filter_export_test_support.h"
#include "io/noise_model_yaml.h"
#include "test_support.h"

#ifdef IMUNOISE_HAVE_OPENCV
#include <opencv2/core/persistence.hpp>
#endif

namespace imunoise::io {
namespace {

using models::AxisModel;
using models::Estimate;
using models::NoiseModel;
using test::expect_throw_containing;
using test_fixture::estimate;
using test_fixture::request;
using test_fixture::worked_example;

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// Six significant digits with a decimal point, as the exports write numbers (1.36136e-05).
std::string detail_real(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

/// The number that follows MARKER in TEXT (std::stod stops at the first non-number
/// character); NaN and a test failure when MARKER is absent. Plain string search: std::regex
/// trips a GCC 12 -Wmaybe-uninitialized false positive in the sanitizer build.
double number_after(const std::string& text, const std::string& marker) {
  const auto at = text.find(marker);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no '" << marker << "' in the text";
    return NAN;
  }
  return std::stod(text.substr(at + marker.size()));
}

/// The value on the header conversion line "#   KEY = FORMULA = VALUE UNIT" (or "%   …").
double header_value(const std::string& text, const std::string& key) {
  for (const char* comment : {"#   ", "%   "}) {
    const auto at = text.find(comment + key + " = ");
    if (at == std::string::npos) continue;
    const auto end = text.find('\n', at);
    const auto line = text.substr(at, end - at);
    return std::stod(line.substr(line.rfind(" = ") + 3));
  }
  ADD_FAILURE() << "no conversion line for " << key;
  return NAN;
}

std::set<std::string> keys_of(const YAML::Node& map) {
  std::set<std::string> keys;
  for (const auto& kv : map) keys.insert(kv.first.as<std::string>());
  return keys;
}

TEST(FilterExport, KalibrKeysAndTheWorkedExampleDensities) {
  const auto text = export_config(worked_example(), request(ExportFormat::kalibr, 200.0));
  const auto yaml = YAML::Load(text);
  // filter-formats.md, Kalibr: the flat keys of imu.yaml.
  EXPECT_EQ(keys_of(yaml),
            (std::set<std::string>{"accelerometer_noise_density", "accelerometer_random_walk",
                                   "gyroscope_noise_density", "gyroscope_random_walk", "rostopic",
                                   "update_rate"}));
  // theory.md §8.2: gyroscope_noise_density 1.1636e-4, gyroscope_random_walk 6.807e-6.
  EXPECT_LT(rel(yaml["gyroscope_noise_density"].as<double>(), 1.1636e-4), 5e-5);
  EXPECT_LT(rel(yaml["gyroscope_random_walk"].as<double>(), 6.807e-6), 5e-5);
  EXPECT_LT(rel(yaml["accelerometer_noise_density"].as<double>(), 1.47100e-3), 1e-5);
  EXPECT_DOUBLE_EQ(yaml["update_rate"].as<double>(), 200.0);
  // §8.2 discrete sigmas at 200 Hz (printed for the user): 1.6455e-3 and 4.813e-7 rad/s.
  EXPECT_LT(rel(number_after(text, "sigma_d = N*sqrt(rate): gyro "), 1.6455e-3), 5e-5);
  EXPECT_LT(rel(number_after(text, "sigma_bd = K/sqrt(rate): gyro "), 4.813e-7), 1e-4);
  // Best estimates drop B and say so.
  EXPECT_NE(text.find("dropped: gyro B = 0.000122173 rad/s"), std::string::npos);
}

TEST(FilterExport, DiscreteSigmasAt100HzForPx4AndVins) {
  // theory.md §8.2 at 100 Hz: σ_gd = 1.1636e-3 rad/s; PX4 bias noise K·√100 = 6.807e-5.
  const auto px4 = export_config(worked_example(), request(ExportFormat::px4));
  EXPECT_LT(rel(number_after(px4, "\n1\t1\tEKF2_GYR_NOISE\t"), 1.1636e-3), 5e-5);
  EXPECT_LT(rel(number_after(px4, "\n1\t1\tEKF2_GYR_B_NOISE\t"), 6.807e-5), 5e-5);
  EXPECT_LT(rel(number_after(px4, "\n1\t1\tEKF2_ACC_NOISE\t"), 1.47100e-2), 1e-5);
  // The accel bias noise 1e-3 is inside PX4's range; EKF2_ACC_NOISE 0.0147 too: no warning.
  EXPECT_EQ(px4.find("WARNING"), std::string::npos);
  // QGC: exactly 5 tab-separated fields on every non-comment line.
  std::istringstream lines(px4);
  int params = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    EXPECT_EQ(std::count(line.begin(), line.end(), '\t'), 4) << line;
    ++params;
  }
  EXPECT_EQ(params, 4);

  const auto vins = YAML::Load(export_config(worked_example(), request(ExportFormat::vins, 200.0)));
  EXPECT_EQ(keys_of(vins), (std::set<std::string>{"acc_n", "gyr_n", "acc_w", "gyr_w", "g_norm"}));
  EXPECT_LT(rel(vins["gyr_n"].as<double>(), 1.6455e-3), 5e-5);
  EXPECT_LT(rel(vins["gyr_w"].as<double>(), 6.80678e-6 * std::sqrt(200.0)), 1e-5);
}

TEST(FilterExport, PositiveRangeWarningForPx4) {
  auto quiet = worked_example();
  for (auto& a : quiet.axes)
    if (a.kind == SensorKind::accel)
      a.terms[static_cast<int>(NoiseTerm::white_noise)] = estimate(1e-4, 1e-4, 1e-4);
  const auto px4 = export_config(quiet, request(ExportFormat::px4));
  EXPECT_NE(px4.find("WARNING: EKF2_ACC_NOISE = 0.001 is outside PX4's allowed range [0.01, 1.0]"),
            std::string::npos);
}

TEST(FilterExport, KfGinsUnitsAndGaussMarkovBias) {
  const auto text = export_config(worked_example(), request(ExportFormat::kf_gins));
  const auto yaml = YAML::Load(text);
  EXPECT_EQ(keys_of(yaml), std::set<std::string>{"imunoise"});
  EXPECT_EQ(keys_of(yaml["imunoise"]),
            (std::set<std::string>{"arw", "vrw", "gbstd", "abstd", "gsstd", "asstd", "corrtime"}));
  const auto n = yaml["imunoise"];
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(rel(n["arw"][i].as<double>(), 0.4), 1e-6);  // deg/√h
    // m/s/√h: 150 µg/√Hz · 60 = 0.0882399
    EXPECT_LT(rel(n["vrw"][i].as<double>(), 150e-6 * 9.80665 * 60.0), 1e-5);
    // §8.3 (b) σ = 1.314e-4 rad/s = 27.103 deg/h
    EXPECT_LT(rel(n["gbstd"][i].as<double>(), 1.314e-4 / (std::numbers::pi / 180.0 / 3600.0)),
              1e-5);
  }
  // accel: B 0.05 mg → (b) computed: σ = 1.075996·B = 5.2761e-4 m/s² = 52.761 mGal
  EXPECT_LT(rel(n["abstd"][0].as<double>(), 1.075996 * 0.05e-3 * 9.80665 / 1e-5), 1e-5);
  EXPECT_LT(rel(n["corrtime"].as<double>(), 15.6 / 3600.0), 1e-5);  // hours
  EXPECT_LT(rel(header_value(text, "gbstd[0]"), 27.1030), 1e-5);
}

TEST(FilterExport, YamlFormatsLoadAndCarryTheDocumentedKeys) {
  const auto m = worked_example();
  // OpenVINS: imu0 with the Kalibr keys and the intrinsics (filter-formats.md).
  const auto ov = YAML::Load(export_config(m, request(ExportFormat::openvins)));
  EXPECT_EQ(keys_of(ov["imu0"]),
            (std::set<std::string>{
                "T_i_b", "accelerometer_noise_density", "accelerometer_random_walk",
                "gyroscope_noise_density", "gyroscope_random_walk", "rostopic", "time_offset",
                "update_rate", "model", "Tw", "R_IMUtoGYRO", "Ta", "R_IMUtoACC", "Tg"}));
  EXPECT_EQ(ov["imu0"]["T_i_b"].size(), 4u);
  EXPECT_EQ(ov["imu0"]["Tg"][2][2].as<double>(), 0.0);
  const auto orb = YAML::Load(export_config(m, request(ExportFormat::orbslam3)));
  EXPECT_EQ(keys_of(orb), (std::set<std::string>{"IMU.NoiseGyro", "IMU.NoiseAcc", "IMU.GyroWalk",
                                                 "IMU.AccWalk", "IMU.Frequency"}));
  EXPECT_LT(rel(orb["IMU.NoiseGyro"].as<double>(), 1.1636e-4), 5e-5);
  const auto okvis = YAML::Load(export_config(m, request(ExportFormat::okvis)));
  EXPECT_EQ(
      keys_of(okvis["imu_params"]),
      (std::set<std::string>{"a_max", "g_max", "sigma_g_c", "sigma_a_c", "sigma_bg", "sigma_ba",
                             "sigma_gw_c", "sigma_aw_c", "tau", "g", "a0", "imu_rate", "T_BS"}));
  EXPECT_EQ(okvis["imu_params"]["T_BS"].size(), 16u);
  const auto rl = YAML::Load(export_config(m, request(ExportFormat::robot_localization)));
  const auto q = rl["ekf_filter_node"]["ros__parameters"]["process_noise_covariance"];
  ASSERT_EQ(q.size(), 225u);
  const double kg2 = std::pow(84.24 * units::kDegPerHourPerSqrtHour, 2);
  EXPECT_LT(rel(q[9 * 15 + 9].as<double>(), kg2), 1e-5);     // vroll
  EXPECT_LT(rel(q[14 * 15 + 14].as<double>(), 1e-8), 1e-5);  // az: K_a² = (1e-4)²
  EXPECT_EQ(q[0].as<double>(), 0.0);
  // Every entry a real (robot_localization declares a double array).
  for (const auto& v : q) EXPECT_NE(v.as<std::string>().find('.'), std::string::npos);
  // The native copy is the model itself.
  const auto native = export_config(m, request(ExportFormat::native));
  EXPECT_EQ(native, format_model_yaml(m));
  EXPECT_EQ(format_model_yaml(parse_model_yaml(native, "native")), native);
}

TEST(FilterExport, ScriptFormatsCarryTheirKeys) {
  const auto m = worked_example();
  const auto py = export_config(m, request(ExportFormat::gnss_ins_sim));
  for (const char* key : {"gyro_b", "gyro_arw", "gyro_b_stability", "gyro_b_corr", "accel_b",
                          "accel_vrw", "accel_b_stability", "accel_b_corr"})
    EXPECT_NE(py.find("    '" + std::string(key) + "': np.array(["), std::string::npos) << key;
  EXPECT_NE(py.find("'gyro_arw': np.array([0.4, 0.4, 0.4])"), std::string::npos);
  EXPECT_NE(py.find("'gyro_b_corr': np.array([15.6, 15.6, 15.6])"), std::string::npos);
  const auto mat = export_config(m, request(ExportFormat::matlab));
  EXPECT_NE(mat.find("gyro = gyroparams( ..."), std::string::npos);
  EXPECT_NE(mat.find("accel = accelparams( ..."), std::string::npos);
  EXPECT_LT(rel(header_value(mat, "gyro.BiasInstability(1)"), 1.22173e-4), 1e-5);
  EXPECT_LT(rel(header_value(mat, "gyro.RandomWalk(3)"), 6.80678e-6), 1e-5);
  // MATLAB comments start with %, and nothing else in the file uses #.
  EXPECT_EQ(mat.find('#'), std::string::npos);
}

TEST(FilterExport, HeaderNamesSourceRulesAndConversions) {
  const auto text = export_config(worked_example(), request(ExportFormat::orbslam3));
  EXPECT_EQ(text.rfind("%YAML:1.0\n", 0), 0u);  // OpenCV needs it as the very first line
  EXPECT_NE(text.find("# model: worked-example.yaml"), std::string::npos);
  EXPECT_NE(text.find("# command: imunoise export worked-example.yaml --to orbslam3"),
            std::string::npos);
  EXPECT_NE(text.find("values: best estimates"), std::string::npos);
  EXPECT_LT(rel(header_value(text, "IMU.GyroWalk"), 6.80678e-6), 1e-5);
}

TEST(FilterExport, ConservativeWritesTheFoldedOverbound) {
  const auto m = worked_example();
  auto r = request(ExportFormat::kalibr, 200.0, true);
  const auto yaml = YAML::Load(export_config(m, r));
  // Hand computation: N_up = 1.02 N, B_up = 1.1 B, K_up = 1.4 K, Q_up = 0.1 N (τ0 = 1/200),
  // T = τ of the ADEV minimum = 29.6 s.
  const double n = 1.02 * 0.4 * units::kDegPerSqrtHour;
  const double b = 1.1 * 25.2 * units::kDegPerHour;
  const double k = 1.4 * 84.24 * units::kDegPerHourPerSqrtHour;
  const double q = 0.1 * 0.4 * units::kDegPerSqrtHour;
  const double floor = 2.0 * std::numbers::ln2 / std::numbers::pi * b * b;
  const double n2 = n * n + floor * 29.6 + 3.0 * q * q * 200.0;
  const double k2 = k * k + 3.0 * floor / 29.6;
  EXPECT_LT(rel(yaml["gyroscope_noise_density"].as<double>(), std::sqrt(n2)), 1e-5);
  EXPECT_LT(rel(yaml["gyroscope_random_walk"].as<double>(), std::sqrt(k2)), 1e-5);
  const auto text = export_config(m, r);
  EXPECT_NE(text.find("values: conservative"), std::string::npos);
  EXPECT_NE(text.find("N'^2 = N^2 + (2 ln2/pi) B^2 T"), std::string::npos);
  // native refuses it: a copy cannot be conservative.
  expect_throw_containing<InputError>(
      [&] { export_config(m, request(ExportFormat::native, 0.0, true)); }, "--conservative");
}

TEST(FilterExport, ErrorsNameWhatIsMissing) {
  auto m = worked_example();
  // No value and no upper bound: Kalibr rejects a zero random walk, so the export refuses.
  for (auto& a : m.axes)
    a.terms[static_cast<int>(NoiseTerm::random_walk)] = estimate(0.0, 0.0, 0.0);
  expect_throw_containing<InputError>(
      [&] { export_config(m, request(ExportFormat::kalibr)); },
      "kalibr: gyro_x random_walk (K) is not identified and the model has no upper bound for it");
  // VINS accepts 0: it is written, and the header says so.
  EXPECT_NE(export_config(m, request(ExportFormat::vins))
                .find("# not identified: gyro_x random_walk (K) has neither a value nor an upper "
                      "bound in the model: 0 is written"),
            std::string::npos);
  auto gyro_only = worked_example();
  gyro_only.axes.resize(3);
  expect_throw_containing<InputError>(
      [&] { export_config(gyro_only, request(ExportFormat::openvins)); }, "no accel axes");
  // MATLAB works with one sensor.
  EXPECT_NO_THROW(export_config(gyro_only, request(ExportFormat::matlab)));
  auto r = request(ExportFormat::vins);
  r.rate_hz = -5.0;
  EXPECT_THROW(export_config(worked_example(), r), InputError);
}

/// The worked example as a 30-min recording would give it: N and B identified, K not (its
/// upper bound 2 K in the model, as ci_high).
NoiseModel short_recording() {
  auto m = worked_example();
  for (auto& a : m.axes) {
    auto& k = a.terms[static_cast<int>(NoiseTerm::random_walk)];
    k = estimate(0.0, 0.0, 2.0 * k.value);
  }
  return m;
}

TEST(FilterExport, TermNotIdentifiedTakesItsUpperBoundByDefault) {
  const auto m = short_recording();
  const double k_g_bound = 2.0 * 84.24 * units::kDegPerHourPerSqrtHour;
  // Every format yields a file; each one carrying K names the upper bound in its header and
  // returns one warning per axis (three gyro, three accel: worst of the three).
  for (auto format : all_export_formats()) {
    if (format == ExportFormat::native) continue;
    const auto out = export_file(m, request(format));
    const auto carries_k = format != ExportFormat::kf_gins &&
                           format != ExportFormat::gnss_ins_sim &&
                           format != ExportFormat::imu_utils;
    const std::string line =
        "upper bound: gyro_x random_walk (K) is not identified; its upper "
        "bound " +
        detail_real(k_g_bound) + " rad/s^1.5 is used in its place";
    EXPECT_EQ(out.text.find(line) != std::string::npos, carries_k) << export_format_name(format);
    EXPECT_EQ(out.warnings.size(), carries_k ? 6u : 0u) << export_format_name(format);
  }
  // Kalibr, which used to refuse, now writes the upper bound.
  const auto yaml = YAML::Load(export_config(m, request(ExportFormat::kalibr)));
  EXPECT_LT(rel(yaml["gyroscope_random_walk"].as<double>(), k_g_bound), 1e-5);
  EXPECT_LT(rel(yaml["accelerometer_random_walk"].as<double>(), 2e-4), 1e-5);
  // --strict restores the refusal, naming format, term and axis.
  auto strict = request(ExportFormat::kalibr);
  strict.strict = true;
  expect_throw_containing<InputError>(
      [&] { export_config(m, strict); },
      "kalibr: gyro_x random_walk (K) is not identified, and --strict refuses to use its upper "
      "bound 1.36136e-05 rad/s^1.5");
  // A format that does not carry K is not refused.
  strict.format = ExportFormat::kf_gins;
  EXPECT_NO_THROW(export_config(m, strict));
}

#ifdef IMUNOISE_HAVE_OPENCV
/// Reads TEXT the way the filters do: cv::FileStorage in memory.
cv::FileStorage open_like_the_filters(const std::string& text) {
  return cv::FileStorage(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
}

TEST(FilterExportOpenCv, FileStorageReadsOpenVinsVinsOrbSlam3AndOkvis) {
  const auto m = worked_example();
  {  // OpenVINS: node[name][r][c] for matrices, reals for the densities.
    auto fs = open_like_the_filters(export_config(m, request(ExportFormat::openvins)));
    ASSERT_TRUE(fs.isOpened());
    const auto imu = fs["imu0"];
    EXPECT_TRUE(imu["gyroscope_noise_density"].isReal());
    EXPECT_LT(rel(static_cast<double>(imu["gyroscope_noise_density"]), 1.1636e-4), 5e-5);
    EXPECT_EQ(static_cast<double>(imu["T_i_b"][3][3]), 1.0);
    EXPECT_EQ(static_cast<std::string>(imu["model"]), "kalibr");
  }
  {  // VINS: the five keys, as doubles.
    auto fs = open_like_the_filters(export_config(m, request(ExportFormat::vins, 200.0)));
    ASSERT_TRUE(fs.isOpened());
    for (const char* key : {"acc_n", "gyr_n", "acc_w", "gyr_w", "g_norm"})
      EXPECT_TRUE(fs[key].isReal()) << key;
    EXPECT_LT(rel(static_cast<double>(fs["gyr_n"]), 1.6455e-3), 5e-5);
  }
  {  // ORB-SLAM3 v1.0 settings: readParameter<float> requires REAL nodes.
    auto fs = open_like_the_filters(export_config(m, request(ExportFormat::orbslam3)));
    ASSERT_TRUE(fs.isOpened());
    for (const char* key :
         {"IMU.NoiseGyro", "IMU.NoiseAcc", "IMU.GyroWalk", "IMU.AccWalk", "IMU.Frequency"})
      EXPECT_TRUE(fs[key].isReal()) << key;
  }
  {  // OKVIS: VioParametersReader asserts isReal() on the sigmas and an integer imu_rate.
    auto fs = open_like_the_filters(export_config(m, request(ExportFormat::okvis)));
    ASSERT_TRUE(fs.isOpened());
    const auto imu = fs["imu_params"];
    for (const char* key : {"a_max", "g_max", "sigma_g_c", "sigma_a_c", "sigma_bg", "sigma_ba",
                            "sigma_gw_c", "sigma_aw_c", "tau", "g"})
      EXPECT_TRUE(imu[key].isReal()) << key;
    EXPECT_TRUE(imu["imu_rate"].isInt());
    EXPECT_TRUE(imu["a0"].isSeq());
    EXPECT_EQ(imu["T_BS"].size(), 16u);
  }
}
#endif

TEST(FilterExport, GoldenFiles) {
  const std::filesystem::path dir =
      std::filesystem::path(IMUNOISE_SOURCE_DIR) / "tests" / "io" / "golden";
  const bool update = std::getenv("IMUNOISE_UPDATE_GOLDEN") != nullptr;
  const auto m = worked_example();
  for (auto format : all_export_formats()) {
    const auto text = export_config(m, request(format));
    const auto path = dir / ("export_" + std::string(export_format_name(format)) + ".txt");
    if (update) {
      std::filesystem::create_directories(dir);
      std::ofstream(path, std::ios::binary) << text;
      continue;
    }
    std::ifstream in(path, std::ios::binary);
    ASSERT_TRUE(in) << path << " missing: run with IMUNOISE_UPDATE_GOLDEN=1 and review it";
    std::stringstream golden;
    golden << in.rdbuf();
    EXPECT_EQ(text, golden.str()) << "differs from " << path;
  }
}

}  // namespace
}  // namespace imunoise::io
