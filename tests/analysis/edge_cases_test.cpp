/// @file
/// @brief Numerical edge cases of the deviation kernels, the pooled (gap-split) estimators,
/// the tau grid and the EDF (issue 9): record lengths not divisible by m, a constant signal,
/// a huge constant bias, counts above 2^31, and the pooling over independent pieces checked
/// against brute-force definitions written out here independently of the kernels.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include "analysis/deviation.h"
#include "analysis/edf.h"
#include "analysis/noise_fit.h"
#include "analysis/psd.h"
#include "analysis/tau_grid.h"
#include "common/errors.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

using test::white_noise;

/// Brute-force overlapping AVAR from rate samples (theory.md §2): every pair of adjacent
/// m-averages inside one piece, σ² = Σ (ȳ_{k+m} − ȳ_k)² / (2·count), in long double.
struct BruteForce {
  long double sum = 0.0L;
  std::int64_t count = 0;
  void add_piece(std::span<const double> y, std::int64_t m) {
    const auto n = static_cast<std::int64_t>(y.size());
    for (std::int64_t k = 0; k + 2 * m <= n; ++k) {
      long double a = 0.0L, b = 0.0L;
      for (std::int64_t i = 0; i < m; ++i) {
        a += y[static_cast<std::size_t>(k + i)];
        b += y[static_cast<std::size_t>(k + m + i)];
      }
      const long double d = (b - a) / static_cast<long double>(m);
      sum += d * d;
      ++count;
    }
  }
  double avar() const {
    return static_cast<double>(sum / (2.0L * static_cast<long double>(count)));
  }
};

/// Brute-force overlapping HVAR from rate samples: (ȳ_{k+2m} − 2ȳ_{k+m} + ȳ_k)² / 6.
double brute_force_hvar(std::span<const std::span<const double>> pieces, std::int64_t m) {
  long double sum = 0.0L;
  std::int64_t count = 0;
  for (const auto& y : pieces) {
    const auto n = static_cast<std::int64_t>(y.size());
    for (std::int64_t k = 0; k + 3 * m <= n; ++k) {
      long double a = 0.0L, b = 0.0L, c = 0.0L;
      for (std::int64_t i = 0; i < m; ++i) {
        a += y[static_cast<std::size_t>(k + i)];
        b += y[static_cast<std::size_t>(k + m + i)];
        c += y[static_cast<std::size_t>(k + 2 * m + i)];
      }
      const long double d = (c - 2.0L * b + a) / static_cast<long double>(m);
      sum += d * d;
      ++count;
    }
  }
  return static_cast<double>(sum / (6.0L * static_cast<long double>(count)));
}

TEST(EdgeCases, OadevOfALengthNotDivisibleByMUsesEveryTerm) {
  // N = 1001 rate samples, m = 7: 1001 = 143·7, but M = 1002 phase samples and M − 2m = 988
  // overlapping terms; ADEV has ⌊1001/7⌋ − 1 = 142 first differences of cluster means.
  const std::vector<double> y = white_noise(1001, 1.0, 7);
  const std::vector<double> x = phase_from_rate(y, 1.0);
  const VarianceEstimate v = allan_family_variance(DeviationType::oadev, x, 7, 1.0);
  EXPECT_EQ(v.n_terms, 988);
  BruteForce bf;
  bf.add_piece(y, 7);
  EXPECT_EQ(bf.count, 988);
  EXPECT_NEAR(v.variance / bf.avar(), 1.0, 1e-12);
  EXPECT_EQ(allan_family_variance(DeviationType::adev, x, 7, 1.0).n_terms, 142);
  // And a length that leaves a remainder of 6 at every m of an octave grid.
  const std::vector<double> y2 = white_noise(1000 + 6, 1.0, 8);
  const std::vector<double> x2 = phase_from_rate(y2, 0.5);
  for (std::int64_t m : {1, 2, 4, 8, 16, 64, 251}) {
    BruteForce b2;
    b2.add_piece(y2, m);
    const VarianceEstimate e = allan_family_variance(DeviationType::oadev, x2, m, 0.5);
    EXPECT_EQ(e.n_terms, b2.count) << m;
    EXPECT_NEAR(e.variance / b2.avar(), 1.0, 1e-12) << m;
  }
}

TEST(EdgeCases, ConstantSignalGivesZeroDeviationsAndTheFitRefusesIt) {
  const std::vector<double> y(4000, 0.25);
  const std::vector<double> x = phase_from_rate(y, 0.01);
  DeviationOptions options;
  const std::vector<std::int64_t> m = averaging_factors(
      parse_tau_grid("octave"), DeviationType::oadev, static_cast<std::int64_t>(x.size()));
  const DeviationCurve curve = compute_deviation(x, 0.01, m, options);
  for (const DeviationPoint& p : curve.points) {
    EXPECT_EQ(p.value, 0.0) << p.m;  // exactly: the mean removal leaves zeros, not rounding
    EXPECT_TRUE(std::isfinite(p.ci_low) && std::isfinite(p.ci_high)) << p.m;
    EXPECT_TRUE(std::isfinite(p.edf)) << p.m;
  }
  const std::vector<FitPoint> points = fit_points(curve);
  test::expect_throw_containing<AnalysisError>([&] { (void)fit_noise_model(points, {}); },
                                               "nothing to fit");
}

