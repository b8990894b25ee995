/// @file
/// @brief Tests of analysis/noise_fit.h.
///
/// Exact-curve tests fit closed-form model curves (noise_terms.h) and must return the model to
/// rounding. Simulated tests generate a channel with models::ChannelSimulator (whose OAVAR
/// matches the closed forms in expectation), compute OADEV on a log:10 grid and fit it with
/// fixed seeds; their tolerances come from the seed study quoted at each test (spread of the
/// estimate over independent seeds), at about 3–4 standard deviations.
#include "analysis/noise_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "analysis/confidence.h"
#include "analysis/deviation.h"
#include "analysis/edf.h"
#include "analysis/tau_grid.h"
#include "common/errors.h"
#include "models/noise_simulator.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

constexpr std::size_t kQ = 0, kN = 1, kB = 2, kK = 3, kR = 4;  // TermFit indices

/// @name Worked example, theory.md §8.2 (SI)
/// @{
constexpr double kExampleN = 1.16355e-4;  // [rad/√s]
constexpr double kExampleB = 1.22173e-4;  // [rad/s]
constexpr double kExampleK = 6.80678e-6;  // [rad/s^{3/2}]
/// @}

/// Exact-curve points on τ = 10^(k/10) s, k = K0 … K1, with a white-FM-like EDF
/// ν = 1.5·T/τ for a T = 10⁵ s record (only its relative size matters here).
std::vector<FitPoint> exact_points(const NoiseCoefficients& model, int k0, int k1,
                                   bool hadamard = false) {
  std::vector<FitPoint> points;
  for (int k = k0; k <= k1; ++k) {
    const double tau = std::pow(10.0, k / 10.0);
    points.push_back(
        {tau, hadamard ? model_hvar(model, tau) : model_avar(model, tau), 1.5e5 / tau});
  }
  return points;
}

/// OADEV points of a simulated channel: DURATION_S at RATE_HZ, seed SEED, log:10 grid.
std::vector<FitPoint> simulated_points(const models::ChannelNoiseModel& model, double rate_hz,
                                       double duration_s, std::uint64_t seed) {
  models::SimulationOptions options;
  options.sample_rate_hz = rate_hz;
  options.seed = seed;
  options.flicker_band = {1.0 / rate_hz, 10.0 * duration_s};
  models::ChannelSimulator simulator(model, options, 0);
  std::vector<double> rate(static_cast<std::size_t>(duration_s * rate_hz));
  simulator.next_block(rate);
  const double tau0 = 1.0 / rate_hz;
  const std::vector<double> phase = phase_from_rate(rate, tau0);
  const auto factors = averaging_factors(parse_tau_grid("log:10"), DeviationType::oadev,
                                         static_cast<std::int64_t>(phase.size()));
  DeviationOptions deviation_options;
  deviation_options.type = DeviationType::oadev;
  return fit_points(compute_deviation(phase, tau0, factors, deviation_options));
}

// ---------------------------------------------------------------------------------------------
// Exact curves

TEST(NoiseFit, RecoversAllFivePowerLawTermsFromAnExactCurve) {
  NoiseCoefficients truth;
  truth.quantization = 1e-5;  // dominates below ~0.03 s
  truth.white_noise = 1e-4;
  truth.bias_instability = 1e-4;  // floor from ~2 s
  truth.random_walk = 1.15e-5;    // from ~100 s
  truth.ramp = 2.1e-7;            // from ~2000 s
  const auto points = exact_points(truth, -20, 40);
  const FitResult fit = fit_noise_model(points);
  for (NoiseTerm term : kNoiseTerms) {
    const auto i = static_cast<std::size_t>(term);
    EXPECT_TRUE(fit.terms[i].identified) << term_name(term);
    EXPECT_NEAR(fit.terms[i].value / coefficient(truth, term), 1.0, 1e-6) << term_name(term);
    EXPECT_NEAR(coefficient(fit.coefficients, term), fit.terms[i].value, 0.0);
    EXPECT_GT(fit.terms[i].contribution, 0.4) << term_name(term);  // each dominates somewhere
  }
  EXPECT_EQ(fit.parameters, 5);
  EXPECT_EQ(fit.used.size(), points.size());
  EXPECT_LT(fit.weighted_sse, 1e-12);
  for (double r : fit.residual_halfwidths) EXPECT_NEAR(r, 0.0, 1e-6);
  // Nothing dropped; the default (automatic) GM fit found no GM term to compare.
  EXPECT_EQ(fit.selection_note, "no Gauss-Markov term identified");
}

