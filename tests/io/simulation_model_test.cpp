/// @file
/// @brief Tests of io/simulation_model.h: every datasheet unit key against the factors of
/// ../shared/docs/theory.md §1.3 computed here from first principles (not from
/// common/units.h), duplicate and unknown keys with their locations, the demo model round trip
/// through the SI keys, and configs/reference-imu.yaml against hand conversions.
#include "io/simulation_model.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

/// @name Unit factors, derived independently of common/units.h: 1 deg = π/180 rad,
/// 1 h = 3600 s (√h = 60 √s), g₀ = 9.80665 m/s² (the definition of the unit g).
/// @{
constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kHourS = 3600.0;
constexpr double kSqrtHourS = 60.0;
constexpr double kG0 = 9.80665;
/// @}

std::string error_of(const std::string& yaml) {
  try {
    parse_simulation_model(yaml, "m.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for:\n" << yaml;
  return {};
}

void expect_contains(const std::string& text, const std::vector<std::string>& fragments) {
  for (const std::string& f : fragments) {
    EXPECT_NE(text.find(f), std::string::npos) << "'" << f << "' not in: " << text;
  }
}

/// One unit key: where it goes, the value written and the SI value expected.
struct UnitCase {
  std::string sensor;  ///< "gyro" or "accel"
  std::string key;
  double value;
  double expected_si;
  std::function<double(const SimulationAxis&)> get;
};

double quantization(const SimulationAxis& a) { return a.coefficients.quantization; }
double white(const SimulationAxis& a) { return a.coefficients.white_noise; }
double instability(const SimulationAxis& a) { return a.coefficients.bias_instability; }
double walk(const SimulationAxis& a) { return a.coefficients.random_walk; }
double ramp(const SimulationAxis& a) { return a.coefficients.ramp; }
double bias(const SimulationAxis& a) { return a.bias; }
double signal(const SimulationAxis& a) { return a.signal; }
double lsb(const SimulationAxis& a) { return a.output_lsb; }

std::vector<UnitCase> unit_cases() {
  const double deg_per_h = kDegree / kHourS;  // deg/h → rad/s
  return {
      // Gyro quantization Q [rad]
      {"gyro", "quantization_rad", 2e-6, 2e-6, quantization},
      {"gyro", "quantization_deg", 1e-3, 1e-3 * kDegree, quantization},
      {"gyro", "quantization_urad", 3.0, 3e-6, quantization},
      // ARW N [rad/√s]: deg/√h = (π/180)/60; (deg/s)/√Hz = (π/180) rad/s·√s (two-sided)
      {"gyro", "arw_rad_per_sqrt_s", 1.2e-4, 1.2e-4, white},
      {"gyro", "arw_deg_per_sqrt_h", 0.4, 0.4 * kDegree / kSqrtHourS, white},
      {"gyro", "arw_deg_per_s_per_sqrt_hz", 6.667e-3, 6.667e-3 * kDegree, white},
      // B [rad/s]
      {"gyro", "bias_instability_rad_per_s", 1e-4, 1e-4, instability},
      {"gyro", "bias_instability_deg_per_h", 25.2, 25.2 * deg_per_h, instability},
      {"gyro", "bias_instability_deg_per_s", 0.007, 0.007 * kDegree, instability},
      // K [rad/s^{3/2}]: deg/h/√h = (π/180)/(3600·60); deg/s/√s = π/180
      {"gyro", "rrw_rad_per_s_sqrt_s", 6.8e-6, 6.8e-6, walk},
      {"gyro", "rrw_deg_per_h_per_sqrt_h", 84.24, 84.24 * kDegree / (kHourS * kSqrtHourS), walk},
      {"gyro", "rrw_deg_per_s_per_sqrt_s", 3.9e-4, 3.9e-4 * kDegree, walk},
      // R [rad/s²]: deg/h² = (π/180)/3600²; (deg/s)/h = (π/180)/3600
      {"gyro", "ramp_rad_per_s2", -1e-7, -1e-7, ramp},
      {"gyro", "ramp_deg_per_h2", 10.0, 10.0 * kDegree / (kHourS * kHourS), ramp},
      {"gyro", "ramp_deg_per_s_per_h", 0.0141, 0.0141 * kDegree / kHourS, ramp},
      // Constant bias and signal [rad/s]
      {"gyro", "bias_rad_per_s", -2e-3, -2e-3, bias},
      {"gyro", "bias_deg_per_h", -36.0, -36.0 * deg_per_h, bias},
      {"gyro", "bias_deg_per_s", 0.1, 0.1 * kDegree, bias},
      {"gyro", "angular_rate_rad_per_s", 7.2921e-5, 7.2921e-5, signal},
      {"gyro", "angular_rate_deg_per_s", 15.0, 15.0 * kDegree, signal},
      {"gyro", "output_lsb_rad_per_s", 1.2e-3, 1.2e-3, lsb},
      {"gyro", "output_lsb_deg_per_s", 1.0 / 14.375, kDegree / 14.375, lsb},
      // Accel quantization Q [m/s]
      {"accel", "quantization_m_per_s", 1e-5, 1e-5, quantization},
      // VRW N [m/s/√s]: m/s/√h = 1/60; µg/√Hz = 9.80665e-6 (m/s²)·√s (two-sided)
      {"accel", "vrw_m_per_s_sqrt_s", 1.47e-3, 1.47e-3, white},
      {"accel", "vrw_m_per_s_per_sqrt_h", 0.0311, 0.0311 / kSqrtHourS, white},
      {"accel", "vrw_ug_per_sqrt_hz", 150.0, 150.0e-6 * kG0, white},
      // B [m/s²]
      {"accel", "bias_instability_m_per_s2", 2.5e-4, 2.5e-4, instability},
      {"accel", "bias_instability_ug", 25.0, 25.0e-6 * kG0, instability},
      {"accel", "bias_instability_mg", 0.05, 0.05e-3 * kG0, instability},
      // K [m/s^{5/2}]: (m/s/h)/√h = 1/(3600·60); µg/√s = 9.80665e-6
      {"accel", "rw_m_per_s2_sqrt_s", 4e-5, 4e-5, walk},
      {"accel", "rw_m_per_s_per_h_per_sqrt_h", 0.5, 0.5 / (kHourS * kSqrtHourS), walk},
      {"accel", "rw_ug_per_sqrt_s", 4.0, 4.0e-6 * kG0, walk},
      // R [m/s³]: (m/s²)/h = 1/3600
      {"accel", "ramp_m_per_s3", 5e-7, 5e-7, ramp},
      {"accel", "ramp_m_per_s2_per_h", 0.0021, 0.0021 / kHourS, ramp},
      // Constant bias and signal [m/s²]
      {"accel", "bias_m_per_s2", 0.05, 0.05, bias},
      {"accel", "bias_mg", -5.0, -5.0e-3 * kG0, bias},
      {"accel", "bias_ug", 300.0, 300.0e-6 * kG0, bias},
      {"accel", "specific_force_m_per_s2", -9.81, -9.81, signal},
      {"accel", "specific_force_g", -1.0, -kG0, signal},
      {"accel", "output_lsb_m_per_s2", 0.0383, 0.0383, lsb},
      {"accel", "output_lsb_mg", 3.9, 3.9e-3 * kG0, lsb},
  };
}

TEST(SimulationModel, EveryUnitKeyConvertsWithTheTheoryFactor) {
  for (const UnitCase& c : unit_cases()) {
    char value[40];
    std::snprintf(value, sizeof value, "%.17g", c.value);
    const SimulationModelFile m =
        parse_simulation_model(c.sensor + ":\n  " + c.key + ": " + value + "\n", "m.yaml");
    const auto& axes = c.sensor == "gyro" ? m.gyro : m.accel;
    for (const SimulationAxis& axis : axes) {  // a sensor-level key applies to x, y and z
      EXPECT_NEAR(c.get(axis), c.expected_si, 1e-14 * std::abs(c.expected_si)) << c.key;
    }
  }
}

TEST(SimulationModel, FactorsMatchTheTheoryTablePrintedValues) {
  // theory.md §1.3 / §8.2 as printed (7 significant digits; tolerance half a unit of the last).
  const auto si = [](const std::string& sensor, const std::string& key, double value,
                     const std::function<double(const SimulationAxis&)>& get) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);
    const SimulationModelFile m =
        parse_simulation_model(sensor + ":\n  " + key + ": " + text + "\n", "m.yaml");
    return get(sensor == "gyro" ? m.gyro[0] : m.accel[0]);
  };
  EXPECT_NEAR(si("gyro", "arw_deg_per_sqrt_h", 1.0, white), 2.908882e-4, 5e-11);
  EXPECT_NEAR(si("gyro", "arw_deg_per_sqrt_h", 0.4, white), 1.16355e-4, 5e-10);  // §8.2
  EXPECT_NEAR(si("gyro", "arw_deg_per_s_per_sqrt_hz", 1.0, white), 1.745329e-2, 5e-9);
  EXPECT_NEAR(si("gyro", "bias_instability_deg_per_h", 1.0, instability), 4.848137e-6, 5e-13);
  EXPECT_NEAR(si("gyro", "bias_instability_deg_per_s", 0.007, instability), 1.22173e-4, 5e-10);
  EXPECT_NEAR(si("gyro", "rrw_deg_per_h_per_sqrt_h", 1.0, walk), 8.080228e-8, 5e-15);
  EXPECT_NEAR(si("gyro", "rrw_deg_per_s_per_sqrt_s", 3.9e-4, walk), 6.80678e-6, 5e-12);  // §8.2
  EXPECT_NEAR(si("gyro", "ramp_deg_per_h2", 1.0, ramp), 1.346705e-9, 5e-16);
  EXPECT_NEAR(si("accel", "vrw_ug_per_sqrt_hz", 1.0, white), 9.80665e-6, 5e-12);
  EXPECT_NEAR(si("accel", "vrw_ug_per_sqrt_hz", 150.0, white), 1.471e-3, 5e-7);  // §8.5
  EXPECT_NEAR(si("accel", "rw_m_per_s_per_h_per_sqrt_h", 1.0, walk), 4.62963e-6, 5e-12);
  EXPECT_NEAR(si("accel", "bias_instability_mg", 1.0, instability), 9.80665e-3, 5e-12);
}

