/// @file
/// @brief Sampling-quality checks of a recording: rate, gaps, time-stamp order and jitter,
/// saturation and quantization step per channel. Pure functions over time stamps and values
/// (pipeline/sampling_timing.cpp, channel_checks.cpp, lsb_estimate.cpp); the text and JSON of
/// `imunoise check` are io/sampling_report.h.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/sampling_gap.h"

namespace imunoise::pipeline {

/// Where something first happened: 0-based sample index, and the file line when known.
struct SampleLocation {
  std::int64_t index = 0;
  std::optional<std::int64_t> line;
};

/// Tunables of the checks.
struct SamplingOptions {
  double gap_factor = kGapFactor;       ///< an interval > gap_factor × median is a gap
  std::int64_t saturation_min_run = 5;  ///< identical samples at min/max that make a run
  /// Maps a 0-based sample index to its 1-based file line (set by readers; may be empty).
  std::function<std::int64_t(std::size_t)> line_of_sample;
};

/// One gap: an interval longer than gap_factor × the median interval.
struct GapRecord {
  SampleLocation after;   ///< the first sample after the gap
  double start_s = 0.0;   ///< time of the sample before the gap, since the first stamp
  double length_s = 0.0;  ///< the interval
};

/// Histogram of the regular intervals (0 < interval ≤ gap limit): equal-width bins from the
/// shortest to the longest. When all are equal within 1e-9 × the median (float rounding of
/// the stamps), one bin centred on the median.
struct IntervalHistogram {
  std::vector<double> bin_low_s, bin_high_s;
  std::vector<std::int64_t> counts;
};

/// Time-stamp checks. All intervals are t[i+1] − t[i].
struct TimingReport {
  bool has_timestamps = false;     ///< false: a fixed rate was given
  double rate_hz = 0.0;            ///< 1 / sample_period_s (or the given rate); 0 if unknown
  double median_interval_s = 0.0;  ///< median of all intervals (of the positive ones if ≤ 0)
  /// Mean of the regular intervals (0 < interval ≤ gap_factor × median) [s]; 0 if none.
  double mean_interval_s = 0.0;
  /// The sample period of the analysis [s]: the median interval, or the mean regular interval
  /// when the two differ by more than kPeriodFromMeanThreshold of the median — stamps that
  /// alternate or are quantized coarser than the jitter (e.g. 0.10, 0.11, 0.10, … s) put the
  /// median on one of the quantized values, while the mean regular interval stays the true
  /// period (theory.md §1.1: τ0 is the sample period).
  double sample_period_s = 0.0;
  bool period_from_mean = false;     ///< sample_period_s is mean_interval_s
  double duration_s = 0.0;           ///< last − first time stamp
  double mean_rate_hz = 0.0;         ///< (n − 1) / duration
  std::int64_t gap_count = 0;        ///< intervals > gap_factor × median
  double longest_gap_s = 0.0;        ///< longest such interval [s]
  std::int64_t missing_samples = 0;  ///< Σ over gaps of round(gap / median) − 1 (saturates)
  std::optional<SampleLocation> first_gap;  ///< sample after the first gap
  std::int64_t non_monotonic_count = 0;     ///< intervals < 0
  std::optional<SampleLocation> first_non_monotonic;
  std::int64_t duplicate_count = 0;  ///< intervals == 0
  std::optional<SampleLocation> first_duplicate;
  double jitter_rms_s = 0.0;  ///< RMS of (interval − median) over 0 < interval ≤ gap limit [s]
  double jitter_max_s = 0.0;  ///< max |interval − median| over the same intervals [s]
  IntervalHistogram interval_histogram;  ///< of the same intervals
  std::vector<GapRecord> gaps;           ///< the first kMaxListedGaps gaps, in time order
};

/// |mean − median| / median of the regular intervals above which TimingReport::sample_period_s
/// is the mean (0.1 %: symmetric jitter moves the mean from the median by ~jitter/√n, far
/// below; a τ axis 0.1 % off is already at the level of a fitted N's interval).
inline constexpr double kPeriodFromMeanThreshold = 1e-3;

/// How many gaps a TimingReport lists one by one (gap_count counts them all).
inline constexpr std::size_t kMaxListedGaps = 10000;

/// Bins of TimingReport::interval_histogram.
inline constexpr int kIntervalHistogramBins = 41;

/// Per-channel checks; values in the channel's unit.
struct ChannelReport {
  std::string name;
  std::string unit;  ///< as reported: "rad/s", "m/s^2" (Channel::unit()), "" = as in the file
  double min = 0.0, max = 0.0, mean = 0.0, std_dev = 0.0;
  bool constant = false;               ///< all samples equal (no saturation runs counted)
  std::int64_t saturation_runs = 0;    ///< runs of ≥ min_run identical samples at min or max
  std::int64_t saturated_samples = 0;  ///< samples in those runs
  std::int64_t longest_saturation_run = 0;
  std::optional<SampleLocation> first_saturation;
  std::optional<double> full_scale;    ///< user limit, if any
  std::int64_t beyond_full_scale = 0;  ///< samples with |value| ≥ full_scale
  std::optional<SampleLocation> first_beyond_full_scale;
  std::optional<double> lsb;  ///< quantization step; empty = none detected
};

/// Everything `imunoise check` reports about a recording.
struct SamplingReport {
  std::int64_t samples = 0;
  TimingReport timing;
  std::vector<ChannelReport> channels;
  std::int64_t non_finite_dropped = 0;  ///< NaN/Inf values met in rows that were dropped
  std::int64_t rows_dropped = 0;        ///< rows dropped because they held NaN/Inf
};

/// One channel's samples as input to the checks.
struct ChannelSamples {
  std::string_view name;
  std::string_view unit;  ///< the unit text the report gives the values (Channel::unit())
  std::span<const double> values;
  std::optional<double> full_scale;  ///< |value| ≥ this is saturated [unit]
};

/// Time-stamp checks over `time_s` (any origin). Fewer than 2 stamps give rate 0.
TimingReport analyze_timing(std::span<const double> time_s, const SamplingOptions& options = {});

/// Timing for a fixed, given rate (no time stamps to check).
TimingReport fixed_rate_timing(double rate_hz, std::int64_t samples);

/// Range, saturation runs, full-scale excursions and quantization step of one channel.
ChannelReport analyze_channel(const ChannelSamples& channel, const SamplingOptions& options = {});

/// analyze_channel over CHANNELS, on up to THREADS threads (0 = all cores); results in order.
/// The checks of one channel are independent of the others, so the result does not depend on
/// the thread count.
std::vector<ChannelReport> analyze_channels(std::span<const ChannelSamples> channels,
                                            const SamplingOptions& options = {},
                                            unsigned threads = 0);

/// Smallest positive step q such that every difference between consecutive samples is an
/// integer multiple of q (within 10 % of q), or empty when none is found, there are fewer than
/// 8 non-zero steps, or the range would span more than 2^24 steps (not an ADC code grid).
std::optional<double> estimate_lsb(std::span<const double> values);

}  // namespace imunoise::pipeline
