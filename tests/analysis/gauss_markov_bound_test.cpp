/// @file
/// @brief Tests of the Gauss–Markov upper-bound curve (analysis::gauss_markov_bound_grid,
/// analysis::gauss_markov_upper_bounds).
///
/// Truths: on exact expectations a GM of the truth lies below its own bound (the truth model's
/// deviance is 0); on OAVAR vectors drawn from their joint distribution under a truth with a GM
/// at the edge of detection (analysis::VarianceDraw, the interval draws' Gaussian copula with χ²
/// marginals), the bound at the truth's T_c holds the truth in at least 95 % of the draws whose
/// fit keeps no GM there (issue 20's coverage target for every coefficient class), within three
/// binomial standard errors.
///
/// Measured with this test's draws (seed 20, 200 draws), the share of draws whose bound holds
/// the truth, GM not identified: with the χ²₁ threshold from the best σ 132/156 = 84.6 % (88 %
/// with GM terms off, where no selection conditions the draws); from the reported model's
/// deviance 143/156; with the chi-bar-square threshold as well (the default) 146/156 = 93.6 %
/// (191/200 = 95.5 % with GM terms off). The nominal level of the χ²₁(95 %) profile's upper end
/// is 97.5 %; the rest of the gap is the conditioning on the selection leaving the GM out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "analysis/deviation_type.h"
#include "analysis/noise_fit.h"
#include "analysis/tau_grid.h"
#include "analysis/variance_covariance.h"
#include "common/errors.h"

