#include "pipeline/start_transient.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "analysis/deviation.h"
#include "analysis/nnls.h"
#include "analysis/noise_terms.h"
#include "common/errors.h"
#include "common/noise_term.h"

namespace imunoise::pipeline {

namespace {

/// Scan segments are multiples of this many samples (and at least twice it).
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

/// The reference model is fitted to block means of this many blocks per record (at least one
/// sample each): the shortest scan segment, T/64, spans 64 of them, so the fit's shortest τ
/// still sees the white noise the contrasts average.
constexpr std::size_t kReferenceBlocks = 4096;

/// The reference starts at 1/this of the record: after a transient of up to T/8 has decayed to
/// e^(−2) of its start.
constexpr std::size_t kReferenceStartDivisor = 4;

/// The scatter the contrasts are compared against: AVAR(τ) = Σ c_k²·φ_k(τ) over the power-law
/// terms N, B, K, R (theory.md §4.1 bases), fitted by NNLS to the octave OAVAR of the last three
/// quarters of the record. A model, not the raw scatter at the contrast's own length: the
/// adjacent-mean difference over T/8 has only ~3 independent copies in that part of the record,
/// and a scale from so few makes Σ z² heavy-tailed (with the median of the squared copies at
/// T/16–T/64 the 99.5 % point for six channels was 28, against χ²₆'s 18.5). The fit pools every
/// octave, the short ones with hundreds of copies each.
struct ReferenceModel {
  static constexpr std::array<NoiseTerm, 4> kTerms = {
      NoiseTerm::white_noise, NoiseTerm::bias_instability, NoiseTerm::random_walk, NoiseTerm::ramp};
  std::array<double, 4> coefficient_squared{};  ///< c_k² of kTerms

