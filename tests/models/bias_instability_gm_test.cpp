/// @file
/// @brief Tests of models/bias_instability_gm.h: the GM ADEV peak constants against the closed
/// form of theory.md §4.1 and the table of Gauss–Markov equivalents in §8.3.
#include "models/bias_instability_gm.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/noise_terms.h"
#include "common/errors.h"
#include "test_support.h"

namespace imunoise::models {
namespace {

/// @name Worked example, theory.md §8.2
/// @{
constexpr double kExampleN = 1.16355e-4;  // [rad/√s]
constexpr double kExampleB = 1.22173e-4;  // [rad/s]
constexpr double kExampleK = 6.80678e-6;  // [rad/s^{3/2}]
constexpr double kTauMin = 29.6;          // τ_min = √3N/K as printed in §8.2 [s]
/// @}

/// q_c² = 2σ²/T_c [rad²/s³] (theory.md §4.1).
double driving_intensity(const GaussMarkov& gm) { return 2.0 * gm.sigma * gm.sigma / gm.tau_c_s; }

TEST(BiasInstabilityGm, PeakConstantsRoundToTheoryValues) {
  const GaussMarkovPeak peak = gauss_markov_adev_peak();
  EXPECT_NEAR(peak.tau_ratio, 1.8926, 0.00005);
  EXPECT_NEAR(peak.adev_ratio, 0.6174, 0.00005);
  // Independent check: it is the maximum of the closed-form GM ADEV.
  const auto adev = [](double x) { return std::sqrt(analysis::gauss_markov_avar(1.0, 1.0, x)); };
  EXPECT_NEAR(adev(peak.tau_ratio), peak.adev_ratio, 1e-14);
  EXPECT_GT(peak.adev_ratio, adev(peak.tau_ratio * (1.0 + 1e-4)));
  EXPECT_GT(peak.adev_ratio, adev(peak.tau_ratio * (1.0 - 1e-4)));
}

TEST(BiasInstabilityGm, ReproducesTheory83Table) {
  // (a) σ = the measured minimum ADEV of the §8.2 curve (N and K lift it above 0.664B).
  NoiseCoefficients curve;
  curve.white_noise = kExampleN;
  curve.bias_instability = kExampleB;
  curve.random_walk = kExampleK;
  const double min_adev = analysis::model_adev(curve, std::sqrt(3.0) * kExampleN / kExampleK);
  const GaussMarkov a = gauss_markov_from_bias_instability(
      kExampleB, kTauMin, GmConvention::min_adev_at_tau_min, min_adev);
  EXPECT_NEAR(a.sigma, 8.661e-5, 0.0005e-5);
  EXPECT_NEAR(a.tau_c_s, 29.6, 0.05);
  EXPECT_NEAR(driving_intensity(a), 5.07e-10, 0.005e-10);

  const GaussMarkov b =
      gauss_markov_from_bias_instability(kExampleB, kTauMin, GmConvention::peak_match);
  // §8.3 prints 1.314e-4 and §4.4 1.0755·B: both from the rounded 0.664/0.6174. The exact
  // √(2 ln2/π)/g* = 0.664282/0.617364 = 1.07600 gives 1.3146e-4, one unit above the last
  // printed digit; checked here to the exact value and to the table within that unit.
  EXPECT_NEAR(b.sigma, 1.314e-4, 0.0010e-4);
  EXPECT_NEAR(b.sigma, 1.3146e-4, 0.00005e-4);
  EXPECT_NEAR(0.664 / 0.6174 * kExampleB, 1.314e-4, 0.0005e-4);  // the table's own rounding
  EXPECT_NEAR(b.sigma / kExampleB, 1.0760, 0.00005);
  EXPECT_NEAR(b.tau_c_s, 15.6, 0.05);
  EXPECT_NEAR(driving_intensity(b), 2.21e-9, 0.005e-9);

  const GaussMarkov c =
      gauss_markov_from_bias_instability(kExampleB, kTauMin, GmConvention::sigma_equals_b);
  EXPECT_NEAR(c.sigma, 1.222e-4, 0.0005e-4);
  EXPECT_NEAR(c.tau_c_s, 29.6, 0.05);
  EXPECT_NEAR(driving_intensity(c), 1.01e-9, 0.005e-9);
}

TEST(BiasInstabilityGm, MinAdevConventionDefaultsToThePureFloor) {
  const GaussMarkov a =
      gauss_markov_from_bias_instability(kExampleB, kTauMin, GmConvention::min_adev_at_tau_min);
  EXPECT_DOUBLE_EQ(a.sigma,
                   std::sqrt(2.0 * std::log(2.0) / std::numbers::pi) * kExampleB);  // 0.6643·B
  EXPECT_NEAR(a.sigma, 8.116e-5, 0.0005e-5);
  EXPECT_EQ(a.tau_c_s, kTauMin);
}

TEST(BiasInstabilityGm, PeakMatchPutsTheGmPeakOnTheFloor) {
  const GaussMarkov b =
      gauss_markov_from_bias_instability(kExampleB, kTauMin, GmConvention::peak_match);
  const double floor_adev = std::sqrt(2.0 * std::log(2.0) / std::numbers::pi) * kExampleB;
  EXPECT_NEAR(std::sqrt(analysis::gauss_markov_avar(b.sigma, b.tau_c_s, kTauMin)) / floor_adev, 1.0,
              1e-12);
}

TEST(BiasInstabilityGm, NamesAndErrors) {
  EXPECT_EQ(name_of(GmConvention::min_adev_at_tau_min), "min_adev_at_tau_min");
  EXPECT_EQ(name_of(GmConvention::peak_match), "peak_match");
  EXPECT_EQ(name_of(GmConvention::sigma_equals_b), "sigma_equals_b");
  test::expect_throw_containing<ContractViolation>(
      [] { gauss_markov_from_bias_instability(-1.0, 10.0, GmConvention::peak_match); },
      "B must be finite and >= 0");
  test::expect_throw_containing<ContractViolation>(
      [] { gauss_markov_from_bias_instability(1.0, 0.0, GmConvention::peak_match); },
      "tau_min must be finite and > 0");
  test::expect_throw_containing<ContractViolation>(
      [] { gauss_markov_from_bias_instability(1.0, 1.0, GmConvention::min_adev_at_tau_min, -2.0); },
      "min_adev must be finite and > 0");
}

}  // namespace
}  // namespace imunoise::models