TEST(NoiseFit, AbsentTermsOfAnExactCurveAreZeroAndNotIdentified) {
  NoiseCoefficients truth;
  truth.white_noise = kExampleN;
  truth.random_walk = kExampleK;
  const FitResult fit = fit_noise_model(exact_points(truth, -20, 35));
  EXPECT_NEAR(fit.coefficients.white_noise / kExampleN, 1.0, 1e-6);
  EXPECT_NEAR(fit.coefficients.random_walk / kExampleK, 1.0, 1e-6);
  for (std::size_t i : {kQ, kB, kR}) {
    EXPECT_FALSE(fit.terms[i].identified) << i;
    EXPECT_EQ(fit.terms[i].value, 0.0) << i;
  }
  EXPECT_EQ(fit.coefficients.quantization, 0.0);
  EXPECT_EQ(fit.coefficients.bias_instability, 0.0);
  EXPECT_EQ(fit.coefficients.ramp, 0.0);
  EXPECT_EQ(fit.parameters, 2);
}

TEST(NoiseFit, RecoversGaussMarkovSigmaAndCorrelationTimeFromAnExactCurve) {
  NoiseCoefficients truth;
  truth.white_noise = 2e-4;
  truth.random_walk = 5e-6;  // K²τ/3 overtakes the GM's 2σ²T_c/τ tail at ~1500 s
  truth.gauss_markov = {{1e-3, 30.0}};
  FitOptions options;
  options.gauss_markov = GaussMarkovMode::on;
  const FitResult fit = fit_noise_model(exact_points(truth, -20, 35), options);
  ASSERT_EQ(fit.coefficients.gauss_markov.size(), 1u) << fit.selection_note;
  EXPECT_NEAR(fit.coefficients.gauss_markov[0].sigma / 1e-3, 1.0, 1e-6);
  EXPECT_NEAR(fit.coefficients.gauss_markov[0].tau_c_s / 30.0, 1.0, 1e-6);
  EXPECT_NEAR(fit.coefficients.white_noise / 2e-4, 1.0, 1e-6);
  EXPECT_NEAR(fit.coefficients.random_walk / 5e-6, 1.0, 1e-6);
  EXPECT_FALSE(fit.terms[kB].identified);
  EXPECT_FALSE(fit.terms[kQ].identified);
  EXPECT_FALSE(fit.terms[kR].identified);
  EXPECT_EQ(fit.parameters, 4) << fit.selection_note;
}

TEST(NoiseFit, RecoversTwoGaussMarkovTermsFromAnExactCurve) {
  NoiseCoefficients truth;
  truth.white_noise = 1e-4;
  truth.gauss_markov = {{5e-4, 2.0}, {3e-4, 300.0}};
  FitOptions options;
  options.gauss_markov = GaussMarkovMode::on;
  options.allow_terms = {false, true, false, true, false};
  const FitResult fit = fit_noise_model(exact_points(truth, -20, 38), options);
  ASSERT_EQ(fit.coefficients.gauss_markov.size(), 2u) << fit.selection_note;
  for (std::size_t j = 0; j < 2; ++j) {
    EXPECT_NEAR(fit.coefficients.gauss_markov[j].sigma / truth.gauss_markov[j].sigma, 1.0, 1e-6);
    EXPECT_NEAR(fit.coefficients.gauss_markov[j].tau_c_s / truth.gauss_markov[j].tau_c_s, 1.0,
                1e-6);
  }
}

