#include "analysis/deviation.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>

#include "analysis/tau_grid.h"
#include "common/errors.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

using test::white_noise;

// Straightforward long-double evaluation of the SP 1065 sums, an independent reference for
// the compensated, blocked and sliding-window kernels.
long double reference_variance(DeviationType type, const std::vector<double>& x, std::int64_t m,
                               double tau0) {
  const auto M = static_cast<std::int64_t>(x.size());
  const long double tau = static_cast<long double>(m) * tau0;
  long double s = 0;
  std::int64_t n = 0;
  auto d2 = [&](std::int64_t k) {
    return static_cast<long double>(x[k + 2 * m]) - 2.0L * x[k + m] + x[k];
  };
  auto d3 = [&](std::int64_t k) {
    return static_cast<long double>(x[k + 3 * m]) - 3.0L * x[k + 2 * m] + 3.0L * x[k + m] - x[k];
  };
  switch (type) {
    case DeviationType::oadev:
      for (std::int64_t k = 0; k + 2 * m < M; ++k, ++n) s += d2(k) * d2(k);
      return s / (2 * tau * tau * n);
    case DeviationType::mdev:
      for (std::int64_t j = 0; j + 3 * m - 1 < M; ++j, ++n) {
        long double w = 0;
        for (std::int64_t k = j; k < j + m; ++k) w += d2(k);
        s += w * w;
      }
      return s / (2.0L * m * m * tau * tau * n);
    case DeviationType::ohdev:
      for (std::int64_t k = 0; k + 3 * m < M; ++k, ++n) s += d3(k) * d3(k);
      return s / (6 * tau * tau * n);
    default:
      return -1;
  }
}

TEST(Deviation, KernelsMatchLongDoubleReference) {
  // Random-walk phase (white FM) of 20 000 points; compare at m that exercise the MDEV lanes
  // (n divisible by 4 or not) and the tail.
  const auto phase = phase_from_rate(white_noise(20000, 1.0, 7), 0.01);
  for (auto type : {DeviationType::oadev, DeviationType::mdev, DeviationType::ohdev}) {
    for (std::int64_t m : {1, 2, 3, 5, 17, 64, 333, 1000, 4000}) {
      if (m > max_averaging_factor(type, static_cast<std::int64_t>(phase.size()))) continue;
      const double got = allan_family_variance(type, phase, m, 0.01).variance;
      const long double want = reference_variance(type, phase, m, 0.01);
      EXPECT_NEAR(got / static_cast<double>(want), 1.0, 1e-12) << to_string(type) << " m=" << m;
    }
  }
}

TEST(Deviation, KernelsKeepFullPrecisionOnLongRecords) {
  // 2^23 white-FM samples: the compensated block sums (OADEV, OHDEV) and the sliding window
  // (MDEV) must agree with long-double references to ~1e-13, i.e. no error growing with M.
  // MDEV reference: window sums from a long-double prefix sum of the second differences.
  const std::int64_t m = 1000;
  const auto phase = phase_from_rate(white_noise(1 << 23, 1.0, 21), 1.0);
  const auto M = static_cast<std::int64_t>(phase.size());
  for (auto type : {DeviationType::oadev, DeviationType::ohdev}) {
    for (std::int64_t mm : {std::int64_t{1}, m}) {
      const double got = allan_family_variance(type, phase, mm, 1.0).variance;
      const long double want = reference_variance(type, phase, mm, 1.0);
      EXPECT_NEAR(got / static_cast<double>(want), 1.0, 1e-13) << to_string(type) << " m=" << mm;
    }
  }
  std::vector<long double> prefix(static_cast<std::size_t>(M - 2 * m + 1), 0.0L);
  for (std::int64_t k = 0; k + 2 * m < M; ++k) {
    prefix[k + 1] =
        prefix[k] + (static_cast<long double>(phase[k + 2 * m]) - 2.0L * phase[k + m] + phase[k]);
  }
  long double s = 0;
  const std::int64_t n = M - 3 * m + 1;
  for (std::int64_t j = 0; j < n; ++j) {
    const long double w = prefix[j + m] - prefix[j];
    s += w * w;
  }
  const long double want = s / (2.0L * m * m * m * m * n);
  const double got = allan_family_variance(DeviationType::mdev, phase, m, 1.0).variance;
  EXPECT_NEAR(got / static_cast<double>(want), 1.0, 1e-12);
}