TEST(SimulationModel, GaussMarkovAndSinusoidItemsAcceptUnitKeys) {
  const SimulationModelFile m = parse_simulation_model(R"(
gyro:
  gauss_markov: [{sigma_deg_per_h: 20, tau_c_h: 0.5}, {sigma_rad_per_s: 1e-4, tau_c_s: 30}]
  sinusoids: [{amplitude_deg_per_s: 0.01, frequency_hz: 2.5, phase_deg: 90}]
accel:
  gauss_markov: [{sigma_mg: 0.1, tau_c_s: 100}, {sigma_ug: 50, tau_c_s: 10}]
  sinusoids: [{amplitude_mg: 2, frequency_hz: 0.1}]
)",
                                                       "m.yaml");
  const SimulationAxis& g = m.gyro[2];
  ASSERT_EQ(g.coefficients.gauss_markov.size(), 2U);
  EXPECT_NEAR(g.coefficients.gauss_markov[0].sigma, 20.0 * kDegree / kHourS, 1e-20);
  EXPECT_DOUBLE_EQ(g.coefficients.gauss_markov[0].tau_c_s, 1800.0);
  EXPECT_DOUBLE_EQ(g.coefficients.gauss_markov[1].tau_c_s, 30.0);
  ASSERT_EQ(g.coefficients.sinusoids.size(), 1U);
  EXPECT_NEAR(g.coefficients.sinusoids[0].amplitude, 0.01 * kDegree, 1e-18);
  EXPECT_DOUBLE_EQ(g.coefficients.sinusoids[0].frequency_hz, 2.5);
  EXPECT_NEAR(g.coefficients.sinusoids[0].phase_rad, std::numbers::pi / 2.0, 1e-15);
  const SimulationAxis& a = m.accel[0];
  ASSERT_EQ(a.coefficients.gauss_markov.size(), 2U);
  EXPECT_NEAR(a.coefficients.gauss_markov[0].sigma, 0.1e-3 * kG0, 1e-18);
  EXPECT_NEAR(a.coefficients.gauss_markov[1].sigma, 50e-6 * kG0, 1e-18);
  EXPECT_NEAR(a.coefficients.sinusoids[0].amplitude, 2e-3 * kG0, 1e-17);
  EXPECT_EQ(a.coefficients.sinusoids[0].phase_rad, 0.0);
}