TEST(NoiseFit, FitsSinusoidAmplitudeAtCandidateFrequencies) {
  NoiseCoefficients truth;
  truth.white_noise = 1e-4;
  truth.sinusoids = {{2e-3, 0.05, 0.0}};
  FitOptions options;
  options.sinusoid_frequencies_hz = {0.05, 1.3};  // the second is absent
  const FitResult fit = fit_noise_model(exact_points(truth, -20, 30), options);
  ASSERT_EQ(fit.coefficients.sinusoids.size(), 1u) << fit.selection_note;
  EXPECT_EQ(fit.coefficients.sinusoids[0].frequency_hz, 0.05);
  EXPECT_NEAR(fit.coefficients.sinusoids[0].amplitude / 2e-3, 1.0, 1e-6);
  EXPECT_NEAR(fit.coefficients.white_noise / 1e-4, 1.0, 1e-6);
  EXPECT_NE(fit.selection_note.find("sinusoid(1.3 Hz)"), std::string::npos) << fit.selection_note;
}

TEST(NoiseFit, HadamardModeUsesTheHvarBasis) {
  NoiseCoefficients truth;
  truth.quantization = 1e-5;
  truth.white_noise = 1e-4;
  truth.bias_instability = 1e-4;
  truth.random_walk = 1.15e-5;
  FitOptions options;
  options.hadamard = true;
  const FitResult fit = fit_noise_model(exact_points(truth, -20, 40, true), options);
  EXPECT_TRUE(fit.hadamard);
  for (std::size_t i : {kQ, kN, kB, kK})
    EXPECT_NEAR(fit.terms[i].value / coefficient(truth, kNoiseTerms[i]), 1.0, 1e-6) << i;
  EXPECT_FALSE(fit.terms[kR].identified);
  EXPECT_NE(fit.selection_note.find("ramp not fitted"), std::string::npos);
}

TEST(NoiseFit, TauRangeAndEdfFiltersSelectThePoints) {
  NoiseCoefficients truth;
  truth.white_noise = 1e-4;
  truth.random_walk = 1e-5;
  auto points = exact_points(truth, -20, 40);
  points[3].edf = 2.0;   // below min_edf
  points[5].edf = -1.0;  // unknown
  FitOptions options;
  options.tau_min_s = 0.05;
  options.tau_max_s = 500.0;
  const FitResult fit = fit_noise_model(points, options);
  for (std::size_t k : fit.used) {
    EXPECT_GE(points[k].tau_s, 0.05);
    EXPECT_LE(points[k].tau_s, 500.0);
    EXPECT_GE(points[k].edf, 4.0);
  }
  EXPECT_GE(fit.tau_min_s, 0.05);
  EXPECT_LE(fit.tau_max_s, 500.0);
  EXPECT_EQ(fit.residual_halfwidths.size(), points.size());
  EXPECT_TRUE(std::isnan(fit.residual_halfwidths[5]));
  EXPECT_NEAR(fit.coefficients.white_noise / 1e-4, 1.0, 1e-6);
}

TEST(NoiseFit, ResidualsAreInCiHalfWidthsOnTheModelSide) {
  NoiseCoefficients truth;
  truth.white_noise = 1e-4;
  auto points = exact_points(truth, 0, 20);
  for (auto& p : points) p.edf = 50.0;
  points[10].avar *= 1.5;  // one point high: its residual is positive, the others ~0
  const FitResult fit = fit_noise_model(points);
  const double model = std::sqrt(model_avar(fit.coefficients, points[10].tau_s));
  const double measured = std::sqrt(points[10].avar);
  const DeviationInterval ci = deviation_interval(measured, 50.0, 0.95);
  EXPECT_NEAR(fit.residual_halfwidths[10], (measured - model) / (measured - ci.low), 1e-12);
  EXPECT_GT(fit.residual_halfwidths[10], 1.0);
}