  double avar(double tau_s) const {
    double v = 0.0;
    for (std::size_t k = 0; k < kTerms.size(); ++k) {
      v += coefficient_squared[k] * analysis::term_avar_basis(kTerms[k], tau_s);
    }
    return v;
  }
};

/// Fits the reference model of X (sample period TAU0_S).
ReferenceModel fit_reference(std::span<const double> x, double tau0_s) {
  const std::span<const double> tail = x.subspan(x.size() / kReferenceStartDivisor);
  const std::size_t b = std::max<std::size_t>(1, x.size() / kReferenceBlocks);
  const std::vector<double> y = block_means(tail, b);
  const double block_s = static_cast<double>(b) * tau0_s;
  const auto length = static_cast<std::int64_t>(y.size());
  // Octave τ up to a sixth of the reference (at least three non-overlapping differences).
  std::vector<std::int64_t> factors;
  for (std::int64_t m = 1; 6 * m <= length; m *= 2) factors.push_back(m);
  if (factors.empty()) return ReferenceModel{};
  const std::vector<double> phase = analysis::phase_from_rate(y, block_s);
  if (!std::all_of(phase.begin(), phase.end(), [](double e) { return std::isfinite(e); })) {
    return ReferenceModel{};  // overflowing values: see the row check below
  }
  const std::vector<analysis::VarianceEstimate> oavar =
      analysis::overlapping_variances(analysis::DeviationType::oadev, phase, factors, block_s);
  std::vector<std::array<double, 4>> rows;
  std::vector<double> rhs;
  // Each row is divided by its estimate's relative standard error, ∝ √(m/L) (theory.md §3), so
  // the fit is in relative terms, as the analysis's own (theory.md §4.3).
  for (std::size_t i = 0; i < factors.size(); ++i) {
    const double v = oavar[i].variance;
    if (!(v > 0.0)) continue;
    const auto md = static_cast<double>(factors[i]);
    const double weight = 1.0 / (v * std::sqrt(md / static_cast<double>(length)));
    std::array<double, 4> row{};
    for (std::size_t k = 0; k < row.size(); ++k) {
      row[k] = weight * analysis::term_avar_basis(ReferenceModel::kTerms[k], md * block_s);
    }
    // Values whose squares overflow (or underflow to a zero weight) are the axis analysis's to
    // report, with file and channel: here the channel takes no part in the scan (z = 0).
    const bool finite =
        std::isfinite(v) && std::isfinite(weight) &&
        std::all_of(row.begin(), row.end(), [](double e) { return std::isfinite(e); });
    if (!finite) return ReferenceModel{};
    rows.push_back(row);
    rhs.push_back(weight * v);
  }
  ReferenceModel model;
  if (rows.empty()) return model;  // a constant channel: no scatter, z = 0
  const auto count = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd a(count, 4);
  Eigen::VectorXd r(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    for (Eigen::Index k = 0; k < 4; ++k) a(i, k) = rows[static_cast<std::size_t>(i)][k];
    r(i) = rhs[static_cast<std::size_t>(i)];
  }
  const Eigen::VectorXd c = analysis::nnls(a, r);
  for (std::size_t k = 0; k < 4; ++k) {
    model.coefficient_squared[k] = c(static_cast<Eigen::Index>(k));
  }
  return model;
}

/// The mean of X's first SEGMENT samples minus the mean of the next SEGMENT.
double first_difference(std::span<const double> x, std::size_t segment) {
  double first = 0.0, second = 0.0;
  for (std::size_t i = 0; i < segment; ++i) {
    first += x[i];
    second += x[segment + i];
  }
  return (first - second) / static_cast<double>(segment);
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
  // The 99.5 % points of the statistic (max over the four segment lengths of Σ z²) under
  // stationary noise, by channel count: the largest over four noise colours — white, white plus
  // a random walk carrying 60 % of the AVAR at T/10, white plus a flicker-like sum of five
  // first-order Gauss–Markov terms one per decade of τ at two levels — of the point measured on
  // 6000 simulated recordings each (tests/validation/start_transient_calibration, seeds 1 and 2),
  // rounded up. The statistic is scale free (a difference of means of a channel over the
  // scatter of the same channel's model), so neither the noise level nor the record length
  // enters. Σ z² is heavier-tailed than χ²_K (99.5 % points 7.9, 10.6, 12.8, 14.9, 16.7, 18.5):
  // the model's long-τ terms (K above all, at T/8) come from few independent differences, and
  // the maximum over four correlated lengths adds to that; white noise alone, where the model
  // is fixed by the short τ, gives 9.7 … 21.6. tests/pipeline/start_transient_test.cpp
  // re-measures the false-alarm rate on fresh seeds (≤ 1 % per recording).
  static constexpr std::array<double, 6> kThreshold{16.0, 20.5, 25.5, 28.0, 30.0, 35.0};
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

  // 1. The statistic: at segment lengths T/8, T/16, T/32 and T/64, the first difference of
  // adjacent means of each channel over its standard deviation under the channel's reference
  // model, √(2·AVAR(segment)) (theory.md §2), squared and summed over the channels. The model is
  // fitted to the last three quarters of the record, where a transient that starts the record has
  // decayed.
  std::vector<ReferenceModel> reference(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) {
    reference[c] = fit_reference(channels[c], tau0_s);
  }
  const auto difference_sd = [&](std::size_t c, double tau_s) {
    return std::sqrt(2.0 * reference[c].avar(tau_s));
  };
  for (const std::size_t divisor : {8u, 16u, 32u, 64u}) {
    const std::size_t segment = usable_segment(static_cast<double>(n) / divisor, n);
    const double segment_s = static_cast<double>(segment) * tau0_s;
    double sum = 0.0;
    std::vector<double> z(channels.size(), 0.0);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const double sd = difference_sd(c, segment_s);
      z[c] = sd > 0.0 ? first_difference(channels[c], segment) / sd : 0.0;
      sum += z[c] * z[c];
    }
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
  // squares of all channels, each scaled by its reference model's difference scatter at T/32.
  const std::size_t b = std::max<std::size_t>(1, n / kFitBlocks);
  std::vector<std::vector<double>> blocks;
  for (const auto& c : channels) blocks.push_back(block_means(c, b));
  const std::size_t nb = blocks.front().size();
  const double record_s = static_cast<double>(n) * tau0_s;
  const double tau_low = 2.0 * static_cast<double>(b) * tau0_s;
  const double tau_high = record_s / 2.0;
  std::vector<double> fit_scale(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const double sd = difference_sd(c, record_s / 32.0);
    fit_scale[c] = sd > 0.0 ? sd : 1.0;
  }
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
      cost += rss / (fit_scale[c] * fit_scale[c]);
    }
    if (cost < best_cost) {
      best_cost = cost;
      out.time_constant_s = tau;
      for (std::size_t c = 0; c < channels.size(); ++c) out.channels[c].amplitude = amplitudes[c];
    }
  }

  // 3. The trim: the start after which every channel's transient |A|·e^(−t/τ) is at most its
  // reference model's ADEV at τ.
  // What remains then adds to the AVAR near τ at most about (0.4·ADEV)² over the fraction 2τ/T' of
  // the differences it reaches (0.41 = the largest adjacent-mean difference of a unit
  // exponential, at segments of 1.26τ) — a few % of the AVAR there, against the transient's
  // factor of several.
  for (std::size_t c = 0; c < channels.size(); ++c) {
    StartTransientChannel& ch = out.channels[c];
    ch.adev_at_tau = std::sqrt(reference[c].avar(out.time_constant_s));
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
