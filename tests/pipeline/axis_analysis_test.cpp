// Tests of the per-axis analysis behind `imunoise analyze` (pipeline/axis_analysis.h) and its
// parametric bootstrap (pipeline/bootstrap.h). Coverage over many realizations is checked by
// tests/validation/fit_validation.cpp; here: single-record behaviour with known truth.
#include "pipeline/axis_analysis.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/noise_terms.h"
#include "analysis/variance_covariance.h"
#include "common/errors.h"
#include "common/units.h"
#include "models/noise_simulator.h"
#include "pipeline/bootstrap.h"
#include "test_support.h"

namespace imunoise::pipeline {
namespace {

std::vector<double> simulate(const NoiseCoefficients& truth, double rate_hz, double duration_s,
                             std::uint64_t seed) {
  models::SimulationOptions sim;
  sim.sample_rate_hz = rate_hz;
  sim.seed = seed;
  sim.flicker_band = {1.0 / rate_hz, duration_s};
  models::ChannelSimulator simulator(models::channel_model_from(truth), sim, 0);
  std::vector<double> out(static_cast<std::size_t>(std::llround(duration_s * rate_hz)));
  simulator.next_block(out);
  return out;
}

NoiseCoefficients white_rw_truth() {
  NoiseCoefficients truth;
  truth.white_noise = 0.4 * units::kDegPerSqrtHour;
  truth.random_walk = 3.9e-4 * units::kDeg;  // theory.md §8.2: crossover with white near 2 s
  return truth;
}

TEST(AxisAnalysis, WhitePlusRandomWalkIsRecoveredWithIntervalsAroundTheTruth) {
  const NoiseCoefficients truth = white_rw_truth();
  const std::vector<double> rate = simulate(truth, 50.0, 2.0 * 3600.0, 11);
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 30;
  const AxisAnalysis a = analyze_axis("gyro_x", SensorKind::gyro, rate, 0.02, 0, options);
  const auto& n = a.model.terms[static_cast<std::size_t>(NoiseTerm::white_noise)];
  const auto& k = a.model.terms[static_cast<std::size_t>(NoiseTerm::random_walk)];
  ASSERT_TRUE(n.identified);
  ASSERT_TRUE(k.identified);
  // One realization: the 95 % intervals contain the truth (a fixed seed; the coverage
  // statistics over 200 seeds are the job of fit_validation).
  EXPECT_LE(n.ci_low, truth.white_noise);
  EXPECT_GE(n.ci_high, truth.white_noise);
  EXPECT_LE(k.ci_low, truth.random_walk);
  EXPECT_GE(k.ci_high, truth.random_walk);
  // N is the best-determined term: 360 000 samples give it a relative σ well under 1 %.
  EXPECT_NEAR(n.value / truth.white_noise, 1.0, 0.03);
  EXPECT_LT(n.ci_high / n.ci_low, 1.1);
  EXPECT_NE(n.interval_method.find("bootstrap"), std::string::npos);
  // Absent terms: not identified, value 0, a finite positive upper bound.
  for (NoiseTerm term : {NoiseTerm::quantization, NoiseTerm::ramp}) {
    const auto& e = a.model.terms[static_cast<std::size_t>(term)];
    EXPECT_FALSE(e.identified) << term_name(term);
    EXPECT_EQ(e.value, 0.0);
    EXPECT_GT(e.ci_high, 0.0);  // a real (profile) upper bound, not the "no bound" 0
  }
  // The fitted model passes its own PSD cross-check, and the read-offs exist.
  ASSERT_TRUE(a.model.psd_check_pass.has_value());
  EXPECT_TRUE(*a.model.psd_check_pass) << a.model.psd_check_note;
  EXPECT_GT(a.model.readoff.slope[static_cast<std::size_t>(NoiseTerm::white_noise)], 0.0);
  EXPECT_FALSE(a.ohdev.points.empty());
}

TEST(AxisAnalysis, BiasInstabilityGetsEveryGaussMarkovConvention) {
  NoiseCoefficients truth = white_rw_truth();
  truth.bias_instability = 0.007 * units::kDeg;
  const std::vector<double> rate = simulate(truth, 20.0, 2.0 * 3600.0, 5);
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;  // least-squares intervals: fast path
  const AxisAnalysis a = analyze_axis("gyro_y", SensorKind::gyro, rate, 0.05, 1, options);
  const auto& b = a.model.terms[static_cast<std::size_t>(NoiseTerm::bias_instability)];
  ASSERT_TRUE(b.identified);
  EXPECT_NEAR(b.value / truth.bias_instability, 1.0, 0.3);
  EXPECT_NE(b.interval_method.find("least squares"), std::string::npos);
  ASSERT_EQ(a.model.bias_instability_gm.size(), 3u);
  // theory.md §8.2: the model ADEV minimum of these coefficients lies at √3·N/K ≈ 29.6 s.
  EXPECT_GT(a.model.tau_min_adev_s, 10.0);
  EXPECT_LT(a.model.tau_min_adev_s, 80.0);
  EXPECT_FALSE(a.model.multi_gm.empty());
  EXPECT_GE(a.model.multi_gm_fraction_inside_ci, 0.8);
}

TEST(AxisAnalysis, LowPassRegionIsDroppedFromTheFit) {
  NoiseCoefficients truth;
  truth.white_noise = 1e-3;
  const std::vector<double> white = simulate(truth, 100.0, 600.0, 3);
  // A 4-tap moving average (a crude anti-alias filter): AVAR at τ0 falls to 1/4 of the white
  // line and approaches it again by τ ≈ 4τ0.
  std::vector<double> filtered(white.size() - 3);
  for (std::size_t i = 0; i < filtered.size(); ++i) {
    filtered[i] = 0.25 * (white[i] + white[i + 1] + white[i + 2] + white[i + 3]);
  }
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const AxisAnalysis plain = analyze_axis("gyro_x", SensorKind::gyro, white, 0.01, 0, options);
  const AxisAnalysis low = analyze_axis("gyro_x", SensorKind::gyro, filtered, 0.01, 0, options);
  EXPECT_DOUBLE_EQ(low_pass_tau_min(plain.oadev), 0.01);
  EXPECT_GT(low_pass_tau_min(low.oadev), 0.01);
  EXPECT_GT(low.fit.tau_min_s, 0.01);
  // With the bent points dropped, N is still right (the average keeps the white level at
  // long τ): within the few-% spread of a 60 000-sample record.
  EXPECT_NEAR(low.model.terms[1].value / truth.white_noise, 1.0, 0.05);
}

TEST(AxisAnalysis, PsdCheckStopsBelowADetectedLowPassCorner) {
  // White noise through a 2nd-order Butterworth at fs/4 (bilinear, corner pre-warped; the
  // gentlest MEMS DLPF): |H|² = 1/(1 + (f/f_c)⁴), 3.6 % down at 0.44·f_c, so a check up to
  // 0.4·fs would fail on the roll-off. The corner is found from the PSD and the check stops at
  // kPsdCheckLowPassFraction of it, where the filter is 0.4 % down.
  NoiseCoefficients truth;
  truth.white_noise = 1e-3;
  const double fs = 100.0, corner = 25.0;
  const std::vector<double> white = simulate(truth, fs, 3600.0, 5);
  const double k = std::tan(std::numbers::pi * corner / fs);
  const double norm = 1.0 / (1.0 + std::numbers::sqrt2 * k + k * k);
  const double b0 = k * k * norm, a1 = 2.0 * (k * k - 1.0) * norm;
  const double a2 = (1.0 - std::numbers::sqrt2 * k + k * k) * norm;
  std::vector<double> filtered(white.size());
  double x1 = 0.0, x2 = 0.0, y1 = 0.0, y2 = 0.0;
  for (std::size_t i = 0; i < white.size(); ++i) {
    const double y = b0 * (white[i] + 2.0 * x1 + x2) - a1 * y1 - a2 * y2;
    x2 = x1;
    x1 = white[i];
    y2 = y1;
    y1 = y;
    filtered[i] = y;
  }
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const AxisAnalysis a = analyze_axis("gyro_x", SensorKind::gyro, filtered, 1.0 / fs, 0, options);
  EXPECT_NEAR(a.psd_check_low_pass_hz / corner, 1.0, 0.05);
  EXPECT_LE(a.psd_check.f_max_hz, kPsdCheckLowPassFraction * a.psd_check_low_pass_hz);
  EXPECT_NE(a.model.psd_check_note.find("up to 1/4 of the low-pass corner"), std::string::npos)
      << a.model.psd_check_note;
  for (const analysis::PsdMisfitBand& band : a.psd_check.misfits)
    EXPECT_NE(band.cause, analysis::PsdMisfitCause::low_pass) << a.model.psd_check_note;
  // The same model over the old band (up to 0.4·fs) fails on the roll-off.
  const analysis::PsdCrossCheck wide =
      analysis::cross_check_psd(a.psd, a.fit.coefficients, 1.0 / fs, 0.4 * fs);
  EXPECT_FALSE(wide.pass);
  ASSERT_FALSE(wide.misfits.empty());
  EXPECT_EQ(wide.misfits.back().cause, analysis::PsdMisfitCause::low_pass);
  // Without the low-pass check (--no-low-pass-check) the band is the full one.
  options.auto_low_pass = false;
  const AxisAnalysis off = analyze_axis("gyro_x", SensorKind::gyro, filtered, 1.0 / fs, 0, options);
  EXPECT_EQ(off.psd_check_low_pass_hz, 0.0);
  EXPECT_GT(off.psd_check.f_max_hz, 0.3 * fs);
}

TEST(AxisAnalysis, CandidateSinusoidIsFittedWithItsAmplitude) {
  NoiseCoefficients truth;
  truth.white_noise = 1e-3;
  // A 0.1 Hz line of amplitude A: its AVAR A²sin⁴(πfτ)/(πfτ)² peaks near τ = 3.7 s at
  // ≈ 0.52·A² = 5e-7, 100× the white level N²/τ there, so the fit must see it.
  truth.sinusoids.push_back({1e-3, 0.1, 0.3});
  const std::vector<double> rate = simulate(truth, 50.0, 3600.0, 9);
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  options.fit.sinusoid_frequencies_hz = {0.1};
  const AxisAnalysis a = analyze_axis("gyro_x", SensorKind::gyro, rate, 0.02, 0, options);
  ASSERT_EQ(a.model.sinusoids.size(), 1u);
  EXPECT_NEAR(std::abs(a.model.sinusoids[0].value.amplitude) / 1e-3, 1.0, 0.1);
  EXPECT_NEAR(a.model.terms[1].value / truth.white_noise, 1.0, 0.05);
}

// Without a candidate the line is found in the PSD, fitted on the samples and removed before
// the deviations. Its amplitude sd is √(C/T) = √(2N²/T) = 2.4e-5 (2.4 % of A): the estimate
// within 4 sd, the 95 % interval 2·1.96 sd wide; the frequency within 1/(4T) (its sd is
// ~√6·σ_A/(π·A·T) ≈ 2e-6 Hz). With the line gone the white-noise fit is that of white noise.
TEST(AxisAnalysis, LineIsFoundFittedAndRemovedWithoutACandidate) {
  NoiseCoefficients truth;
  truth.white_noise = 1e-3;
  truth.sinusoids.push_back({1e-3, 0.1, 0.3});
  const double duration_s = 3600.0;
  const std::vector<double> rate = simulate(truth, 50.0, duration_s, 9);
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const AxisAnalysis a = analyze_axis("gyro_x", SensorKind::gyro, rate, 0.02, 0, options);
  ASSERT_EQ(a.model.sinusoids.size(), 1u);
  const models::SinusoidEstimate& line = a.model.sinusoids[0];
  const double sd = std::sqrt(2.0 * 1e-6 / duration_s);
  EXPECT_NEAR(line.value.amplitude, 1e-3, 4.0 * sd);
  EXPECT_NEAR(line.amplitude_ci_high - line.amplitude_ci_low, 2.0 * 1.959964 * sd, 0.2 * sd);
  EXPECT_NEAR(line.value.frequency_hz, 0.1, 0.25 / duration_s);
  EXPECT_NE(a.model.fit_note.find("1 spectral line found"), std::string::npos) << a.model.fit_note;
  EXPECT_NEAR(a.model.terms[1].value / truth.white_noise, 1.0, 0.05);
  EXPECT_FALSE(a.model.terms[2].identified);  // the line's AVAR hump is not read as B
  // --no-lines: nothing searched, nothing fitted.
  options.find_lines = false;
  EXPECT_TRUE(
      analyze_axis("gyro_x", SensorKind::gyro, rate, 0.02, 0, options).model.sinusoids.empty());
}

TEST(AxisAnalysis, BadRecordsGiveClearErrors) {
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const std::vector<double> constant(1000, 0.25);
  test::expect_throw_containing<AnalysisError>(
      [&] { analyze_axis("gyro_z", SensorKind::gyro, constant, 0.01, 0, options); }, "constant");
  std::vector<double> with_nan(1000, 0.0);
  for (std::size_t i = 0; i < with_nan.size(); ++i) with_nan[i] = std::sin(0.1 * i);
  with_nan[500] = std::numeric_limits<double>::quiet_NaN();
  test::expect_throw_containing<AnalysisError>(
      [&] { analyze_axis("accel_x", SensorKind::accel, with_nan, 0.01, 0, options); },
      "sample 500");
  const std::vector<double> tiny{1.0, 2.0, 3.0};
  test::expect_throw_containing<AnalysisError>(
      [&] { analyze_axis("accel_y", SensorKind::accel, tiny, 0.01, 0, options); },
      "too few samples");
}

TEST(Bootstrap, UpperBoundOfAnAbsentTermIsAboveZeroAndBelowWhatTheDataWouldShow) {
  const NoiseCoefficients truth = white_rw_truth();
  const std::vector<double> rate = simulate(truth, 50.0, 3600.0, 21);
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const AxisAnalysis a = analyze_axis("gyro_x", SensorKind::gyro, rate, 0.02, 0, options);
  const std::vector<analysis::FitPoint> points = analysis::fit_points(a.oadev);
  const double bound = analysis::profile_upper_bound(points, a.fit, NoiseTerm::ramp, 0.95);
  ASSERT_TRUE(std::isfinite(bound));
  EXPECT_GT(bound, 0.0);
  // A ramp of the bound's size adds R²τ²/2 at the longest τ: at most the width of that point's
  // interval, i.e. of the order of the AVAR there — so the bound is not vacuous.
  const auto& last = a.oadev.points.back();
  EXPECT_LT(bound * last.tau_s / std::sqrt(2.0), 3.0 * last.value);
}

TEST(Bootstrap, UpperBoundWidensWithTheCorrelationAlongTheTermsDirection) {
  // The bound's deviance rise is χ²₁ times the variance inflation of the term's direction:
  // 1 for independent points (identity correlation), more under the model's correlation of the
  // OAVAR estimates (analysis/variance_covariance.h), which for the ramp — carried by the few,
  // strongly correlated longest-τ points — is well above 1.
  const NoiseCoefficients truth = white_rw_truth();
  const std::vector<double> rate = simulate(truth, 50.0, 3600.0, 21);
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const AxisAnalysis a = analyze_axis("gyro_x", SensorKind::gyro, rate, 0.02, 0, options);
  const std::vector<analysis::FitPoint> points = analysis::fit_points(a.oadev);
  std::vector<std::int64_t> used_m;
  for (std::size_t k : a.fit.used) used_m.push_back(a.oadev.points[k].m);
  const std::size_t n = used_m.size();
  const analysis::VarianceCovariance vc = analysis::overlapping_variance_covariance(
      a.fit.coefficients, 0.02, static_cast<std::int64_t>(rate.size()), used_m);
  std::vector<double> model(n * n), identity(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    identity[i * n + i] = 1.0;
    for (std::size_t j = 0; j < n; ++j) {
      model[i * n + j] =
          vc.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) /
          std::sqrt(vc.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) *
                    vc.covariance(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j)));
    }
  }
  const int iterations = analysis::FitOptions{}.weight_iterations;
  const double independent =
      analysis::profile_upper_bound(points, a.fit, NoiseTerm::ramp, 0.95, iterations, identity);
  const double correlated =
      analysis::profile_upper_bound(points, a.fit, NoiseTerm::ramp, 0.95, iterations, model);
  const double octaves = analysis::profile_upper_bound(points, a.fit, NoiseTerm::ramp, 0.95);
  ASSERT_TRUE(std::isfinite(independent) && std::isfinite(correlated) && std::isfinite(octaves));
  EXPECT_LT(independent, octaves);  // n_used/n_eff > 1 on the log:10 grid
  EXPECT_GT(correlated, 1.1 * independent);
  // The bound in the model (analyze_axis passes the model's correlation) is that one.
  EXPECT_DOUBLE_EQ(a.model.terms[static_cast<std::size_t>(NoiseTerm::ramp)].ci_high, correlated);
  test::expect_throw_containing<ContractViolation>(
      [&] {
        analysis::profile_upper_bound(points, a.fit, NoiseTerm::ramp, 0.95, iterations,
                                      std::vector<double>(3, 1.0));
      },
      "n_used x n_used");
}

