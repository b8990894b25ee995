/// @file
/// @brief IEEE-952 slope read-off (see slope_readoff.h).
#include "analysis/slope_readoff.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::analysis {
namespace {

/// Longest run of at least 2 contiguous indices with |slope − target| ≤ tolerance;
/// returns {first, count} (count 0 when none).
std::pair<std::size_t, std::size_t> longest_run(const std::vector<double>& slope, double target) {
  std::size_t best_first = 0, best_count = 0;
  std::size_t k = 0;
  while (k < slope.size()) {
    if (std::abs(slope[k] - target) > kSlopeTolerance) {
      ++k;
      continue;
    }
    const std::size_t first = k;
    while (k < slope.size() && std::abs(slope[k] - target) <= kSlopeTolerance) ++k;
    if (k - first > best_count) {
      best_first = first;
      best_count = k - first;
    }
  }
  if (best_count < 2) return {0, 0};
  return {best_first, best_count};
}

/// Fixed-slope line fitted on a run and read at τ = READ_AT; B (slope 0) uses the minimum.
SlopeReadoffTerm read_term(std::span<const double> tau, std::span<const double> adev,
                           const std::vector<double>& slope, double target, double read_at) {
  SlopeReadoffTerm term;
  const auto [first, count] = longest_run(slope, target);
  if (count == 0) return term;
  term.found = true;
  term.points = count;
  term.tau_low_s = tau[first];
  term.tau_high_s = tau[first + count - 1];
  if (target == 0.0) {
    // B = floor/√(2 ln2/π) (theory.md §4.1 table, "B = floor/0.6643").
    const double floor =
        *std::min_element(adev.begin() + static_cast<std::ptrdiff_t>(first),
                          adev.begin() + static_cast<std::ptrdiff_t>(first + count));
    term.value = floor / std::sqrt(2.0 * std::numbers::ln2 / std::numbers::pi);
    return term;
  }
  double intercept = 0.0;  // mean of ln σ − s·ln τ: the least-squares line of fixed slope s
  for (std::size_t k = first; k < first + count; ++k)
    intercept += std::log(adev[k]) - target * std::log(tau[k]);
  intercept /= static_cast<double>(count);
  term.value = std::exp(intercept + target * std::log(read_at));
  return term;
}

}  // namespace

SlopeReadoff slope_readoff(std::span<const double> tau_s, std::span<const double> adev) {
  IMUNOISE_EXPECT(tau_s.size() == adev.size(), "slope_readoff: " + std::to_string(tau_s.size()) +
                                                   " tau values but " +
                                                   std::to_string(adev.size()) + " deviations");
  IMUNOISE_CHECK(
      tau_s.size() >= 3, AnalysisError,
      "slope_readoff: at least 3 points are needed (got " + std::to_string(tau_s.size()) + ")");
  for (std::size_t k = 0; k < tau_s.size(); ++k) {
    IMUNOISE_CHECK(
        std::isfinite(tau_s[k]) && tau_s[k] > 0.0 && std::isfinite(adev[k]) && adev[k] > 0.0,
        AnalysisError,
        "slope_readoff: point " + std::to_string(k) + " needs finite tau > 0 and " +
            "deviation > 0 (got tau " + std::to_string(tau_s[k]) + " s, deviation " +
            std::to_string(adev[k]) + ")");
    IMUNOISE_EXPECT(
        k == 0 || tau_s[k] > tau_s[k - 1],
        "slope_readoff: tau must be strictly increasing (point " + std::to_string(k) + ")");
  }
  const std::size_t n = tau_s.size();
  std::vector<double> slope(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t lo = k == 0 ? 0 : k - 1;
    const std::size_t hi = k + 1 == n ? n - 1 : k + 1;
    slope[k] =
        (std::log(adev[hi]) - std::log(adev[lo])) / (std::log(tau_s[hi]) - std::log(tau_s[lo]));
  }
  SlopeReadoff out;
  out[NoiseTerm::quantization] = read_term(tau_s, adev, slope, -1.0, std::sqrt(3.0));
  out[NoiseTerm::white_noise] = read_term(tau_s, adev, slope, -0.5, 1.0);
  out[NoiseTerm::bias_instability] = read_term(tau_s, adev, slope, 0.0, 0.0);
  out[NoiseTerm::random_walk] = read_term(tau_s, adev, slope, 0.5, 3.0);
  out[NoiseTerm::ramp] = read_term(tau_s, adev, slope, 1.0, std::sqrt(2.0));
  return out;
}

}  // namespace imunoise::analysis