TEST(SimulationModel, AxisValuesOverrideSharedOnesInAnyUnit) {
  const SimulationModelFile m = parse_simulation_model(
      "gyro:\n  arw_rad_per_sqrt_s: 1e-4\n  x: {arw_deg_per_sqrt_h: 0.4}\n", "m.yaml");
  EXPECT_NEAR(m.gyro[0].coefficients.white_noise, 0.4 * kDegree / kSqrtHourS, 1e-18);
  EXPECT_EQ(m.gyro[1].coefficients.white_noise, 1e-4);
  EXPECT_EQ(m.gyro[2].coefficients.white_noise, 1e-4);
}

TEST(SimulationModel, OneTermInTwoUnitsIsAnErrorNamingBothKeys) {
  expect_contains(error_of("gyro:\n  arw_rad_per_sqrt_s: 1e-4\n  arw_deg_per_sqrt_h: 0.4\n"),
                  {"m.yaml:3:3", "gyro.arw_deg_per_sqrt_h", "arw_rad_per_sqrt_s", "(line 2)"});
  expect_contains(
      error_of("accel:\n  z:\n    specific_force_g: -1\n    specific_force_m_per_s2: -9.8\n"),
      {"m.yaml:4:5", "accel.z.specific_force_m_per_s2", "specific_force_g"});
  expect_contains(error_of("gyro:\n  gauss_markov: [{sigma_rad_per_s: 1e-4, tau_c_s: 3, "
                           "tau_c_h: 1}]\n"),
                  {"m.yaml:2", "gyro.gauss_markov[0].tau_c_h", "tau_c_s"});
}