TEST(Deviation, ModifiedKernelHandlesTinyRecords) {
  // n = M − 3m + 1 from 1 to 7 terms: lanes empty, partial, and tail-only paths.
  for (std::size_t M = 4; M < 12; ++M) {
    const auto x = white_noise(M, 1.0, M);
    const double got = allan_family_variance(DeviationType::mdev, x, 1, 1.0).variance;
    EXPECT_NEAR(got / static_cast<double>(reference_variance(DeviationType::mdev, x, 1, 1.0)), 1.0,
                1e-13)
        << M;
  }
}

TEST(Deviation, WhiteRateNoiseFollowsNSquaredOverTau) {
  // White rate noise, per-sample σ_d = N/√τ0 → AVAR = N²/τ (theory.md §4.1). With 10^6
  // samples, at m = 100 the OADEV EDF is ≈ 1.4·10^4 → relative σ² error ≈ √(2/ν) ≈ 1.2 %;
  // 6 % is five standard deviations.
  const double tau0 = 0.01, N = 2e-3;
  const auto y = white_noise(1'000'000, N / std::sqrt(tau0), 11);
  const auto phase = phase_from_rate(y, tau0);
  for (std::int64_t m : {1, 10, 100}) {
    const double tau = m * tau0;
    const double avar = allan_family_variance(DeviationType::oadev, phase, m, tau0).variance;
    EXPECT_NEAR(avar / (N * N / tau), 1.0, 0.06) << m;
    // MVAR/AVAR → 1/2 for white FM at large m (theory.md §2) — checked at m = 100.
  }
  const double mvar = allan_family_variance(DeviationType::mdev, phase, 100, tau0).variance;
  const double avar = allan_family_variance(DeviationType::oadev, phase, 100, tau0).variance;
  EXPECT_NEAR(mvar / avar, 0.5, 0.05);
  // HVAR = N²/τ as well (theory.md §4.1 table).
  const double hvar = allan_family_variance(DeviationType::ohdev, phase, 100, tau0).variance;
  EXPECT_NEAR(hvar / (N * N / 1.0), 1.0, 0.08);
}

TEST(Deviation, HugeConstantBiasDoesNotCostDigits) {
  // 10^6 × the noise as a constant bias: the mean is removed before integrating, so the
  // result equals the bias-free one to the input's own rounding (1e6·ε ≈ 1e-10 relative).
  // A plain cumulative sum would reach 10^12 and lose ~4 digits here.
  const auto noise = white_noise(2'000'000, 1.0, 5);
  std::vector<double> biased(noise);
  for (double& v : biased) v += 1e6;
  const auto p0 = phase_from_rate(noise, 1.0);
  const auto p1 = phase_from_rate(biased, 1.0);
  for (auto type :
       {DeviationType::oadev, DeviationType::mdev, DeviationType::ohdev, DeviationType::totdev}) {
    for (std::int64_t m : {1, 1000}) {
      const double a = allan_family_variance(type, p0, m, 1.0).variance;
      const double b = allan_family_variance(type, p1, m, 1.0).variance;
      EXPECT_NEAR(b / a, 1.0, 1e-8) << to_string(type) << " m=" << m;
    }
  }
}

TEST(Deviation, PhaseAndRateInputAgree) {
  const double tau0 = 0.5;
  const auto y = white_noise(5000, 3.0, 9);
  const auto from_rate = phase_from_rate(y, tau0);
  // The same signal as raw (not mean-removed) phase: x_k = τ0·Σ y.
  std::vector<double> raw(y.size() + 1, 0.0);
  for (std::size_t k = 0; k < y.size(); ++k) raw[k + 1] = raw[k] + tau0 * y[k];
  const auto from_phase = detrended_phase(raw);
  for (auto type :
       {DeviationType::adev, DeviationType::oadev, DeviationType::mdev, DeviationType::tdev,
        DeviationType::hdev, DeviationType::ohdev, DeviationType::totdev}) {
    for (std::int64_t m : {1, 7, 100}) {
      const double a = allan_family_variance(type, from_rate, m, tau0).variance;
      const double b = allan_family_variance(type, from_phase, m, tau0).variance;
      EXPECT_NEAR(b / a, 1.0, 1e-10) << to_string(type) << " m=" << m;
    }
  }
}

