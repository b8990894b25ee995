#include "pipeline/outliers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::pipeline {

namespace {

/// 1/Φ⁻¹(3/4): MAD × this estimates σ of a Gaussian.
constexpr double kMadToSigma = 1.482602218505602;

/// Median of the values (copied; the input is left unchanged).
double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// 1.4826 × median |v − median v|.
double robust_scale(std::vector<double> v) {
  const double m = median_of(v);
  for (double& x : v) x = std::abs(x - m);
  return kMadToSigma * median_of(std::move(v));
}

/// At most this many values enter a robust scale (a stride through the samples): the MAD of
/// 65536 Gaussian values has a relative standard error of 1.36/√65536 = 0.5 %, and the scan
/// stays a few passes over the record.
constexpr std::size_t kScaleSamples = 65536;

/// VALUE(i) at every ⌈n/kScaleSamples⌉-th i < N: the residuals are computed where sampled, not
/// held for the whole record (at 24 h at 1 kHz one array of them is 0.66 GB per channel in
/// flight, which set the analysis's peak memory; the flags are kept as index lists for the
/// same reason).
template <class Value>
std::vector<double> strided(std::size_t n, Value value) {
  const std::size_t stride = std::max<std::size_t>(1, (n + kScaleSamples - 1) / kScaleSamples);
  std::vector<double> out;
  out.reserve(n / stride + 1);
  for (std::size_t i = 0; i < n; i += stride) out.push_back(value(i));
  return out;
}

/// Median of the up-to-four neighbours x_{k±1}, x_{k±2} inside X (the mean of the middle two
/// of four; of three, the middle one; of two, their mean).
double neighbour_median(std::span<const double> x, std::size_t k) {
  if (k >= 2 && k + 2 < x.size()) {
    // The middle two of four: the sum less the smallest and the largest.
    const double a = x[k - 2], b = x[k - 1], c = x[k + 1], d = x[k + 2];
    const double low = std::min(std::min(a, b), std::min(c, d));
    const double high = std::max(std::max(a, b), std::max(c, d));
    return 0.5 * (a + b + c + d - low - high);
  }
  double v[4];
  int n = 0;
  if (k >= 2) v[n++] = x[k - 2];
  if (k >= 1) v[n++] = x[k - 1];
  if (k + 1 < x.size()) v[n++] = x[k + 1];
  if (k + 2 < x.size()) v[n++] = x[k + 2];
  std::sort(v, v + n);
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Up to kGoodNeighbours good samples on each side of K within ±2·kGoodNeighbours, their mean:
/// the second pass's local level. A mean of 8 (not the median of 4) because the miss rate of a
/// spike depends on the residual's own scale: σ_r = σ·√(1 + 1/8) = 1.06σ against 1.14σ for the
/// median of 4, so a ±8σ spike is missed when its noise pulls it back by 3.76σ_r (P 0.01 %)
/// instead of 3.0σ_r (0.13 %, each carrying 64σ²: N +0.2 % at 5 % spikes). NaN when a side
/// has no good sample within reach.
constexpr std::size_t kGoodNeighbours = 4;
/// The first pass's flagged samples (increasing; rare: the scan holds no per-sample array) as
/// the second pass walks the record: a cursor to the first flag at or after k − 2·kGoodNeighbours.
class NearFlags {
 public:
  explicit NearFlags(std::span<const std::size_t> flags) : flags_(flags) {}
  /// The flags within ±2·kGoodNeighbours of K (K never decreases between calls, except that a
  /// call with a smaller K restarts the search).
  std::span<const std::size_t> around(std::size_t k) {
    constexpr std::size_t reach = 2 * kGoodNeighbours;
    const std::size_t low = k >= reach ? k - reach : 0;
    if (k < last_k_) next_ = 0;
    last_k_ = k;
    while (next_ < flags_.size() && flags_[next_] < low) ++next_;
    std::size_t end = next_;
    while (end < flags_.size() && flags_[end] <= k + reach) ++end;
    return flags_.subspan(next_, end - next_);
  }

 private:
  std::span<const std::size_t> flags_;
  std::size_t next_ = 0, last_k_ = 0;
};

/// NEAR: the flagged samples within ±2·kGoodNeighbours of K (NearFlags::around).
double good_neighbour_mean(std::span<const double> x, std::span<const std::size_t> near,
                           std::size_t k) {
  constexpr std::size_t reach = 2 * kGoodNeighbours;
  if (near.empty() && k >= kGoodNeighbours && k + kGoodNeighbours < x.size()) {
    // No flag in reach (the usual case): the four nearest on each side, summed in the order
    // of the general loop below, so the mean is the same to the bit.
    double sum = 0.0;
    for (std::size_t d = 1; d <= kGoodNeighbours; ++d) sum += x[k - d];
    for (std::size_t d = 1; d <= kGoodNeighbours; ++d) sum += x[k + d];
    return sum / static_cast<double>(2 * kGoodNeighbours);
  }
  const auto is_bad = [near](std::size_t i) {
    return std::find(near.begin(), near.end(), i) != near.end();
  };
  double sum = 0.0;
  std::size_t left = 0, right = 0;
  for (std::size_t d = 1; d <= reach && left < kGoodNeighbours && d <= k; ++d) {
    if (!is_bad(k - d)) sum += x[k - d], ++left;
  }
  for (std::size_t d = 1; d <= reach && right < kGoodNeighbours && k + d < x.size(); ++d) {
    if (!is_bad(k + d)) sum += x[k + d], ++right;
  }
  if (left + right < kGoodNeighbours) return std::numeric_limits<double>::quiet_NaN();
  return sum / static_cast<double>(left + right);
}

/// E[r²; |r| > c] / E[r²] for Gaussian r: 2(cφ(c) + Φ(−c)).
double gaussian_tail_variance_fraction(double c) {
  const double phi = std::exp(-0.5 * c * c) / std::sqrt(2.0 * std::numbers::pi);
  return 2.0 * (c * phi + 0.5 * std::erfc(c / std::numbers::sqrt2));
}

}  // namespace

OutlierPolicy parse_outlier_policy(std::string_view text, std::string_view setting) {
  if (text == "keep") return OutlierPolicy::keep;
  if (text == "clip") return OutlierPolicy::clip;
  if (text == "drop") return OutlierPolicy::drop;
  std::string message(setting);
  message.append(": expected keep, clip or drop, got '").append(text).append("'");
  throw InputError(message);
}

OutlierScan find_outliers(std::span<const double> x) {
  OutlierScan out;
  if (x.size() < 16) return out;
  const std::size_t n = x.size();
  // r_k = x_k − the median of its four neighbours (first pass), computed where needed.
  const auto first_residual = [&x](std::size_t k) { return x[k] - neighbour_median(x, k); };
  // The scale of r from all samples (the outliers inflate it a little), then once more from
  // the samples inside the first threshold, and the outliers beyond the second.
  const std::vector<double> r_sample = strided(n, first_residual);
  out.residual_scale = robust_scale(r_sample);
  if (!(out.residual_scale > 0.0)) return out;  // e.g. a coarse LSB: no scale to judge by
  {
    std::vector<double> inside;
    inside.reserve(r_sample.size());
    for (double v : r_sample) {
      if (std::abs(v) <= kOutlierThreshold * out.residual_scale) inside.push_back(v);
    }
    // Cutting at 4σ drops 6.3e-5 of a Gaussian: the MAD of the rest is 0.99996 of σ's.
    const double rescaled = robust_scale(std::move(inside));
    if (rescaled > 0.0) out.residual_scale = rescaled;
  }
  const double limit = kOutlierThreshold * out.residual_scale;
  std::vector<std::size_t> first;
  for (std::size_t k = 0; k < n; ++k) {
    if (std::abs(first_residual(k)) > limit) first.push_back(k);
  }
  // Second pass: each sample against the mean of its good neighbours, and the scale again from
  // these residuals. In the first pass two spikes of one sign among the four neighbours lift
  // their median by several σ and inflate the scale, so a spike can stay below the threshold:
  // at 5 % spikes of ±8σ about 0.4 % of them, each carrying 64σ², which left N +0.5 % after
  // the drop — against intervals of ±0.2 % (the battery's outliers class). A sample without
  // good neighbours on reach keeps its first-pass residual.
  NearFlags near(first);
  const auto second_residual = [&](std::size_t k) {
    const double m = good_neighbour_mean(x, near.around(k), k);
    return std::isfinite(m) ? x[k] - m : first_residual(k);
  };
  {
    std::vector<double> inside;
    const std::vector<double> r2 = strided(n, second_residual);
    inside.reserve(r2.size());
    for (double v : r2) {
      if (std::abs(v) <= limit) inside.push_back(v);
    }
    const double rescaled = robust_scale(std::move(inside));
    if (rescaled > 0.0) out.residual_scale = rescaled;
  }
  const double limit2 = kOutlierThreshold * out.residual_scale;
  double total = 0.0, flagged = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double r = second_residual(k);
    const double s = r * r;
    total += s;
    if (std::abs(r) > limit2) {
      out.indices.push_back(k);
      flagged += s;
      out.largest = std::max(out.largest, std::abs(r) / out.residual_scale);
    }
  }
  // The per-sample σ from the first differences between good samples only (with 5 % spikes
  // a tenth of all differences hold one, which would inflate the MAD by 13 %).
  std::vector<double> d;
  const std::size_t stride = std::max<std::size_t>(1, (n + kScaleSamples - 1) / kScaleSamples);
  d.reserve(n / stride + 1);
  const auto is_bad = [&out](std::size_t i) {
    return std::binary_search(out.indices.begin(), out.indices.end(), i);
  };
  for (std::size_t k = 0; k + 1 < n; k += stride) {
    if (!is_bad(k) && !is_bad(k + 1)) d.push_back(x[k + 1] - x[k]);
  }
  out.sample_sigma = robust_scale(std::move(d)) / std::numbers::sqrt2;
  if (total > 0.0) {
    // What Gaussian noise of the robust scale puts beyond the threshold is not an outlier's.
    const double expected = gaussian_tail_variance_fraction(kOutlierThreshold) *
                            static_cast<double>(n) * out.residual_scale * out.residual_scale;
    out.excess_variance_fraction = std::max(0.0, (flagged - expected) / total);
  }
  out.significant = out.excess_variance_fraction >= kOutlierFindingFraction;
  return out;
}