TEST(SimulationModel, UnknownKeyIsLocatedAndListsTheAcceptedKeys) {
  const std::string e = error_of("gyro:\n  x:\n    arw_deg_per_sqrt_hr: 0.4\n");
  expect_contains(e, {"m.yaml:3:5", "gyro.x.arw_deg_per_sqrt_hr", "unknown key",
                      "arw_rad_per_sqrt_s|arw_deg_per_sqrt_h|arw_deg_per_s_per_sqrt_hz",
                      "ramp_rad_per_s2|ramp_deg_per_h2|ramp_deg_per_s_per_h", "gauss_markov"});
  EXPECT_EQ(e.find("x, y, z"), std::string::npos) << "axes are not accepted inside an axis";
  expect_contains(error_of("accel:\n  vrw_ug_per_sqrt_hz: 150\n  bias_instability_ng: 3\n"),
                  {"m.yaml:3:3", "accel.bias_instability_ng", "unknown key",
                   "bias_instability_m_per_s2|bias_instability_ug|bias_instability_mg", "x, y, z"});
  expect_contains(error_of("gyro:\n  gauss_markov: [{sigma_mg: 1, tau_c_s: 3}]\n"),
                  {"gyro.gauss_markov[0].sigma_mg", "unknown key",
                   "sigma_rad_per_s|sigma_deg_per_h|sigma_deg_per_s"});
  expect_contains(error_of("magnetometer: {}\n"), {"m.yaml:1:1", "magnetometer", "unknown key"});
}