TEST(NoiseFit, ArbitraryPositiveCurvesGiveFiniteNonNegativeCoefficients) {
  // Robustness: random positive variances (log-uniform over 6 decades) and EDFs; the fit must
  // return finite coefficients ≥ 0 (never NaN), with or without GM terms.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> log_value(-12.0, -6.0), log_edf(0.5, 5.0);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<FitPoint> points;
    for (int k = -10; k <= 30; ++k)
      points.push_back(
          {std::pow(10.0, k / 10.0), std::pow(10.0, log_value(rng)), std::pow(10.0, log_edf(rng))});
    FitOptions options;
    options.gauss_markov = trial % 2 == 0 ? GaussMarkovMode::on : GaussMarkovMode::off;
    const FitResult fit = fit_noise_model(points, options);
    for (NoiseTerm term : kNoiseTerms) {
      const double c = coefficient(fit.coefficients, term);
      EXPECT_TRUE(std::isfinite(c) && c >= 0.0) << trial << " " << term_name(term);
    }
    for (const GaussMarkov& gm : fit.coefficients.gauss_markov)
      EXPECT_TRUE(std::isfinite(gm.sigma) && gm.sigma > 0.0 && gm.tau_c_s > 0.0) << trial;
    EXPECT_TRUE(std::isfinite(fit.weighted_sse) && std::isfinite(fit.deviance)) << trial;
  }
}

TEST(NoiseFit, FitPointsCapsTheEdfOfMisidentifiedLongTauPoints) {
  // A point at m = 10⁴ of M = 3.6·10⁵ whose noise identification fell back to white PM
  // (alpha 2) carries an EDF of order M; fit_points caps it at the white-FM value.
  DeviationCurve curve;
  curve.type = DeviationType::oadev;
  curve.tau0_s = 0.01;
  curve.n_phase = 360001;
  DeviationPoint p;
  p.m = 10000;
  p.tau_s = 100.0;
  p.value = 1e-5;
  p.alpha = 2;
  p.edf = edf_for(DeviationType::oadev, 2, p.m, curve.n_phase);
  curve.points.push_back(p);
  p.m = 1;
  p.tau_s = 0.01;
  p.alpha = 0;
  p.edf = edf_for(DeviationType::oadev, 0, p.m, curve.n_phase);
  curve.points.push_back(p);
  const std::vector<FitPoint> points = fit_points(curve);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_GT(curve.points[0].edf, 1e5);
  EXPECT_NEAR(points[0].edf, edf_for(DeviationType::oadev, 0, 10000, curve.n_phase), 1e-9);
  EXPECT_LT(points[0].edf, 100.0);
  EXPECT_EQ(points[1].edf, curve.points[1].edf);  // a white-FM EDF is left alone
  EXPECT_DOUBLE_EQ(points[0].avar, 1e-10);
  curve.type = DeviationType::mdev;
  test::expect_throw_containing<ContractViolation>([&] { fit_points(curve); }, "not mdev");
}

// ---------------------------------------------------------------------------------------------
// Refit and multi-GM

TEST(NoiseFit, RefitWithTheFitsOwnStructureReproducesTheFit) {
  NoiseCoefficients truth;
  truth.white_noise = 2e-4;
  truth.random_walk = 5e-6;
  truth.gauss_markov = {{1e-3, 30.0}};
  auto points = exact_points(truth, -20, 35);
  FitOptions options;
  options.gauss_markov = GaussMarkovMode::on;
  const FitResult fit = fit_noise_model(points, options);
  // Same points: same estimate (the GM T_c is re-searched from the structure's value).
  const FitResult same = refit_fixed_terms(points, fit, options);
  EXPECT_EQ(same.used, fit.used);
  // To the T_c search's stopping width (1e-6 in ln T_c; the coefficients follow T_c linearly).
  EXPECT_NEAR(same.coefficients.white_noise / fit.coefficients.white_noise, 1.0, 1e-6);
  EXPECT_NEAR(same.coefficients.random_walk / fit.coefficients.random_walk, 1.0, 1e-6);
  ASSERT_EQ(same.coefficients.gauss_markov.size(), 1u);
  EXPECT_NEAR(same.coefficients.gauss_markov[0].tau_c_s / 30.0, 1.0, 1e-6);
  // Different data, same structure: no selection, T_c follows the data within ±1/3 decade.
  NoiseCoefficients other = truth;
  other.gauss_markov = {{1.2e-3, 40.0}};
  other.white_noise = 1e-4;
  const auto other_points = exact_points(other, -20, 35);
  const FitResult refit = refit_fixed_terms(other_points, fit, options);
  ASSERT_EQ(refit.coefficients.gauss_markov.size(), 1u);
  EXPECT_NEAR(refit.coefficients.gauss_markov[0].tau_c_s / 40.0, 1.0, 1e-6);
  EXPECT_NEAR(refit.coefficients.gauss_markov[0].sigma / 1.2e-3, 1.0, 1e-6);
  EXPECT_NEAR(refit.coefficients.white_noise / 1e-4, 1.0, 1e-6);
  EXPECT_FALSE(refit.terms[kB].identified);
  EXPECT_EQ(refit.selection_note, "");
}

