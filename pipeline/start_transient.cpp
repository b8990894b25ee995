#include "pipeline/start_transient.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "common/errors.h"

namespace imunoise::pipeline {

namespace {

/// Median of χ²₁ (the squared standard normal): median(d²) / this estimates E[d²] for a
/// zero-mean Gaussian d, robustly to the few differences a transient still reaches.
constexpr double kChiSquare1Median = 0.454936423119572;

/// Segments per block: the segment means are sums of this many block means, and the reference
/// differences start every block (an eighth of a segment), overlapping.
constexpr std::size_t kBlocksPerSegment = 8;

/// Means of consecutive blocks of B samples of X (the tail shorter than B is left out).
std::vector<double> block_means(std::span<const double> x, std::size_t b) {
  const std::size_t nb = x.size() / b;
  std::vector<double> out(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    double sum = 0.0;
    for (std::size_t k = 0; k < b; ++k) sum += x[i * b + k];
    out[i] = sum / static_cast<double>(b);
  }
  return out;
}

/// Means of the segments of kBlocksPerSegment blocks starting at every block.
std::vector<double> segment_means(const std::vector<double>& blocks) {
  if (blocks.size() < kBlocksPerSegment) return {};
  std::vector<double> out(blocks.size() - kBlocksPerSegment + 1);
  for (std::size_t i = 0; i < out.size(); ++i) {
    double sum = 0.0;
    for (std::size_t k = 0; k < kBlocksPerSegment; ++k) sum += blocks[i + k];
    out[i] = sum / static_cast<double>(kBlocksPerSegment);
  }
  return out;
}

/// The reference differences start at 1/this of the record: after a transient of up to T/8
/// has decayed to e^(−2) of its start (a residue the median ignores).
constexpr std::size_t kReferenceStartDivisor = 4;

/// The difference of the first two adjacent segment means and the robust RMS of the same
/// difference over the last three quarters of the record (differences starting at every block
/// there).
struct ScaleScan {
  double first_difference = 0.0;
  double reference_rms = 0.0;
};

/// Scan of X at segments of SEGMENT samples (SEGMENT a multiple of kBlocksPerSegment, at least
/// 2 per block, and at most a quarter of X).
ScaleScan scan_scale(std::span<const double> x, std::size_t segment) {
  const std::size_t b = segment / kBlocksPerSegment;
  const std::vector<double> seg = segment_means(block_means(x, b));
  ScaleScan out;
  const std::size_t nb = x.size() / b;
  out.first_difference = seg[0] - seg[kBlocksPerSegment];
  std::vector<double> squares;
  for (std::size_t i = nb / kReferenceStartDivisor; i + kBlocksPerSegment < seg.size(); ++i) {
    const double d = seg[i] - seg[i + kBlocksPerSegment];
    squares.push_back(d * d);
  }
  if (squares.empty()) return out;
  auto mid = squares.begin() + static_cast<std::ptrdiff_t>(squares.size() / 2);
  std::nth_element(squares.begin(), mid, squares.end());
  out.reference_rms = std::sqrt(*mid / kChiSquare1Median);
  return out;
}

/// Segment length in samples for a requested one: a multiple of kBlocksPerSegment in
/// [2·kBlocksPerSegment, N/4].
std::size_t usable_segment(double wanted, std::size_t n) {
  const double high = static_cast<double>(n / 4);
  const double low = 2.0 * kBlocksPerSegment;
  const double clamped = std::clamp(wanted, low, std::max(low, high));
  return std::max<std::size_t>(2 * kBlocksPerSegment, static_cast<std::size_t>(clamped) /
                                                          kBlocksPerSegment * kBlocksPerSegment);
}

/// The record is divided into this many blocks to fit A·e^(−t/τ) + c.
constexpr std::size_t kFitBlocks = 256;

/// Block mean of e^(−t/τ) over block I of B samples at τ0: e^(−iβ)(1 − e^(−β))/β, β = Bτ0/τ.
double exponential_block_mean(std::size_t i, double beta) {
  return std::exp(-static_cast<double>(i) * beta) * (-std::expm1(-beta)) / beta;
}

/// Least squares of Y = c + A·G: returns A and the residual sum of squares.
std::pair<double, double> fit_offset_and_amplitude(const std::vector<double>& y,
                                                   const std::vector<double>& g) {
  const double n = static_cast<double>(y.size());
  double sy = 0.0, sg = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    sy += y[i];
    sg += g[i];
  }
  const double my = sy / n, mg = sg / n;
  double sgg = 0.0, sgy = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    sgg += (g[i] - mg) * (g[i] - mg);
    sgy += (g[i] - mg) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(sgg > 0.0)) return {0.0, syy};
  const double a = sgy / sgg;
  return {a, std::max(0.0, syy - a * sgy)};
}

}  // namespace

double start_transient_threshold(std::size_t channels) {
  // The 99.5 % points of the statistic (max over the three segment lengths of Σ z²) under
  // stationary noise, by channel count: the largest over three noise colours — white, white
  // plus a random walk carrying 60 % of the AVAR at T/10, white plus a flicker-like sum of five
  // first-order Gauss-Markov terms one per decade of τ — of the point measured on 4000
  // simulated recordings each, rounded up. The statistic is scale free (a ratio of means of
  // the same channel at the same averaging time), so neither the noise level nor the record
  // length enters. Each z is a difference of two adjacent means over its own robust scatter
  // (the median of ≈ 80 overlapping squared differences over the last three quarters), so Σ z² is
  // heavier-tailed than χ²_K (whose 99.5 % points are 7.9, 10.6, 12.8, 14.9, 16.7, 18.5), and the
  // maximum over three correlated lengths adds to that. tests/pipeline/start_transient_test.cpp
  // re-measures the false-alarm rate on fresh seeds (≤ 1 % per recording).
  static constexpr std::array<double, 6> kThreshold{14.0, 17.0, 20.0, 23.0, 25.0, 28.0};
  if (channels == 0) return std::numeric_limits<double>::infinity();
  if (channels <= kThreshold.size()) return kThreshold[channels - 1];
  return kThreshold.back() + 3.0 * static_cast<double>(channels - kThreshold.size());
}

