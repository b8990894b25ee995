/// @file
/// @brief Power-law fractional-frequency noise, S_y(f) = h·f^alpha, by the Kasdin–Walter
/// fractional-difference filter (N. J. Kasdin, "Discrete simulation of colored noise and
/// stochastic processes and 1/f^α power law noise generation", Proc. IEEE 83(5), 1995).
/// Used to test noise identification and EDFs on signals of known type (theory.md §3.4).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace imunoise::models {

/// Impulse response of the filter (1 − z⁻¹)^{alpha/2}: c₀ = 1, c_k = c_{k−1}·(k − 1 − alpha/2)/k
/// (Kasdin 1995 eq. 116 with exponent −alpha). alpha = 0 gives the identity, −2 a running sum,
/// 2 a first difference.
/// @param[in] alpha exponent of S_y(f), one of 2, 1, 0, −1, −2
/// @param[in] n     number of coefficients
/// @throws ContractViolation for another alpha.
std::vector<double> kasdin_walter_coefficients(int alpha, std::size_t n);

/// n samples y_k of fractional-frequency noise with one-sided PSD S_y(f) = h·f^alpha at low
/// frequency, for a sampling interval τ0 = 1 (time in units of τ0): white Gaussian w_k of
/// variance h/(2(2π)^alpha) filtered by kasdin_walter_coefficients(), whose exact discrete
/// PSD is 2·var(w)·(2 sin πf)^alpha. The filter starts from rest, so alpha ≤ −1 outputs are
/// the usual non-stationary (flicker/random-walk) records starting at 0. alpha = ±1 convolve
/// with the full filter (FFTW for n > 256, a direct sum below); alpha = 2, −2 use the
/// equivalent difference / running sum. Deterministic for a seed (std::mt19937_64 and
/// std::normal_distribution of the standard library in use).
/// @param[in] alpha 2 white PM, 1 flicker PM, 0 white FM, −1 flicker FM, −2 random-walk FM
/// @param[in] n     number of samples
/// @param[in] seed  random seed
/// @param[in] h     PSD coefficient h_alpha ≥ 0 (unit: y² · τ0^{1+alpha})
/// @throws ContractViolation for alpha outside {2, 1, 0, −1, −2} or h negative / not finite.
std::vector<double> power_law_noise(int alpha, std::size_t n, std::uint64_t seed, double h = 1.0);

}  // namespace imunoise::models
