/// @file
/// @brief Tests of ins/noise_from_model.h: a hand-built NoiseModel mapped to InsSensorNoise
/// (per-axis N, K, B as one GM by the §8.3 conventions, the largest fitted GM without B,
/// interval upper ends when conservative), and the axis-count checks.
#include "ins/noise_from_model.h"

#include <gtest/gtest.h>

#include <string>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::ins {
namespace {

constexpr double kN = 1.16355e-4;  // theory.md §8.2 ARW, 0.4 deg/√h [rad/√s]
constexpr double kB = 1.22173e-4;  // theory.md §8.2 bias instability, 25.2 deg/h [rad/s]
constexpr double kK = 6.80678e-6;  // theory.md §8.2 RRW [rad/s^{3/2}]

models::Estimate estimate(double value, double high) {
  models::Estimate e;
  e.value = value;
  e.ci_low = 0.5 * value;
  e.ci_high = high;
  e.identified = value > 0.0;
  return e;
}

/// An axis with N, B, K and upper interval ends 1.1 N, 1.2 B, 2 K; τ_min = 29.6 s (§8.2).
models::AxisModel axis(const std::string& name, SensorKind kind, double n, double b, double k) {
  models::AxisModel a;
  a.name = name;
  a.kind = kind;
  a.terms[static_cast<int>(NoiseTerm::white_noise)] = estimate(n, 1.1 * n);
  a.terms[static_cast<int>(NoiseTerm::bias_instability)] = estimate(b, 1.2 * b);
  a.terms[static_cast<int>(NoiseTerm::random_walk)] = estimate(k, 2.0 * k);
  a.tau_min_adev_s = 29.6;
  a.fit_tau_min_s = 0.01;
  a.fit_tau_max_s = 3000.0;
  return a;
}

/// Six axes in a scrambled order: x, y, z must come from the name suffixes.
models::NoiseModel six_axis_model() {
  models::NoiseModel m;
  m.sample_rate_hz = 200.0;
  m.axes.push_back(axis("accel_z", SensorKind::accel, 3.0e-3, 0.0, 3.0e-5));
  m.axes.push_back(axis("gyro_y", SensorKind::gyro, 2.0e-4, 0.0, 1.0e-6));
  m.axes.push_back(axis("gyro_x", SensorKind::gyro, kN, kB, kK));
  m.axes.push_back(axis("accel_x", SensorKind::accel, 1.47e-3, 4.9e-4, 1.0e-5));
  m.axes.push_back(axis("gyro_z", SensorKind::gyro, 1.0e-4, 0.0, 3.0e-6));
  m.axes.push_back(axis("accel_y", SensorKind::accel, 2.0e-3, 0.0, 2.0e-5));
  // gyro_y: no B but two fitted GM terms; the larger σ (5e-5 rad/s, 300 s) stands for it.
  m.axes[1].gauss_markov.push_back({{2.0e-5, 100.0}, 1.0e-5, 3.0e-5, 50.0, 200.0});
  m.axes[1].gauss_markov.push_back({{5.0e-5, 300.0}, 4.0e-5, 6.0e-5, 200.0, 400.0});
  return m;
}

TEST(InsSensorNoise, MapsEachAxisOfAModel) {
  const InsSensorNoise noise = ins_sensor_noise(six_axis_model(), InsNoiseOptions{});
  // gyro x: the §8.2 gyro; B as GM (b) peak match (theory.md §4.4): σ = 0.6643·B/g* =
  // 1.0760·B, T_c = τ_min/x* = 29.6/1.8926 s (the §8.3 table prints 1.314e-4 and 15.6: it
  // rounds 0.664/0.6174 to 1.0755 and T_c to 15.6).
  EXPECT_EQ(noise.gyro[0].white_noise, kN);
  EXPECT_EQ(noise.gyro[0].random_walk, kK);
  EXPECT_NEAR(noise.gyro[0].bias_gm.sigma, 1.0760 * kB, 0.0001 * kB);
  EXPECT_NEAR(noise.gyro[0].bias_gm.tau_c_s, 29.6 / 1.8926, 0.001);
  // gyro y: no B, so the largest fitted GM term.
  EXPECT_EQ(noise.gyro[1].white_noise, 2.0e-4);
  EXPECT_EQ(noise.gyro[1].random_walk, 1.0e-6);
  EXPECT_EQ(noise.gyro[1].bias_gm.sigma, 5.0e-5);
  EXPECT_EQ(noise.gyro[1].bias_gm.tau_c_s, 300.0);
  // gyro z: neither B nor GM.
  EXPECT_EQ(noise.gyro[2].white_noise, 1.0e-4);
  EXPECT_EQ(noise.gyro[2].random_walk, 3.0e-6);
  EXPECT_EQ(noise.gyro[2].bias_gm.sigma, 0.0);
  // accel x, y, z: N and K by axis; B = 4.9e-4 m/s² on x.
  EXPECT_EQ(noise.accel[0].white_noise, 1.47e-3);
  EXPECT_EQ(noise.accel[1].white_noise, 2.0e-3);
  EXPECT_EQ(noise.accel[2].white_noise, 3.0e-3);
  EXPECT_EQ(noise.accel[0].random_walk, 1.0e-5);
  EXPECT_EQ(noise.accel[1].random_walk, 2.0e-5);
  EXPECT_EQ(noise.accel[2].random_walk, 3.0e-5);
  EXPECT_NEAR(noise.accel[0].bias_gm.sigma, 1.0760 * 4.9e-4, 0.0001 * 4.9e-4);  // §4.4 (b)
  EXPECT_EQ(noise.accel[1].bias_gm.sigma, 0.0);
  // Constants are the caller's: a stationary noise fit cannot see them.
  for (const auto* sensor : {&noise.gyro, &noise.accel}) {
    for (const SensorAxisNoise& a : *sensor) {
      EXPECT_EQ(a.turn_on_bias_sigma, 0.0);
      EXPECT_EQ(a.scale_factor_sigma, 0.0);
    }
  }
}

TEST(InsSensorNoise, ConventionAndConservativeOptions) {
  InsNoiseOptions options;
  options.gm_convention = models::GmConvention::sigma_equals_b;
  options.conservative = true;
  const InsSensorNoise noise = ins_sensor_noise(six_axis_model(), options);
  // Upper interval ends: 1.1 N, 2 K, B → 1.2 B; (c) σ = B, T_c = τ_min (§4.4, §8.3).
  EXPECT_DOUBLE_EQ(noise.gyro[0].white_noise, 1.1 * kN);
  EXPECT_DOUBLE_EQ(noise.gyro[0].random_walk, 2.0 * kK);
  EXPECT_DOUBLE_EQ(noise.gyro[0].bias_gm.sigma, 1.2 * kB);
  EXPECT_DOUBLE_EQ(noise.gyro[0].bias_gm.tau_c_s, 29.6);
  EXPECT_DOUBLE_EQ(noise.gyro[1].bias_gm.sigma, 6.0e-5);  // the fitted GM's upper σ
  EXPECT_DOUBLE_EQ(noise.accel[0].bias_gm.sigma, 1.2 * 4.9e-4);
}

TEST(InsSensorNoise, NeedsThreeGyroAndThreeAccelAxes) {
  models::NoiseModel two;
  two.sample_rate_hz = 200.0;
  two.axes.push_back(axis("gyro_x", SensorKind::gyro, kN, 0.0, kK));
  two.axes.push_back(axis("accel_x", SensorKind::accel, 1e-3, 0.0, 1e-5));
  test::expect_throw_containing<InputError>([&] { ins_sensor_noise(two, {}); },
                                            "needs three gyro and three accel axes; the model "
                                            "has 1 and 1");
  models::NoiseModel seven = six_axis_model();
  seven.axes.push_back(axis("gyro_w", SensorKind::gyro, kN, 0.0, kK));
  test::expect_throw_containing<InputError>([&] { ins_sensor_noise(seven, {}); },
                                            "the model has 4 and 3");
  models::NoiseModel no_rate = six_axis_model();
  no_rate.sample_rate_hz = 0.0;
  test::expect_throw_containing<InputError>([&] { ins_sensor_noise(no_rate, {}); },
                                            "sample_rate_hz must be > 0");
}

TEST(InsSensorNoise, ModelTermsAsStatesCarriesMultiGmFittedGmAndRamp) {
  // gyro_x: B with multi_gm → the multi_gm terms, no single GM; gyro_y: no B, two fitted GMs →
  // both as gm_terms; accel_x: B without multi_gm → the single-GM fallback (named by
  // single_gm_fallback_axes); accel_z: a ramp.
  models::NoiseModel m = six_axis_model();
  m.axes[2].multi_gm = {{1.0e-4, 3.0}, {9.0e-5, 30.0}, {8.0e-5, 300.0}};
  m.axes[0].terms[static_cast<int>(NoiseTerm::ramp)] = estimate(2e-7, 3e-7);
  InsNoiseOptions o;
  o.model_terms_as_states = true;
  const InsSensorNoise noise = ins_sensor_noise(m, o);
  EXPECT_EQ(noise.gyro[0].bias_gm.sigma, 0.0);
  ASSERT_EQ(noise.gyro[0].gm_terms.size(), 3u);
  EXPECT_EQ(noise.gyro[0].gm_terms[1].sigma, 9.0e-5);
  EXPECT_EQ(noise.gyro[0].gm_terms[1].tau_c_s, 30.0);
  EXPECT_EQ(noise.gyro[0].white_noise, kN);
  EXPECT_EQ(noise.gyro[0].random_walk, kK);
  EXPECT_EQ(noise.gyro[1].bias_gm.sigma, 0.0);
  ASSERT_EQ(noise.gyro[1].gm_terms.size(), 2u);
  EXPECT_EQ(noise.gyro[1].gm_terms[0].sigma, 2.0e-5);
  EXPECT_EQ(noise.gyro[1].gm_terms[1].tau_c_s, 300.0);
  // The fallback is the same single GM as without the option.
  const InsSensorNoise single = ins_sensor_noise(m, InsNoiseOptions{});
  EXPECT_GT(noise.accel[0].bias_gm.sigma, 0.0);
  EXPECT_EQ(noise.accel[0].bias_gm.sigma, single.accel[0].bias_gm.sigma);
  EXPECT_EQ(noise.accel[0].bias_gm.tau_c_s, single.accel[0].bias_gm.tau_c_s);
  EXPECT_TRUE(noise.accel[0].gm_terms.empty());
  EXPECT_EQ(noise.accel[2].ramp, 2e-7);
  EXPECT_EQ(single.accel[2].ramp, 0.0);
  EXPECT_TRUE(single.gyro[0].gm_terms.empty());
  EXPECT_EQ(single_gm_fallback_axes(m), std::vector<std::string>{"accel_x"});
}

}  // namespace
}  // namespace imunoise::ins