StartTransient detect_start_transient(std::span<const std::span<const double>> channels,
                                      std::span<const std::string> names, double tau0_s) {
  IMUNOISE_EXPECT(channels.size() == names.size(), "detect_start_transient: names and channels");
  StartTransient out;
  if (channels.empty()) return out;
  const std::size_t n = channels.front().size();
  for (const auto& c : channels) {
    IMUNOISE_EXPECT(c.size() == n, "detect_start_transient: channels of different lengths");
  }
  if (n < kStartTransientMinSamples) return out;
  out.scanned = true;
  out.threshold = start_transient_threshold(channels.size());
  out.channels.resize(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) out.channels[c].name = names[c];

  // 1. The statistic: at segment lengths T/16, T/32 and T/64, the first difference of adjacent
  // means of each channel over its scatter in the last three quarters of the record (where a
  // transient that starts the record has decayed), squared and summed over the channels.
  std::vector<double> reference_rms(channels.size(), 0.0);
  for (const std::size_t divisor : {16u, 32u, 64u}) {
    const std::size_t segment = usable_segment(static_cast<double>(n) / divisor, n);
    double sum = 0.0;
    std::vector<double> z(channels.size(), 0.0);
    std::vector<double> rms(channels.size(), 0.0);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const ScaleScan s = scan_scale(channels[c], segment);
      rms[c] = s.reference_rms;
      z[c] = s.reference_rms > 0.0 ? s.first_difference / s.reference_rms : 0.0;
      sum += z[c] * z[c];
    }
    if (divisor == 32u) reference_rms = rms;
    if (sum > out.statistic) {
      out.statistic = sum;
      out.segment_s = static_cast<double>(segment) * tau0_s;
      for (std::size_t c = 0; c < channels.size(); ++c) out.channels[c].z = z[c];
    }
  }
  out.detected = out.statistic > out.threshold;
  if (!out.detected) return out;

  // 2. Amplitude and time constant: A_c·e^(−t/τ) + c_c fitted to 256 block means of every
  // channel, τ common (one thermal cause) and chosen on a log grid by the residual sum of
  // squares of all channels, each scaled by its scatter at T/32.
  const std::size_t b = std::max<std::size_t>(1, n / kFitBlocks);
  std::vector<std::vector<double>> blocks;
  for (const auto& c : channels) blocks.push_back(block_means(c, b));
  const std::size_t nb = blocks.front().size();
  const double record_s = static_cast<double>(n) * tau0_s;
  const double tau_low = 2.0 * static_cast<double>(b) * tau0_s;
  const double tau_high = record_s / 2.0;
  constexpr int kGrid = 48;
  double best_cost = std::numeric_limits<double>::infinity();
  std::vector<double> g(nb);
  for (int k = 0; k <= kGrid; ++k) {
    const double tau = tau_low * std::pow(tau_high / tau_low, static_cast<double>(k) / kGrid);
    const double beta = static_cast<double>(b) * tau0_s / tau;
    for (std::size_t i = 0; i < nb; ++i) g[i] = exponential_block_mean(i, beta);
    double cost = 0.0;
    std::vector<double> amplitudes(channels.size());
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const auto [a, rss] = fit_offset_and_amplitude(blocks[c], g);
      amplitudes[c] = a;
      const double scale = reference_rms[c] > 0.0 ? reference_rms[c] : 1.0;
      cost += rss / (scale * scale);
    }
    if (cost < best_cost) {
      best_cost = cost;
      out.time_constant_s = tau;
      for (std::size_t c = 0; c < channels.size(); ++c) out.channels[c].amplitude = amplitudes[c];
    }
  }

  // 3. The trim: the start after which every channel's transient |A|·e^(−t/τ) is at most its
  // model-free ADEV at τ (the last three quarters' adjacent-mean scatter / √2 at segments of τ).
  // What remains then adds to the AVAR near τ at most about (0.4·ADEV)² over the fraction 2τ/T' of
  // the differences it reaches (0.41 = the largest adjacent-mean difference of a unit
  // exponential, at segments of 1.26τ) — a few % of the AVAR there, against the transient's
  // factor of several.
  const std::size_t tau_segment = usable_segment(out.time_constant_s / tau0_s, n);
  for (std::size_t c = 0; c < channels.size(); ++c) {
    StartTransientChannel& ch = out.channels[c];
    ch.adev_at_tau = scan_scale(channels[c], tau_segment).reference_rms / std::sqrt(2.0);
    if (ch.adev_at_tau > 0.0 && std::abs(ch.amplitude) > ch.adev_at_tau) {
      out.trim_s = std::max(
          out.trim_s, out.time_constant_s * std::log(std::abs(ch.amplitude) / ch.adev_at_tau));
    }
  }
  if (out.trim_s > record_s / 2.0) {
    out.trim_s = record_s / 2.0;
    out.trim_capped = true;
  }
  return out;
}

}  // namespace imunoise::pipeline
