/// @file
/// @brief B → Gauss–Markov conventions (see bias_instability_gm.h, theory.md §4.4).
#include "models/bias_instability_gm.h"

#include <cmath>
#include <numbers>
#include <string>

#include "common/errors.h"

namespace imunoise::models {
namespace {

/// AVAR/σ² of a first-order GM at x = τ/T_c (theory.md §4.1); used for x ≥ 1 only, where the
/// bracket has no cancellation problem.
double gm_avar_ratio(double x) {
  return (2.0 * x - 3.0 + 4.0 * std::exp(-x) - std::exp(-2.0 * x)) / (x * x);
}

/// x²·d/dx of gm_avar_ratio() times x: x(2 − 4e^{−x} + 2e^{−2x}) − 2(2x − 3 + 4e^{−x} − e^{−2x});
/// positive below the peak, negative above.
double gm_avar_slope_numerator(double x) {
  const double e = std::exp(-x);
  return 2.0 * x * (1.0 - e) * (1.0 - e) - 2.0 * (2.0 * x - 3.0 + 4.0 * e - e * e);
}

GaussMarkovPeak compute_peak() {
  // Bisection on [1, 3]: the numerator is +0.127 at 1 and −0.976 at 3, with a single root.
  double lo = 1.0, hi = 3.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (gm_avar_slope_numerator(mid) > 0.0 ? lo : hi) = mid;
  }
  const double x = 0.5 * (lo + hi);
  return {x, std::sqrt(gm_avar_ratio(x))};
}

}  // namespace

std::string_view name_of(GmConvention convention) {
  switch (convention) {
    case GmConvention::min_adev_at_tau_min:
      return "min_adev_at_tau_min";
    case GmConvention::peak_match:
      return "peak_match";
    case GmConvention::sigma_equals_b:
      return "sigma_equals_b";
  }
  return "unknown";
}

const std::map<std::string, GmConvention, std::less<>>& gm_conventions_by_name() {
  static const std::map<std::string, GmConvention, std::less<>> map = [] {
    std::map<std::string, GmConvention, std::less<>> m;
    for (GmConvention c : {GmConvention::min_adev_at_tau_min, GmConvention::peak_match,
                           GmConvention::sigma_equals_b})
      m.emplace(std::string(name_of(c)), c);
    return m;
  }();
  return map;
}

GaussMarkovPeak gauss_markov_adev_peak() {
  static const GaussMarkovPeak peak = compute_peak();
  return peak;
}

GaussMarkov gauss_markov_from_bias_instability(double bias_instability, double tau_min_s,
                                               GmConvention convention,
                                               std::optional<double> min_adev) {
  // The callers pass a fitted model's values or a model.yaml's, which the reader checked;
  // a model without τ of the ADEV minimum is refused by the caller (filter_parameters).
  IMUNOISE_EXPECT(std::isfinite(bias_instability) && bias_instability >= 0.0,
                  "gauss_markov_from_bias_instability: B must be finite and >= 0 (got " +
                      std::to_string(bias_instability) + ")");
  IMUNOISE_EXPECT(std::isfinite(tau_min_s) && tau_min_s > 0.0,
                  "gauss_markov_from_bias_instability: tau_min must be finite and > 0 s (got " +
                      std::to_string(tau_min_s) + ")");
  IMUNOISE_EXPECT(!min_adev || (std::isfinite(*min_adev) && *min_adev > 0.0),
                  "gauss_markov_from_bias_instability: min_adev must be finite and > 0");
  // ADEV of a pure bias-instability floor: √(2 ln2/π)·B = 0.6643·B (theory.md §4.1).
  const double floor = std::sqrt(2.0 * std::numbers::ln2 / std::numbers::pi) * bias_instability;
  switch (convention) {
    case GmConvention::min_adev_at_tau_min:
      return {min_adev ? *min_adev : floor, tau_min_s};
    case GmConvention::peak_match: {
      // Put the GM ADEV maximum g*·σ at τ* = x*·T_c onto the floor at τ_min.
      const GaussMarkovPeak peak = gauss_markov_adev_peak();
      return {floor / peak.adev_ratio, tau_min_s / peak.tau_ratio};
    }
    case GmConvention::sigma_equals_b:
      return {bias_instability, tau_min_s};
  }
  return {};
}

}  // namespace imunoise::models