TEST(SimulationModel, RangeAndTypeErrorsNameTheKeyPath) {
  expect_contains(error_of("gyro:\n  x:\n    bias_instability_deg_per_h: -3\n"),
                  {"m.yaml:3:33", "gyro.x.bias_instability_deg_per_h", "must be >= 0"});
  expect_contains(error_of("accel:\n  vrw_ug_per_sqrt_hz: abc\n"),
                  {"accel.vrw_ug_per_sqrt_hz", "finite number", "'abc'"});
  expect_contains(error_of("gyro:\n  gauss_markov: [{sigma_rad_per_s: 1e-4, tau_c_h: 0}]\n"),
                  {"gyro.gauss_markov[0].tau_c_h", "> 0"});
  expect_contains(error_of("gyro:\n  gauss_markov: [{sigma_rad_per_s: 1e-4}]\n"),
                  {"gyro.gauss_markov[0]", "missing key tau_c_s|tau_c_h"});
  expect_contains(error_of("sample_rate_hz: 0\n"), {"sample_rate_hz", "> 0"});
  expect_contains(error_of("flicker_band_s: [10, 1]\n"),
                  {"flicker_band_s", "tau_min_s < tau_max_s"});
  expect_contains(error_of("gyro: [1, 2\n"), {"m.yaml", "YAML syntax"});
  // Negative values are allowed where they make sense.
  const SimulationModelFile m =
      parse_simulation_model("gyro:\n  ramp_deg_per_h2: -2\n  bias_deg_per_s: -0.1\n", "m.yaml");
  EXPECT_LT(m.gyro[0].coefficients.ramp, 0.0);
  EXPECT_LT(m.gyro[0].bias, 0.0);
}

TEST(SimulationModel, MissingFileIsAnInputErrorNamingIt) {
  test::expect_throw_containing<InputError>(
      [] { load_simulation_model("/nonexistent/model.yaml"); },
      "/nonexistent/model.yaml: cannot open the model file");
}

std::string config_path(const std::string& name) {
  return std::string(IMUNOISE_SOURCE_DIR) + "/configs/" + name;
}

void expect_same_axis(const SimulationAxis& a, const SimulationAxis& b, const std::string& label) {
  EXPECT_EQ(a.coefficients.quantization, b.coefficients.quantization) << label;
  EXPECT_EQ(a.coefficients.white_noise, b.coefficients.white_noise) << label;
  EXPECT_EQ(a.coefficients.bias_instability, b.coefficients.bias_instability) << label;
  EXPECT_EQ(a.coefficients.random_walk, b.coefficients.random_walk) << label;
  EXPECT_EQ(a.coefficients.ramp, b.coefficients.ramp) << label;
  EXPECT_EQ(a.bias, b.bias) << label;
  EXPECT_EQ(a.signal, b.signal) << label;
  EXPECT_EQ(a.output_lsb, b.output_lsb) << label;
  EXPECT_EQ(a.coefficients.gauss_markov.size(), b.coefficients.gauss_markov.size()) << label;
  EXPECT_EQ(a.coefficients.sinusoids.size(), b.coefficients.sinusoids.size()) << label;
}

/// SI_TERMS (" key=value key=value") as the body of a YAML mapping.
std::string as_yaml_mapping(const std::string& si_terms) {
  std::string yaml;
  std::size_t start = 0;
  while (start < si_terms.size()) {
    const std::size_t begin = si_terms.find_first_not_of(' ', start);
    if (begin == std::string::npos) break;
    std::size_t end = si_terms.find(' ', begin);
    if (end == std::string::npos) end = si_terms.size();
    std::string pair = si_terms.substr(begin, end - begin);
    pair.replace(pair.find('='), 1, ": ");
    yaml += "    " + pair + "\n";
    start = end;
  }
  return yaml;
}