TEST(NoiseFit, RefitRejectsAStructureThatDoesNotMatchThePoints) {
  NoiseCoefficients truth;
  truth.white_noise = 1e-4;
  const auto points = exact_points(truth, 0, 20);
  const FitResult fit = fit_noise_model(points);
  const std::vector<FitPoint> fewer(points.begin(), points.begin() + 5);
  test::expect_throw_containing<ContractViolation>([&] { refit_fixed_terms(fewer, fit, {}); },
                                                   "out of range");
}

// ---------------------------------------------------------------------------------------------
// Simulated recordings (ChannelSimulator → OADEV, log:10 grid). Spreads quoted are the mean ±
// standard deviation of estimate/truth over seeds 1–100 (GM: 1–60) of the same configuration,
// measured with this estimator; tolerances are ≥ 3 standard deviations.

TEST(NoiseFit, SimulatedWhiteAndRandomWalk) {
  // §8 N and K, 2 h at 100 Hz. Seed study: N 1.0001 ± 0.0009, K 0.993 ± 0.082; K identified
  // in 100/100 seeds, one of Q, B, R wrongly kept in 1/100.
  models::ChannelNoiseModel model;
  model.white_noise = kExampleN;
  model.random_walk = kExampleK;
  FitOptions power_law;  // the automatic GM choice on this truth: AutomaticGaussMarkov… below
  power_law.gauss_markov = GaussMarkovMode::off;
  const FitResult fit = fit_noise_model(simulated_points(model, 100.0, 7200.0, 3), power_law);
  EXPECT_NEAR(fit.coefficients.white_noise / kExampleN, 1.0, 0.02);
  EXPECT_NEAR(fit.coefficients.random_walk / kExampleK, 1.0, 0.25);
  EXPECT_TRUE(fit.terms[kK].identified);
  EXPECT_FALSE(fit.terms[kQ].identified) << fit.selection_note;
  EXPECT_FALSE(fit.terms[kB].identified) << fit.selection_note;
  EXPECT_FALSE(fit.terms[kR].identified) << fit.selection_note;
}

