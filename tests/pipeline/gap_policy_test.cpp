// Tests of the gap policy (pipeline/gap_policy.h) and of the per-axis analysis over gap-free
// pieces (analyze_axis_pieces), plus the numerical edge cases of analyze_axis (issue 9):
// too short, constant, non-finite, near the float limits, a huge constant bias.
#include "pipeline/gap_policy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "common/errors.h"
#include "pipeline/axis_analysis.h"
#include "test_support.h"

namespace imunoise::pipeline {
namespace {

using test::white_noise;

/// Time stamps at PERIOD with the listed sample ranges [begin, end) removed (the gaps).
std::vector<double> stamps_without(std::size_t n, double period,
                                   const std::vector<SampleRange>& removed) {
  std::vector<double> t;
  for (std::size_t i = 0; i < n; ++i) {
    bool cut = false;
    for (const SampleRange& r : removed) cut = cut || (i >= r.begin && i < r.end);
    if (!cut) t.push_back(static_cast<double>(i) * period);
  }
  return t;
}

/// Every finite number of an axis model that ends up in model.yaml.
void expect_finite_model(const models::AxisModel& m) {
  for (const models::Estimate& e : m.terms) {
    EXPECT_TRUE(std::isfinite(e.value) && std::isfinite(e.ci_low) && std::isfinite(e.ci_high))
        << m.name;
  }
  EXPECT_TRUE(std::isfinite(m.fit_tau_min_s) && std::isfinite(m.fit_tau_max_s)) << m.name;
  for (double v : m.readoff.slope) EXPECT_TRUE(std::isfinite(v)) << m.name;
  for (double v : m.readoff.psd) EXPECT_TRUE(std::isfinite(v)) << m.name;
}

TEST(GapPolicy, AbsurdGapsSaturateTheMissingCountInsteadOfOverflowing) {
  // A ratio beyond int64 (and an infinite one) has no llround; the count saturates, as the
  // sampling report's does, so --gaps interpolate refuses it with its usual message.
  const std::vector<double> t{0.0, 1.0, 2.0, 1e300, 1e300 + 1.0};
  const auto gaps = find_time_gaps(t, 1.0);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_EQ(gaps[0].after, 3u);
  EXPECT_EQ(gaps[0].missing, std::numeric_limits<std::int64_t>::max());
  EXPECT_GT(gaps[0].missing, max_interpolated_gap(t.size()));
}

TEST(GapPolicy, ParsesTheThreePoliciesAndNamesTheFlagOtherwise) {
  EXPECT_EQ(parse_gap_policy("refuse"), GapPolicy::refuse);
  EXPECT_EQ(parse_gap_policy("split"), GapPolicy::split);
  EXPECT_EQ(parse_gap_policy("interpolate"), GapPolicy::interpolate);
  test::expect_throw_containing<InputError>([] { (void)parse_gap_policy("fill", "--gaps"); },
                                            "--gaps");
}

TEST(GapPolicy, FindsEveryGapWithTheSamplingReportCriterion) {
  // 10 ms grid, samples 100–104 and 300–399 missing; one stamp 14 ms after its predecessor
  // (jitter, not a gap: the limit is 1.5 × the period); a duplicate and a step back are
  // not gaps either.
  std::vector<double> t = stamps_without(1000, 0.01, {{100, 105}, {300, 400}});
  t[500] += 0.004;
  t.insert(t.begin() + 600, t[599]);
  const std::vector<TimeGap> gaps = find_time_gaps(t, 0.01);
  ASSERT_EQ(gaps.size(), 2u);
  EXPECT_EQ(gaps[0].after, 100u);
  EXPECT_EQ(gaps[0].missing, 5);
  EXPECT_NEAR(gaps[0].start_s, 0.99, 1e-12);
  EXPECT_NEAR(gaps[0].length_s, 0.06, 1e-12);
  EXPECT_EQ(gaps[1].after, 295u);
  EXPECT_EQ(gaps[1].missing, 100);
  test::expect_throw_containing<ContractViolation>([&] { (void)find_time_gaps(t, 0.0); }, "period");
}

TEST(GapPolicy, SplitKeepsThePiecesLongEnoughAndCountsTheRest) {
  const std::vector<TimeGap> gaps{{500, 0, 0, 3}, {560, 0, 0, 2}, {2000, 0, 0, 9}};
  const GapSplit s = split_at_gaps(2500, gaps, 100);
  ASSERT_EQ(s.pieces.size(), 3u);
  EXPECT_EQ(s.pieces[0].begin, 0u);
  EXPECT_EQ(s.pieces[0].end, 500u);
  EXPECT_EQ(s.pieces[1].begin, 560u);
  EXPECT_EQ(s.pieces[1].end, 2000u);
  EXPECT_EQ(s.pieces[2].size(), 500u);
  EXPECT_EQ(s.dropped_pieces, 1u);
  EXPECT_EQ(s.dropped_samples, 60u);
  const GapSplit none = split_at_gaps(50, {}, 100);
  EXPECT_TRUE(none.pieces.empty());
  EXPECT_EQ(none.dropped_samples, 50u);
}

TEST(GapPolicy, InterpolationFillsExactlyTheMissingSamplesOnTheLine) {
  const std::vector<double> v{1.0, 2.0, 3.0, 7.0, 7.0, -1.0};
  // Gap of 3 missing before index 3 (3 → 7 in four steps), gap of 1 before index 5.
  const std::vector<TimeGap> gaps{{3, 0, 0, 3}, {5, 0, 0, 1}};
  const std::vector<double> f = interpolate_gaps(v, gaps);
  const std::vector<double> expected{1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 7.0, 3.0, -1.0};
  EXPECT_EQ(f, expected);
  // A constant channel stays exactly constant; values near the float limits stay finite.
  const std::vector<double> c{0.1, 0.1, 0.1};
  for (double x : interpolate_gaps(c, std::vector<TimeGap>{{1, 0, 0, 7}})) EXPECT_EQ(x, 0.1);
  const std::vector<double> big{-1.7e308, 1.7e308};
  for (double x : interpolate_gaps(big, std::vector<TimeGap>{{1, 0, 0, 3}})) {
    EXPECT_TRUE(std::isfinite(x));
  }
  EXPECT_EQ(max_interpolated_gap(10'000), 100);
  EXPECT_EQ(max_interpolated_gap(10'000'000), 1000);
  EXPECT_EQ(max_interpolated_gap(50), 1);
}

TEST(GapPolicy, SplitRecoversWhiteNoiseWithinItsStatisticalTolerance) {
  // White rate noise of ARW N at 100 Hz (AVAR = N²/τ, theory.md §4.1), gaps cut out; one
  // piece of 60 samples between two gaps is too short and dropped.
  const double tau0 = 0.01;
  const double n_true = 2e-3;
  const std::size_t n = 60000;
  const std::vector<double> y = white_noise(n, n_true / std::sqrt(tau0), 17);
  const std::vector<SampleRange> cut{
      {10000, 10050}, {30000, 30500}, {50000, 50010}, {50070, 50100}};
  std::vector<double> kept_values;
  for (std::size_t i = 0; i < n; ++i) {
    bool removed = false;
    for (const SampleRange& r : cut) removed = removed || (i >= r.begin && i < r.end);
    if (!removed) kept_values.push_back(y[i]);
  }
  const std::vector<double> t = stamps_without(n, tau0, cut);
  const std::vector<TimeGap> gaps = find_time_gaps(t, tau0);
  ASSERT_EQ(gaps.size(), 4u);
  const GapSplit split = split_at_gaps(kept_values.size(), gaps, kMinPieceSamples);
  ASSERT_EQ(split.pieces.size(), 4u);
  EXPECT_EQ(split.dropped_pieces, 1u);
  EXPECT_EQ(split.dropped_samples, 60u);
  std::vector<std::span<const double>> pieces;
  for (const SampleRange& r : split.pieces) {
    pieces.push_back(std::span<const double>(kept_values).subspan(r.begin, r.size()));
  }
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const AxisAnalysis a = analyze_axis_pieces("gyro_x", SensorKind::gyro, pieces, tau0, 0, options);
  ASSERT_FALSE(a.oadev.points.empty());
  EXPECT_EQ(a.oadev.piece_n_phase.size(), 4u);
  const auto& nn = a.model.terms[static_cast<std::size_t>(NoiseTerm::white_noise)];
  ASSERT_TRUE(nn.identified);
  // σ̂ at m = 1 has relative SD 1/√(2ν) (χ²_ν, theory.md §3.1); the fit of a white record is
  // dominated by that point. Four of those, and the truth inside the fit's own interval.
  const double nu1 = a.oadev.points.front().edf;
  EXPECT_GT(nu1, 30000.0);
  EXPECT_NEAR(nn.value / n_true, 1.0, 4.0 / std::sqrt(2.0 * nu1)) << nn.value;
  EXPECT_LE(nn.ci_low, n_true);
  EXPECT_GE(nn.ci_high, n_true);
  EXPECT_NE(a.model.fit_note.find("pooled over 4 gap-free pieces"), std::string::npos)
      << a.model.fit_note;
  expect_finite_model(a.model);
  for (const auto& p : a.oadev.points) EXPECT_TRUE(std::isfinite(p.value) && p.value > 0.0);
  for (double d : a.psd.density) EXPECT_TRUE(std::isfinite(d) && d > 0.0);
}

TEST(GapPolicy, OnePieceIsExactlyTheSingleRecordAnalysis) {
  const std::vector<double> y = white_noise(20000, 0.01, 4);
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const AxisAnalysis a = analyze_axis("gyro_z", SensorKind::gyro, y, 0.005, 2, options);
  const std::span<const double> one[] = {y};
  const AxisAnalysis b = analyze_axis_pieces("gyro_z", SensorKind::gyro, one, 0.005, 2, options);
  ASSERT_EQ(a.oadev.points.size(), b.oadev.points.size());
  for (std::size_t i = 0; i < a.oadev.points.size(); ++i) {
    EXPECT_EQ(a.oadev.points[i].value, b.oadev.points[i].value);
    EXPECT_EQ(a.oadev.points[i].ci_high, b.oadev.points[i].ci_high);
  }
  EXPECT_EQ(a.psd.density, b.psd.density);
  for (std::size_t t = 0; t < a.model.terms.size(); ++t) {
    EXPECT_EQ(a.model.terms[t].value, b.model.terms[t].value);
    EXPECT_EQ(a.model.terms[t].ci_high, b.model.terms[t].ci_high);
  }
  EXPECT_EQ(a.model.fit_note, b.model.fit_note);
}

TEST(AxisEdgeCases, TooShortConstantAndNonFiniteRecordsAreClearErrors) {
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  for (std::size_t n : {std::size_t{1}, std::size_t{2}, std::size_t{15}}) {
    const std::vector<double> y = white_noise(n, 1.0, 1);
    test::expect_throw_containing<AnalysisError>(
        [&] { (void)analyze_axis("gyro_x", SensorKind::gyro, y, 0.01, 0, options); },
        "too few samples");
  }
  const std::vector<double> constant(5000, -9.80665);
  test::expect_throw_containing<AnalysisError>(
      [&] { (void)analyze_axis("accel_z", SensorKind::accel, constant, 0.01, 5, options); },
      "the signal is constant");
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {std::nan(""), inf, -inf}) {
    std::vector<double> y = white_noise(5000, 1.0, 2);
    y[1234] = bad;
    test::expect_throw_containing<AnalysisError>(
        [&] { (void)analyze_axis("gyro_y", SensorKind::gyro, y, 0.01, 1, options); },
        "sample 1234");
  }
}

TEST(AxisEdgeCases, ValuesNearTheFloatLimitsGiveAResultOrAClearError) {
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const std::vector<double> unit = white_noise(20000, 1.0, 9);
  // Scales the squares (and the fit's squared variances) survive: a finite, right result.
  for (double scale : {1e-30, 1e-12, 1e12, 1e30}) {
    std::vector<double> y(unit);
    for (double& v : y) v *= scale;
    const AxisAnalysis a = analyze_axis("gyro_x", SensorKind::gyro, y, 0.01, 0, options);
    expect_finite_model(a.model);
    const double n = a.model.terms[static_cast<std::size_t>(NoiseTerm::white_noise)].value;
    EXPECT_NEAR(n / (scale * std::sqrt(0.01)), 1.0, 0.05) << scale;
  }
  // Beyond: refused with the reason, never Inf/NaN in a result.
  for (double scale : {1e-300, 1e-310, 1e-60, 1e60, 1e150, 1e300}) {
    std::vector<double> y(unit);
    for (double& v : y) v *= scale;
    test::expect_throw_containing<AnalysisError>(
        [&] { (void)analyze_axis("gyro_x", SensorKind::gyro, y, 0.01, 0, options); },
        "double precision");
  }
  // A spread that itself overflows (−1.5e308 … 1.5e308) is the same clear error.
  std::vector<double> y(unit);
  for (std::size_t i = 0; i < y.size(); ++i) y[i] = (i % 2 == 0 ? 1.5e308 : -1.5e308);
  test::expect_throw_containing<AnalysisError>(
      [&] { (void)analyze_axis("gyro_x", SensorKind::gyro, y, 0.01, 0, options); },
      "double precision");
}

TEST(AxisEdgeCases, HugeConstantBiasGivesTheCoefficientsOfTheNoiseAlone) {
  // Accelerometer-like: noise 1e-3 on a bias of 1e3 (10^6 × the noise).
  AxisAnalysisOptions options;
  options.bootstrap_replicates = 0;
  const std::vector<double> noise = white_noise(50000, 1e-3, 12);
  std::vector<double> biased(noise.size());
  for (std::size_t i = 0; i < noise.size(); ++i) biased[i] = 1e3 + noise[i];
  const AxisAnalysis a = analyze_axis("accel_x", SensorKind::accel, noise, 0.01, 3, options);
  const AxisAnalysis b = analyze_axis("accel_x", SensorKind::accel, biased, 0.01, 3, options);
  ASSERT_EQ(a.oadev.points.size(), b.oadev.points.size());
  for (std::size_t i = 0; i < a.oadev.points.size(); ++i) {
    EXPECT_NEAR(b.oadev.points[i].value / a.oadev.points[i].value, 1.0, 1e-6) << i;
  }
  const std::size_t w = static_cast<std::size_t>(NoiseTerm::white_noise);
  EXPECT_NEAR(b.model.terms[w].value / a.model.terms[w].value, 1.0, 1e-6);
}

}  // namespace
}  // namespace imunoise::pipeline
