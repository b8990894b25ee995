// Tests of pipeline/drift_analysis.h on simulated stationary recordings with known noise
// (white, random walk and a Gauss–Markov bias — terms the covariance model carries exactly):
// the NEES of the covariance prediction lies in its χ² band, the 2-D coverage matches
// 1 − e^{−k²/2} within binomial sampling error, the Monte Carlo envelope agrees with the
// covariance DRMS within its χ² interval, and the stationarity check refuses motion.
#include "pipeline/drift_analysis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "analysis/chi_square.h"
#include "common/errors.h"
#include "ins/error_state_model.h"

namespace imunoise::pipeline {
namespace {

constexpr double kLatitude = 45.0 * units::kDeg;
constexpr double kRate = 20.0;  // Hz: fast enough for 2-D drift, small enough for the test time

/// A tactical-grade-ish model so that 120-s drifts stay in the linear regime: gyro N, K and a
/// GM bias; accel N, K and a GM bias (SI).
ins::InsSensorNoise noise_model() {
  ins::InsSensorNoise n;
  for (int i = 0; i < 3; ++i) {
    n.gyro[i].white_noise = 2e-5;  // ≈ 0.07 deg/√h
    n.gyro[i].random_walk = 2e-7;
    n.gyro[i].bias_gm = {5e-6, 100.0};
    n.accel[i].white_noise = 5e-4;
    n.accel[i].random_walk = 2e-5;
    n.accel[i].bias_gm = {2e-4, 50.0};
  }
  return n;
}

/// The simulator's model of the same noise, plus (WITH_SIGNAL) the true signal of a level IMU
/// at rest at kLatitude with heading 0.
models::ImuNoiseModel simulator_model(const ins::InsSensorNoise& n, bool with_signal = true) {
  auto nominal = ins::stationary_nominal(kLatitude, 0.0, 0.0);
  if (!with_signal) {
    nominal.w_ib_b_rad_per_s.setZero();
    nominal.f_ib_b_m_per_s2.setZero();
  }
  models::ImuNoiseModel m;
  for (int i = 0; i < 3; ++i) {
    m.gyro[i].white_noise = n.gyro[i].white_noise;
    m.gyro[i].random_walk = n.gyro[i].random_walk;
    m.gyro[i].gauss_markov = {{n.gyro[i].bias_gm.sigma, n.gyro[i].bias_gm.tau_c_s}};
    m.gyro[i].constant = nominal.w_ib_b_rad_per_s(i);
    m.accel[i].white_noise = n.accel[i].white_noise;
    m.accel[i].random_walk = n.accel[i].random_walk;
    m.accel[i].gauss_markov = {{n.accel[i].bias_gm.sigma, n.accel[i].bias_gm.tau_c_s}};
    m.accel[i].constant = nominal.f_ib_b_m_per_s2(i);
  }
  return m;
}

struct Recording {
  std::array<std::vector<double>, 6> data;
  ImuSeries series() const {
    ImuSeries s;
    for (int c = 0; c < 6; ++c) s.channels[c] = data[c];
    s.sample_period_s = 1.0 / kRate;
    return s;
  }
};

Recording simulate(const ins::InsSensorNoise& n, double duration_s, std::uint64_t seed) {
  Recording r;
  const auto samples = static_cast<std::size_t>(std::llround(duration_s * kRate));
  for (auto& d : r.data) d.resize(samples);
  models::SimulationOptions so;
  so.sample_rate_hz = kRate;
  so.seed = seed;
  models::ImuSimulator simulator(simulator_model(n), so);
  simulator.next_block({std::span<double>(r.data[0]), std::span<double>(r.data[1]),
                        std::span<double>(r.data[2]), std::span<double>(r.data[3]),
                        std::span<double>(r.data[4]), std::span<double>(r.data[5])});
  return r;
}

DriftOptions options() {
  DriftOptions o;
  o.latitude_rad = kLatitude;
  o.heading_rad = 0.0;
  o.align_s = 30.0;
  o.navigation_s = 120.0;
  o.output_step_s = 1.0;
  o.report_times_s = {60.0, 120.0};
  return o;
}

TEST(DriftAnalysis, CovariancePredictionIsConsistentWithSimulatedSegments) {
  // M = 60 segments of 150 s: the 95 % band of the mean NEES is [χ²_{120}(0.025),
  // χ²_{120}(0.975)]/60 = [1.53, 2.52]; the coverage of a k-σ ellipse is binomial with
  // n = 60, so 3 binomial σ around p = 0.393 / 0.865 / 0.989 are ±0.19 / ±0.13 / ±0.04.
  const auto noise = noise_model();
  const auto rec = simulate(noise, 60 * 150.0, 7);
  const auto drift = analyze_drift(rec.series(), noise, options());
  ASSERT_EQ(drift.segments.size(), 60u);
  for (const auto& seg : drift.segments) {
    ASSERT_EQ(seg.attitude_error_ned_rad.size(), drift.time_s.size());
    ASSERT_EQ(seg.position_error_ne_m.size(), drift.time_s.size());
  }
  ASSERT_EQ(drift.consistency.size(), 2u);
  const std::array<double, 3> expected{1 - std::exp(-0.5), 1 - std::exp(-2.0), 1 - std::exp(-4.5)};
  for (const auto& c : drift.consistency) {
    std::printf(
        "t = %g s: mean NEES %.3f [%.3f, %.3f], coverage %.3f/%.3f/%.3f, RMS ratio %.3f "
        "[%.3f, %.3f], predicted DRMS %.4g m\n",
        c.time_s, c.mean_nees, c.nees_band_low, c.nees_band_high, c.coverage[0], c.coverage[1],
        c.coverage[2], c.rms_ratio, c.rms_ratio_ci_low, c.rms_ratio_ci_high, c.predicted_drms_m);
    EXPECT_TRUE(c.nees_inside) << "t = " << c.time_s << " s: mean NEES " << c.mean_nees
                               << " not in [" << c.nees_band_low << ", " << c.nees_band_high << "]";
    EXPECT_NEAR(c.nees_band_low, analysis::chi_square_quantile(0.025, 120) / 60, 1e-12);
    // Two report times: each joint band at √0.95 = 0.974679 (Šidák), wider than the per-time one.
    const double joint = std::sqrt(0.95);
    EXPECT_NEAR(c.nees_joint_band_low, analysis::chi_square_quantile((1 - joint) / 2, 120) / 60,
                1e-12);
    EXPECT_NEAR(c.nees_joint_band_high, analysis::chi_square_quantile((1 + joint) / 2, 120) / 60,
                1e-12);
    EXPECT_LT(c.nees_joint_band_low, c.nees_band_low);
    EXPECT_GT(c.nees_joint_band_high, c.nees_band_high);
    EXPECT_TRUE(c.nees_inside_joint_band);
    for (int k = 0; k < 3; ++k) {
      const double sd = std::sqrt(expected[k] * (1 - expected[k]) / 60.0);
      EXPECT_NEAR(c.coverage[k], expected[k], 3 * sd + 1.0 / 60) << "k = " << k + 1;
    }
    EXPECT_GT(c.rms_ratio_ci_high, 1.0);
    EXPECT_LT(c.rms_ratio_ci_low, 1.0);
    EXPECT_LE(c.rms_ratio_ci_low, c.rms_ratio);
    EXPECT_GE(c.rms_ratio_ci_high, c.rms_ratio);
  }
  EXPECT_TRUE(check_stationary(rec.series(), noise).stationary);
}

TEST(DriftAnalysis, MonteCarloAgreesWithTheCovarianceWhereTheModelIsLinear) {
  // 200 runs: RMS²/DRMS² ~ χ²_{400}/400 for isotropic errors, 99.9 % interval ≈ [0.79, 1.24]
  // (so RMS within [0.89, 1.11] of DRMS).
  const auto noise = noise_model();
  const auto o = options();
  const auto env = monte_carlo_drift(simulator_model(noise, false), models::FlickerBand{}, noise,
                                     1.0 / kRate, o, 200, 11);
  ins::DriftPredictionOptions p;
  p.latitude_rad = kLatitude;
  p.step_s = 1.0;
  p.times_s = env.time_s;
  p.alignment_time_s = o.align_s;
  const auto prediction = ins::predict_stationary_drift(noise, p);
  const double low = std::sqrt(analysis::chi_square_quantile(0.0005, 400) / 400);
  const double high = std::sqrt(analysis::chi_square_quantile(0.9995, 400) / 400);
  for (double t : {30.0, 60.0, 120.0}) {
    const auto i = static_cast<std::size_t>(t) - 1;
    const double ratio = env.radial_rms_m[i] / prediction.horizontal_drms_m[i];
    std::printf("t = %g s: Monte Carlo RMS %.4g m, covariance DRMS %.4g m, ratio %.3f\n", t,
                env.radial_rms_m[i], prediction.horizontal_drms_m[i], ratio);
    EXPECT_GT(ratio, low) << "t = " << t;
    EXPECT_LT(ratio, high) << "t = " << t;
    EXPECT_LT(env.radial_p50_m[i], env.radial_p95_m[i]);
  }
}

TEST(DriftAnalysis, MotionIsDetected) {
  const auto noise = noise_model();
  auto rec = simulate(noise, 600.0, 3);
  // A 5 deg/s turn about z for 10 s.
  for (std::size_t k = 4000; k < 4200; ++k) rec.data[2][k] += 5.0 * units::kDeg;
  auto check = check_stationary(rec.series(), noise);
  EXPECT_FALSE(check.stationary);
  EXPECT_NE(check.reason.find("turns"), std::string::npos) << check.reason;
  // Tilted by 5° after half the record: gravity moves between the x and z axes.
  rec = simulate(noise, 600.0, 3);
  const double g = 9.80620;
  for (std::size_t k = 6000; k < rec.data[0].size(); ++k) {
    rec.data[3][k] += g * std::sin(5.0 * units::kDeg);
    rec.data[5][k] += g * (1.0 - std::cos(5.0 * units::kDeg));
  }
  check = check_stationary(rec.series(), noise);
  EXPECT_FALSE(check.stationary);
  EXPECT_NE(check.reason.find("tilts"), std::string::npos) << check.reason;
  // Vibration: white noise 10× the model's on every accel channel.
  rec = simulate(noise, 600.0, 3);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 10 * 5e-4 * std::sqrt(kRate));
  for (std::size_t k = 0; k < 2000; ++k) rec.data[4][k] += normal(rng);
  check = check_stationary(rec.series(), noise);
  EXPECT_FALSE(check.stationary);
  EXPECT_NE(check.reason.find("accelerometer noise"), std::string::npos) << check.reason;
}

TEST(DriftAnalysis, AnAngleCounterGyroAtRestIsStationaryWhenTheModelHasItsQuantization) {
  // A tactical gyro read out as an angle counter: the angle (true rate·t plus white rate noise
  // N, integrated) rounded to a step Δ, the rate sample the difference of two counts over Δt.
  // Its per-sample scatter is that of the rounding, 2Q²/Δt² with Q = Δ/√12, far above N²/Δt;
  // a check that leaves Q out calls this recording of an IMU at rest "not stationary" (seen on
  // the tactical class of the validation battery: 3.008× the model's σ).
  auto noise = noise_model();
  auto rec = simulate(noise, 600.0, 4);
  const double dt = 1.0 / kRate;
  const double step = 2e-6;  // Δ [rad]: Q = 5.8e-7 rad, √2·Q/Δt = 1.6e-5 rad/s against N/√Δt = 9e-5
  const double large_step = 4e-5;  // Q = 1.15e-5 rad: √2·Q/Δt = 3.3e-4 rad/s, 3.6× N/√Δt
  for (int i = 0; i < 3; ++i) {
    double angle = 0.0, counted = 0.0;
    for (double& rate : rec.data[static_cast<std::size_t>(i)]) {
      angle += rate * dt;
      const double count =
          std::round(angle / (i == 0 ? large_step : step)) * (i == 0 ? large_step : step);
      rate = (count - counted) / dt;
      counted = count;
    }
  }
  const MotionCheck without_q = check_stationary(rec.series(), noise);
  EXPECT_FALSE(without_q.stationary);
  EXPECT_GT(without_q.max_gyro_std_ratio, 3.0);
  noise.gyro[0].quantization = large_step / std::sqrt(12.0);
  noise.gyro[1].quantization = noise.gyro[2].quantization = step / std::sqrt(12.0);
  const MotionCheck check = check_stationary(rec.series(), noise);
  EXPECT_TRUE(check.stationary) << check.reason;
}

TEST(DriftAnalysis, ClearErrors) {
  const auto noise = noise_model();
  const auto rec = simulate(noise, 200.0, 1);
  try {
    analyze_drift(rec.series(), noise, options());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at least 2 are needed"), std::string::npos) << e.what();
  }
  auto o = options();
  o.report_times_s = {500.0};
  EXPECT_THROW(analyze_drift(simulate(noise, 400.0, 1).series(), noise, o), InputError);
  o = options();
  o.align_s = 0.0;
  EXPECT_THROW(analyze_drift(rec.series(), noise, o), InputError);
}

// The progress callback only observes: the Monte Carlo envelope is bit-identical with it, and
// it counts the runs up to the total.
TEST(DriftAnalysis, MonteCarloProgressDoesNotChangeTheEnvelope) {
  const auto noise = noise_model();
  DriftOptions o = options();
  const auto plain = monte_carlo_drift(simulator_model(noise, false), models::FlickerBand{}, noise,
                                       1.0 / kRate, o, 6, 5);
  std::vector<std::int64_t> done_seen;
  o.progress = [&](std::string_view stage, std::int64_t done, std::int64_t total) {
    EXPECT_EQ(stage, "Monte Carlo");
    EXPECT_EQ(total, 6);
    done_seen.push_back(done);
  };
  const auto reported = monte_carlo_drift(simulator_model(noise, false), models::FlickerBand{},
                                          noise, 1.0 / kRate, o, 6, 5);
  EXPECT_EQ(done_seen, (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(plain.radial_rms_m, reported.radial_rms_m);
  EXPECT_EQ(plain.radial_p95_m, reported.radial_p95_m);
}

TEST(DriftAnalysis, RampPredictionMatchesTheDeterministicMechanization) {
  // A ramp R·t alone is deterministic: every Monte Carlo run (the simulator's ramp starts at
  // the segment's first sample, like a recording whose slope is the same in every segment)
  // aligns and navigates the same error, so its radial RMS is |e(t)|. The covariance carries
  // the slope as a state with E s² = R² and the alignment residuals ∓R·T_a/2 (leveling, bias
  // removal), so its DRMS must equal |e(t)| up to the mechanization's nonlinearity (tilts of
  // ~1e-4 rad here: ≪ 1 %) — one gyro and one accelerometer axis, separately (the covariance
  // takes independent slopes, a single deterministic slope has no partner to correlate with).
  const auto o = options();
  for (int channel : {1, 3}) {  // gyro y (east at heading 0), accel x (north)
    models::ImuNoiseModel sim;
    ins::InsSensorNoise noise;
    if (channel < 3) {
      sim.gyro[channel].ramp = 2e-8;  // rad/s²
      noise.gyro[channel].ramp = 2e-8;
    } else {
      sim.accel[channel - 3].ramp = 2e-6;  // m/s³
      noise.accel[channel - 3].ramp = 2e-6;
    }
    const auto env = monte_carlo_drift(sim, models::FlickerBand{}, noise, 1.0 / kRate, o, 2, 5);
    ins::DriftPredictionOptions p;
    p.latitude_rad = kLatitude;
    p.times_s = env.time_s;
    p.alignment_time_s = o.align_s;
    const auto prediction = ins::predict_stationary_drift(noise, p);
    for (double t : {30.0, 60.0, 120.0}) {
      const auto i = static_cast<std::size_t>(t) - 1;
      EXPECT_NEAR(prediction.horizontal_drms_m[i] / env.radial_rms_m[i], 1.0, 0.01)
          << "channel " << channel << ", t = " << t << ": covariance "
          << prediction.horizontal_drms_m[i] << " m, mechanized " << env.radial_rms_m[i] << " m";
    }
  }
}

}  // namespace
}  // namespace imunoise::pipeline