TEST(Deviation, ConstantSignalGivesZeroWithoutNaN) {
  const std::vector<double> y(1000, 4.25);
  const auto phase = phase_from_rate(y, 1.0);
  const std::int64_t factors[] = {1, 2, 8};
  DeviationOptions options;
  const auto curve = compute_deviation(phase, 1.0, factors, options);
  for (const auto& p : curve.points) {
    EXPECT_EQ(p.value, 0.0);
    EXPECT_FALSE(std::isnan(p.ci_low) || std::isnan(p.ci_high) || std::isnan(p.edf));
  }
}

TEST(Deviation, ResultsDoNotDependOnThreadCount) {
  const auto phase = phase_from_rate(white_noise(200'000, 1.0, 3), 1.0);
  const auto factors = averaging_factors(parse_tau_grid("log:5"), DeviationType::oadev,
                                         static_cast<std::int64_t>(phase.size()));
  DeviationOptions one;
  one.threads = 1;
  DeviationOptions many;
  many.threads = 4;
  const auto a = compute_deviation(phase, 1.0, factors, one);
  const auto b = compute_deviation(phase, 1.0, factors, many);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].value, b.points[i].value);
    EXPECT_EQ(a.points[i].ci_low, b.points[i].ci_low);
    EXPECT_EQ(a.points[i].alpha, b.points[i].alpha);
  }
}