TEST(EdgeCases, HugeConstantBiasLeavesTheDeviationsUnchanged) {
  // Bias 1e6 × the noise σ: the mean removal before the compensated integration
  // (theory.md §2 "Numerics") keeps the digits. The only loss is the rounding of bias + noise
  // in the input itself, ~1e-16 · 1e6 relative to the noise.
  const std::vector<double> noise = white_noise(200000, 1e-3, 11);
  std::vector<double> biased(noise.size());
  for (std::size_t i = 0; i < noise.size(); ++i) biased[i] = 1e3 + noise[i];
  DeviationOptions options;
  options.alpha = 0;
  for (DeviationType type : {DeviationType::oadev, DeviationType::ohdev, DeviationType::mdev}) {
    options.type = type;
    const std::vector<double> x0 = phase_from_rate(noise, 0.01);
    const std::vector<double> x1 = phase_from_rate(biased, 0.01);
    const std::vector<std::int64_t> m =
        averaging_factors(parse_tau_grid("octave"), type, static_cast<std::int64_t>(x0.size()));
    const DeviationCurve a = compute_deviation(x0, 0.01, m, options);
    const DeviationCurve b = compute_deviation(x1, 0.01, m, options);
    ASSERT_EQ(a.points.size(), b.points.size());
    for (std::size_t i = 0; i < a.points.size(); ++i) {
      EXPECT_NEAR(b.points[i].value / a.points[i].value, 1.0, 1e-6)
          << to_string(type) << " m = " << a.points[i].m;
    }
  }
}

TEST(EdgeCases, PooledOadevEqualsTheAvarOfEveryDifferenceThatDoesNotStraddleAGap) {
  // Four pieces of one white record, of lengths that leave remainders at every m; some
  // pieces are too short for the largest m and must simply stop contributing there.
  const std::vector<double> y = white_noise(1001 + 537 + 260 + 151, 2e-3, 21);
  std::vector<std::span<const double>> rate_pieces;
  std::size_t at = 0;
  for (std::size_t n : {1001, 537, 260, 151}) {
    rate_pieces.emplace_back(std::span<const double>(y).subspan(at, n));
    at += n;
  }
  std::vector<std::vector<double>> phases;
  for (const auto& p : rate_pieces) phases.push_back(phase_from_rate(p, 0.02));
  const std::vector<std::span<const double>> phase_spans(phases.begin(), phases.end());
  DeviationOptions options;
  options.alpha = 0;
  const std::vector<std::int64_t> factors{1, 2, 3, 7, 16, 50, 75, 76, 100, 131, 200, 250};
  const DeviationCurve curve = compute_pooled_deviation(phase_spans, 0.02, factors, options);
  ASSERT_EQ(curve.points.size(), factors.size());
  EXPECT_EQ(curve.n_phase, 1002 + 538 + 261 + 152);
  EXPECT_EQ(curve.piece_n_phase.size(), 4u);
  for (const DeviationPoint& p : curve.points) {
    BruteForce bf;
    double edf = 0.0;
    for (std::size_t k = 0; k < rate_pieces.size(); ++k) {
      bf.add_piece(rate_pieces[k], p.m);
      const auto n_phase = static_cast<std::int64_t>(phases[k].size());
      if (n_phase - 2 * p.m >= 1) edf += edf_for(DeviationType::oadev, 0, p.m, n_phase);
    }
    EXPECT_EQ(p.n_terms, bf.count) << p.m;
    EXPECT_NEAR(p.value * p.value / bf.avar(), 1.0, 1e-12) << p.m;
    EXPECT_NEAR(p.edf / edf, 1.0, 1e-12) << p.m;  // independent pieces: EDFs add
    EXPECT_LT(p.ci_low, p.value);
    EXPECT_GT(p.ci_high, p.value);
    EXPECT_DOUBLE_EQ(curve_edf(curve, 0, p.m), p.edf);
  }
  // OHDEV likewise (third differences inside each piece).
  options.type = DeviationType::ohdev;
  const std::vector<std::int64_t> hf{1, 5, 33, 86, 200};
  const DeviationCurve h = compute_pooled_deviation(phase_spans, 0.02, hf, options);
  for (const DeviationPoint& p : h.points) {
    EXPECT_NEAR(p.value * p.value / brute_force_hvar(rate_pieces, p.m), 1.0, 1e-12) << p.m;
  }
  // Beyond the longest piece's stop ratio: the same clear error as for one record.
  test::expect_throw_containing<AnalysisError>(
      [&] {
        const std::vector<std::int64_t> too_big{251};
        (void)compute_pooled_deviation(phase_spans, 0.02, too_big, DeviationOptions{});
      },
      "too few samples for the requested tau");
  // Total deviation cannot be pooled this way: refused, not silently wrong.
  options.type = DeviationType::totdev;
  test::expect_throw_containing<ContractViolation>(
      [&] { (void)compute_pooled_deviation(phase_spans, 0.02, factors, options); },
      "cannot be pooled");
}

