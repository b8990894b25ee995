/// @file
/// @brief Closed-form AVAR/HVAR of the noise terms (see noise_terms.h, theory.md §4.1).
#include "analysis/noise_terms.h"

#include <cmath>
#include <numbers>
#include <string>

#include "common/errors.h"

namespace imunoise::analysis {
namespace {

using std::numbers::ln2;
using std::numbers::pi;

void check_tau(double tau_s, const char* where) {
  IMUNOISE_CHECK(
      std::isfinite(tau_s) && tau_s > 0.0, AnalysisError,
      std::string(where) + ": tau must be finite and > 0 s (got " + std::to_string(tau_s) + ")");
}

void check_gauss_markov(double sigma, double tau_c_s, double tau_s, const char* where) {
  IMUNOISE_CHECK(
      std::isfinite(sigma) && sigma >= 0.0, AnalysisError,
      std::string(where) + ": sigma must be finite and >= 0 (got " + std::to_string(sigma) + ")");
  IMUNOISE_CHECK(std::isfinite(tau_c_s) && tau_c_s > 0.0, AnalysisError,
                 std::string(where) + ": correlation time must be finite and > 0 s (got " +
                     std::to_string(tau_c_s) + ")");
  check_tau(tau_s, where);
}

/// Σ_{n≥3} (−1)ⁿ·(Σ_j w_j·k_jⁿ)·xⁿ/n! — the Taylor series of Σ_j w_j·e^{−k_j x} with its
/// polynomial part (n ≤ 2) removed, which the callers know cancels exactly. Used for x ≤ 0.5,
/// where 30 terms reach full precision (the largest rate k = 3 gives 1.5³⁰/30! ≈ 7e-28).
template <std::size_t J>
double exponential_series_tail(double x, const std::array<double, J>& weights,
                               const std::array<double, J>& rates) {
  double sum = 0.0;
  double power_over_factorial = 1.0;  // xⁿ/n!
  std::array<double, J> rate_power;   // k_jⁿ
  rate_power.fill(1.0);
  for (int n = 1; n <= 30; ++n) {
    power_over_factorial *= x / n;
    double weighted = 0.0;
    for (std::size_t j = 0; j < J; ++j) {
      rate_power[j] *= rates[j];
      weighted += weights[j] * rate_power[j];
    }
    if (n >= 3) sum += ((n % 2 == 0) ? 1.0 : -1.0) * weighted * power_over_factorial;
  }
  return sum;
}

}  // namespace

double term_avar_basis(NoiseTerm term, double tau_s) {
  check_tau(tau_s, "term_avar_basis");
  switch (term) {
    case NoiseTerm::quantization:
      return 3.0 / (tau_s * tau_s);
    case NoiseTerm::white_noise:
      return 1.0 / tau_s;
    case NoiseTerm::bias_instability:
      return 2.0 * ln2 / pi;
    case NoiseTerm::random_walk:
      return tau_s / 3.0;
    case NoiseTerm::ramp:
      return 0.5 * tau_s * tau_s;
  }
  return 0.0;
}

double term_hvar_basis(NoiseTerm term, double tau_s) {
  check_tau(tau_s, "term_hvar_basis");
  switch (term) {
    case NoiseTerm::quantization:
      return (10.0 / 3.0) / (tau_s * tau_s);
    case NoiseTerm::white_noise:
      return 1.0 / tau_s;
    case NoiseTerm::bias_instability:
      return (8.0 * ln2 - 3.0 * std::log(3.0)) / (2.0 * pi);  // theory.md §4.1 HVAR column
    case NoiseTerm::random_walk:
      return tau_s / 6.0;
    case NoiseTerm::ramp:
      return 0.0;
  }
  return 0.0;
}

double gauss_markov_avar(double sigma, double tau_c_s, double tau_s) {
  check_gauss_markov(sigma, tau_c_s, tau_s, "gauss_markov_avar");
  const double x = tau_s / tau_c_s;
  // Bracket 2x − 3 + 4e^{−x} − e^{−2x}: the constant and linear parts cancel the exponentials'
  // first terms, leaving (2/3)x³ + O(x⁴); evaluated directly it would lose all digits as x → 0.
  const double bracket = x <= 0.5 ? exponential_series_tail<2>(x, {4.0, -1.0}, {1.0, 2.0})
                                  : 2.0 * x - 3.0 + 4.0 * std::exp(-x) - std::exp(-2.0 * x);
  // (σ²T²/τ²)·bracket written as σ²·bracket/x² to avoid overflow of T² for huge T.
  return sigma * sigma * bracket / (x * x);
}

double gauss_markov_hvar(double sigma, double tau_c_s, double tau_s) {
  check_gauss_markov(sigma, tau_c_s, tau_s, "gauss_markov_hvar");
  const double x = tau_s / tau_c_s;
  // 6x − 10 + 15e^{−x} − 6e^{−2x} + e^{−3x} = x³ + 0·x⁴ + O(x⁵): same cancellation as above.
  const double bracket =
      x <= 0.5
          ? exponential_series_tail<3>(x, {15.0, -6.0, 1.0}, {1.0, 2.0, 3.0})
          : 6.0 * x - 10.0 + 15.0 * std::exp(-x) - 6.0 * std::exp(-2.0 * x) + std::exp(-3.0 * x);
  return sigma * sigma * bracket / (3.0 * x * x);
}

double sinusoid_avar(double amplitude, double f_hz, double tau_s) {
  check_tau(tau_s, "sinusoid_avar");
  IMUNOISE_CHECK(std::isfinite(amplitude) && std::isfinite(f_hz) && f_hz >= 0.0, AnalysisError,
                 "sinusoid_avar: amplitude and frequency must be finite, frequency >= 0 Hz");
  if (f_hz == 0.0) return 0.0;
  const double x = pi * f_hz * tau_s;
  const double s = std::sin(x);
  return amplitude * amplitude * (s * s) * (s * s) / (x * x);
}

double sinusoid_hvar(double amplitude, double f_hz, double tau_s) {
  check_tau(tau_s, "sinusoid_hvar");
  IMUNOISE_CHECK(std::isfinite(amplitude) && std::isfinite(f_hz) && f_hz >= 0.0, AnalysisError,
                 "sinusoid_hvar: amplitude and frequency must be finite, frequency >= 0 Hz");
  if (f_hz == 0.0) return 0.0;
  const double x = pi * f_hz * tau_s;
  const double s2 = std::sin(x) * std::sin(x);
  return (4.0 / 3.0) * amplitude * amplitude * s2 * s2 * s2 / (x * x);
}

double term_basis(NoiseTerm term, double tau_s, bool hadamard) {
  return hadamard ? term_hvar_basis(term, tau_s) : term_avar_basis(term, tau_s);
}

double gauss_markov_variance(double sigma, double tau_c_s, double tau_s, bool hadamard) {
  return hadamard ? gauss_markov_hvar(sigma, tau_c_s, tau_s)
                  : gauss_markov_avar(sigma, tau_c_s, tau_s);
}

double sinusoid_variance(double amplitude, double f_hz, double tau_s, bool hadamard) {
  return hadamard ? sinusoid_hvar(amplitude, f_hz, tau_s) : sinusoid_avar(amplitude, f_hz, tau_s);
}

double model_variance(const NoiseCoefficients& model, double tau_s, bool hadamard) {
  double sum = 0.0;
  for (NoiseTerm term : kNoiseTerms) {
    const double c = coefficient(model, term);
    sum += c * c * term_basis(term, tau_s, hadamard);
  }
  for (const GaussMarkov& gm : model.gauss_markov)
    sum += gauss_markov_variance(gm.sigma, gm.tau_c_s, tau_s, hadamard);
  for (const Sinusoid& s : model.sinusoids)
    sum += sinusoid_variance(s.amplitude, s.frequency_hz, tau_s, hadamard);
  return sum;
}

double model_avar(const NoiseCoefficients& model, double tau_s) {
  return model_variance(model, tau_s, false);
}

double model_adev(const NoiseCoefficients& model, double tau_s) {
  return std::sqrt(model_avar(model, tau_s));
}

double model_hvar(const NoiseCoefficients& model, double tau_s) {
  return model_variance(model, tau_s, true);
}

double model_hdev(const NoiseCoefficients& model, double tau_s) {
  return std::sqrt(model_hvar(model, tau_s));
}

}  // namespace imunoise::analysis