namespace imunoise::analysis {
namespace {

TEST(GaussMarkovBoundGrid, RoundValuesCoveringTheRange) {
  const std::vector<double> grid = gauss_markov_bound_grid(0.01, 1500.0);
  ASSERT_FALSE(grid.empty());
  EXPECT_EQ(grid.front(), 0.01);
  EXPECT_EQ(grid.back(), 1780.0);  // the first grid value at or above 1500 s
  EXPECT_EQ(grid.size(), 22u);     // 0.01 … 1780: 5.25 decades at 4 per decade, both ends
  const std::vector<double> decade{1.0, 1.78, 3.16, 5.62, 10.0};
  EXPECT_EQ(gauss_markov_bound_grid(1.0, 10.0), decade);
  EXPECT_EQ(gauss_markov_bound_grid(1.2, 1.3), (std::vector<double>{1.0, 1.78}));
  EXPECT_THROW(gauss_markov_bound_grid(0.0, 1.0), ContractViolation);
  EXPECT_THROW(gauss_markov_bound_grid(2.0, 1.0), ContractViolation);
}

/// The battery's gm gyro_y (2 h at 100 Hz): N and a GM of T_c = 300 s whose ADEV peak is 4× the
/// N line, which the default selection identifies in about 1 record of 20.
struct EdgeCase {
  NoiseCoefficients truth;
  double tau0_s = 0.01;
  std::int64_t samples = 720000;
  std::vector<std::int64_t> m;
  VarianceCovariance moments;
};

EdgeCase edge_case() {
  EdgeCase c;
  c.truth.white_noise = 5.236e-5;
  c.truth.gauss_markov = {{1.4238e-5, 300.0}};
  c.m = averaging_factors(parse_tau_grid("log:10"), DeviationType::oadev, c.samples + 1);
  c.moments = overlapping_variance_covariance(c.truth, c.tau0_s, c.samples, c.m);
  return c;
}

std::vector<FitPoint> points_of(const EdgeCase& c, const std::vector<double>& avar) {
  std::vector<FitPoint> points;
  for (std::size_t i = 0; i < c.m.size(); ++i)
    points.push_back({static_cast<double>(c.m[i]) * c.tau0_s, avar[i], c.moments.edf[i]});
  return points;
}

/// The correlation of the estimates at FIT.used under FIT's model, row-major.
std::vector<double> used_correlation(const EdgeCase& c, const FitResult& fit) {
  std::vector<std::int64_t> used_m;
  for (std::size_t k : fit.used) used_m.push_back(c.m[k]);
  const Eigen::MatrixXd rho = correlation_matrix(overlapping_variance_covariance(
      std::getenv("GMTRUTHC") ? c.truth : fit.coefficients, c.tau0_s, c.samples, used_m));
  std::vector<double> out(rho.size());
  for (Eigen::Index i = 0; i < rho.rows(); ++i)
    for (Eigen::Index j = 0; j < rho.cols(); ++j) out[i * rho.cols() + j] = rho(i, j);
  return out;
}

TEST(GaussMarkovUpperBounds, ExactExpectationsLieBelowTheCurve) {
  const EdgeCase c = edge_case();
  const std::vector<FitPoint> points = points_of(c, c.moments.expected);
  FitOptions options;
  options.gauss_markov = GaussMarkovMode::off;  // the power-law model stands in for the GM
  const FitResult fit = fit_noise_model(points, options);
  ASSERT_TRUE(fit.coefficients.gauss_markov.empty());
  const std::vector<double> grid{30.0, 300.0, 3000.0};
  const std::vector<GaussMarkovBound> bounds = gauss_markov_upper_bounds(
      points, fit, grid, 0.95, std::getenv("GMIT") ? 25 : 5, used_correlation(c, fit));
  ASSERT_EQ(bounds.size(), 3u);
  EXPECT_EQ(bounds[1].tau_c_s, 300.0);
  EXPECT_GE(bounds[1].sigma_max, c.truth.gauss_markov[0].sigma);
  // Informative: a GM twice the truth's at its T_c is excluded.
  EXPECT_LT(bounds[1].sigma_max, 2.0 * c.truth.gauss_markov[0].sigma);
}

TEST(GaussMarkovUpperBounds, HoldsTheTruthAtItsConfidenceOnDrawnRecords) {
  const EdgeCase c = edge_case();
  const VarianceDraw draw(c.moments);
  std::mt19937_64 rng(20);
  std::normal_distribution<double> normal;
  std::vector<double> u(c.m.size()), avar(c.m.size());
  const double truth_sigma = c.truth.gauss_markov[0].sigma;
  const std::vector<double> grid{300.0};
  constexpr int kDraws = 200;
  int without_gm = 0, covered = 0;
  std::vector<double> ratios;
  for (int r = 0; r < kDraws; ++r) {
    for (double& x : u) x = normal(rng);
    draw.draw(u, avar);
    const std::vector<FitPoint> points = points_of(c, avar);
    FitOptions o;
    if (std::getenv("GMOFF")) o.gauss_markov = GaussMarkovMode::off;
    const FitResult fit = fit_noise_model(points, o);  // the default: GM fitted apart, compared
    const bool gm_near = std::any_of(
        fit.coefficients.gauss_markov.begin(), fit.coefficients.gauss_markov.end(),
        [](const GaussMarkov& g) { return std::abs(std::log(g.tau_c_s / 300.0)) < std::log(3.0); });
    if (gm_near) continue;  // identified: its own interval speaks for it
    ++without_gm;
    const std::vector<GaussMarkovBound> bounds = gauss_markov_upper_bounds(
        points, fit, grid, 0.95, std::getenv("GMIT") ? 25 : 5, used_correlation(c, fit));
    ASSERT_EQ(bounds.size(), 1u);
    covered += truth_sigma <= bounds[0].sigma_max;
    if (std::getenv("GMLEVELS")) {
      static int c99 = 0, c999 = 0, cnt = 0;
      ++cnt;
      c99 += truth_sigma <=
             gauss_markov_upper_bounds(points, fit, grid, 0.99, 5, used_correlation(c, fit))[0]
                 .sigma_max;
      c999 += truth_sigma <=
              gauss_markov_upper_bounds(points, fit, grid, 0.999, 5, used_correlation(c, fit))[0]
                  .sigma_max;
      if (r == kDraws - 1) printf("levels: 0.99 %d/%d 0.999 %d/%d\n", c99, cnt, c999, cnt);
    }
    ratios.push_back(bounds[0].sigma_max / truth_sigma);
  }
  // The selection leaves this GM out in most draws (battery: 19 of 20 records).
  ASSERT_GE(without_gm, kDraws / 2);
  // Issue 20's 95 %, three binomial standard errors below it.
  const double p = 0.95;
  const double n = without_gm;
  EXPECT_GE(covered / n, p - 3.0 * std::sqrt(p * (1.0 - p) / n)) << covered << " of " << without_gm;
  // Informative: the median bound stays within 2× the truth (the bound of an undetected GM is
  // not a formality).
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  EXPECT_LT(ratios[ratios.size() / 2], 2.0);
  printf("covered %d of %d median ratio %g\n", covered, without_gm, ratios[ratios.size() / 2]);
}

TEST(GaussMarkovUpperBounds, EmptyWithoutPointsAndRejectsBadTimes) {
  const EdgeCase c = edge_case();
  const std::vector<FitPoint> points = points_of(c, c.moments.expected);
  FitResult empty;
  EXPECT_TRUE(gauss_markov_upper_bounds(points, empty, std::vector<double>{1.0}, 0.95).empty());
  const FitResult fit = fit_noise_model(points);
  EXPECT_THROW(gauss_markov_upper_bounds(points, fit, std::vector<double>{0.0}, 0.95),
               ContractViolation);
}

}  // namespace
}  // namespace imunoise::analysis