TEST(EdgeCases, PooledDeviationOfOnePieceIsTheSingleRecordCurve) {
  const std::vector<double> y = white_noise(5000, 1.0, 3);
  const std::vector<double> x = phase_from_rate(y, 0.1);
  const std::span<const double> one[] = {x};
  const std::vector<std::int64_t> m{1, 3, 10, 100, 1250};
  const DeviationCurve a = compute_deviation(x, 0.1, m, {});
  const DeviationCurve b = compute_pooled_deviation(one, 0.1, m, {});
  ASSERT_EQ(a.points.size(), b.points.size());
  EXPECT_TRUE(b.piece_n_phase.empty());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].value, b.points[i].value);
    EXPECT_EQ(a.points[i].edf, b.points[i].edf);
  }
}

TEST(EdgeCases, PooledWelchWeightsPiecesBySegmentCount) {
  const std::vector<double> y = white_noise(20000, 1.0, 5);
  const std::span<const double> all(y);
  // One piece: exactly welch_psd.
  const std::span<const double> one[] = {all};
  const Spectrum single = welch_psd(all, 100.0);
  const Spectrum pooled_one = pooled_welch_psd(one, 100.0);
  EXPECT_EQ(single.density, pooled_one.density);
  EXPECT_EQ(single.dof, pooled_one.dof);
  // Three pieces (the last shorter than a segment, left out): the longest fixes L.
  const std::span<const double> pieces[] = {all.subspan(0, 12000), all.subspan(12000, 7900),
                                            all.subspan(19900, 100)};
  std::size_t used = 0;
  const Spectrum p = pooled_welch_psd(pieces, 100.0, {}, &used);
  EXPECT_EQ(used, 2u);
  EXPECT_EQ(p.segment_length, 1024u);  // largest power of two <= 12000/8
  WelchOptions fixed;
  fixed.segment_length = 1024;
  const Spectrum a = welch_psd(pieces[0], 100.0, fixed);
  const Spectrum b = welch_psd(pieces[1], 100.0, fixed);
  EXPECT_EQ(p.segments, a.segments + b.segments);
  const double ka = static_cast<double>(a.segments), kb = static_cast<double>(b.segments);
  for (std::size_t j = 0; j < p.density.size(); ++j) {
    EXPECT_NEAR(p.density[j], (ka * a.density[j] + kb * b.density[j]) / (ka + kb),
                1e-12 * p.density[j]);
    // Variance of the segment-weighted mean of independent estimates.
    const double dof = (ka + kb) * (ka + kb) / (ka * ka / a.dof[j] + kb * kb / b.dof[j]);
    EXPECT_NEAR(p.dof[j], dof, 1e-9 * dof);
    EXPECT_GT(p.dof[j], a.dof[j]);
  }
  // White noise of unit variance at 100 Hz: one-sided level 2/100 (theory.md §1.2).
  const Spectrum binned = log_bin(p);
  double mean = 0.0;
  for (double d : binned.density) mean += d;
  mean /= static_cast<double>(binned.density.size());
  EXPECT_NEAR(mean / 0.02, 1.0, 0.1);
  // No piece long enough for one segment: a clear error.
  fixed.segment_length = 20000;
  test::expect_throw_containing<ContractViolation>(
      [&] { (void)pooled_welch_psd(pieces, 100.0, fixed); }, "no piece is as long");
}

