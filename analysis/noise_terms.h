/// @file
/// @brief Closed-form Allan (AVAR) and Hadamard (HVAR) variances of the stochastic error terms
/// of one sensor axis (theory.md §4.1): the five IEEE-952 power-law terms, first-order
/// Gauss–Markov processes and sinusoids, and of a whole NoiseCoefficients model.
///
/// Units: τ in s; a variance is in (rate unit)², e.g. (rad/s)² for a gyro. Each power-law term
/// is written as c²·φ(τ) with c its coefficient (Q, N, B, K, R) and φ its "basis", so a model
/// is linear in the squared coefficients (the basis of the §4.3 fit).
#pragma once

#include <array>
#include <string_view>

#include "common/noise_coefficients.h"

namespace imunoise::analysis {

/// @name Power-law bases (theory.md §4.1 table)
/// @{

/// AVAR basis φ(τ) of TERM, AVAR = c²·φ(τ): 3/τ², 1/τ, 2 ln2/π, τ/3, τ²/2 for Q, N, B, K, R.
/// @param[in] tau_s averaging time τ > 0 [s] (AnalysisError otherwise)
double term_avar_basis(NoiseTerm term, double tau_s);

/// HVAR basis of TERM, HVAR = c²·φ_H(τ): (10/3)/τ², 1/τ, (8 ln2 − 3 ln3)/(2π) = 0.3580, τ/6,
/// and 0 for the ramp (a linear drift is removed by the second difference).
double term_hvar_basis(NoiseTerm term, double tau_s);

/// @}
/// @name Gauss–Markov and sinusoid (theory.md §4.1)
/// @{

/// AVAR of a first-order Gauss–Markov process of stationary σ and correlation time T_c,
/// (σ²T_c²/τ²)·[2x − 3 + 4e^{−x} − e^{−2x}], x = τ/T_c. The bracket cancels to (2/3)x³ for
/// x ≪ 1, so it is summed as a series there (full relative precision down to x → 0).
/// @param[in] sigma   σ_GM ≥ 0 [rate unit]
/// @param[in] tau_c_s T_c > 0 [s]
/// @param[in] tau_s   τ > 0 [s]
double gauss_markov_avar(double sigma, double tau_c_s, double tau_s);

/// HVAR of the same process, (σ²T_c²/(3τ²))·[6x − 10 + 15e^{−x} − 6e^{−2x} + e^{−3x}]; from
/// HVAR = [15D(τ) − 6D(2τ) + D(3τ)]/(6τ²) with the phase structure function
/// D(s) = 2σ²T_c²(s/T_c − 1 + e^{−s/T_c}). Limits σ²τ/(3T_c) (RW, K² = 2σ²/T_c) and 2σ²T_c/τ.
double gauss_markov_hvar(double sigma, double tau_c_s, double tau_s);

/// AVAR of A·sin(2πft + φ): A²·sin⁴(πfτ)/(πfτ)²; zero at τ = k/f.
/// @param[in] amplitude A ≥ 0 [rate unit]; f_hz ≥ 0 [Hz] (f = 0 gives 0: a constant)
double sinusoid_avar(double amplitude, double f_hz, double tau_s);

/// HVAR of the same sinusoid: (4/3)A²·sin⁶(πfτ)/(πfτ)² (Hadamard kernel (8/3)sin⁶x/x² applied
/// to the one-sided line A²/2).
double sinusoid_hvar(double amplitude, double f_hz, double tau_s);

/// @}
/// @name Either variance: HADAMARD selects the HVAR column of theory.md §4.1, else AVAR
/// @{
double term_basis(NoiseTerm term, double tau_s, bool hadamard);
double gauss_markov_variance(double sigma, double tau_c_s, double tau_s, bool hadamard);
double sinusoid_variance(double amplitude, double f_hz, double tau_s, bool hadamard);
/// HVAR (HADAMARD) or AVAR of the sum of all terms of MODEL at τ [rate unit²].
double model_variance(const NoiseCoefficients& model, double tau_s, bool hadamard);

/// @}
/// @name Whole model
/// @{

/// AVAR of the sum of all terms of MODEL at τ [rate unit²] (theory.md §4.1, §4.3 model).
double model_avar(const NoiseCoefficients& model, double tau_s);
/// √model_avar() [rate unit].
double model_adev(const NoiseCoefficients& model, double tau_s);
/// HVAR of the sum of all terms of MODEL at τ [rate unit²].
double model_hvar(const NoiseCoefficients& model, double tau_s);
/// √model_hvar() [rate unit].
double model_hdev(const NoiseCoefficients& model, double tau_s);

/// @}

}  // namespace imunoise::analysis