TEST(NoiseFit, SimulatedWhiteFlickerAndRandomWalkWithMultiGmRepresentation) {
  // §8 N, B, K, 2 h at 100 Hz. Seed study: N 0.9999 ± 0.0009, B 1.004 ± 0.017 (identified
  // 100/100); K is weak here (the RRW line only crosses the floor at 426 s, the record ends at
  // 1800 s): 0.60 ± 0.58, often not identified. Multi-GM replacement of B: on average 99.7 % of
  // the fitted points inside their 95 % CI.
  models::ChannelNoiseModel model;
  model.white_noise = kExampleN;
  model.bias_instability = kExampleB;
  model.random_walk = kExampleK;
  const auto points = simulated_points(model, 100.0, 7200.0, 5);
  const FitResult fit = fit_noise_model(points);
  EXPECT_NEAR(fit.coefficients.white_noise / kExampleN, 1.0, 0.02);
  ASSERT_TRUE(fit.terms[kB].identified);
  EXPECT_NEAR(fit.coefficients.bias_instability / kExampleB, 1.0, 0.15);
  EXPECT_FALSE(fit.terms[kQ].identified) << fit.selection_note;
  EXPECT_GT(fraction_inside_ci(points, fit.used, fit.coefficients), 0.9);

  const std::vector<GaussMarkov> gms = multi_gm_representation(points, fit);
  EXPECT_GE(gms.size(), 2u);
  NoiseCoefficients replaced = fit.coefficients;
  replaced.bias_instability = 0.0;
  replaced.gauss_markov.insert(replaced.gauss_markov.end(), gms.begin(), gms.end());
  EXPECT_GE(fraction_inside_ci(points, fit.used, replaced), 0.95);
  for (const GaussMarkov& gm : gms) {
    EXPECT_GE(gm.tau_c_s, fit.tau_min_s * (1.0 - 1e-12));
    EXPECT_LE(gm.tau_c_s, fit.tau_max_s * (1.0 + 1e-12));
    // One GM per decade stands for flicker with σ² ≈ B²·ln10/π each (noise_simulator.h).
    EXPECT_LT(gm.sigma, 3.0 * kExampleB * std::sqrt(std::log(10.0) / std::numbers::pi));
  }
  // Without B there is nothing to replace.
  FitResult no_b = fit;
  no_b.terms[kB] = {};
  no_b.coefficients.bias_instability = 0.0;
  EXPECT_TRUE(multi_gm_representation(points, no_b).empty());
}

TEST(NoiseFit, SimulatedWhiteAndGaussMarkov) {
  // N = 5e-4 rad/√s, GM σ = 1e-3 rad/s, T_c = 30 s, 2 h at 100 Hz, GM mode on. Seed study:
  // σ 1.000 ± 0.054, T_c 1.005 ± 0.114 (largest-σ GM); exactly one GM in 59/60 seeds.
  models::ChannelNoiseModel model;
  model.white_noise = 5e-4;
  model.gauss_markov = {{1e-3, 30.0}};
  FitOptions options;
  options.gauss_markov = GaussMarkovMode::on;
  const FitResult fit = fit_noise_model(simulated_points(model, 100.0, 7200.0, 2), options);
  ASSERT_EQ(fit.coefficients.gauss_markov.size(), 1u) << fit.selection_note;
  EXPECT_NEAR(fit.coefficients.gauss_markov[0].sigma / 1e-3, 1.0, 0.2);
  EXPECT_NEAR(fit.coefficients.gauss_markov[0].tau_c_s / 30.0, 1.0, 0.35);
  EXPECT_NEAR(fit.coefficients.white_noise / 5e-4, 1.0, 0.02);
  EXPECT_FALSE(fit.terms[kB].identified) << fit.selection_note;
  EXPECT_FALSE(fit.terms[kK].identified) << fit.selection_note;
  EXPECT_EQ(fit.parameters, 3);
}

TEST(NoiseFit, AutomaticGaussMarkovModeKeepsGmTermsWhereTheDataShowThem) {
  // The default mode fits the power-law model and the model with GM terms apart and keeps the
  // lower penalized deviance (GaussMarkovMode::automatic). Seed study, seeds 1–100, 2 h at
  // 100 Hz: N + GM (σ 1e-3 rad/s, T_c 30 s) GM kept 100/100 (one GM in 99, mean σ/σ_true 1.005,
  // T_c/T_c,true 1.013), B or K never; N + K (§8) GM kept 2/100 (T_c ≈ 195 s standing in for
  // K, seeds 3 and 55), K 98/100; N + B + K GM 0/100; white only (1 h) GM 0/100. Bounds below
  // from those rates: P(> 2 of 20 | p = 0.02) = 0.7 %, P(< 9 of 10 | p = 0.99) = 0.4 %.
  models::ChannelNoiseModel with_gm;
  with_gm.white_noise = 5e-4;
  with_gm.gauss_markov = {{1e-3, 30.0}};
  int gm_kept = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const FitResult fit = fit_noise_model(simulated_points(with_gm, 100.0, 7200.0, seed));
    gm_kept += fit.coefficients.gauss_markov.size() == 1;
    EXPECT_FALSE(fit.terms[kB].identified || fit.terms[kK].identified) << fit.selection_note;
  }
  EXPECT_GE(gm_kept, 9);
  models::ChannelNoiseModel random_walk;
  random_walk.white_noise = kExampleN;
  random_walk.random_walk = kExampleK;
  int false_gm = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const FitResult fit = fit_noise_model(simulated_points(random_walk, 100.0, 7200.0, seed));
    false_gm += !fit.coefficients.gauss_markov.empty();
    EXPECT_NE(fit.selection_note.find("Gauss-Markov "), std::string::npos);
  }
  EXPECT_LE(false_gm, 2);
  models::ChannelNoiseModel white;
  white.white_noise = kExampleN;
  int white_gm = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed)
    white_gm += !fit_noise_model(simulated_points(white, 100.0, 3600.0, seed))
                     .coefficients.gauss_markov.empty();
  EXPECT_EQ(white_gm, 0);
}

