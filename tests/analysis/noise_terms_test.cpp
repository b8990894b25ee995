/// @file
/// @brief Tests of analysis/noise_terms.h against independent computations: the AVAR/HVAR of
/// a stationary process from its autocovariance by numerical integration, asymptotic limits,
/// and the worked example of ../shared/docs/theory.md §8.2.
#include "analysis/noise_terms.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "common/errors.h"
#include "common/units.h"

namespace imunoise::analysis {
namespace {

using std::numbers::pi;

/// @name Worked example, theory.md §8.2 (ITG-3200 figures, K read as deg/s/√s)
/// @{
constexpr double kExampleN = 1.16355e-4;  // 0.4 deg/√h [rad/√s]
constexpr double kExampleB = 1.22173e-4;  // 0.007 deg/s [rad/s]
constexpr double kExampleK = 6.80678e-6;  // 3.9e-4 deg/s/√s [rad/s^{3/2}]
NoiseCoefficients example_model() {
  NoiseCoefficients c;
  c.white_noise = kExampleN;
  c.bias_instability = kExampleB;
  c.random_walk = kExampleK;
  return c;
}
/// @}

/// Composite Simpson rule of F on [a, b] with N (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 == 1 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

/// Cov(ȳ_i, ȳ_{i+k}) of τ-averages of a stationary rate with autocovariance R:
/// (1/τ²)∫_{−τ}^{τ}(τ − |u|)·R(u + kτ) du, split at u = 0 where the triangle has its kink
/// (R itself is smooth on each half for k ≥ 1 and even-symmetric for k = 0).
double averaged_covariance(const std::function<double(double)>& R, double tau, int k) {
  const auto integrand = [&](double u) { return (tau - std::abs(u)) * R(u + k * tau); };
  return (simpson(integrand, -tau, 0.0, 20000) + simpson(integrand, 0.0, tau, 20000)) / (tau * tau);
}

/// AVAR = ½E[(ȳ₂ − ȳ₁)²] = C(0) − C(1); HVAR = (1/6)E[(ȳ₃ − 2ȳ₂ + ȳ₁)²] = C(0) − (4/3)C(1)
/// + (1/3)C(2) (theory.md §2 definitions, written with the covariances of adjacent averages).
double numerical_avar(const std::function<double(double)>& R, double tau) {
  return averaged_covariance(R, tau, 0) - averaged_covariance(R, tau, 1);
}
double numerical_hvar(const std::function<double(double)>& R, double tau) {
  return averaged_covariance(R, tau, 0) - (4.0 / 3.0) * averaged_covariance(R, tau, 1) +
         (1.0 / 3.0) * averaged_covariance(R, tau, 2);
}

TEST(NoiseTerms, NamesAndOrder) {
  EXPECT_EQ(term_name(NoiseTerm::quantization), "quantization");
  EXPECT_EQ(term_name(NoiseTerm::white_noise), "white_noise");
  EXPECT_EQ(term_name(NoiseTerm::bias_instability), "bias_instability");
  EXPECT_EQ(term_name(NoiseTerm::random_walk), "random_walk");
  EXPECT_EQ(term_name(NoiseTerm::ramp), "ramp");
  for (std::size_t i = 0; i < kNoiseTerms.size(); ++i)
    EXPECT_EQ(static_cast<std::size_t>(kNoiseTerms[i]), i);
}

TEST(NoiseTerms, AvarBasisMatchesTheoryTable) {
  const double tau = 7.0;
  EXPECT_DOUBLE_EQ(term_avar_basis(NoiseTerm::quantization, tau), 3.0 / 49.0);
  EXPECT_DOUBLE_EQ(term_avar_basis(NoiseTerm::white_noise, tau), 1.0 / 7.0);
  EXPECT_NEAR(term_avar_basis(NoiseTerm::bias_instability, tau), 0.4413, 5e-5);  // §4.1
  EXPECT_DOUBLE_EQ(term_avar_basis(NoiseTerm::random_walk, tau), 7.0 / 3.0);
  EXPECT_DOUBLE_EQ(term_avar_basis(NoiseTerm::ramp, tau), 24.5);
}

TEST(NoiseTerms, HvarBasisMatchesTheoryTable) {
  const double tau = 7.0;
  EXPECT_DOUBLE_EQ(term_hvar_basis(NoiseTerm::quantization, tau), (10.0 / 3.0) / 49.0);
  EXPECT_DOUBLE_EQ(term_hvar_basis(NoiseTerm::white_noise, tau), 1.0 / 7.0);
  EXPECT_NEAR(term_hvar_basis(NoiseTerm::bias_instability, tau), 0.3580, 5e-5);  // §4.1
  EXPECT_DOUBLE_EQ(term_hvar_basis(NoiseTerm::random_walk, tau), 7.0 / 6.0);
  EXPECT_EQ(term_hvar_basis(NoiseTerm::ramp, tau), 0.0);
}

TEST(NoiseTerms, GaussMarkovAvarMatchesNumericalAutocovarianceIntegral) {
  const double sigma = 2.0e-3, tau_c = 30.0;
  const auto R = [&](double u) { return sigma * sigma * std::exp(-std::abs(u) / tau_c); };
  for (double ratio : {0.01, 0.1, 0.5, 1.0, 1.8926, 5.0, 30.0, 100.0}) {
    const double tau = ratio * tau_c;
    const double numeric = numerical_avar(R, tau);
    EXPECT_NEAR(gauss_markov_avar(sigma, tau_c, tau) / numeric, 1.0, 1e-9) << "tau/Tc " << ratio;
    const double numeric_h = numerical_hvar(R, tau);
    EXPECT_NEAR(gauss_markov_hvar(sigma, tau_c, tau) / numeric_h, 1.0, 1e-8) << "tau/Tc " << ratio;
  }
}

TEST(NoiseTerms, GaussMarkovAvarIsStableAtExtremeRatios) {
  const double sigma = 1.0e-3, tau_c = 10.0;
  // τ ≪ T_c: random walk with K² = q_c² = 2σ²/T_c, AVAR (2/3)σ²τ/T_c (theory.md §4.1).
  const double small = 1e-8 * tau_c;
  EXPECT_NEAR(gauss_markov_avar(sigma, tau_c, small) / (2.0 / 3.0 * sigma * sigma * 1e-8), 1.0,
              1e-7);
  EXPECT_NEAR(gauss_markov_hvar(sigma, tau_c, small) / (sigma * sigma * 1e-8 / 3.0), 1.0, 1e-7);
  // τ ≫ T_c: white noise with N² = 2σ²T_c, AVAR 2σ²T_c/τ.
  const double large = 1e8 * tau_c;
  EXPECT_NEAR(gauss_markov_avar(sigma, tau_c, large) / (2.0 * sigma * sigma * tau_c / large), 1.0,
              1e-7);
  EXPECT_NEAR(gauss_markov_hvar(sigma, tau_c, large) / (2.0 * sigma * sigma * tau_c / large), 1.0,
              1e-7);
  // Series and closed form agree where they hand over (x = 0.5).
  const double below = gauss_markov_avar(sigma, tau_c, 0.5 * tau_c * (1.0 - 1e-12));
  const double above = gauss_markov_avar(sigma, tau_c, 0.5 * tau_c * (1.0 + 1e-12));
  EXPECT_NEAR(below / above, 1.0, 1e-11);
}

TEST(NoiseTerms, GaussMarkovAdevPeaksAt1p8926Tc) {
  // theory.md §4.1: maximum at τ* = 1.8926·T_c with ADEV 0.6174·σ.
  const double sigma = 1.0, tau_c = 1.0;
  const double peak = std::sqrt(gauss_markov_avar(sigma, tau_c, 1.8926));
  EXPECT_NEAR(peak, 0.6174, 5e-5);
  EXPECT_GT(peak, std::sqrt(gauss_markov_avar(sigma, tau_c, 1.8926 * 1.001)));
  EXPECT_GT(peak, std::sqrt(gauss_markov_avar(sigma, tau_c, 1.8926 / 1.001)));
}

TEST(NoiseTerms, SinusoidMatchesNumericalAutocovarianceAndVanishesAtMultiplesOfPeriod) {
  const double amplitude = 3.0e-4, f = 0.2;
  // Random-phase sinusoid: R(u) = (A²/2)·cos(2πfu).
  const auto R = [&](double u) { return 0.5 * amplitude * amplitude * std::cos(2 * pi * f * u); };
  for (double tau : {0.3, 1.0, 1.85, 3.7, 12.0}) {
    EXPECT_NEAR(sinusoid_avar(amplitude, f, tau) / numerical_avar(R, tau), 1.0, 1e-9) << tau;
    EXPECT_NEAR(sinusoid_hvar(amplitude, f, tau) / numerical_hvar(R, tau), 1.0, 1e-8) << tau;
  }
  for (int k = 1; k <= 5; ++k) {
    EXPECT_LT(sinusoid_avar(amplitude, f, k / f), 1e-28 * amplitude * amplitude) << k;
    EXPECT_LT(sinusoid_hvar(amplitude, f, k / f), 1e-28 * amplitude * amplitude) << k;
  }
  EXPECT_EQ(sinusoid_avar(amplitude, 0.0, 1.0), 0.0);
}

TEST(NoiseTerms, ModelAvarReproducesTheWorkedExample) {
  // theory.md §8.2: ADEV 8.13e-3 deg/s at 1 s, minimum 4.96e-3 at τ_min = √3N/K = 29.6 s,
  // 5.21e-3 at 100 s, 8.51e-3 at 1000 s; printed to 3 digits → ±0.005e-3.
  const NoiseCoefficients model = example_model();
  const auto adev_deg = [&](double tau) { return model_adev(model, tau) / units::kDegPerS; };
  EXPECT_NEAR(adev_deg(1.0), 8.13e-3, 0.005e-3);
  EXPECT_NEAR(adev_deg(100.0), 5.21e-3, 0.005e-3);
  EXPECT_NEAR(adev_deg(1000.0), 8.51e-3, 0.005e-3);
  const double tau_min = std::sqrt(3.0) * kExampleN / kExampleK;
  EXPECT_NEAR(tau_min, 29.6, 0.05);
  EXPECT_NEAR(adev_deg(tau_min), 4.96e-3, 0.005e-3);
  EXPECT_LT(adev_deg(tau_min), adev_deg(tau_min * 1.01));
  EXPECT_LT(adev_deg(tau_min), adev_deg(tau_min / 1.01));
  // Crossovers ARW→floor 2.06 s and floor→RRW 426 s (§8.2).
  const double floor = kExampleB * kExampleB * term_avar_basis(NoiseTerm::bias_instability, 1.0);
  EXPECT_NEAR(kExampleN * kExampleN / floor, 2.06, 0.005);
  EXPECT_NEAR(3.0 * floor / (kExampleK * kExampleK), 426.0, 0.5);
  // The model is the sum of its terms, and the HDEV sum uses the HVAR bases.
  EXPECT_DOUBLE_EQ(model_avar(model, 10.0),
                   kExampleN * kExampleN / 10.0 + floor + kExampleK * kExampleK * 10.0 / 3.0);
  EXPECT_DOUBLE_EQ(model_hvar(model, 10.0),
                   kExampleN * kExampleN / 10.0 +
                       kExampleB * kExampleB * term_hvar_basis(NoiseTerm::bias_instability, 10.0) +
                       kExampleK * kExampleK * 10.0 / 6.0);
}

TEST(NoiseTerms, ModelIncludesGaussMarkovAndSinusoidTerms) {
  NoiseCoefficients model;
  model.gauss_markov = {{1e-3, 5.0}, {2e-3, 50.0}};
  model.sinusoids = {{1e-4, 0.3, 1.0}};
  const double tau = 4.0;
  EXPECT_DOUBLE_EQ(model_avar(model, tau), gauss_markov_avar(1e-3, 5.0, tau) +
                                               gauss_markov_avar(2e-3, 50.0, tau) +
                                               sinusoid_avar(1e-4, 0.3, tau));
  EXPECT_DOUBLE_EQ(model_adev(model, tau), std::sqrt(model_avar(model, tau)));
}

TEST(NoiseTerms, RejectsNonPositiveTauAndCorrelationTime) {
  EXPECT_THROW(term_avar_basis(NoiseTerm::white_noise, 0.0), AnalysisError);
  EXPECT_THROW(term_hvar_basis(NoiseTerm::white_noise, -1.0), AnalysisError);
  EXPECT_THROW(gauss_markov_avar(1.0, 0.0, 1.0), AnalysisError);
  EXPECT_THROW(gauss_markov_hvar(1.0, 1.0, std::nan("")), AnalysisError);
  EXPECT_THROW(sinusoid_avar(1.0, -1.0, 1.0), AnalysisError);
}

}  // namespace
}  // namespace imunoise::analysis
