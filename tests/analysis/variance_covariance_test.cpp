// Tests of analysis/variance_covariance.h against independent truths: the expectations against
// the closed-form AVAR/HVAR laws of theory.md §4.1 (analysis/noise_terms), the EDF of each
// power-law noise against the Greenhall–Riley EDF [GR03] (analysis/edf, itself checked against
// Stable32), and the covariance across τ against a Monte Carlo of exactly simulated white and
// random-walk rate noise (std::mt19937_64 here; nothing from models/).
#include "analysis/variance_covariance.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>
#include <vector>

#include "analysis/edf.h"
#include "analysis/noise_terms.h"
#include "common/errors.h"

namespace imunoise::analysis {
namespace {

constexpr double kTau0 = 0.01;
constexpr std::int64_t kSamples = 100'000;

NoiseCoefficients only(NoiseTerm term, double value) {
  NoiseCoefficients c;
  coefficient(c, term) = value;
  return c;
}

void expect_expectations_match(const NoiseCoefficients& c, bool hadamard, const char* what) {
  const std::vector<std::int64_t> m{1, 2, 3, 10, 100, 1000, 10000};
  const VarianceCovariance v = overlapping_variance_covariance(c, kTau0, kSamples, m, hadamard);
  for (std::size_t i = 0; i < m.size(); ++i) {
    const double tau = static_cast<double>(m[i]) * kTau0;
    EXPECT_NEAR(v.expected[i] / model_variance(c, tau, hadamard), 1.0, 1e-9)
        << what << (hadamard ? " HVAR" : " AVAR") << " m=" << m[i];
  }
}

TEST(VarianceCovariance, ExpectationsAreTheClosedFormLawsOfEveryTerm) {
  for (const bool hadamard : {false, true}) {
    expect_expectations_match(only(NoiseTerm::quantization, 2e-5), hadamard, "Q");
    expect_expectations_match(only(NoiseTerm::white_noise, 1e-4), hadamard, "N");
    expect_expectations_match(only(NoiseTerm::bias_instability, 3e-5), hadamard, "B");
    expect_expectations_match(only(NoiseTerm::random_walk, 5e-6), hadamard, "K");
    if (!hadamard) expect_expectations_match(only(NoiseTerm::ramp, 1e-7), hadamard, "R");
    NoiseCoefficients gm;
    gm.gauss_markov = {{2e-4, 0.05}, {1e-4, 30.0}, {5e-5, 2000.0}};
    expect_expectations_match(gm, hadamard, "GM");
    NoiseCoefficients line;
    // Frequencies with no whole number of periods in any τ of the list (else both sides are 0).
    line.sinusoids = {{1e-3, 0.3712, 0.2}, {2e-4, 7.13, 1.0}};
    expect_expectations_match(line, hadamard, "sinusoid");
  }
}

TEST(VarianceCovariance, EdfOfWhiteRateNoiseIsTheExactClosedForm) {
  // SP 1065 Table 5, white FM, fully overlapping AVAR: ν = (3(M−1)/2m − 2(M−2)/M)·4m²/(4m²+5),
  // exact (Lesage & Audoin) where m ≪ M.
  const std::vector<std::int64_t> m{1, 2, 3, 5, 16, 100};
  const VarianceCovariance v =
      overlapping_variance_covariance(only(NoiseTerm::white_noise, 1e-4), kTau0, kSamples, m);
  for (std::size_t i = 0; i < m.size(); ++i) {
    EXPECT_NEAR(v.edf[i] / edf_simple_oadev(0, m[i], kSamples + 1), 1.0, 1e-4) << "m=" << m[i];
  }
}

TEST(VarianceCovariance, EdfOfEachPowerLawIsGreenhallRileyWhereTheirModelIsExact) {
  // GR03 evaluates the same generalized-covariance sums, but with the unmodified filters of
  // small m replaced by their modified form (F = m) and the lag sum cut at (d+1)·m: exact for
  // white PM at every m, for white and random-walk FM once m ≫ 1 (their lag sums end there),
  // and within the tail GR03 omits (≤ 0.5 %) for flicker FM.
  struct Case {
    NoiseTerm term;
    int alpha;
    std::int64_t m_from;
    double tolerance;
  };
  const Case cases[] = {{NoiseTerm::quantization, 2, 1, 1e-4},
                        {NoiseTerm::white_noise, 0, 1000, 2e-3},
                        {NoiseTerm::bias_instability, -1, 16, 5e-3},
                        {NoiseTerm::random_walk, -2, 100, 1e-4}};
  const std::vector<std::int64_t> m{1, 2, 5, 16, 100, 1000, 10000, 30000};
  for (const bool hadamard : {false, true}) {
    for (const Case& c : cases) {
      const VarianceCovariance v =
          overlapping_variance_covariance(only(c.term, 1e-4), kTau0, kSamples, m, hadamard);
      for (std::size_t i = 0; i < m.size(); ++i) {
        if (m[i] < c.m_from || (hadamard && m[i] > kSamples / 3)) continue;
        const double gr = edf_greenhall_direct(c.alpha, hadamard ? 3 : 2, m[i], kSamples + 1,
                                               /*overlapping=*/true, /*modified=*/false);
        EXPECT_NEAR(v.edf[i] / gr, 1.0, c.tolerance)
            << term_name(c.term) << (hadamard ? " HVAR" : " AVAR") << " m=" << m[i] << ": "
            << v.edf[i] << " vs GR03 " << gr;
      }
    }
  }
}

TEST(VarianceCovariance, GaussMarkovTendsToWhiteAndToRandomWalkNoise) {
  // theory.md §4.1: τ ≫ T_c → white with N = σ√(2T_c); τ ≪ T_c → random walk with K = σ√(2/T_c).
  const std::vector<std::int64_t> m{100, 300, 1000};
  NoiseCoefficients fast, slow;
  fast.gauss_markov = {{1e-3, 1e-3}};
  slow.gauss_markov = {{1e-3, 1e6}};
  const VarianceCovariance f = overlapping_variance_covariance(fast, kTau0, kSamples, m);
  const VarianceCovariance s = overlapping_variance_covariance(slow, kTau0, kSamples, m);
  const VarianceCovariance white = overlapping_variance_covariance(
      only(NoiseTerm::white_noise, 1e-3 * std::sqrt(2e-3)), kTau0, kSamples, m);
  const VarianceCovariance walk = overlapping_variance_covariance(
      only(NoiseTerm::random_walk, 1e-3 * std::sqrt(2e-6)), kTau0, kSamples, m);
  for (std::size_t i = 0; i < m.size(); ++i) {
    EXPECT_NEAR(f.edf[i] / white.edf[i], 1.0, 5e-3) << "fast GM, m=" << m[i];
    EXPECT_NEAR(s.edf[i] / walk.edf[i], 1.0, 5e-3) << "slow GM, m=" << m[i];
    for (std::size_t j = 0; j < m.size(); ++j) {
      const auto ii = static_cast<Eigen::Index>(i), jj = static_cast<Eigen::Index>(j);
      EXPECT_NEAR(f.covariance(ii, jj) / white.covariance(ii, jj), 1.0, 1e-2);
      EXPECT_NEAR(s.covariance(ii, jj) / walk.covariance(ii, jj), 1.0, 1e-2);
    }
  }
}

TEST(VarianceCovariance, LongRecordWithFlickerGivesAPositiveDefiniteCorrelation) {
  // 8 h at 400 Hz (11.5 M samples) of white + flicker + random walk on a log:10 grid: the
  // correlation matrix is positive definite and the EDF at m = 1, where white noise carries
  // 99.9 % of the variance, is within 1 % of white's 2M/3. (The lag sum once ran over the whole
  // record, where the flicker's cross-covariance is below double precision's resolution of its
  // terms; the rounding summed over 10⁷ lags made the matrix indefinite, min eigenvalue −0.1.)
  NoiseCoefficients c;
  c.white_noise = 1.18e-4;
  c.bias_instability = 1.26e-4;
  c.random_walk = 7.6e-6;
  const std::int64_t n = 8 * 3600 * 400;
  std::vector<std::int64_t> m;
  for (double x = 1.0; x < static_cast<double>(n) / 8.0; x *= std::pow(10.0, 0.1)) {
    const auto mi = static_cast<std::int64_t>(std::llround(x));
    if (m.empty() || mi != m.back()) m.push_back(mi);
  }
  const VarianceCovariance v = overlapping_variance_covariance(c, 1.0 / 400.0, n, m);
  const Eigen::Index k = v.covariance.rows();
  Eigen::MatrixXd correlation(k, k);
  for (Eigen::Index i = 0; i < k; ++i) {
    for (Eigen::Index j = 0; j < k; ++j) {
      correlation(i, j) = v.covariance(i, j) / std::sqrt(v.covariance(i, i) * v.covariance(j, j));
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(correlation);
  EXPECT_GT(eigen.eigenvalues()(0), 0.0);
  const double white_edf = edf_simple_oadev(0, 1, n + 1);
  EXPECT_NEAR(v.edf[0] / white_edf, 1.0, 0.01) << v.edf[0] << " vs " << white_edf;
}

/// Overlapping AVAR of rate samples Y at averaging factor M (its own few lines).
double oavar(const std::vector<double>& y, std::int64_t m, double tau0) {
  std::vector<double> x(y.size() + 1, 0.0);
  for (std::size_t i = 0; i < y.size(); ++i) x[i + 1] = x[i] + y[i] * tau0;
  const auto n = static_cast<std::int64_t>(x.size()) - 2 * m;
  double s = 0.0;
  for (std::int64_t k = 0; k < n; ++k) {
    const double d = x[static_cast<std::size_t>(k + 2 * m)] -
                     2.0 * x[static_cast<std::size_t>(k + m)] + x[static_cast<std::size_t>(k)];
    s += d * d;
  }
  const double tau = static_cast<double>(m) * tau0;
  return s / (2.0 * tau * tau * static_cast<double>(n));
}

TEST(VarianceCovariance, CovarianceAcrossTauMatchesAMonteCarloOfWhitePlusRandomWalk) {
  // White rate N plus a τ0-averaged random walk K (exact: the walk's increments over a sample
  // and its within-sample average drawn jointly), both crossing near m = 30.
  const double n_coef = 1e-3, k_coef = 3e-4, tau0 = 0.01;
  const std::int64_t samples = 3000;
  const std::vector<std::int64_t> m{1, 4, 16, 64, 256};
  NoiseCoefficients c;
  c.white_noise = n_coef;
  c.random_walk = k_coef;
  const VarianceCovariance v = overlapping_variance_covariance(c, tau0, samples, m);

  const int runs = 4000;
  std::mt19937_64 rng(20261201);
  std::normal_distribution<double> normal;
  std::vector<std::vector<double>> est(m.size(), std::vector<double>(runs));
  std::vector<double> y(static_cast<std::size_t>(samples));
  // Within one sample of length τ0 the walk w(t) moves by K√τ0·z1; its average over the sample
  // is w0 + K√τ0·(z1/2 + z2/√12).
  for (int r = 0; r < runs; ++r) {
    double w = 0.0;
    for (double& yi : y) {
      const double z1 = normal(rng), z2 = normal(rng);
      const double average = w + k_coef * std::sqrt(tau0) * (0.5 * z1 + z2 / std::sqrt(12.0));
      w += k_coef * std::sqrt(tau0) * z1;
      yi = average + n_coef / std::sqrt(tau0) * normal(rng);
    }
    for (std::size_t i = 0; i < m.size(); ++i)
      est[i][static_cast<std::size_t>(r)] = oavar(y, m[i], tau0);
  }
  std::vector<double> mean(m.size(), 0.0);
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (const double e : est[i]) mean[i] += e / runs;
    // The mean of RUNS estimates: standard error √(Var/runs).
    const double se =
        std::sqrt(v.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) / runs);
    EXPECT_NEAR(mean[i], v.expected[i], 4.0 * se) << "m=" << m[i];
  }
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (std::size_t j = i; j < m.size(); ++j) {
      double cov = 0.0;
      for (int r = 0; r < runs; ++r) {
        cov += (est[i][static_cast<std::size_t>(r)] - mean[i]) *
               (est[j][static_cast<std::size_t>(r)] - mean[j]);
      }
      cov /= runs - 1;
      const double predicted =
          v.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
      const double vi = v.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i));
      const double vj = v.covariance(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j));
      // Standard error of a sample covariance of near-Gaussian variables: √((σi²σj² + c²)/R);
      // the estimates at large m are skewed (few dof), so allow 5 standard errors.
      const double se = std::sqrt((vi * vj + predicted * predicted) / runs);
      EXPECT_NEAR(cov, predicted, 5.0 * se) << "m=" << m[i] << "," << m[j];
      if (i != j) {
        EXPECT_GT(predicted, 0.0);  // neighbouring τ correlate positively (theory.md §3.5)
      }
    }
  }
}

TEST(VarianceCovariance, CallerBugsAreContractViolations) {
  const std::vector<std::int64_t> m{1, 10};
  const std::vector<std::int64_t> too_long{60};
  EXPECT_THROW(overlapping_variance_covariance(only(NoiseTerm::white_noise, 1.0), 0.0, 100, m),
               ContractViolation);
  EXPECT_THROW(
      overlapping_variance_covariance(only(NoiseTerm::white_noise, 1.0), 1.0, 100, too_long),
      ContractViolation);
  EXPECT_THROW(overlapping_variance_covariance(only(NoiseTerm::white_noise, -1.0), 1.0, 100, m),
               ContractViolation);
}

}  // namespace
}  // namespace imunoise::analysis
