// Tests of pipeline/sensor_states.h, the state models `imunoise discretize` discretizes: the
// per-axis sensor error states of a hand-built NoiseModel against the closed forms of
// theory.md §6.1 (RW: Q_c = K²; GM: F = −1/T_c, Q_c = 2σ²/T_c, P₀ = σ²; ramp: P₀ = diag(0,
// R²)), the B → GM conversion of §4.4 (b), the white-noise σ of §6.2, the terms each bias
// model leaves out, and the INS error-state layouts of §6.3.
#include "pipeline/sensor_states.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "ins/noise_from_model.h"

namespace imunoise::pipeline {
namespace {

constexpr double kN = 1.16355e-4;  // theory.md §8.2 ARW, 0.4 deg/√h [rad/√s]
constexpr double kB = 1.22173e-4;  // theory.md §8.2 bias instability, 25.2 deg/h [rad/s]
constexpr double kK = 6.80678e-6;  // theory.md §8.2 RRW [rad/s^{3/2}]
constexpr double kTauMin = 29.6;   // τ of the ADEV minimum [s] (§8.2)
constexpr double kDt = 0.005;      // 200 Hz step [s]

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

models::Estimate estimate(double value) {
  models::Estimate e;
  e.value = value;
  e.ci_low = 0.5 * value;
  e.ci_high = 2.0 * value;
  e.identified = value > 0.0;
  return e;
}

/// An axis with N, B, K and ramp R (upper interval ends twice the values); τ_min = 29.6 s.
models::AxisModel axis(const std::string& name, SensorKind kind, double n, double b, double k,
                       double r = 0.0) {
  models::AxisModel a;
  a.name = name;
  a.kind = kind;
  a.terms[NoiseTerm::white_noise] = estimate(n);
  a.terms[NoiseTerm::bias_instability] = estimate(b);
  a.terms[NoiseTerm::random_walk] = estimate(k);
  a.terms[NoiseTerm::ramp] = estimate(r);
  a.tau_min_adev_s = kTauMin;
  a.fit_tau_min_s = 0.01;
  a.fit_tau_max_s = 3000.0;
  return a;
}

models::NoiseModel one_gyro(const models::AxisModel& a) {
  models::NoiseModel m;
  m.sample_rate_hz = 200.0;
  m.axes.push_back(a);
  return m;
}

models::FilterParameterOptions each_axis(bool conservative = false) {
  models::FilterParameterOptions o;
  o.axis = models::AxisChoice::each;
  o.conservative = conservative;
  o.gm_convention = models::GmConvention::peak_match;
  o.filter_rate_hz = 1.0 / kDt;
  return o;
}

TEST(SensorStates, RandomWalkBiasIsOneStateWithQcKSquared) {
  const SensorStates s = sensor_states(one_gyro(axis("gyro_x", SensorKind::gyro, kN, kB, kK)),
                                       ins::BiasModel::random_walk, each_axis(), kDt);
  ASSERT_EQ(s.continuous.state_names, (std::vector<std::string>{"gyro_x_bias_rw_rad_per_s"}));
  EXPECT_EQ(s.continuous.F(0, 0), 0.0);
  EXPECT_LT(rel(s.continuous.Qc(0, 0), kK * kK), 1e-15);
  // B is left out, and said to be.
  ASSERT_EQ(s.dropped.size(), 1u);
  EXPECT_EQ(s.dropped[0].axis, "gyro_x");
  EXPECT_EQ(s.dropped[0].kind, DroppedTerm::Kind::gauss_markov);
  EXPECT_EQ(s.description,
            "per-axis sensor error states (theory.md §6.1); white noise is an input");
}

TEST(SensorStates, WhiteNoiseIsAnInputWithItsPerSampleSigmas) {
  const SensorStates s = sensor_states(one_gyro(axis("gyro_x", SensorKind::gyro, kN, 0.0, kK)),
                                       ins::BiasModel::random_walk, each_axis(), kDt);
  ASSERT_EQ(s.white_noise.size(), 1u);
  EXPECT_EQ(s.white_noise[0].axis, "gyro_x");
  EXPECT_EQ(s.white_noise[0].kind, SensorKind::gyro);
  EXPECT_EQ(s.white_noise[0].density, kN);
  // theory.md §6.2: σ_rate = N/√Δt (1.6455e-3 rad/s at 200 Hz, §8.2), σ_increment = N·√Δt.
  EXPECT_LT(rel(s.white_noise[0].rate_sigma, kN / std::sqrt(kDt)), 1e-15);
  EXPECT_LT(rel(s.white_noise[0].rate_sigma, 1.6455e-3), 5e-5);
  EXPECT_LT(rel(s.white_noise[0].increment_sigma, kN * std::sqrt(kDt)), 1e-15);
  EXPECT_TRUE(s.dropped.empty());  // no B, no GM: nothing left out
}

TEST(SensorStates, GaussMarkovBiasIsBAsOneGmByTheConvention) {
  const SensorStates s = sensor_states(one_gyro(axis("gyro_x", SensorKind::gyro, kN, kB, kK)),
                                       ins::BiasModel::gauss_markov, each_axis(), kDt);
  ASSERT_EQ(s.continuous.state_names,
            (std::vector<std::string>{"gyro_x_bias_instability_gm_rad_per_s"}));
  // §4.4 (b) peak match: σ = 1.075996·B, T_c = τ_min/1.892618.
  const double sigma = 1.075996 * kB, tc = kTauMin / 1.892618;
  EXPECT_LT(rel(s.continuous.F(0, 0), -1.0 / tc), 1e-6);
  EXPECT_LT(rel(s.continuous.Qc(0, 0), 2.0 * sigma * sigma / tc), 1e-5);
  EXPECT_LT(rel(s.continuous.initial_variance(0), sigma * sigma), 1e-5);
  ASSERT_EQ(s.dropped.size(), 1u);
  EXPECT_EQ(s.dropped[0].kind, DroppedTerm::Kind::random_walk);
}

TEST(SensorStates, BothBiasModelsKeepEveryTermAndTheRampIsBiasAndSlope) {
  constexpr double kR = 1e-7;  // ramp [rad/s²]
  models::AxisModel a = axis("accel_x", SensorKind::accel, 1.47e-3, 4.9e-4, 1e-4, kR);
  a.gauss_markov.push_back({{2.0e-4, 100.0}, 1.0e-4, 3.0e-4, 50.0, 200.0});
  const SensorStates s = sensor_states(one_gyro(a), ins::BiasModel::both, each_axis(), kDt);
  EXPECT_EQ(s.continuous.state_names,
            (std::vector<std::string>{"accel_x_bias_rw_m_per_s2", "accel_x_bias_gm1_m_per_s2",
                                      "accel_x_bias_instability_gm_m_per_s2",
                                      "accel_x_ramp_m_per_s2", "accel_x_ramp_slope_m_per_s3"}));
  EXPECT_TRUE(s.dropped.empty());
  // The fitted GM: F = −1/T_c, P₀ = σ².
  EXPECT_EQ(s.continuous.F(1, 1), -1.0 / 100.0);
  EXPECT_EQ(s.continuous.initial_variance(1), 2.0e-4 * 2.0e-4);
  // Ramp [bias, slope]: P₀ = diag(0, R²).
  EXPECT_EQ(s.continuous.initial_variance(3), 0.0);
  EXPECT_EQ(s.continuous.initial_variance(4), kR * kR);
  EXPECT_EQ(s.white_noise[0].kind, SensorKind::accel);
}

TEST(SensorStates, ConservativeFittedGmTakesTheUpperEndOfSigma) {
  models::AxisModel a = axis("gyro_x", SensorKind::gyro, kN, 0.0, 0.0);
  a.gauss_markov.push_back({{2.0e-5, 100.0}, 1.0e-5, 3.0e-5, 50.0, 200.0});
  const SensorStates best =
      sensor_states(one_gyro(a), ins::BiasModel::gauss_markov, each_axis(false), kDt);
  const SensorStates upper =
      sensor_states(one_gyro(a), ins::BiasModel::gauss_markov, each_axis(true), kDt);
  EXPECT_EQ(best.continuous.initial_variance(0), 2.0e-5 * 2.0e-5);
  EXPECT_EQ(upper.continuous.initial_variance(0), 3.0e-5 * 3.0e-5);
  // With the RW model the fitted GM is left out even without B.
  const SensorStates rw =
      sensor_states(one_gyro(a), ins::BiasModel::random_walk, each_axis(false), kDt);
  EXPECT_EQ(rw.continuous.states(), 0);
  ASSERT_EQ(rw.dropped.size(), 1u);
  EXPECT_EQ(rw.dropped[0].kind, DroppedTerm::Kind::gauss_markov);
}

TEST(DroppedTerms, EachBiasModelLeavesOutWhatItCannotCarry) {
  ins::SensorAxisNoise n;
  n.random_walk = kK;
  n.bias_gm = {1e-4, 10.0};
  ASSERT_EQ(dropped_terms(n, ins::BiasModel::random_walk, "gyro_y").size(), 1u);
  EXPECT_EQ(dropped_terms(n, ins::BiasModel::random_walk, "gyro_y")[0].kind,
            DroppedTerm::Kind::gauss_markov);
  EXPECT_EQ(dropped_terms(n, ins::BiasModel::random_walk, "gyro_y")[0].axis, "gyro_y");
  ASSERT_EQ(dropped_terms(n, ins::BiasModel::gauss_markov, "gyro_y").size(), 1u);
  EXPECT_EQ(dropped_terms(n, ins::BiasModel::gauss_markov, "gyro_y")[0].kind,
            DroppedTerm::Kind::random_walk);
  EXPECT_TRUE(dropped_terms(n, ins::BiasModel::both, "gyro_y").empty());
  EXPECT_TRUE(dropped_terms(ins::SensorAxisNoise{}, ins::BiasModel::random_walk, "x").empty());
}

models::NoiseModel six_axes() {
  models::NoiseModel m;
  m.sample_rate_hz = 200.0;
  for (const char* n : {"gyro_x", "gyro_y", "gyro_z"})
    m.axes.push_back(axis(n, SensorKind::gyro, kN, kB, kK));
  for (const char* n : {"accel_x", "accel_y", "accel_z"})
    m.axes.push_back(axis(n, SensorKind::accel, 1.471e-3, 4.9e-4, 1e-4));
  return m;
}

TEST(InsStates, LayoutsHaveTheSizesOfTheErrorStateModel) {
  const ins::InsSensorNoise noise = ins::ins_sensor_noise(six_axes(), ins::InsNoiseOptions{});
  const struct {
    ins::BiasModel bias;
    bool scale_factors;
    int states;
  } cases[] = {{ins::BiasModel::random_walk, false, 15},
               {ins::BiasModel::both, false, 21},
               {ins::BiasModel::random_walk, true, 21},
               {ins::BiasModel::both, true, 27}};
  for (const auto& c : cases) {
    InsStateOptions o;
    o.error_state.bias = c.bias;
    o.error_state.scale_factors = c.scale_factors;
    o.error_state.height_hold = true;
    o.dt_s = 1.0;
    const SensorStates s = ins_states(noise, o);
    EXPECT_EQ(s.continuous.states(), c.states);
    EXPECT_EQ(s.continuous.state_names[0], "att_err_n_rad");
    // The gyro-bias RW driving noise has intensity K² (§6.1).
    const int w = ins::ErrorStateLayout::kGyroBiasNoise;
    EXPECT_LT(rel(s.continuous.Qc(w, w), kK * kK), 1e-12);
    EXPECT_EQ(s.white_noise.size(), 6u);
  }
}

TEST(InsStates, WhiteNoiseGyrosThenAccelsAndDroppedTermsPerAxis) {
  const ins::InsSensorNoise noise = ins::ins_sensor_noise(six_axes(), ins::InsNoiseOptions{});
  InsStateOptions o;
  o.error_state.bias = ins::BiasModel::random_walk;
  o.latitude_deg = 30.5;
  o.height_m = 100.0;
  o.heading_deg = -10.0;
  o.dt_s = 0.01;
  const SensorStates s = ins_states(noise, o);
  const std::vector<std::string> order{"gyro_x",  "gyro_y",  "gyro_z",
                                       "accel_x", "accel_y", "accel_z"};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(s.white_noise[i].axis, order[i]);
    EXPECT_EQ(s.white_noise[i].kind, i < 3 ? SensorKind::gyro : SensorKind::accel);
  }
  EXPECT_LT(rel(s.white_noise[0].rate_sigma, kN / std::sqrt(0.01)), 1e-15);
  // Every axis has B: with the RW model each loses its GM, gyro and accel of x, then y, z.
  ASSERT_EQ(s.dropped.size(), 6u);
  const std::vector<std::string> dropped_order{"gyro_x",  "accel_x", "gyro_y",
                                               "accel_y", "gyro_z",  "accel_z"};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(s.dropped[i].axis, dropped_order[i]);
    EXPECT_EQ(s.dropped[i].kind, DroppedTerm::Kind::gauss_markov);
  }
  EXPECT_EQ(s.description,
            "INS error state (theory.md §6.3, §7.4), stationary at latitude 30.5 deg, height "
            "100 m, heading -10 deg");
  o.error_state.height_hold = true;
  EXPECT_EQ(ins_states(noise, o).description,
            "INS error state (theory.md §6.3, §7.4), stationary at latitude 30.5 deg, height "
            "100 m, heading -10 deg, vertical channel held");
}

TEST(InsStates, ScaleFactorSigmasBecomeTheirInitialVariance) {
  const ins::InsSensorNoise noise = ins::ins_sensor_noise(six_axes(), ins::InsNoiseOptions{});
  InsStateOptions o;
  o.error_state.scale_factors = true;
  o.gyro_scale_factor_sigma = 100e-6;
  o.accel_scale_factor_sigma = 300e-6;
  o.dt_s = 1.0;
  const SensorStates s = ins_states(noise, o);
  const ins::ErrorStateLayout layout = ins::error_state_layout(o.error_state);
  ASSERT_TRUE(layout.accel_scale.has_value());
  ASSERT_TRUE(layout.gyro_scale.has_value());
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(s.continuous.initial_variance(*layout.gyro_scale + i), 100e-6 * 100e-6);
    EXPECT_EQ(s.continuous.initial_variance(*layout.accel_scale + i), 300e-6 * 300e-6);
  }
}

}  // namespace
}  // namespace imunoise::pipeline
