/// @file
/// @brief Outliers (isolated spikes) in one channel's rate samples: found against a robust
/// scale, and kept, clipped or dropped (`analyze --outliers`). Pure computation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace imunoise::pipeline {

/// What to do with the outliers of a channel.
enum class OutlierPolicy {
  keep,  ///< analyse the samples as recorded
  clip,  ///< pull each outlier to the threshold around its neighbours' median
  /// replace each outlier by the mean of the good samples within ±kOutlierLevelHalfWindow
  /// plus white noise of the robust per-sample σ (seeded): the grid stays regular and the
  /// sample keeps the variance of its neighbours (the default)
  drop,
};

/// Parses "keep" / "clip" / "drop"; InputError "SETTING: expected keep, clip or drop, got
/// 'TEXT'" otherwise.
OutlierPolicy parse_outlier_policy(std::string_view text, std::string_view setting);

/// Outliers sit beyond this many robust scales of the residual r_k = x_k − the local level:
/// a first pass against the median of x_{k−2}, x_{k−1}, x_{k+1}, x_{k+2}, a second against
/// the mean of the 8 nearest samples the first pass left (4 per side within ±8).
inline constexpr double kOutlierThreshold = 4.0;
/// Half window of the local level that replaces a dropped outlier [samples].
inline constexpr std::size_t kOutlierLevelHalfWindow = 512;

/// The outliers of one channel.
struct OutlierScan {
  std::vector<std::size_t> indices;  ///< samples beyond the threshold, increasing
  double residual_scale = 0.0;       ///< 1.4826·MAD of the second pass's r [channel unit]
  double sample_sigma = 0.0;  ///< robust per-sample σ: 1.4826·MAD of the first differences / √2
  double largest = 0.0;       ///< largest |r| of an outlier, in residual scales
  /// Share of Σ r² carried by the flagged samples beyond what Gaussian noise puts past the
  /// threshold (0.00113 of Σ r² at 4 scales).
  double excess_variance_fraction = 0.0;
  /// The finding: the excess carries at least kOutlierFindingFraction of Σ r² (an effect of
  /// ≥ 0.25 % on N).
  bool significant = false;
};

/// Smallest excess variance fraction reported as a finding.
inline constexpr double kOutlierFindingFraction = 0.005;

/// Scans X (needs at least 16 samples; fewer: an empty scan).
OutlierScan find_outliers(std::span<const double> x);

/// X with the outliers of SCAN handled by POLICY (keep: X unchanged). SEED makes the drop's
/// noise reproducible.
std::vector<double> apply_outlier_policy(std::span<const double> x, const OutlierScan& scan,
                                         OutlierPolicy policy, std::uint64_t seed);

/// Mean square of the first differences of X (for white noise 2σ²: the effect of the outliers
/// on N² is the ratio of this before and after).
double mean_square_difference(std::span<const double> x);

}  // namespace imunoise::pipeline
