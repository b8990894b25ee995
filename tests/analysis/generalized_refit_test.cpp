/// @file
/// @brief Tests of the generalized-least-squares refit (analysis::generalized_refit,
/// refit_fixed_terms with a correlation).
///
/// Truths: with the identity correlation GLS is the independent-point fit at its fixed point; on
/// Gaussian draws of the OAVAR vector with the covariance of analysis/variance_covariance.h,
/// the GLS estimate's spread is the closed form (ΦᵀC⁻¹Φ)⁻¹ (Gauss–Markov theorem) and never
/// above the independent-point fit's.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <vector>

#include "analysis/noise_fit.h"
#include "analysis/noise_terms.h"
#include "analysis/variance_covariance.h"
#include "common/errors.h"

namespace imunoise::analysis {
namespace {

constexpr std::size_t kN = 1, kK = 3;

struct WalkCase {
  NoiseCoefficients truth;
  std::vector<std::int64_t> m;
  std::vector<FitPoint> points;  ///< at the expectations, EDF under the truth
  VarianceCovariance moments;
  std::vector<double> correlation;  ///< row-major
  FitResult structure;              ///< N and K identified
};

/// White noise N and a random walk K crossing at τ ≈ 30 s, 2 h at 100 Hz, octave grid
/// (nearly independent points, where GLS gains least) or a log:10 grid (strongly correlated).
WalkCase white_and_walk(bool dense) {
  WalkCase s;
  s.truth.white_noise = 1e-4;
  s.truth.random_walk = 3e-6;
  const double tau0 = 0.01;
  const std::int64_t n = 720000;
  for (double m = 1; m <= static_cast<double>(n) / 8; m *= dense ? std::pow(10.0, 0.1) : 2.0) {
    const auto mi = static_cast<std::int64_t>(std::llround(m));
    if (s.m.empty() || mi > s.m.back()) s.m.push_back(mi);
  }
  s.moments = overlapping_variance_covariance(s.truth, tau0, n, s.m);
  const std::size_t k = s.m.size();
  for (std::size_t i = 0; i < k; ++i)
    s.points.push_back(
        {static_cast<double>(s.m[i]) * tau0, s.moments.expected[i], s.moments.edf[i]});
  s.correlation.assign(k * k, 0.0);
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < k; ++j)
      s.correlation[i * k + j] =
          s.moments.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) /
          std::sqrt(
              s.moments.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) *
              s.moments.covariance(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j)));
  FitOptions options;
  options.allow_terms = {false, true, false, true, false};
  options.gauss_markov = GaussMarkovMode::off;
  options.selection_threshold = 0.0;
  s.structure = fit_noise_model(s.points, options);
  return s;
}

TEST(GeneralizedRefit, IdentityCorrelationIsTheIndependentPointFit) {
  WalkCase s = white_and_walk(false);
  // Perturb the points so that the fit is not trivially exact.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  for (FitPoint& p : s.points) p.avar *= 1.0 + 0.3 * normal(rng) / std::sqrt(p.edf);
  const std::size_t k = s.points.size();
  std::vector<double> identity(k * k, 0.0);
  for (std::size_t i = 0; i < k; ++i) identity[i * k + i] = 1.0;
  // The independent-point fit re-weighted to its fixed point: GLS with the identity and that
  // fit's model as the weights reproduces it.
  FitOptions converged;
  converged.weight_iterations = 60;
  const FitResult independent = refit_fixed_terms(s.points, s.structure, converged);
  const FitResult gls = generalized_refit(s.points, independent, FitOptions{}, identity);
  EXPECT_NEAR(gls.coefficients.white_noise / independent.coefficients.white_noise, 1.0, 1e-9);
  EXPECT_NEAR(gls.coefficients.random_walk / independent.coefficients.random_walk, 1.0, 1e-9);
  EXPECT_EQ(gls.residual_halfwidths.size(), s.points.size());  // a complete result
  EXPECT_TRUE(independent.residual_halfwidths.empty());
}

