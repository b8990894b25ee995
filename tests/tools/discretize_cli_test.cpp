/// @file
/// @brief End-to-end tests of `imunoise discretize` (tools/cmd_discretize.cpp): the states it
/// builds from a model.yaml, Φ and Q_d against the closed forms of theory.md §6.2, the
/// 15/21-state INS layouts, YAML and JSON agreeing, and clean failures.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "common/sensor_kind.h"
#include "test_support.h"

namespace imunoise::test {
namespace {

/// One model axis in the short form of docs/model-yaml.md.
std::string axis(const std::string& name, SensorKind kind, double n, double b, double k) {
  const auto by_kind = [kind](const char* gyro_key, const char* accel_key) {
    return std::string(kind == SensorKind::gyro ? gyro_key : accel_key);
  };
  const std::string q = by_kind("quantization_rad", "quantization_m_per_s");
  const std::string w = by_kind("white_noise_rad_per_sqrt_s", "white_noise_m_per_s_sqrt_s");
  const std::string bi = by_kind("bias_instability_rad_per_s", "bias_instability_m_per_s2");
  const std::string rw = by_kind("random_walk_rad_per_s_sqrt_s", "random_walk_m_per_s2_sqrt_s");
  const std::string r = by_kind("ramp_rad_per_s2", "ramp_m_per_s3");
  std::ostringstream s;
  s << "  " << name << ":\n    sensor: " << sensor_name(kind) << "\n"
    << "    " << q << ": {value: 0}\n    " << w << ": {value: " << n << "}\n"
    << "    " << bi << ": {value: " << b << "}\n    " << rw << ": {value: " << k << "}\n"
    << "    " << r << ": {value: 0}\n"
    << "    fit: {tau_min_s: 0.005, tau_max_s: 3000, tau_of_min_adev_s: 29.6, note: \"\"}\n";
  return s.str();
}

/// theory.md §8 gyro (N, B, K) on x, y, z and an accelerometer.
std::filesystem::path write_model(const std::filesystem::path& dir, bool six_axes) {
  std::string text =
      "format: imunoise-noise-model\nformat_version: 1\nsample_rate_hz: 200\naxes:\n";
  for (const char* n : {"gyro_x", "gyro_y", "gyro_z"}) {
    text += axis(n, SensorKind::gyro, 1.16355e-4, 1.22173e-4, 6.80678e-6);
    if (!six_axes) break;
  }
  for (const char* n : {"accel_x", "accel_y", "accel_z"}) {
    text += axis(n, SensorKind::accel, 1.471e-3, 4.9e-4, 1e-4);
    if (!six_axes) break;
  }
  const auto path = dir / "model.yaml";
  std::ofstream(path) << text;
  return path;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

TEST(DiscretizeCli, SensorStatesMatchTheClosedForms) {
  const auto dir = make_temp_dir("discretize-sensor");
  const auto model = write_model(dir, false);
  const double dt = 0.005, k = 6.80678e-6;
  auto r = run_imunoise("discretize " + model.string() + " --dt 0.005 -o " + (dir / "rw").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = read_json(dir / "rw" / "discrete_model.json");
  ASSERT_EQ(j["states"], (nlohmann::json{"gyro_x_bias_rw_rad_per_s", "accel_x_bias_rw_m_per_s2"}));
  // RW: Φ = 1, Q_d = K²Δt (theory.md §6.2).
  EXPECT_EQ(j["phi"][0][0].get<double>(), 1.0);
  EXPECT_LT(rel(j["qd"][0][0].get<double>(), k * k * dt), 1e-14);
  EXPECT_LT(rel(j["qd"][1][1].get<double>(), 1e-8 * dt), 1e-14);
  // White noise is an input: per-sample rate σ = N/√Δt = 1.6455e-3 rad/s at 200 Hz (§8.2).
  EXPECT_LT(rel(j["white_noise"][0]["rate_sigma_rad_per_s"].get<double>(), 1.6455e-3), 5e-5);
  EXPECT_NE(j["notes"].dump().find("bias instability / GM terms not represented"),
            std::string::npos);

  r = run_imunoise("discretize " + model.string() + " --dt 0.005 --bias gm -o " +
                   (dir / "gm").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = read_json(dir / "gm" / "discrete_model.json");
  ASSERT_EQ(j["states"][0], "gyro_x_bias_instability_gm_rad_per_s");
  // B → GM (b): σ = 1.075996·B, T_c = 29.6/1.892618; Φ = e^{−Δt/T_c}, Q_d = σ²(1 − Φ²).
  const double sigma = 1.075996 * 1.22173e-4, tc = 29.6 / 1.892618;
  const double phi = std::exp(-dt / tc);
  EXPECT_LT(rel(j["phi"][0][0].get<double>(), phi), 1e-6);
  EXPECT_LT(rel(j["qd"][0][0].get<double>(), sigma * sigma * (1.0 - phi * phi)), 1e-5);
  EXPECT_LT(rel(j["initial_variance"][0].get<double>(), sigma * sigma), 1e-5);
}

TEST(DiscretizeCli, InsErrorStateLayoutsAndYamlAgreesWithJson) {
  const auto dir = make_temp_dir("discretize-ins");
  const auto model = write_model(dir, true);
  const struct {
    const char* flags;
    std::size_t states;
  } cases[] = {{"--states 15", 15},
               {"--states 15 --bias both", 21},
               {"--states 21", 21},
               {"--states 21 --bias both", 27}};
  for (const auto& c : cases) {
    const auto out = dir / std::to_string(c.states);
    const auto r = run_imunoise("discretize " + model.string() + " --dt 1 " + c.flags +
                                " --height-hold -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << c.flags << ": " << r.err;
    const auto j = read_json(out / "discrete_model.json");
    EXPECT_EQ(j["states"].size(), c.states) << c.flags;
    EXPECT_EQ(j["qd"].size(), c.states) << c.flags;
    EXPECT_EQ(j["states"][0], "att_err_n_rad");
    // Q_d symmetric, with the gyro-bias RW block K²Δt on its diagonal (state 12).
    for (std::size_t a = 0; a < c.states; ++a)
      for (std::size_t b = 0; b < a; ++b)
        EXPECT_EQ(j["qd"][a][b].get<double>(), j["qd"][b][a].get<double>());
    if (std::string(c.flags).find("both") != std::string::npos ||
        std::string(c.flags).find("gm") == std::string::npos) {
      EXPECT_LT(rel(j["qd"][12][12].get<double>(), 6.80678e-6 * 6.80678e-6), 1e-9) << c.flags;
    }
    // The YAML carries the same numbers (shortest round-trip text).
    std::ifstream yaml(out / "discrete_model.yaml");
    std::stringstream text;
    text << yaml.rdbuf();
    EXPECT_NE(text.str().find("# " + std::to_string(c.states) + " states"), std::string::npos);
    EXPECT_NE(text.str().find("dt_s: 1\n"), std::string::npos);
  }
}

TEST(DiscretizeCli, CleanFailures) {
  const auto dir = make_temp_dir("discretize-fail");
  const auto model = write_model(dir, false);
  auto r = run_imunoise("discretize " + model.string() + " --dt 1 --states 15 -o " +
                        (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("needs three gyro and three accel axes; the model has 1 and 1"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o" / "discrete_model.json"));
  r = run_imunoise("discretize " + model.string() + " --dt -1 -o " + (dir / "o").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--dt"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace imunoise::test
