/// @file
/// @brief A single first-order Gauss–Markov stand-in for bias instability B, for filters that
/// cannot carry 1/f noise (theory.md §4.4 conventions (a)–(c), worked example §8.3).
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "common/noise_coefficients.h"

namespace imunoise::models {

/// How σ_GM and T_c are derived from B and the location τ_min of the ADEV minimum (§4.4).
enum class GmConvention {
  min_adev_at_tau_min,  ///< (a) σ = minimum ADEV (0.6643·B for a pure floor), T_c = τ_min
  peak_match,           ///< (b) GM ADEV peak placed on the floor: T_c = τ_min/x*,
                        ///<     σ = 0.6643·B/g* = 1.0760·B (x* = 1.8926, g* = 0.6174;
                        ///<     theory.md's 1.0755 comes from 0.664/0.6174 rounded)
  sigma_equals_b        ///< (c) σ = B, T_c = τ_min
};

/// "min_adev_at_tau_min", "peak_match" or "sigma_equals_b".
std::string_view name_of(GmConvention convention);

/// Every convention by its name_of(), for the settings that choose one (CLI --gm-convention,
/// the Python export).
const std::map<std::string, GmConvention, std::less<>>& gm_conventions_by_name();

/// Location and height of the first-order GM ADEV maximum in units of T_c and σ: x* = τ*/T_c
/// and g* = ADEV(τ*)/σ, from the root of d/dx[(2x − 3 + 4e^{−x} − e^{−2x})/x²] = 0, i.e.
/// x(1 − e^{−x})² = 2x − 3 + 4e^{−x} − e^{−2x} (theory.md §4.1 rounds them to 1.8926, 0.6174).
struct GaussMarkovPeak {
  double tau_ratio;   ///< x* = τ*/T_c
  double adev_ratio;  ///< g* = ADEV(τ*)/σ_GM
};
GaussMarkovPeak gauss_markov_adev_peak();

/// The GM that stands in for bias instability B under CONVENTION (theory.md §4.4).
/// @param[in] bias_instability B ≥ 0 [rad/s | m/s²]
/// @param[in] tau_min_s        τ of the ADEV minimum / flat region [s], > 0
/// @param[in] convention       (a), (b) or (c)
/// @param[in] min_adev         (a) only: the measured minimum ADEV [rad/s | m/s²]. The §8.3
///                             table uses it (8.661e-5 rad/s: the floor lifted by N and K);
///                             without it (a) takes the pure-floor value √(2 ln2/π)·B.
/// @return σ_GM and T_c; the driving intensity is q_c² = 2σ²/T_c.
/// @throws ContractViolation when B < 0, τ_min ≤ 0, min_adev ≤ 0 or any is not finite.
GaussMarkov gauss_markov_from_bias_instability(double bias_instability, double tau_min_s,
                                               GmConvention convention,
                                               std::optional<double> min_adev = std::nullopt);

}  // namespace imunoise::models