TEST(GeneralizedRefit, SpreadOnGaussianDrawsIsTheGaussMarkovBound) {
  for (const bool dense : {false, true}) {
    const WalkCase s = white_and_walk(dense);
    const auto k = static_cast<Eigen::Index>(s.m.size());
    // Closed form: c = (N², K²), Var ĉ_GLS = (ΦᵀC⁻¹Φ)⁻¹ with C the covariance of the estimates.
    Eigen::MatrixXd phi(k, 2);
    for (Eigen::Index i = 0; i < k; ++i) {
      phi(i, 0) =
          term_basis(NoiseTerm::white_noise, s.points[static_cast<std::size_t>(i)].tau_s, false);
      phi(i, 1) =
          term_basis(NoiseTerm::random_walk, s.points[static_cast<std::size_t>(i)].tau_s, false);
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(s.moments.covariance);
    ASSERT_EQ(llt.info(), Eigen::Success);
    const Eigen::MatrixXd gls_covariance = (phi.transpose() * llt.solve(phi)).inverse();
    const Eigen::MatrixXd factor = llt.matrixL();

    const int draws = 400;
    std::mt19937_64 rng(dense ? 20261203 : 20261204);
    std::normal_distribution<double> normal;
    std::vector<FitPoint> points = s.points;
    std::vector<double> k2_gls, k2_wls, n2_gls;
    for (int r = 0; r < draws; ++r) {
      Eigen::VectorXd z(k);
      for (Eigen::Index i = 0; i < k; ++i) z(i) = normal(rng);
      const Eigen::VectorXd y = factor * z;
      for (Eigen::Index i = 0; i < k; ++i)
        points[static_cast<std::size_t>(i)].avar =
            std::max(1e-3 * s.moments.expected[static_cast<std::size_t>(i)],
                     s.moments.expected[static_cast<std::size_t>(i)] + y(i));
      const FitResult gls = refit_fixed_terms(points, s.structure, FitOptions{}, s.correlation);
      const FitResult wls = refit_fixed_terms(points, s.structure, FitOptions{});
      k2_gls.push_back(gls.terms[kK].value * gls.terms[kK].value);
      n2_gls.push_back(gls.terms[kN].value * gls.terms[kN].value);
      k2_wls.push_back(wls.terms[kK].value * wls.terms[kK].value);
    }
    const auto variance = [](const std::vector<double>& v) {
      double mean = 0.0, ss = 0.0;
      for (double x : v) mean += x / static_cast<double>(v.size());
      for (double x : v) ss += (x - mean) * (x - mean);
      return ss / static_cast<double>(v.size() - 1);
    };
    // A sample variance of 400 draws is within ±4·√(2/399) = ±28 % of the truth (4 SE).
    // Measured here: var K² GLS/bound 0.90 (octave) and 0.79 (log:10; the NNLS clips K² at 0
    // in the draws that would go negative), the independent-point fit 1.10 and 0.92. A GLS
    // that re-derived its weights from each draw's own fit was 1.61 and 1.53: hence the
    // weights held at the structure's model (analysis/noise_fit.cpp, Data::weight_model).
    const double tolerance = 4.0 * std::sqrt(2.0 / (draws - 1));
    EXPECT_NEAR(variance(k2_gls) / gls_covariance(1, 1), 1.0, tolerance) << "dense " << dense;
    EXPECT_NEAR(variance(n2_gls) / gls_covariance(0, 0), 1.0, tolerance) << "dense " << dense;
    EXPECT_LE(variance(k2_gls), variance(k2_wls)) << "dense " << dense;
  }
}

TEST(GeneralizedRefit, WrongSizedCorrelationIsAContractViolation) {
  const WalkCase s = white_and_walk(false);
  const std::vector<double> wrong(3, 0.0);
  EXPECT_THROW(generalized_refit(s.points, s.structure, FitOptions{}, wrong), ContractViolation);
  EXPECT_THROW(generalized_refit(s.points, s.structure, FitOptions{}, {}), ContractViolation);
}

}  // namespace
}  // namespace imunoise::analysis
