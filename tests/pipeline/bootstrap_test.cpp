// Tests of pipeline/bootstrap.h's two replicate sources: the variance-distribution draw
// (analysis/variance_covariance.h: OAVAR vectors drawn from their distribution under the fit,
// at a cost independent of the record) against the reference that simulates whole records.
// Their coverage over many records is the validation battery's job (tests/validation).
#include "pipeline/bootstrap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/units.h"
#include "models/noise_simulator.h"
#include "pipeline/axis_analysis.h"

namespace imunoise::pipeline {
namespace {

struct FittedRecord {
  NoiseCoefficients truth;
  std::int64_t samples = 0;
  double tau0_s = 0.0;
  AxisAnalysis analysis;
  std::vector<analysis::FitPoint> points;
  std::vector<std::int64_t> m;
  analysis::FitOptions fit_options;
};

/// White + random walk (theory.md §8.2 values), 2 h at 50 Hz, fitted without intervals.
FittedRecord white_rw_record() {
  FittedRecord r;
  r.truth.white_noise = 0.4 * units::kDegPerSqrtHour;
  r.truth.random_walk = 3.9e-4 * units::kDeg;
  r.tau0_s = 0.02;
  r.samples = 360'000;
  models::SimulationOptions sim;
  sim.sample_rate_hz = 50.0;
  sim.seed = 5;
  sim.flicker_band = {r.tau0_s, static_cast<double>(r.samples) * r.tau0_s};
  models::ChannelSimulator simulator(models::channel_model_from(r.truth), sim, 0);
  std::vector<double> rate(static_cast<std::size_t>(r.samples));
  simulator.next_block(rate);
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  r.analysis = analyze_axis("gyro_x", SensorKind::gyro, rate, r.tau0_s, 0, options);
  r.points = analysis::fit_points(r.analysis.oadev);
  for (const auto& p : r.analysis.oadev.points) r.m.push_back(p.m);
  r.fit_options = options.fit;
  r.fit_options.tau_min_s = r.analysis.fit.tau_min_s;
  return r;
}

BootstrapResult run(const FittedRecord& r, ReplicateSource source, int replicates,
                    unsigned threads) {
  BootstrapOptions options;
  options.source = source;
  options.replicates = replicates;
  options.seed = 3;
  options.threads = threads;
  return bootstrap_fit(r.analysis.fit, r.points, r.m, r.samples, r.tau0_s, r.fit_options, options);
}

double log_width(const Interval& i) { return std::log(i.high / i.low); }

TEST(Bootstrap, VarianceDistributionDrawMatchesTheSimulatedRecords) {
  const FittedRecord r = white_rw_record();
  ASSERT_TRUE(r.analysis.fit.terms[static_cast<std::size_t>(NoiseTerm::white_noise)].identified);
  ASSERT_TRUE(r.analysis.fit.terms[static_cast<std::size_t>(NoiseTerm::random_walk)].identified);
  const int replicates = 100;
  const BootstrapResult drawn = run(r, ReplicateSource::variance_distribution, replicates, 1);
  const BootstrapResult simulated = run(r, ReplicateSource::simulated_record, replicates, 2);
  ASSERT_EQ(drawn.replicates, replicates);
  // Each width is t·sd from 100 replicates, known to ±1/√(2·100) = 7 %; the ratio of two to
  // ±10 %: three standard errors.
  for (const NoiseTerm term : {NoiseTerm::white_noise, NoiseTerm::random_walk}) {
    const auto t = static_cast<std::size_t>(term);
    EXPECT_NEAR(log_width(drawn.terms[t]) / log_width(simulated.terms[t]), 1.0, 0.3)
        << term_name(term);
    // One record, a fixed seed: the truth inside (coverage is the battery's job).
    EXPECT_LE(drawn.terms[t].low, coefficient(r.truth, term)) << term_name(term);
    EXPECT_GE(drawn.terms[t].high, coefficient(r.truth, term)) << term_name(term);
  }
}

TEST(Bootstrap, VarianceDistributionDrawDoesNotDependOnTheThreads) {
  const FittedRecord r = white_rw_record();
  const BootstrapResult one = run(r, ReplicateSource::variance_distribution, 40, 1);
  const BootstrapResult two = run(r, ReplicateSource::variance_distribution, 40, 2);
  for (std::size_t t = 0; t < 5; ++t) {
    EXPECT_EQ(one.terms[t].low, two.terms[t].low);
    EXPECT_EQ(one.terms[t].high, two.terms[t].high);
  }
}

}  // namespace
}  // namespace imunoise::pipeline

namespace imunoise::pipeline {
namespace {

TEST(Bootstrap, VarianceDistributionDrawOfADeterministicModelIsItsExpectation) {
  // A fit of a ramp alone: no variance under the model at any τ (EDF 0), so every draw is the
  // expectation and the refit returns the fitted ramp; nothing fails on the 0/0 correlation.
  std::vector<analysis::FitPoint> points;
  std::vector<std::int64_t> m;
  const double tau0 = 0.1, ramp = 1e-6;
  for (std::int64_t k = 1; k <= 1000; k *= 2) {
    const double tau = static_cast<double>(k) * tau0;
    points.push_back({tau, 0.5 * ramp * ramp * tau * tau, 50.0});
    m.push_back(k);
  }
  analysis::FitOptions fit_options;
  fit_options.allow_terms = {false, false, false, false, true};
  const analysis::FitResult fit = analysis::fit_noise_model(points, fit_options);
  ASSERT_TRUE(fit.terms[static_cast<std::size_t>(NoiseTerm::ramp)].identified);
  BootstrapOptions options;
  options.source = ReplicateSource::variance_distribution;
  options.replicates = 20;
  const BootstrapResult r = bootstrap_fit(fit, points, m, 100000, tau0, fit_options, options);
  EXPECT_EQ(r.replicates, 20);
  const Interval& i = r.terms[static_cast<std::size_t>(NoiseTerm::ramp)];
  EXPECT_NEAR(i.low / ramp, 1.0, 1e-6);
  EXPECT_NEAR(i.high / ramp, 1.0, 1e-6);
}

}  // namespace
}  // namespace imunoise::pipeline