TEST(NoiseFit, ARampGivesWayToARandomWalkOnlyWhereTheyFitAlike) {
  // After the elimination a ramp without K is replaced by K when K fits within a third of a
  // parameter's penalty. Seed study, seeds 1–100, 2 h at 100 Hz, default options: N + B + K
  // (§8) R kept in 7/100 before the rule, 1/100 with it (6 swaps, rises −1.1 … 6.5); the
  // ramp truth of SimulatedQuantizationWhiteAndRamp R kept 99/100 before, 90/100 with it
  // (rises of the 9 swapped −13 … 9.1, of the kept mostly 12–32). Bounds: P(≥ 3 of 30 |
  // p = 0.01) = 0.3 %, P(≤ 22 of 30 | p = 0.9) = 0.8 %.
  models::ChannelNoiseModel walk;
  walk.white_noise = kExampleN;
  walk.bias_instability = kExampleB;
  walk.random_walk = kExampleK;
  models::ChannelNoiseModel ramp;
  ramp.quantization = 1e-4;
  ramp.white_noise = 1e-4;
  ramp.ramp = 2.7e-8;
  // The rule acts in the power-law selection, so the GM candidate (the costly half of the
  // default fit, 35x slower under the sanitizers) is left out here; the seed study above is
  // of the default mode.
  FitOptions power_law;
  power_law.gauss_markov = GaussMarkovMode::off;
  int false_ramps = 0, ramps_kept = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const FitResult w = fit_noise_model(simulated_points(walk, 100.0, 7200.0, seed), power_law);
    false_ramps += w.terms[kR].identified;
    if (w.selection_note.find("ramp replaced by random_walk") != std::string::npos) {
      EXPECT_TRUE(w.terms[kK].identified && !w.terms[kR].identified) << w.selection_note;
    }
    ramps_kept += fit_noise_model(simulated_points(ramp, 100.0, 7200.0, seed), power_law)
                      .terms[kR]
                      .identified;
  }
  EXPECT_LE(false_ramps, 2);
  EXPECT_GE(ramps_kept, 23);
}

TEST(NoiseFit, SimulatedQuantizationWhiteAndRamp) {
  // Q = 1e-4 rad, N = 1e-4 rad/√s, R = 2.7e-8 rad/s² (crossovers ~3 s and ~300 s), 2 h at
  // 100 Hz. Seed study: Q 1.000 ± 0.001, N 1.000 ± 0.009, R 0.99 ± 0.11 (the ramp rises over
  // the last 0.8 decade only, where it competes with K: in 10/100 seeds K is kept instead,
  // 9 of them by the ramp-to-walk rule, see ARampGivesWayToARandomWalkOnlyWhereTheyFitAlike).
  models::ChannelNoiseModel model;
  model.quantization = 1e-4;
  model.white_noise = 1e-4;
  model.ramp = 2.7e-8;
  const FitResult fit = fit_noise_model(simulated_points(model, 100.0, 7200.0, 1));
  EXPECT_NEAR(fit.coefficients.quantization / 1e-4, 1.0, 0.02);
  EXPECT_NEAR(fit.coefficients.white_noise / 1e-4, 1.0, 0.05);
  ASSERT_TRUE(fit.terms[kR].identified) << fit.selection_note;
  EXPECT_NEAR(fit.coefficients.ramp / 2.7e-8, 1.0, 0.35);
  EXPECT_FALSE(fit.terms[kB].identified) << fit.selection_note;
  EXPECT_FALSE(fit.terms[kK].identified) << fit.selection_note;
}