TEST(SimulationModel, DemoModelLoadsAndRoundTripsThroughTheSiKeys) {
  const SimulationModelFile demo = load_simulation_model(config_path("demo_imu.yaml"));
  EXPECT_EQ(demo.name, "demo consumer MEMS IMU (theory.md §8)");
  ASSERT_TRUE(demo.sample_rate_hz.has_value());
  EXPECT_EQ(*demo.sample_rate_hz, 100.0);
  EXPECT_FALSE(demo.flicker_band.has_value());
  const double gyro_bias[] = {2.0e-3, -1.5e-3, 1.0e-3};
  const double accel_bias[] = {0.05, -0.03, 0.08};
  for (std::size_t a = 0; a < 3; ++a) {
    EXPECT_EQ(demo.gyro[a].coefficients.white_noise, 1.16355e-4);
    EXPECT_EQ(demo.gyro[a].coefficients.bias_instability, 1.22173e-4);
    EXPECT_EQ(demo.gyro[a].coefficients.random_walk, 6.80678e-6);
    EXPECT_EQ(demo.gyro[a].bias, gyro_bias[a]);
    EXPECT_EQ(demo.accel[a].coefficients.white_noise, 1.471e-3);
    EXPECT_EQ(demo.accel[a].coefficients.bias_instability, 2.5e-4);
    EXPECT_EQ(demo.accel[a].coefficients.random_walk, 4.0e-5);
    EXPECT_EQ(demo.accel[a].bias, accel_bias[a]);
  }
  EXPECT_EQ(demo.accel[2].signal, -9.80665);
  EXPECT_EQ(channel_model(demo.accel[2]).constant, 0.08 - 9.80665);

  // Written back under the SI keys (as the CSV header does) and read again: the same model.
  std::string yaml;
  const auto write_back = [&yaml](SensorKind kind, const std::array<SimulationAxis, 3>& axes) {
    yaml += std::string(sensor_name(kind)) + ":\n";
    for (std::size_t a = 0; a < 3; ++a) {
      yaml += std::string("  ") + "xyz"[a] + ":\n" + as_yaml_mapping(si_terms_text(axes[a], kind));
    }
  };
  write_back(SensorKind::gyro, demo.gyro);
  write_back(SensorKind::accel, demo.accel);
  const SimulationModelFile again = parse_simulation_model(yaml, "again.yaml");
  for (std::size_t a = 0; a < 3; ++a) {
    expect_same_axis(again.gyro[a], demo.gyro[a], "gyro " + std::to_string(a));
    expect_same_axis(again.accel[a], demo.accel[a], "accel " + std::to_string(a));
  }
}

TEST(SimulationModel, ReferenceImuGyroXMatchesHandConversions) {
  // reference-imu.md Table 1, gyro x, converted by hand (theory.md §1.3 and the readings
  // documented in the file): N 0.4055 deg/√h, B 0.0072 deg/s, K 3.8758e-4 deg/s/√s,
  // R 0.0141 (deg/s)/h.
  const SimulationModelFile ref = load_simulation_model(config_path("reference-imu.yaml"));
  ASSERT_TRUE(ref.sample_rate_hz.has_value());
  EXPECT_EQ(*ref.sample_rate_hz, 50.0);
  const NoiseCoefficients& x = ref.gyro[0].coefficients;
  EXPECT_NEAR(x.white_noise, 0.4055 * (std::numbers::pi / 180.0) / 60.0, 1e-18);
  EXPECT_NEAR(x.white_noise, 1.179552e-4, 5e-11);
  EXPECT_NEAR(x.bias_instability, 0.0072 * std::numbers::pi / 180.0, 1e-18);
  EXPECT_NEAR(x.bias_instability, 1.256637e-4, 5e-11);
  EXPECT_NEAR(x.random_walk, 3.8758e-4 * std::numbers::pi / 180.0, 1e-19);
  EXPECT_NEAR(x.random_walk, 6.764547e-6, 5e-13);
  EXPECT_NEAR(x.ramp, 0.0141 * (std::numbers::pi / 180.0) / 3600.0, 1e-21);
  EXPECT_NEAR(x.ramp, 6.835873e-8, 5e-15);
  EXPECT_EQ(x.quantization, 0.0);
  EXPECT_TRUE(x.gauss_markov.empty());
  EXPECT_EQ(ref.gyro[0].bias, 0.0);
  // Other axes keep their own values; the level FRD accelerometer z senses −g₀.
  EXPECT_NEAR(ref.gyro[1].coefficients.bias_instability, 0.0030 * kDegree, 1e-18);
  EXPECT_NEAR(ref.accel[0].coefficients.white_noise, 0.0311 / 60.0, 1e-18);
  EXPECT_NEAR(ref.accel[0].coefficients.ramp, 0.0021 / 3600.0, 1e-20);
  EXPECT_EQ(ref.accel[0].coefficients.random_walk, 4.9391e-5);
  EXPECT_EQ(ref.accel[2].signal, -kG0);
  EXPECT_EQ(ref.accel[0].signal, 0.0);
}

}  // namespace
}  // namespace imunoise::io
