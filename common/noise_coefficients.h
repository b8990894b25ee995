/// @file
/// @brief The stochastic error model of one sensor axis as plain SI values (theory.md §1.3,
/// §4.1): the five IEEE-952 coefficients plus first-order Gauss–Markov terms and sinusoids.
/// Shared by analysis (fitting), models (simulation, state models) and io (model files), so
/// it lives in the lowest layer and knows nothing but numbers.
#pragma once

#include <vector>

#include "common/noise_term.h"

namespace imunoise {

/// First-order Gauss–Markov (exponentially correlated) term, theory.md §4.1:
/// autocovariance σ²·e^{−|s|/T_c}, AVAR peak 0.6174·σ at τ = 1.8926·T_c.
struct GaussMarkov {
  double sigma = 0.0;    ///< stationary standard deviation σ_GM [rad/s | m/s²]
  double tau_c_s = 0.0;  ///< correlation time T_c [s], > 0
};

/// The largest σ of one more first-order Gauss–Markov term of correlation time tau_c_s that the
/// data allow beside the fitted model (analysis::gauss_markov_upper_bounds): a GM (σ, tau_c_s)
/// with σ above sigma_max is excluded at the model's confidence.
struct GaussMarkovBound {
  double tau_c_s = 0.0;    ///< correlation time T_c [s], > 0
  double sigma_max = 0.0;  ///< [rad/s | m/s²]
};

/// Deterministic sinusoid A·sin(2π f t + φ); AVAR A²·sin⁴(πfτ)/(πfτ)² (theory.md §4.1).
struct Sinusoid {
  double amplitude = 0.0;     ///< A [rad/s | m/s²]
  double frequency_hz = 0.0;  ///< f [Hz]
  double phase_rad = 0.0;     ///< φ [rad]
};

/// Coefficients of one axis (gyro: rad, rad/s; accelerometer: m/s, m/s²), each ≥ 0;
/// 0 means the term is absent / not identified. AVAR of the sum (theory.md §4.1):
/// σ²(τ) = 3Q²/τ² + N²/τ + (2 ln2/π)B² + K²τ/3 + R²τ²/2 + Σ GM_j(τ) + Σ sine_j(τ).
struct NoiseCoefficients {
  double quantization = 0.0;      ///< Q [rad | m/s]
  double white_noise = 0.0;       ///< N, ARW/VRW [rad/√s | m/s/√s]
  double bias_instability = 0.0;  ///< B [rad/s | m/s²]
  double random_walk = 0.0;       ///< K, RRW / accel RW [rad/s^{3/2} | m/s^{5/2}]
  double ramp = 0.0;              ///< R [rad/s² | m/s³]
  std::vector<GaussMarkov> gauss_markov;
  std::vector<Sinusoid> sinusoids;
};

/// The coefficient of TERM in C (Q, N, B, K or R), to read or to set.
constexpr double& coefficient(NoiseCoefficients& c, NoiseTerm term) {
  switch (term) {
    case NoiseTerm::quantization:
      return c.quantization;
    case NoiseTerm::white_noise:
      return c.white_noise;
    case NoiseTerm::bias_instability:
      return c.bias_instability;
    case NoiseTerm::random_walk:
      return c.random_walk;
    case NoiseTerm::ramp:
      break;
  }
  return c.ramp;
}
constexpr double coefficient(const NoiseCoefficients& c, NoiseTerm term) {
  return coefficient(const_cast<NoiseCoefficients&>(c), term);
}

}  // namespace imunoise
