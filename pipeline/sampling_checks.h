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

/// The median interval of integer stamps, exactly: stamps that are whole ticks of
/// 1 / ticks_per_second s have whole-tick intervals, whose median is a whole or (even count)
/// half number of ticks. Kept as 2 × that count and 2 × ticks per second, both exact integers,
/// so the period and the rate are each one correctly rounded division.
struct ExactMedianInterval {
  double twice_ticks = 0.0;             ///< 2 × the median interval [ticks] (> 0)
  double twice_ticks_per_second = 0.0;  ///< 2 × ticks per second
  double seconds() const { return twice_ticks / twice_ticks_per_second; }
  double rate_hz() const { return twice_ticks_per_second / twice_ticks; }
};

/// The exact median interval of TICKS (stamps counted in ticks of 1 / TICKS_PER_SECOND s, a
/// power of ten: 1e9 for ns) when every value is a whole number of at most 2^53 in magnitude
/// (the integer stamps' differences held exactly; the int64 arithmetic in doubles), and the
/// median is positive; else nullopt. The median of the positive intervals when most are 0, as
/// analyze_timing takes it.
std::optional<ExactMedianInterval> exact_tick_median(std::span<const double> ticks,
                                                     double ticks_per_second);

/// Time-stamp checks over `time_s` (any origin). Fewer than 2 stamps give rate 0. The median
/// interval is EXACT when given (exact_tick_median of the same stamps before their conversion to
/// seconds: 200 Hz stamps 5 000 000 ns apart give 200 Hz); else, for stamps on a decimal grid
/// (decimal_grid_digits: every stamp a whole number of 10^-d s, as text with at most d decimals
/// gives), the median on the grid (snap_to_decimal_grid) and the rate 10^d / (whole steps), so
/// stamps k·0.0025 s give 400 Hz, not 1 / (a median interval rounded in double).
TimingReport analyze_timing(std::span<const double> time_s, const SamplingOptions& options = {},
                            const std::optional<ExactMedianInterval>& exact = std::nullopt);

/// @name Decimal grids of time stamps
/// @{
/// The most decimals a grid may have (ns).
inline constexpr int kMaxGridDigits = 9;
/// True when STAMP is a whole number of 10^-DIGITS (DIGITS in [0, kMaxGridDigits]) within 4 ulp
/// of the scaled value, the rounding a parsed or computed stamp carries; false as well when that
/// tolerance would reach 1/64 of a step (the grid cannot be told from rounding any more).
bool on_decimal_grid(double stamp, int digits);
/// The fewest DIGITS with every stamp on_decimal_grid, or nullopt (none up to kMaxGridDigits).
std::optional<int> decimal_grid_digits(std::span<const double> stamps);
/// MEDIAN, the median interval between stamps on the grid of DIGITS decimals, made exact: the
/// nearest half-multiple of 10^-DIGITS (each interval is within 1/32 step of a whole number of
/// steps, so that is the median of the exact intervals). Non-positive MEDIAN stays as it is.
double snap_to_decimal_grid(double median, int digits);
/// @}

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