TEST(Deviation, SharedPassesGiveEachFactorItsOwnSumAtAnyThreadCount) {
  // OADEV/OHDEV curves share cache-resident passes among the small factors (order·m up to
  // kSharedPassSpan = 98304 samples) and evaluate the larger ones in runs of up to
  // kLargePassFactors = 8 per pass. Every point must equal the single-factor estimator bit for
  // bit, agree with a long-double reference, and not depend on how many threads split the
  // factors. The factors straddle the boundary of both orders, and both orders have more than
  // 8 large factors, listed out of order, so runs of several sizes form.
  const auto phase = phase_from_rate(white_noise(150'000, 1.0, 5), 1.0);
  const std::vector<std::int64_t> factors = {
      1,     2,     3,     7,     64,    1000,  32767, 32768, 32769, 49151, 49152, 49153,
      40000, 35000, 45000, 38000, 36000, 42000, 44000, 47000, 33000, 60000, 52000, 70000,
      55000, 58000, 65000, 50000, 62000, 74000, 71000, 73000, 56000, 68000, 51000, 66000};
  for (auto type : {DeviationType::oadev, DeviationType::ohdev}) {
    const std::int64_t max_m = max_averaging_factor(type, static_cast<std::int64_t>(phase.size()));
    std::vector<std::int64_t> usable;
    for (std::int64_t m : factors) {
      if (m <= max_m) usable.push_back(m);
    }
    DeviationOptions options;
    options.type = type;
    options.alpha = 0;
    options.threads = 1;
    const auto one = compute_deviation(phase, 1.0, usable, options);
    for (unsigned threads : {2u, 3u, 5u}) {
      options.threads = threads;
      const auto many = compute_deviation(phase, 1.0, usable, options);
      for (std::size_t i = 0; i < usable.size(); ++i) {
        EXPECT_EQ(many.points[i].value, one.points[i].value)
            << to_string(type) << " m=" << usable[i] << " threads=" << threads;
      }
    }
    for (std::size_t i = 0; i < usable.size(); ++i) {
      const VarianceEstimate single = allan_family_variance(type, phase, usable[i], 1.0);
      EXPECT_EQ(one.points[i].value, std::sqrt(single.variance)) << to_string(type);
      EXPECT_EQ(one.points[i].n_terms, single.n_terms);
      const long double want = reference_variance(type, phase, usable[i], 1.0);
      EXPECT_NEAR(single.variance / static_cast<double>(want), 1.0, 1e-13)
          << to_string(type) << " m=" << usable[i];
    }
  }
}

TEST(Deviation, AllanHadamardCurvesEqualEachCurveAloneBitForBit) {
  // `analyze` computes OADEV and OHDEV together: a factor of both lists is read once for
  // both orders (joint passes, small ones sharing a cache-resident pass up to 3m = 98304,
  // large ones 8 per pass), the rest one order at a time. Each curve must be the one its
  // statistic gives alone, bit for bit, for one record at any thread count and for pieces.
  // M = 250 001 is no multiple of the 2048-sample block, so the last blocks of every factor
  // end at different points for the two orders. Both statistics reach m = M/4 = 62 500.
  std::vector<double> rate = white_noise(250'000, 1.0, 17);
  double walk = 0.0;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> step(0.0, 0.01);
  for (double& v : rate) v += (walk += step(rng));  // rate random walk: no two sums alike
  const auto phase = phase_from_rate(rate, 0.01);
  const std::vector<std::int64_t> oadev_factors = {
      1,     2,     3,     3,     7,     64,    1000,  32767, 32768, 32769, 49152, 49153,
      40000, 35000, 45000, 38000, 36000, 42000, 44000, 47000, 33000, 55000, 62500, 41000};
  const std::vector<std::int64_t> ohdev_factors = {3,     49153, 1,     12345, 32769, 40001, 58000,
                                                   62500, 35000, 47000, 44000, 42000, 38000, 36000,
                                                   45000, 33000, 41000, 40000, 2,     32768};
  DeviationOptions options;
  options.alpha = 0;
  const auto expect_same = [](const DeviationCurve& got, const DeviationCurve& want,
                              const std::string& what) {
    ASSERT_EQ(got.points.size(), want.points.size()) << what;
    EXPECT_EQ(got.type, want.type) << what;
    EXPECT_EQ(got.n_phase, want.n_phase) << what;
    EXPECT_EQ(got.piece_n_phase, want.piece_n_phase) << what;
    for (std::size_t i = 0; i < want.points.size(); ++i) {
      const DeviationPoint& g = got.points[i];
      const DeviationPoint& w = want.points[i];
      EXPECT_EQ(g.m, w.m) << what;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(g.value), std::bit_cast<std::uint64_t>(w.value))
          << what << " m=" << w.m;
      EXPECT_EQ(g.n_terms, w.n_terms) << what << " m=" << w.m;
      EXPECT_EQ(g.edf, w.edf) << what << " m=" << w.m;
      EXPECT_EQ(g.ci_low, w.ci_low) << what << " m=" << w.m;
      EXPECT_EQ(g.ci_high, w.ci_high) << what << " m=" << w.m;
    }
  };
  DeviationOptions alone = options;
  alone.threads = 1;
  alone.type = DeviationType::oadev;
  const DeviationCurve oadev = compute_deviation(phase, 0.01, oadev_factors, alone);
  alone.type = DeviationType::ohdev;
  const DeviationCurve ohdev = compute_deviation(phase, 0.01, ohdev_factors, alone);
  // The joint kernel against an independent long-double sum, not only against its sibling.
  for (const DeviationPoint& p : ohdev.points) {
    const long double want = reference_variance(DeviationType::ohdev, phase, p.m, 0.01);
    EXPECT_NEAR(p.value * p.value / static_cast<double>(want), 1.0, 1e-13) << p.m;
  }
  const std::span<const double> whole[] = {phase};
  for (unsigned threads : {1u, 2u, 3u, 5u}) {
    options.threads = threads;
    const AllanHadamardCurves both =
        compute_pooled_allan_hadamard(whole, 0.01, oadev_factors, ohdev_factors, options);
    expect_same(both.oadev, oadev, "oadev, threads " + std::to_string(threads));
    expect_same(both.ohdev, ohdev, "ohdev, threads " + std::to_string(threads));
  }

  // Pieces: three gap-free pieces of unequal length, the shorter ones without terms at the
  // largest factors.
  std::vector<std::vector<double>> piece_phases;
  std::size_t at = 0;
  for (std::size_t n : {std::size_t{180'000}, std::size_t{40'000}, std::size_t{30'000}}) {
    piece_phases.push_back(phase_from_rate(std::span<const double>(rate).subspan(at, n), 0.01));
    at += n;
  }
  const std::vector<std::span<const double>> pieces(piece_phases.begin(), piece_phases.end());
  const std::int64_t longest = static_cast<std::int64_t>(piece_phases.front().size());
  const auto usable = [&](const std::vector<std::int64_t>& factors, DeviationType type) {
    std::vector<std::int64_t> out;
    for (std::int64_t m : factors) {
      if (m <= max_averaging_factor(type, longest)) out.push_back(m);
    }
    return out;
  };
  const std::vector<std::int64_t> piece_oadev = usable(oadev_factors, DeviationType::oadev);
  const std::vector<std::int64_t> piece_ohdev = usable(ohdev_factors, DeviationType::ohdev);
  alone.type = DeviationType::oadev;
  const DeviationCurve pooled_oadev = compute_pooled_deviation(pieces, 0.01, piece_oadev, alone);
  alone.type = DeviationType::ohdev;
  const DeviationCurve pooled_ohdev = compute_pooled_deviation(pieces, 0.01, piece_ohdev, alone);
  for (unsigned threads : {1u, 3u}) {
    options.threads = threads;
    const AllanHadamardCurves both =
        compute_pooled_allan_hadamard(pieces, 0.01, piece_oadev, piece_ohdev, options);
    expect_same(both.oadev, pooled_oadev, "pooled oadev, threads " + std::to_string(threads));
    expect_same(both.ohdev, pooled_ohdev, "pooled ohdev, threads " + std::to_string(threads));
  }

  // A factor beyond the OHDEV stop ratio is refused as it is for OHDEV alone.
  const std::vector<std::int64_t> too_big = {62501};
  EXPECT_THROW((void)compute_pooled_allan_hadamard(whole, 0.01, oadev_factors, too_big, options),
               AnalysisError);
}

TEST(Deviation, PhaseInPlaceEqualsPhaseFromRateBitForBit) {
  // The bootstrap turns each simulated record into phase in its own array; it must be the
  // phase every other path computes. A bias makes the mean removal matter.
  for (std::size_t n :
       {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{1000}, std::size_t{100'003}}) {
    std::vector<double> rate = white_noise(n, 0.3, 11);
    for (double& v : rate) v += 7.25;
    const std::vector<double> want = phase_from_rate(rate, 0.0025);
    std::vector<double> samples = rate;
    phase_from_rate_in_place(samples, 0.0025);
    ASSERT_EQ(samples.size(), want.size()) << n;
    for (std::size_t k = 0; k < want.size(); ++k) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(samples[k]), std::bit_cast<std::uint64_t>(want[k]))
          << "n=" << n << " k=" << k;
    }
  }
}

TEST(Deviation, OverlappingVariancesEqualOneFactorAtATime) {
  // Many factors at once (shared small-factor pass, grouped large factors) against one
  // allan_family_variance per factor, bit for bit; factors out of order and repeated.
  const auto phase = phase_from_rate(white_noise(120'000, 1.0, 9), 0.01);
  const std::vector<std::int64_t> factors = {40000, 1,     3,     3,     50000, 20,    49153, 35000,
                                             999,   59000, 36000, 37000, 38000, 41000, 42000, 2};
  for (auto type : {DeviationType::oadev, DeviationType::ohdev}) {
    const std::int64_t max_m = max_averaging_factor(type, static_cast<std::int64_t>(phase.size()));
    std::vector<std::int64_t> usable;
    for (std::int64_t m : factors) {
      if (m <= max_m) usable.push_back(m);
    }
    const auto many = overlapping_variances(type, phase, usable, 0.01);
    ASSERT_EQ(many.size(), usable.size());
    for (std::size_t i = 0; i < usable.size(); ++i) {
      const VarianceEstimate one = allan_family_variance(type, phase, usable[i], 0.01);
      EXPECT_EQ(many[i].variance, one.variance) << to_string(type) << " m=" << usable[i];
      EXPECT_EQ(many[i].n_terms, one.n_terms);
    }
  }
  const std::int64_t no_term[] = {60001};  // 120 001 phase samples: 2m > M − 1
  EXPECT_THROW((void)overlapping_variances(DeviationType::oadev, phase, no_term, 0.01),
               AnalysisError);
  const std::int64_t one[] = {1};
  EXPECT_THROW((void)overlapping_variances(DeviationType::mdev, phase, one, 0.01),
               ContractViolation);
}

TEST(Deviation, BadArgumentsAreClearErrors) {
  const std::vector<double> phase(10, 0.0);
  EXPECT_THROW(allan_family_variance(DeviationType::oadev, phase, 0, 1.0), ContractViolation);
  EXPECT_THROW(allan_family_variance(DeviationType::oadev, phase, 5, 1.0), AnalysisError);
  EXPECT_THROW(allan_family_variance(DeviationType::oadev, phase, 1, 0.0), ContractViolation);
  const std::int64_t too_big[] = {3};
  EXPECT_THROW(compute_deviation(phase, 1.0, too_big, DeviationOptions{}), AnalysisError);
}

}  // namespace
}  // namespace imunoise::analysis