TEST(NoiseFit, ModelSelectionRejectsAbsentTermsInWhiteNoise) {
  // White noise only, 1 h at 100 Hz, seeds 1–10: count the seeds in which any of Q, B, K, R
  // is identified. Seed study over 600 seeds: 4 (0.7 %) with kSelectionThreshold = 12
  // (κ = 6.6: 4.0 %, κ = 9: 2.0 %).
  models::ChannelNoiseModel model;
  model.white_noise = kExampleN;
  int false_identifications = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const FitResult fit = fit_noise_model(simulated_points(model, 100.0, 3600.0, seed));
    EXPECT_TRUE(fit.terms[kN].identified);
    EXPECT_NEAR(fit.coefficients.white_noise / kExampleN, 1.0, 0.02);
    if (fit.terms[kQ].identified || fit.terms[kB].identified || fit.terms[kK].identified ||
        fit.terms[kR].identified) {
      ++false_identifications;
      ADD_FAILURE() << "seed " << seed << ": " << fit.selection_note;  // measured: none
    }
  }
  EXPECT_LE(false_identifications, 1);
}

TEST(NoiseFit, ModelSelectionKeepsAVisibleRandomWalk) {
  // White + RW with the §8 K (crossover 29.6 s, record 2 h): K kept in 10/10 seeds (seed study
  // 100/100; with K/2 still 75/80, with K/10 about half).
  models::ChannelNoiseModel model;
  model.white_noise = kExampleN;
  model.random_walk = kExampleK;
  int identified = 0;
  for (std::uint64_t seed = 11; seed <= 20; ++seed)
    identified +=
        fit_noise_model(simulated_points(model, 100.0, 7200.0, seed)).terms[kK].identified;
  EXPECT_EQ(identified, 10);
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST(NoiseFit, RejectsTooShortRecordsNanAndAllZero) {
  std::vector<FitPoint> one_good = {{1.0, 1e-8, 100.0}, {2.0, 1e-8, 3.0}, {4.0, 1e-8, 1.0}};
  test::expect_throw_containing<AnalysisError>(
      [&] { fit_noise_model(one_good); },
      "only 1 of 3 tau points has nu >= 4; the recording is too short for a fit");
  std::vector<FitPoint> with_nan = {{1.0, 1e-8, 100.0},
                                    {2.0, std::numeric_limits<double>::quiet_NaN(), 50.0}};
  test::expect_throw_containing<AnalysisError>([&] { fit_noise_model(with_nan); },
                                               "point 1 has a non-finite value");
  std::vector<FitPoint> zeros = {{1.0, 0.0, 100.0}, {2.0, 0.0, 50.0}};
  test::expect_throw_containing<AnalysisError>([&] { fit_noise_model(zeros); },
                                               "all variances are zero");
  test::expect_throw_containing<AnalysisError>([&] { fit_noise_model({}); }, "no points");
  std::vector<FitPoint> range = {{1.0, 1e-8, 100.0}, {2.0, 1e-8, 50.0}, {4.0, 1e-8, 25.0}};
  FitOptions narrow;
  narrow.tau_min_s = 3.0;
  test::expect_throw_containing<AnalysisError>([&] { fit_noise_model(range, narrow); },
                                               "widen tau_min_s/tau_max_s");
  FitOptions bad;
  bad.weight_iterations = -1;
  test::expect_throw_containing<ContractViolation>([&] { fit_noise_model(range, bad); },
                                                   "weight_iterations");
}

}  // namespace
}  // namespace imunoise::analysis