// The progress callback (common/progress_callback.h) only observes: the same record gives
// bit-identical curves, coefficients and intervals with and without it, also with the bootstrap on
// two threads reporting concurrently. The reports cover the documented units: 4 + replicates,
// ending at done == total with stage "done".
TEST(AxisAnalysis, ProgressCallbackDoesNotChangeTheResult) {
  const std::vector<double> rate = simulate(white_rw_truth(), 50.0, 600.0, 5);
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 8;
  options.threads = 2;
  const AxisAnalysis quiet = analyze_axis("gyro_x", SensorKind::gyro, rate, 0.02, 0, options);

  std::mutex mutex;
  std::vector<std::string> stages;
  std::int64_t largest = -1, total_seen = 0, calls = 0;
  options.progress = [&](std::string_view stage, std::int64_t done, std::int64_t total) {
    std::lock_guard<std::mutex> lock(mutex);
    if (stages.empty() || stages.back() != stage) stages.emplace_back(stage);
    largest = std::max(largest, done);
    total_seen = total;
    ++calls;
  };
  const AxisAnalysis reported = analyze_axis("gyro_x", SensorKind::gyro, rate, 0.02, 0, options);

  EXPECT_EQ(total_seen, 4 + 8);
  EXPECT_EQ(largest, total_seen);
  EXPECT_EQ(calls, 6 + 8);  // 0, OADEV, OHDEV, fit, PSD, each replicate, done
  ASSERT_FALSE(stages.empty());
  EXPECT_EQ(stages.front(), "deviations");
  EXPECT_EQ(stages.back(), "done");

  ASSERT_EQ(quiet.oadev.points.size(), reported.oadev.points.size());
  for (std::size_t i = 0; i < quiet.oadev.points.size(); ++i) {
    EXPECT_EQ(quiet.oadev.points[i].value, reported.oadev.points[i].value);
    EXPECT_EQ(quiet.oadev.points[i].ci_low, reported.oadev.points[i].ci_low);
  }
  ASSERT_EQ(quiet.ohdev.points.size(), reported.ohdev.points.size());
  for (std::size_t i = 0; i < quiet.ohdev.points.size(); ++i) {
    EXPECT_EQ(quiet.ohdev.points[i].value, reported.ohdev.points[i].value);
  }
  EXPECT_EQ(quiet.psd.density, reported.psd.density);
  for (std::size_t t = 0; t < quiet.model.terms.size(); ++t) {
    EXPECT_EQ(quiet.model.terms[t].value, reported.model.terms[t].value) << t;
    EXPECT_EQ(quiet.model.terms[t].ci_low, reported.model.terms[t].ci_low) << t;
    EXPECT_EQ(quiet.model.terms[t].ci_high, reported.model.terms[t].ci_high) << t;
  }
}

}  // namespace
}  // namespace imunoise::pipeline
