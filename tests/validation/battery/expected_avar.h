/// @file
/// @brief The battery's own closed-form expected AVARs and its own overlapping-AVAR estimator,
/// written from ../shared/docs/theory.md §2 and §4.1 (no imunoise code). The discrete forms
/// hold exactly for the point-valued samples generator.h makes; derivations in
/// docs/validation.md ("Expected AVAR of each term").
///
/// Everything is per cluster size m (τ = m·τ0); AVAR in the channel's rate unit squared.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace imunoise::battery {

/// @name Estimator
/// @{

/// Overlapping AVAR of rate samples Y at cluster size M (theory.md §2, phase form with
/// θ_k = Σ_{i<k} y_i, M_θ = n + 1): Σ_k (θ_{k+2m} − 2θ_{k+m} + θ_k)² / (2m²(M_θ − 2m)).
/// The mean is removed first and the sums run in long double. Needs n ≥ 2m.
double overlapping_avar(std::span<const double> y, std::size_t m);
/// overlapping_avar() at each of MS (the cumulative sum formed once).
std::vector<double> overlapping_avars(std::span<const double> y, std::span<const std::size_t> ms);

/// @}
/// @name Closed forms, exact for the generator's discrete samples
/// @{

/// White rate noise N: N²/τ (point-sampled white is exact at every m).
double white_avar(double n, double tau_s);
/// Angle-counter quantization, white angle noise of variance Q²: 3Q²/τ² (every m ≥ 1).
double quantization_avar(double q, double tau_s);
/// Discrete random walk of step K·√τ0 [ZH08]: K²τ0(2m²+1)/(6m) = K²τ/3 + K²τ0²/(6τ).
double random_walk_avar(double k, double tau0_s, std::size_t m);
/// Ramp R·t: R²τ²/2 (deterministic; the estimator gives it exactly).
double ramp_avar(double r, double tau_s);
/// Point-sampled AR(1), φ = e^{−τ0/T_c}, σ_w² = σ²(1−φ²) [ZH08]:
/// σ_w²[m − 3φ − mφ² + 4φ^{m+1} − φ^{2m+1}] / [m²(1−φ)²(1−φ²)].
double gauss_markov_avar(double sigma, double tau_c_s, double tau0_s, std::size_t m);
/// Sinusoid of amplitude A at F, random phase, point-sampled:
/// A²·sin⁴(πfmτ0) / (m²·sin²(πfτ0)) (the discrete Allan transfer function).
double sinusoid_avar(double a, double f_hz, double tau0_s, std::size_t m);
/// Flicker synthesized by flicker_samples() over an FFT of LENGTH, output = every STRIDE-th
/// sample: Σ_{0<j<L/2} 2c_j²·sin⁴(πjsm/L)/(m² sin²(πjs/L)), c_j² = B²/(πj), s = STRIDE.
double flicker_avar(double b, std::size_t length, std::size_t m, std::size_t stride = 1);
/// Stationary process with autocovariance R(l) = AUTOCOV[l] (0 beyond): the lag sum
/// (1/(2m²))·Σ_{|l|≤2m} w_m(l)·R(|l|), w(0) = 2m, w(l) = 2m − 3|l| (|l| ≤ m),
/// w(l) = |l| − 2m (m < |l| ≤ 2m).
double stationary_avar(std::span<const double> autocov, std::size_t m);
/// What overlapping_avar() returns for the warm-up a·e^{−kτ0/τ_w} alone over N samples
/// (deterministic, geometric sums).
double warmup_oavar(double a, double tau_w_s, double tau0_s, std::size_t n, std::size_t m);

/// @}
/// @name Helpers for the phenomena
/// @{

/// Autocovariance R(l), l = 0 … until negligible, of unit-variance white noise filtered by
/// the Butterworth COEFFICIENTS (impulse response to 1e-17 of its peak).
std::vector<double> filtered_white_autocov(const std::array<double, 5>& coefficients);
/// Σ_{|j|} R(j·d): with R of filtered_white_autocov times σ², τ0_out times this is the N² of
/// the filtered white noise decimated by D without averaging (docs/validation.md).
double aliased_white_gain(std::span<const double> autocov, std::size_t d);

/// @}

}  // namespace imunoise::battery
