/// @file
/// @brief Tests of analysis/selection_uncertainty.h and analysis::refit_with_term_held().
///
/// Exact curves (closed-form AVAR of analysis/noise_terms.h): a fit whose structure lacks a
/// term, re-fitted with that term held at its true value on a curve that has it, must return
/// the other terms' true values to rounding — the held term is then exactly the missing part of
/// the model. The coverage the widening buys is measured on the validation battery
/// (docs/validation.md), not here.
#include "analysis/selection_uncertainty.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/noise_terms.h"
#include "common/errors.h"

namespace imunoise::analysis {
namespace {

constexpr std::size_t kN = 1, kB = 2, kK = 3;

/// Exact OAVAR points on τ = 10^(k/10) s, k = K0 … K1, white-FM-like EDF 1.5·T/τ (T = 10⁵ s).
std::vector<FitPoint> exact_points(const NoiseCoefficients& model, int k0, int k1) {
  std::vector<FitPoint> points;
  for (int k = k0; k <= k1; ++k) {
    const double tau = std::pow(10.0, k / 10.0);
    points.push_back({tau, model_avar(model, tau), 1.5e5 / tau});
  }
  return points;
}

NoiseCoefficients white_and_flicker() {
  NoiseCoefficients c;
  c.white_noise = 1.16355e-4;       // theory.md §8.2 [rad/√s]
  c.bias_instability = 1.22173e-4;  // [rad/s]
  return c;
}

TEST(RefitWithTermHeld, HoldingTheMissingTermAtItsTrueValueReturnsTheOthersExactly) {
  // The structure: N + B fitted on a curve without K (K not identified there).
  const FitResult structure = fit_noise_model(exact_points(white_and_flicker(), -20, 40));
  ASSERT_TRUE(structure.terms[kN].identified);
  ASSERT_TRUE(structure.terms[kB].identified);
  ASSERT_FALSE(structure.terms[kK].identified);
  // Data with K = 6.8e-6: holding K there leaves exactly N + B for the two free terms.
  NoiseCoefficients with_k = white_and_flicker();
  with_k.random_walk = 6.80678e-6;
  std::vector<FitPoint> points = exact_points(with_k, -20, 40);
  const FitResult held =
      refit_with_term_held(points, structure, NoiseTerm::random_walk, with_k.random_walk);
  EXPECT_NEAR(held.terms[kN].value / with_k.white_noise, 1.0, 1e-9);
  EXPECT_NEAR(held.terms[kB].value / with_k.bias_instability, 1.0, 1e-9);
  EXPECT_FALSE(held.terms[kK].identified);
  EXPECT_EQ(held.coefficients.random_walk, with_k.random_walk);
  EXPECT_NEAR(held.deviance, 0.0, 1e-12);
  // Held at 0 it is the structure's own fit.
  const FitResult at_zero = refit_with_term_held(points, structure, NoiseTerm::random_walk, 0.0);
  const FitResult same = refit_fixed_terms(points, structure, FitOptions{});
  EXPECT_NEAR(at_zero.terms[kB].value / same.terms[kB].value, 1.0, 1e-12);
  EXPECT_NEAR(at_zero.terms[kN].value / same.terms[kN].value, 1.0, 1e-12);
}

TEST(RefitWithTermHeld, RejectsAnIdentifiedTermAndABadValue) {
  const std::vector<FitPoint> points = exact_points(white_and_flicker(), -20, 40);
  const FitResult fit = fit_noise_model(points);
  EXPECT_THROW(refit_with_term_held(points, fit, NoiseTerm::white_noise, 1e-4), ContractViolation);
  EXPECT_THROW(refit_with_term_held(points, fit, NoiseTerm::random_walk, -1.0), ContractViolation);
  EXPECT_THROW(refit_with_term_held(points, fit, NoiseTerm::random_walk, NAN), ContractViolation);
}

TEST(SelectionWidenedIntervals, AModelWithEveryTermIdentifiedIsLeftAsItIs) {
  NoiseCoefficients truth = white_and_flicker();
  truth.random_walk = 6.80678e-6;
  truth.quantization = 1e-6;
  truth.ramp = 1e-7;
  const std::vector<FitPoint> points = exact_points(truth, -20, 40);
  const FitResult fit = fit_noise_model(points);
  PerTerm<CoefficientInterval> given{};
  PerTerm<double> bounds{};
  for (NoiseTerm t : kNoiseTerms) {
    ASSERT_TRUE(fit.terms[t].identified) << term_name(t);
    given[t] = {0.9 * fit.terms[t].value, 1.1 * fit.terms[t].value};
  }
  const PerTerm<SelectionWidening> w = selection_widened_intervals(points, fit, given, bounds);
  for (NoiseTerm t : kNoiseTerms) {
    EXPECT_EQ(w[t].interval.low, given[t].low);
    EXPECT_EQ(w[t].interval.high, given[t].high);
    EXPECT_TRUE(w[t].moved_by.empty());
  }
}

TEST(SelectionWidenedIntervals, ADroppedRandomWalkAtItsBoundLowersTheFlickerEnd) {
  // N + B exact; K not identified. With K held at a bound the long-τ variance K carries
  // is taken from B, so B's interval extends down, and only down: the conditional log
  // half-width ln(1/0.95) and the shift ln(B'/B) of the held fit in quadrature.
  const std::vector<FitPoint> points = exact_points(white_and_flicker(), -20, 40);
  const FitResult fit = fit_noise_model(points);
  ASSERT_FALSE(fit.terms[kK].identified);
  const double bound = 3e-6;
  PerTerm<CoefficientInterval> given{};
  PerTerm<double> bounds{};
  bounds[NoiseTerm::random_walk] = bound;
  const double b = fit.terms[kB].value, n = fit.terms[kN].value;
  given[NoiseTerm::bias_instability] = {0.95 * b, 1.05 * b};
  given[NoiseTerm::white_noise] = {0.99 * n, 1.01 * n};
  const PerTerm<SelectionWidening> w = selection_widened_intervals(points, fit, given, bounds);
  const FitResult held = refit_with_term_held(points, fit, NoiseTerm::random_walk, bound);
  const double ratio = held.terms[kB].value / b;
  ASSERT_LT(ratio, 1.0);
  const double expected_low = b * std::exp(-std::hypot(std::log(1.0 / 0.95), std::log(ratio)));
  EXPECT_NEAR(w[NoiseTerm::bias_instability].interval.low, expected_low, 1e-14 * b);
  EXPECT_LT(expected_low, 0.95 * b);
  EXPECT_EQ(w[NoiseTerm::bias_instability].interval.high, 1.05 * b);
  EXPECT_EQ(w[NoiseTerm::bias_instability].moved_by, "random_walk");
  // The dropped term itself is returned as given.
  EXPECT_EQ(w[NoiseTerm::random_walk].interval.high, 0.0);
  EXPECT_TRUE(w[NoiseTerm::random_walk].moved_by.empty());
}

}  // namespace
}  // namespace imunoise::analysis
