/// @file
/// @brief Detection of a warm-up (thermal start-up transient) at the start of a recording, its
/// amplitude and time constant, and how much of the start to trim. Pure computation on the
/// rate samples of the channels of one recording. The scatter it compares against is that of a
/// power-law model (N, B, K, R) fitted to the last three quarters of the same channel (theory.md
/// §2: the variance of a difference of adjacent means is twice the AVAR, at any position of a
/// record with stationary increments).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace imunoise::pipeline {

/// One channel's part of the scan.
struct StartTransientChannel {
  std::string name;
  /// (mean of the first segment − mean of the second) / the standard deviation of that
  /// difference under the reference model, at the segment that gave the recording's statistic.
  double z = 0.0;
  double amplitude = 0.0;  ///< fitted transient at t = 0, A in A·e^(−t/τ) [channel unit]
  /// ADEV of the channel's reference model at the fitted τ [channel unit] (the model is fitted
  /// to the last three quarters of the record).
  double adev_at_tau = 0.0;
};

/// The scan of one recording.
struct StartTransient {
  bool scanned = false;   ///< false: the record is too short (fewer than kMinSamples)
  bool detected = false;  ///< statistic > threshold
  /// max over the segment lengths T/8, T/16, T/32, T/64 of Σ_channels z², and its threshold for the
  /// number of channels (start_transient_threshold).
  double statistic = 0.0;
  double threshold = 0.0;
  double segment_s = 0.0;        ///< segment length of the maximum [s]
  double time_constant_s = 0.0;  ///< fitted τ of A·e^(−t/τ), common to the channels [s]
  /// Start to drop so that every channel's remaining transient |A|·e^(−t/τ) is at most its ADEV
  /// at τ; capped at half the record [s]. 0 when nothing was detected.
  double trim_s = 0.0;
  bool trim_capped = false;  ///< the trim wanted more than half the record
  std::vector<StartTransientChannel> channels;
};

/// Fewest samples a scan needs: 64 segments of at least 16 samples.
inline constexpr std::size_t kStartTransientMinSamples = 1024;

/// The threshold on the scan statistic for K channels (1 ≤ K ≤ 6, larger K uses 6's growth):
/// the 99.5 % point of the statistic under stationary noise, so that a clean recording of any
/// number of channels false-alarms in ≤ 1 % of cases (derivation and simulation:
/// start_transient.cpp and tests/pipeline/start_transient_test.cpp).
double start_transient_threshold(std::size_t channels);

/// Scans CHANNELS (same length each, sample period TAU0_S) for a start transient; NAMES names
/// them (same size). Throws ContractViolation on mismatched sizes.
StartTransient detect_start_transient(std::span<const std::span<const double>> channels,
                                      std::span<const std::string> names, double tau0_s);

}  // namespace imunoise::pipeline
