// Tests of the robotics family of io/filter_export (LIO-SAM, FAST-LIO, Basalt, GTSAM,
// ArduPilot EKF3, Kimera-VIO, imu_utils): each file read back with a parser of its kind —
// yaml-cpp (the YAML of ROS parameter files), nlohmann::json (Basalt's JSON), OpenCV's
// FileStorage (Kimera's and imu_utils' own reader/writer) where installed — and every number
// compared with the model's value converted here, independently of the writer, from the
// meaning each consumer gives the key (docs/exports.md): densities N, K; per-sample variances
// N²·rate, K²·rate (FAST-LIO); σ = N/√dt (ArduPilot); the ADEV floor √(2 ln2/π)·B (imu_utils).
// The golden files of these formats are checked by FilterExport.GoldenFiles.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>
#include <string>

#include "common/errors.h"
#include "common/units.h"
#include "io/filter_export.h"
#include "io/filter_export_test_support.h"
#include "test_support.h"

#ifdef IMUNOISE_HAVE_OPENCV
#include <opencv2/core/persistence.hpp>
#endif

namespace imunoise::io {
namespace {

using test_fixture::estimate;
using test_fixture::request;
using test_fixture::worked_example;

// The worked example's values in SI, from their published units (theory.md §8).
const double kNg = 0.4 * std::numbers::pi / 180.0 / 60.0;             // 0.4 deg/√h
const double kKg = 84.24 * std::numbers::pi / 180.0 / 3600.0 / 60.0;  // 84.24 deg/h/√h
const double kBg = 25.2 * std::numbers::pi / 180.0 / 3600.0;          // 25.2 deg/h
const double kNa = 150e-6 * 9.80665;                                  // 150 µg/√Hz
const double kKa = 1e-4;                                              // m/s^2.5
const double kBa = 0.05e-3 * 9.80665;                                 // 0.05 mg
const double kRate = 200.0;                                           // Hz

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }
constexpr double kSixDigits = 5e-6;  // the files print six significant digits

std::set<std::string> keys_of(const YAML::Node& map) {
  std::set<std::string> keys;
  for (const auto& kv : map) keys.insert(kv.first.as<std::string>());
  return keys;
}

TEST(FilterExportRobotics, LioSamDensitiesUnderItsNamespace) {
  const auto yaml = YAML::Load(export_config(worked_example(), request(ExportFormat::lio_sam)));
  const auto p = yaml["lio_sam"];
  EXPECT_EQ(keys_of(p), (std::set<std::string>{"imuAccNoise", "imuGyrNoise", "imuAccBiasN",
                                               "imuGyrBiasN", "imuGravity", "imuRPYWeight"}));
  // imuPreintegration.cpp: pow(imuAccNoise, 2) is GTSAM's continuous covariance: a density.
  EXPECT_LT(rel(p["imuAccNoise"].as<double>(), kNa), kSixDigits);
  EXPECT_LT(rel(p["imuGyrNoise"].as<double>(), kNg), kSixDigits);
  EXPECT_LT(rel(p["imuAccBiasN"].as<double>(), kKa), kSixDigits);
  EXPECT_LT(rel(p["imuGyrBiasN"].as<double>(), kKg), kSixDigits);
  EXPECT_DOUBLE_EQ(p["imuGravity"].as<double>(), 9.80665);
}

TEST(FilterExportRobotics, FastLioPerSampleVariancesScaleWithTheRate) {
  for (const double rate : {kRate, 400.0}) {
    const auto yaml =
        YAML::Load(export_config(worked_example(), request(ExportFormat::fast_lio, rate)));
    const auto m = yaml["mapping"];
    EXPECT_EQ(keys_of(m), (std::set<std::string>{"acc_cov", "gyr_cov", "b_acc_cov", "b_gyr_cov"}));
    // Per-sample σ of white noise sampled every dt is N/√dt (theory.md §1.2): σ² = N²/dt.
    const double dt = 1.0 / rate;
    EXPECT_LT(rel(m["gyr_cov"].as<double>(), std::pow(kNg / std::sqrt(dt), 2)), 2 * kSixDigits);
    EXPECT_LT(rel(m["acc_cov"].as<double>(), std::pow(kNa / std::sqrt(dt), 2)), 2 * kSixDigits);
    // dt² · b_cov per step must equal the random walk's K²·dt: b_cov = K²/dt.
    EXPECT_LT(rel(m["b_gyr_cov"].as<double>() * dt * dt, kKg * kKg * dt), 2 * kSixDigits);
    EXPECT_LT(rel(m["b_acc_cov"].as<double>() * dt * dt, kKa * kKa * dt), 2 * kSixDigits);
  }
}

TEST(FilterExportRobotics, BasaltJsonValue0FirstWithThreeAxisArrays) {
  const auto j =
      nlohmann::ordered_json::parse(export_config(worked_example(), request(ExportFormat::basalt)));
  // Basalt loads its calibration with an unnamed cereal load: the first member is read.
  ASSERT_EQ(j.begin().key(), "value0");
  const auto& v = j["value0"];
  EXPECT_DOUBLE_EQ(v["imu_update_rate"].get<double>(), kRate);
  for (const char* key : {"accel_noise_std", "gyro_noise_std", "accel_bias_std", "gyro_bias_std"})
    ASSERT_EQ(v[key].size(), 3u) << key;
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(rel(v["accel_noise_std"][i].get<double>(), kNa), kSixDigits);
    EXPECT_LT(rel(v["gyro_noise_std"][i].get<double>(), kNg), kSixDigits);
    EXPECT_LT(rel(v["accel_bias_std"][i].get<double>(), kKa), kSixDigits);
    EXPECT_LT(rel(v["gyro_bias_std"][i].get<double>(), kKg), kSixDigits);
  }
  // The header travels as an array of strings (JSON has no comments).
  ASSERT_TRUE(j["imunoise_header"].is_array());
  EXPECT_EQ(j["imunoise_header"][0].get<std::string>(),
            "imunoise export for Basalt (calibration JSON)");
}

