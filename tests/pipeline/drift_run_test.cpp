// Tests of pipeline/drift_run.h, the drift job of `imunoise drift`, on a simulated stationary
// recording of a level IMU at rest with white + random-walk noise (terms the fitted model below
// carries exactly): the result holds what the three files need, each part agreeing with an
// independent computation from the others; refusals carry their reason and name no CLI flag
// (the CLI adds the flag); `force` runs past time gaps and motion.
#include "pipeline/drift_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/errors.h"
#include "ins/error_state_model.h"
#include "models/noise_simulator.h"

namespace imunoise::pipeline {
namespace {

constexpr double kRate = 20.0;  // Hz
constexpr double kLatitudeDeg = 45.0;
constexpr double kGyroN = 2e-5, kGyroK = 2e-7;    // rad/√s, rad/s/√s
constexpr double kAccelN = 5e-4, kAccelK = 2e-5;  // m/s/√s, m/s²/√s

/// The fitted model of the simulated noise: N and K per axis, nothing else.
models::NoiseModel fitted_model() {
  models::NoiseModel m;
  m.sensor_name = "drift run test";
  m.sample_rate_hz = kRate;
  for (int c = 0; c < 6; ++c) {
    models::AxisModel a;
    a.name = kImuChannelNames[c];
    a.kind = c < 3 ? SensorKind::gyro : SensorKind::accel;
    a.terms[NoiseTerm::white_noise].value = a.kind == SensorKind::gyro ? kGyroN : kAccelN;
    a.terms[NoiseTerm::white_noise].identified = true;
    a.terms[NoiseTerm::random_walk].value = a.kind == SensorKind::gyro ? kGyroK : kAccelK;
    a.terms[NoiseTerm::random_walk].identified = true;
    m.axes.push_back(a);
  }
  return m;
}

/// DURATION_S of the six channels at rest at kLatitudeDeg, heading 0, plus the noise of
/// fitted_model(); a sinusoid of TURN_DEG_PER_S on gyro z when not 0 (the IMU turns).
Recording simulated_recording(double duration_s, double turn_deg_per_s = 0.0) {
  const auto nominal = ins::stationary_nominal(kLatitudeDeg * units::kDeg, 0.0, 0.0);
  models::ImuNoiseModel model;
  for (int i = 0; i < 3; ++i) {
    model.gyro[i].white_noise = kGyroN;
    model.gyro[i].random_walk = kGyroK;
    model.gyro[i].constant = nominal.w_ib_b_rad_per_s(i);
    model.accel[i].white_noise = kAccelN;
    model.accel[i].random_walk = kAccelK;
    model.accel[i].constant = nominal.f_ib_b_m_per_s2(i);
  }
  if (turn_deg_per_s != 0.0) model.gyro[2].sinusoids = {{turn_deg_per_s * units::kDeg, 0.2, 0.0}};
  models::SimulationOptions so;
  so.sample_rate_hz = kRate;
  so.seed = 3;
  models::ImuSimulator simulator(model, so);
  const auto n = static_cast<std::size_t>(std::llround(duration_s * kRate));
  Recording r;
  r.source_path = "sim.csv";
  r.sample_period_s = 1.0 / kRate;
  for (int c = 0; c < 6; ++c) {
    Channel channel;
    channel.name = kImuChannelNames[c];
    channel.kind = kImuChannelKinds[c];
    channel.values.resize(n);
    r.channels.push_back(std::move(channel));
  }
  simulator.next_block(
      {std::span<double>(r.channels[0].values), std::span<double>(r.channels[1].values),
       std::span<double>(r.channels[2].values), std::span<double>(r.channels[3].values),
       std::span<double>(r.channels[4].values), std::span<double>(r.channels[5].values)});
  return r;
}

DriftRunOptions options() {
  DriftRunOptions o;
  o.location = {kLatitudeDeg, 0.0, 0.0, true};
  o.heading_rad = 0.0;
  o.align_s = 10.0;
  o.navigation_s = 20.0;
  o.report_times_s = {10.0, 20.0};
  o.monte_carlo_runs = 4;
  o.seed = 9;
  o.model_path = "model.yaml";
  return o;
}

/// The DriftRefused of F, with its reason checked; its message must name no flag.
template <class F>
std::string refusal_of(F&& f, DriftRefusal expected) {
  try {
    f();
  } catch (const DriftRefused& e) {
    EXPECT_EQ(e.reason(), expected) << e.what();
    EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no DriftRefused thrown";
  return {};
}

TEST(DriftRun, ResultHoldsWhatTheFilesNeedAndItsPartsAgree) {
  const Recording rec = simulated_recording(200.0);  // 6 segments of 30 s, 20 s left over
  const DriftResult r = run_drift(rec, fitted_model(), options());
  const DriftSummary& s = r.summary;
  EXPECT_EQ(s.recording, "sim.csv");
  EXPECT_EQ(s.model, "model.yaml");
  EXPECT_TRUE(s.location.given);
  EXPECT_EQ(s.protocol.segments, 6u);
  EXPECT_EQ(s.protocol.align_s, 10.0);
  EXPECT_EQ(s.protocol.navigation_s, 20.0);
  EXPECT_EQ(s.protocol.bias_instability_as_gm, "peak_match");
  EXPECT_FALSE(s.protocol.heading.empty());
  EXPECT_TRUE(s.motion.stationary);
  EXPECT_FALSE(s.forced);
  ASSERT_TRUE(s.monte_carlo);
  EXPECT_EQ(s.monte_carlo->runs, 4);
  EXPECT_EQ(s.monte_carlo->seed, 9u);

  const DriftSeries& e = r.series;
  ASSERT_EQ(e.time_s.size(), 20u);  // 1 s steps over 20 s
  EXPECT_EQ(e.time_s.front(), 1.0);
  EXPECT_EQ(e.time_s.back(), 20.0);
  for (const auto* v : {&e.predicted_north_sigma_m, &e.predicted_east_sigma_m, &e.predicted_drms_m,
                        &e.predicted_velocity_drms_m_per_s, &e.predicted_roll_sigma_rad,
                        &e.predicted_pitch_sigma_rad, &e.predicted_heading_sigma_rad,
                        &e.predicted_attitude_sigma_rad, &e.recorded_rms_m, &e.mc_radial_p50_m,
                        &e.mc_radial_p68_m, &e.mc_radial_p95_m, &e.mc_radial_rms_m}) {
    EXPECT_EQ(v->size(), e.time_s.size());
  }
  ASSERT_EQ(r.segments.size(), 6u);
  for (std::size_t k = 0; k < r.segments.size(); ++k) {
    EXPECT_EQ(r.segments[k].start_s, 30.0 * static_cast<double>(k));
    EXPECT_EQ(r.segments[k].time_s, e.time_s);
    EXPECT_EQ(r.segments[k].position_error_ne_m.size(), e.time_s.size());
  }
  for (std::size_t i = 0; i < e.time_s.size(); ++i) {
    double ss = 0.0;
    for (const DriftSegment& seg : r.segments) ss += seg.position_error_ne_m[i].squaredNorm();
    EXPECT_DOUBLE_EQ(e.recorded_rms_m[i], std::sqrt(ss / 6.0)) << "i = " << i;
    EXPECT_DOUBLE_EQ(e.predicted_drms_m[i],
                     std::hypot(e.predicted_north_sigma_m[i], e.predicted_east_sigma_m[i]));
    EXPECT_LE(e.mc_radial_p50_m[i], e.mc_radial_p95_m[i]);
  }
  ASSERT_EQ(s.consistency.size(), 2u);
  for (const DriftConsistency& c : s.consistency) {
    const auto i = static_cast<std::size_t>(c.time_s) - 1;
    EXPECT_EQ(c.predicted_drms_m, e.predicted_drms_m[i]);
    EXPECT_DOUBLE_EQ(c.actual_rms_m, e.recorded_rms_m[i]);
    ASSERT_TRUE(c.monte_carlo_radial_rms_m && c.monte_carlo_radial_p95_m);
    EXPECT_EQ(*c.monte_carlo_radial_rms_m, e.mc_radial_rms_m[i]);
    EXPECT_EQ(*c.monte_carlo_radial_p95_m, e.mc_radial_p95_m[i]);
  }
}

TEST(DriftRun, WithoutTheMonteCarloItsPartsAreEmpty) {
  DriftRunOptions o = options();
  o.monte_carlo_runs = 0;
  const DriftResult r = run_drift(simulated_recording(100.0), fitted_model(), o);
  EXPECT_FALSE(r.summary.monte_carlo);
  EXPECT_TRUE(r.series.mc_radial_rms_m.empty());
  for (const DriftConsistency& c : r.summary.consistency) EXPECT_FALSE(c.monte_carlo_radial_rms_m);
}

TEST(DriftRun, RefusalsSayWhatIsWrongWithoutNamingAFlag) {
  const models::NoiseModel model = fitted_model();
  DriftRunOptions o = options();
  o.monte_carlo_runs = 0;

  Recording rec = simulated_recording(100.0);
  rec.channels.erase(rec.channels.begin() + 4);  // accel_y
  EXPECT_EQ(refusal_of([&] { run_drift(rec, model, o); }, DriftRefusal::missing_channel),
            "sim.csv: drift needs all six channels; accel_y is missing");

  rec = simulated_recording(100.0);
  rec.report.timing.gap_count = 2;
  EXPECT_NE(refusal_of([&] { run_drift(rec, model, o); }, DriftRefusal::time_gaps)
                .find("sim.csv: the recording has 2 time gap(s)"),
            std::string::npos);
  o.force = true;
  EXPECT_EQ(run_drift(rec, model, o).summary.protocol.segments, 3u);
  o.force = false;

  rec = simulated_recording(100.0, 20.0);
  EXPECT_NE(refusal_of([&] { run_drift(rec, model, o); }, DriftRefusal::not_stationary)
                .find("sim.csv: the IMU is not stationary ("),
            std::string::npos);
  o.force = true;
  const DriftResult forced = run_drift(rec, model, o);
  EXPECT_FALSE(forced.summary.motion.stationary);
  EXPECT_TRUE(forced.summary.forced);
  o.force = false;

  rec = simulated_recording(50.0);  // one segment of 30 s
  EXPECT_NE(refusal_of([&] { run_drift(rec, model, o); }, DriftRefusal::too_few_segments)
                .find("at least 2 are needed"),
            std::string::npos);
}

TEST(DriftRun, ProgressReportsTheSegmentsThenTheMonteCarlo) {
  std::vector<std::string> stages;
  const ProgressCallback progress = [&](std::string_view stage, std::int64_t, std::int64_t) {
    if (stages.empty() || stages.back() != stage) stages.emplace_back(stage);
  };
  run_drift(simulated_recording(100.0), fitted_model(), options(), progress);
  EXPECT_EQ(stages, (std::vector<std::string>{"segments", "Monte Carlo"}));
}

TEST(DriftRun, BudgetRowsSumToThePredictedVarianceAtTheReportTimes) {
  const DriftResult r = run_drift(simulated_recording(200.0), fitted_model(), options());
  // The report times flagged, in order, among a log-spaced grid that ends at the navigation
  // end (for the stacked plot).
  std::vector<double> flagged;
  for (std::size_t k = 0; k < r.budget.time_s.size(); ++k)
    if (r.budget.report_time[k]) flagged.push_back(r.budget.time_s[k]);
  std::vector<double> report;
  for (const DriftConsistency& c : r.summary.consistency) report.push_back(c.time_s);
  EXPECT_EQ(flagged, report);
  EXPECT_GT(r.budget.time_s.size(), report.size());
  EXPECT_TRUE(std::is_sorted(r.budget.time_s.begin(), r.budget.time_s.end()));
  EXPECT_EQ(r.budget.time_s.back(), r.series.time_s.back());
  for (std::size_t k = 0; k < r.budget.time_s.size(); ++k) {
    const auto i = static_cast<std::size_t>(
        std::find(r.series.time_s.begin(), r.series.time_s.end(), r.budget.time_s[k]) -
        r.series.time_s.begin());
    ASSERT_LT(i, r.series.time_s.size());
    const double drms = r.series.predicted_drms_m[i];
    EXPECT_DOUBLE_EQ(r.budget.predicted_variance_m2[k], drms * drms);
    double sum = 0.0;
    for (const double v : r.budget.variance_m2[k]) sum += v;
    EXPECT_NEAR(sum / (drms * drms), 1.0, 1e-9);
    // White + RW model, heading given exactly: no ramp, no heading, no B contribution.
    EXPECT_EQ(r.budget.variance_m2[k][static_cast<std::size_t>(ins::DriftBudgetTerm::ramp)], 0.0);
    EXPECT_EQ(r.budget.variance_m2[k][static_cast<std::size_t>(ins::DriftBudgetTerm::heading)],
              0.0);
  }
}

TEST(DriftRun, HoldoutFitsTheFirstHalfAndJudgesTheSecond) {
  // 600 s at 20 Hz, segments of 10 + 20 s: 10 per half. The first half is fitted by
  // analyze_recording() (its defaults, bootstrap included); its prediction must be close to
  // that of the true model: at 20 s the variance is ≥ 90 % gyro white noise (g·N_g t^{5/2}
  // /√20 and its alignment residual g·(N_g/√T_a)·t³/6), whose fitted N has a relative σ of
  // ~1/√(2·3000) ≈ 1.3 % from 6000 samples; 15 % leaves room for K, which 300 s cannot pin
  // down, at its ≤ 10 % share. The segments judged are the 10 of the second half.
  const Recording recording = simulated_recording(600.0);
  DriftRunOptions o = options();
  o.monte_carlo_runs = 0;
  o.holdout_half = true;
  o.holdout_analysis.axis.bootstrap_replicates = 20;
  const DriftResult r = run_drift(recording, fitted_model(), o);
  ASSERT_TRUE(r.summary.holdout.has_value());
  const DriftHoldout& h = *r.summary.holdout;
  EXPECT_EQ(h.segments, 10u);
  EXPECT_EQ(r.summary.protocol.segments, 20u);
  EXPECT_NE(h.fitted_on.find("first half: samples 0 ... 5999"), std::string::npos) << h.fitted_on;
  EXPECT_NE(h.judged_on.find("second half: samples 6000 ... 11999"), std::string::npos)
      << h.judged_on;
  ASSERT_EQ(h.consistency.size(), r.summary.consistency.size());
  for (std::size_t k = 0; k < h.consistency.size(); ++k) {
    const DriftConsistency& held = h.consistency[k];
    const DriftConsistency& same = r.summary.consistency[k];
    EXPECT_EQ(held.time_s, same.time_s);
    EXPECT_NEAR(held.predicted_drms_m / same.predicted_drms_m, 1.0, 0.15) << held.time_s;
    EXPECT_FALSE(held.monte_carlo_radial_rms_m.has_value());
    EXPECT_GT(held.actual_rms_m, 0.0);
    // The band is that of M = 10 segments: χ²_{20} 2.5 % quantile 9.591 (printed tables) / 10.
    EXPECT_NEAR(held.nees_band_low, 0.9591, 1e-4);
  }
  o.holdout_half = false;
  EXPECT_FALSE(run_drift(recording, fitted_model(), o).summary.holdout.has_value());
}

}  // namespace
}  // namespace imunoise::pipeline