TEST(EdgeCases, CountsAbove2To31KeepTheirArithmeticIn64Bits) {
  // 3e9 phase samples, only as a count: grid, term counts, stop ratios and EDF must not wrap.
  const std::int64_t n = 3'000'000'001;
  EXPECT_EQ(max_averaging_factor(DeviationType::oadev, n), 750'000'000);
  EXPECT_EQ(max_averaging_factor(DeviationType::adev, n), 600'000'000);
  EXPECT_EQ(max_averaging_factor(DeviationType::totdev, n), 1'500'000'000);
  EXPECT_EQ(estimator_term_count(DeviationType::oadev, n, 750'000'000), 1'500'000'001);
  EXPECT_EQ(estimator_term_count(DeviationType::ohdev, n, 7), n - 21);
  EXPECT_EQ(estimator_term_count(DeviationType::mdev, n, 1'000'000'000), 2);  // M − 3m + 1
  for (const char* grid : {"octave", "decade", "log:10"}) {
    const std::vector<std::int64_t> m =
        averaging_factors(parse_tau_grid(grid), DeviationType::oadev, n);
    ASSERT_FALSE(m.empty()) << grid;
    EXPECT_EQ(m.front(), 1) << grid;
    for (std::size_t i = 1; i < m.size(); ++i) EXPECT_GT(m[i], m[i - 1]) << grid;
    EXPECT_LE(m.back(), 750'000'000) << grid;
    EXPECT_GT(m.back(), 100'000'000) << grid;
  }
  const std::vector<std::int64_t> octave =
      averaging_factors(parse_tau_grid("octave"), DeviationType::oadev, n);
  EXPECT_EQ(octave.back(), std::int64_t{1} << 29);
  // EDF at the largest m and at m = 1: finite, positive, and of the right size (white FM at
  // m = 1: about 3(M−1)/(2m)·4/9 ≈ 0.67 M; Greenhall's m = 1 model gives ~0.78 M).
  for (int alpha : {2, 1, 0, -1, -2}) {
    for (std::int64_t m : {std::int64_t{1}, std::int64_t{1000}, std::int64_t{750'000'000}}) {
      const double edf = edf_for(DeviationType::oadev, alpha, m, n);
      EXPECT_TRUE(std::isfinite(edf) && edf > 0.0) << alpha << " " << m;
      EXPECT_LT(edf, 2.0 * static_cast<double>(n)) << alpha << " " << m;
    }
  }
  EXPECT_NEAR(edf_for(DeviationType::oadev, 0, 1, n) / static_cast<double>(n), 0.78, 0.02);
  // Larger still (1e10, where S·(M − L) would pass 2^63): the overlapping EDF stays sane.
  const std::int64_t huge = 10'000'000'000;
  const double e_huge = edf_for(DeviationType::oadev, 0, huge / 4, huge);
  EXPECT_TRUE(std::isfinite(e_huge) && e_huge > 0.0 && e_huge < 10.0) << e_huge;
  // Thêo1's (M − m)·m/2 terms pass 2^63 there: saturated, not wrapped to a negative count.
  EXPECT_EQ(estimator_term_count(DeviationType::theo1, huge, huge / 2),
            std::numeric_limits<std::int64_t>::max());
  // The explicit-list refusal names the need without overflowing m·r.
  test::expect_throw_containing<AnalysisError>(
      [&] {
        (void)averaging_factors(parse_tau_grid("4611686018427387904"), DeviationType::oadev, 1000);
      },
      "more than 2^63");
}

TEST(EdgeCases, ExplicitTausBeyondTheStopRatioAreAClearError) {
  // M = 1001 phase samples: OADEV allows m ≤ 250; m = 600 (> N/2) is refused with the reason.
  test::expect_throw_containing<AnalysisError>(
      [] { (void)averaging_factors(parse_tau_grid("1,10,600"), DeviationType::oadev, 1001); },
      "the largest usable m is 250");
  // Automatic grids never go beyond it.
  for (const char* grid : {"octave", "decade", "all", "log:20"}) {
    for (std::int64_t m : averaging_factors(parse_tau_grid(grid), DeviationType::oadev, 1001)) {
      EXPECT_LE(m, 250) << grid;
    }
  }
}

TEST(EdgeCases, OneAndTwoSampleRecordsAreTooShort) {
  // Every grid refuses them (the stop ratio needs M ≥ 4 phase samples, theory.md §2); the
  // bare kernel at m = 1 refuses one sample (no second difference) and answers two with its
  // single term.
  for (std::size_t n : {std::size_t{1}, std::size_t{2}}) {
    const std::vector<double> y{1.0, 3.0};
    const std::vector<double> x = phase_from_rate(std::span<const double>(y).first(n), 1.0);
    test::expect_throw_containing<AnalysisError>(
        [&] {
          (void)averaging_factors(parse_tau_grid("octave"), DeviationType::oadev,
                                  static_cast<std::int64_t>(x.size()));
        },
        "too few samples");
  }
  const std::vector<double> one{1.0};
  test::expect_throw_containing<AnalysisError>(
      [&] { (void)allan_family_variance(DeviationType::oadev, phase_from_rate(one, 1.0), 1, 1.0); },
      "too few samples");
  const std::vector<double> two{1.0, 3.0};
  const VarianceEstimate v =
      allan_family_variance(DeviationType::oadev, phase_from_rate(two, 1.0), 1, 1.0);
  EXPECT_EQ(v.n_terms, 1);
  EXPECT_DOUBLE_EQ(v.variance, 2.0);  // (3 − 1)²/2
}

}  // namespace
}  // namespace imunoise::analysis