TEST(FilterExportRobotics, GtsamContinuousCovariancesOnTheDiagonal) {
  const auto text = export_config(worked_example(), request(ExportFormat::gtsam));
  const auto y = YAML::Load(text);
  const std::map<std::string, double> expected{{"accelerometerCovariance", kNa * kNa},
                                               {"gyroscopeCovariance", kNg * kNg},
                                               {"biasAccCovariance", kKa * kKa},
                                               {"biasOmegaCovariance", kKg * kKg},
                                               {"integrationCovariance", 1e-8}};
  for (const auto& [key, value] : expected) {
    ASSERT_EQ(y[key].size(), 3u) << key;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        if (r == c)
          EXPECT_LT(rel(y[key][r][c].as<double>(), value), 2 * kSixDigits) << key;
        else
          EXPECT_EQ(y[key][r][c].as<double>(), 0.0) << key;
      }
  }
  // Both snippets carry the same numbers (the Python one is run in tests/tools).
  EXPECT_NE(text.find("# p->biasOmegaCovariance = gtsam::Vector3(4.63323e-11, 4.63323e-11, "
                      "4.63323e-11).asDiagonal();"),
            std::string::npos);
  EXPECT_NE(text.find("# p.setBiasOmegaCovariance(np.diag([4.63323e-11, 4.63323e-11, "
                      "4.63323e-11]))"),
            std::string::npos);
}

/// The NAME VALUE lines of a .parm file.
std::map<std::string, double> parm_values(const std::string& text) {
  std::map<std::string, double> out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name, rest;
    double value = NAN;
    fields >> name >> value;
    EXPECT_FALSE(fields >> rest) << "more than NAME VALUE: " << line;
    out[name] = value;
  }
  return out;
}

TEST(FilterExportRobotics, ArduPilotEkf3AtItsTwelveMillisecondStep) {
  const auto out = export_file(worked_example(), request(ExportFormat::ardupilot));
  const auto v = parm_values(out.text);
  ASSERT_EQ(v.size(), 4u);
  // Delta-angle variance (dt·GYRO_P_NSE)² = N²·dt → GYRO_P_NSE = N/√dt, dt = 12 ms.
  const double dt = 0.012;
  EXPECT_LT(rel(v.at("EK3_GYRO_P_NSE"), kNg / std::sqrt(dt)), kSixDigits);
  EXPECT_LT(rel(v.at("EK3_ACC_P_NSE"), kNa / std::sqrt(dt)), kSixDigits);
  // Bias state (delta angle bias = b·dt) step std dt²·GBIAS = K·√dt·dt → GBIAS = K/√dt.
  EXPECT_LT(rel(v.at("EK3_GBIAS_P_NSE"), kKg / std::sqrt(dt)), kSixDigits);
  EXPECT_LT(rel(v.at("EK3_ABIAS_P_NSE"), kKa / std::sqrt(dt)), kSixDigits);
  EXPECT_TRUE(out.warnings.empty());
}

TEST(FilterExportRobotics, ArduPilotClampsToTheDocumentedRangesAndWarns) {
  auto quiet = worked_example();  // a navigation-grade accel: N_a·√83.3 below 0.01 m/s²
  for (auto& a : quiet.axes)
    if (a.kind == SensorKind::accel)
      a.terms[static_cast<int>(NoiseTerm::white_noise)] = estimate(1e-4, 1e-4, 1e-4);
  const auto out = export_file(quiet, request(ExportFormat::ardupilot));
  EXPECT_EQ(parm_values(out.text).at("EK3_ACC_P_NSE"), 0.01);  // @Range: 0.01 1.0
  ASSERT_EQ(out.warnings.size(), 1u);
  EXPECT_NE(out.warnings[0].find("EK3_ACC_P_NSE = 0.000912871 m/s/s is outside EKF3's "
                                 "documented range [0.01, 1.0]: 0.01 is written"),
            std::string::npos)
      << out.warnings[0];
  EXPECT_NE(out.text.find("# WARNING: EK3_ACC_P_NSE"), std::string::npos);
}