std::vector<double> apply_outlier_policy(std::span<const double> x, const OutlierScan& scan,
                                         OutlierPolicy policy, std::uint64_t seed) {
  std::vector<double> y(x.begin(), x.end());
  if (policy == OutlierPolicy::keep || scan.indices.empty()) return y;
  if (policy == OutlierPolicy::clip) {
    const double limit = kOutlierThreshold * scan.residual_scale;
    for (std::size_t k : scan.indices) {
      const double m = neighbour_median(x, k);
      y[k] = std::clamp(x[k], m - limit, m + limit);
    }
    return y;
  }
  // drop: the local level is the mean of the good samples within ±W (prefix sums over the
  // samples with the outliers zeroed, and a count of the good ones). Why a mean over ±W and
  // fresh noise rather than the straight line between the neighbours: the line makes the
  // sample a copy of its neighbours, which raises the white-noise AVAR of every block holding
  // them by 1.5σ² per replaced sample (N +3.7 % at 5 % outliers); fresh noise of σ adds σ² in
  // place of the lost sample's σ², and the level's own correlation with the block, σ²·(its
  // samples inside the block)/(2W + 1), stays below 0.1 % of N² for blocks of m ≤ 20 samples
  // at 5 % outliers. The level keeps the colored noise (B, K) below 1/(2W τ0).
  std::vector<char> bad(x.size(), 0);
  for (std::size_t k : scan.indices) bad[k] = 1;
  std::vector<double> sum(x.size() + 1, 0.0);
  std::vector<std::size_t> count(x.size() + 1, 0);
  const double offset = x.empty() ? 0.0 : x[0];  // keeps the prefix sums small
  for (std::size_t k = 0; k < x.size(); ++k) {
    sum[k + 1] = sum[k] + (bad[k] ? 0.0 : x[k] - offset);
    count[k + 1] = count[k] + (bad[k] ? 0 : 1);
  }
  std::mt19937_64 rng(seed);
  const auto uniform = [&rng] {
    return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53;  // in (0, 1)
  };
  for (std::size_t k : scan.indices) {
    const std::size_t lo = k >= kOutlierLevelHalfWindow ? k - kOutlierLevelHalfWindow : 0;
    const std::size_t hi = std::min(x.size(), k + kOutlierLevelHalfWindow + 1);
    const std::size_t n = count[hi] - count[lo];
    const double level =
        n > 0 ? offset + (sum[hi] - sum[lo]) / static_cast<double>(n) : neighbour_median(x, k);
    // Box–Muller (own transform: the same draws with every standard library).
    const double w =
        std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * std::numbers::pi * uniform());
    y[k] = level + scan.sample_sigma * w;
  }
  return y;
}

double mean_square_difference(std::span<const double> x) {
  if (x.size() < 2) return 0.0;
  double s = 0.0;
  for (std::size_t k = 0; k + 1 < x.size(); ++k) {
    const double d = x[k + 1] - x[k];
    s += d * d;
  }
  return s / static_cast<double>(x.size() - 1);
}

}  // namespace imunoise::pipeline
