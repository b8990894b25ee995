// Tests of the outlier scan and policies (pipeline/outliers.h) against simulations with known
// parameters: white noise with and without ±8σ spikes, whose AVAR is the closed form σ²/m.
#include "pipeline/outliers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::pipeline {
namespace {

std::vector<double> white(std::size_t n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  std::vector<double> x(n);
  for (double& v : x) v = normal(rng);
  return x;
}

/// Overlapping AVAR of rate samples X at cluster size M (theory.md §2), by the battery's
/// definition: half the mean square of the differences of adjacent M-means.
double overlapping_avar(const std::vector<double>& x, std::size_t m) {
  std::vector<double> prefix(x.size() + 1, 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) prefix[i + 1] = prefix[i] + x[i];
  double s = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 0; k + 2 * m <= x.size(); ++k) {
    const double a = (prefix[k + m] - prefix[k]) / static_cast<double>(m);
    const double b = (prefix[k + 2 * m] - prefix[k + m]) / static_cast<double>(m);
    s += (b - a) * (b - a);
    ++count;
  }
  return 0.5 * s / static_cast<double>(count);
}

TEST(Outliers, CleanGaussianNoiseGivesNoFinding) {
  // r = x − median of 4 neighbours has σ_r ≈ 1.14σ; beyond 4σ_r a Gaussian has 6.3e-5 of its
  // samples (≈ 13 of 2e5) carrying 0.11 % of Σ r² — all of which the excess subtracts.
  std::mt19937_64 rng(11);
  const std::vector<double> x = white(200000, rng);
  const OutlierScan s = find_outliers(x);
  EXPECT_FALSE(s.significant);
  EXPECT_LT(s.excess_variance_fraction, kOutlierFindingFraction);
  EXPECT_LT(s.indices.size(), 60u);  // mean ≈ 13, Poisson: 60 is 13 SD above
  EXPECT_NEAR(s.sample_sigma, 1.0, 0.02);
}

TEST(Outliers, SpikesAreFoundAndDropKeepsTheWhiteNoiseUnbiased) {
  // 5 % spikes of ±8σ (the battery's outliers class): the recorded white variance is
  // σ²(1 + p·k²) = 4.2σ² (N +105 %). After drop, AVAR(m) should be σ²/m: its relative SE
  // at m = 1 and 10 with n = 4e5 is about √(1/n·(3m... )) < 0.6 %; 2 % is over 3 SE, and the
  // bias left by the drop (the level's correlation 2p·m/(2W+1), 0.01 % at m = 10) is far below.
  std::mt19937_64 rng(12);
  std::vector<double> x = white(400000, rng);
  std::bernoulli_distribution spike(0.05), sign(0.5);
  std::vector<char> is_spike(x.size(), 0);
  std::size_t spikes = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (spike(rng)) {
      x[k] += sign(rng) ? 8.0 : -8.0;
      is_spike[k] = 1;
      ++spikes;
    }
  }
  const OutlierScan s = find_outliers(x);
  ASSERT_TRUE(s.significant);
  // An 8σ spike is past the 4σ_r ≈ 4.56σ threshold unless its own noise and the neighbours'
  // median pull it back by 3σ: P ≈ Φ(−3.0) = 0.13 % (more when two of its four neighbours are
  // spikes of its sign, 0.4 % of the spikes): ≥ 99 % found. A clean sample is flagged when two
  // same-sign spikes among its neighbours move their median by ≳ 4σ: at most about
  // 6·0.025²·2 = 0.75 % of the samples, i.e. 15 % of the spikes' count; 5 % bounds what was seen.
  std::size_t found = 0;
  for (std::size_t k : s.indices) found += is_spike[k];
  EXPECT_GE(static_cast<double>(found), 0.99 * static_cast<double>(spikes));
  EXPECT_LE(static_cast<double>(s.indices.size() - found), 0.05 * static_cast<double>(spikes));
  EXPECT_NEAR(overlapping_avar(x, 1), 4.2, 0.1);  // as recorded
  const std::vector<double> y = apply_outlier_policy(x, s, OutlierPolicy::drop, 1);
  // SE of the OAVAR of white noise: √(3/n) = 0.27 % at m = 1, √(2/ν) with ν ≈ 1.5n/m = 0.58 %
  // at m = 10; 1.2 % and 2.5 % are 4.4 SE. Spikes the scan misses would show here: each left
  // carries 64σ², so 0.4 % of them missed gives +1 % (the first pass alone left about that).
  EXPECT_NEAR(overlapping_avar(y, 1), 1.0, 0.012) << overlapping_avar(y, 1);
  EXPECT_NEAR(overlapping_avar(y, 10) * 10.0, 1.0, 0.025) << overlapping_avar(y, 10) * 10.0;
  EXPECT_NEAR(std::sqrt(mean_square_difference(x) / mean_square_difference(y)) - 1.0,
              std::sqrt(4.2) - 1.0, 0.05);
}

TEST(Outliers, ClipPullsOutliersToTheThresholdAndKeepLeavesThem) {
  std::mt19937_64 rng(13);
  std::vector<double> x = white(20000, rng);
  x[5000] += 50.0;
  x[12000] -= 50.0;
  const OutlierScan s = find_outliers(x);
  ASSERT_GE(s.indices.size(), 2u);
  const std::vector<double> clipped = apply_outlier_policy(x, s, OutlierPolicy::clip, 0);
  EXPECT_LT(std::abs(clipped[5000]), 4.0 * s.residual_scale + 3.0);
  EXPECT_LT(std::abs(clipped[12000]), 4.0 * s.residual_scale + 3.0);
  EXPECT_EQ(apply_outlier_policy(x, s, OutlierPolicy::keep, 0), x);
}

TEST(Outliers, PolicyNamesAreParsedAndOthersRefused) {
  EXPECT_EQ(parse_outlier_policy("keep", "--outliers"), OutlierPolicy::keep);
  EXPECT_EQ(parse_outlier_policy("clip", "--outliers"), OutlierPolicy::clip);
  EXPECT_EQ(parse_outlier_policy("drop", "--outliers"), OutlierPolicy::drop);
  try {
    parse_outlier_policy("remove", "--outliers");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--outliers: expected keep, clip or drop, got 'remove'");
  }
}

}  // namespace
}  // namespace imunoise::pipeline