TEST(FilterExportRobotics, KimeraAndImuUtilsKeys) {
  const auto k = YAML::Load(export_config(worked_example(), request(ExportFormat::kimera)));
  EXPECT_EQ(keys_of(k), (std::set<std::string>{
                            "imu_preintegration_type", "T_BS", "rate_hz", "gyroscope_noise_density",
                            "gyroscope_random_walk", "accelerometer_noise_density",
                            "accelerometer_random_walk", "imu_integration_sigma", "imu_time_shift",
                            "do_initial_time_alignment", "n_gravity"}));
  EXPECT_LT(rel(k["gyroscope_random_walk"].as<double>(), kKg), kSixDigits);
  EXPECT_EQ(k["T_BS"]["data"].size(), 16u);
  const auto u = YAML::Load(export_config(worked_example(), request(ExportFormat::imu_utils)));
  EXPECT_EQ(u["Gyr"]["unit"].as<std::string>(), " rad/s");
  // imu_utils' meanings: gyr_n = √rate·ADEV(1 s) ≈ N_g·√rate; acc_n = ADEV(1 s) ≈ N_a; the w
  // keys = the ADEV minimum, the floor √(2 ln2/π)·B where B dominates.
  const double floor = std::sqrt(2.0 * std::numbers::ln2 / std::numbers::pi);
  EXPECT_LT(rel(u["Gyr"]["avg-axis"]["gyr_n"].as<double>(), kNg * std::sqrt(kRate)), kSixDigits);
  EXPECT_LT(rel(u["Gyr"]["z-axis"]["gyr_w"].as<double>(), floor * kBg), kSixDigits);
  EXPECT_LT(rel(u["Acc"]["x-axis"]["acc_n"].as<double>(), kNa), kSixDigits);
  EXPECT_LT(rel(u["Acc"]["avg-axis"]["acc_w"].as<double>(), floor * kBa), kSixDigits);
}

#ifdef IMUNOISE_HAVE_OPENCV
cv::FileStorage open_like_opencv(const std::string& text) {
  return cv::FileStorage(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
}

TEST(FilterExportRoboticsOpenCv, KimeraReadsWhatImuFrontendParamsReads) {
  auto fs = open_like_opencv(export_config(worked_example(), request(ExportFormat::kimera)));
  ASSERT_TRUE(fs.isOpened());
  EXPECT_TRUE(fs["imu_preintegration_type"].isInt());
  for (const char* key : {"rate_hz", "gyroscope_noise_density", "gyroscope_random_walk",
                          "accelerometer_noise_density", "accelerometer_random_walk",
                          "imu_integration_sigma", "imu_time_shift"})
    EXPECT_TRUE(fs[key].isReal()) << key;
  EXPECT_LT(rel(static_cast<double>(fs["accelerometer_noise_density"]), kNa), kSixDigits);
  EXPECT_EQ(fs["T_BS"]["data"].size(), 16u);
  EXPECT_EQ(static_cast<double>(fs["T_BS"]["data"][15]), 1.0);
  std::vector<double> g;
  fs["n_gravity"] >> g;
  ASSERT_EQ(g.size(), 3u);
  EXPECT_DOUBLE_EQ(g[2], -9.80665);
}

TEST(FilterExportRoboticsOpenCv, ImuUtilsFileReadsAsOpenCvWroteItsOwn) {
  auto fs = open_like_opencv(export_config(worked_example(), request(ExportFormat::imu_utils)));
  ASSERT_TRUE(fs.isOpened());
  EXPECT_EQ(static_cast<std::string>(fs["type"]), "IMU");
  EXPECT_EQ(static_cast<std::string>(fs["name"]), "theory.md §8 consumer MEMS");
  EXPECT_EQ(static_cast<std::string>(fs["Acc"]["unit"]), " m/s^2");
  EXPECT_LT(rel(static_cast<double>(fs["Gyr"]["x-axis"]["gyr_n"]), kNg * std::sqrt(kRate)),
            kSixDigits);
  EXPECT_LT(rel(static_cast<double>(fs["Acc"]["y-axis"]["acc_w"]),
                std::sqrt(2.0 * std::numbers::ln2 / std::numbers::pi) * kBa),
            kSixDigits);
}
#endif

}  // namespace
}  // namespace imunoise::io
