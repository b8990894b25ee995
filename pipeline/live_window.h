/// @file
/// @brief The rolling window of `imunoise live`: decoded IMU samples in, bounded by data time
/// and by a sample count, with the counts of what was rejected and why, the decision when the
/// window is worth analysing, and its snapshot as the columns of recording_from_imu_samples
/// (the conversion of the LCM log reader, so both see the same numbers). Pure computation:
/// the subscription, decoding and the analysis thread stay with the caller.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "pipeline/imu_samples.h"

namespace imunoise::pipeline {

/// One decoded IMU sample: the fields a reader uses, in SI.
struct ImuSample {
  std::int64_t utime_us = 0;  ///< stamp [µs], any epoch (from the network: may be anything)
  bool increments = false;    ///< `values` are increments per sample, not rates
  /// gyro x y z, accel x y z: rates [rad/s, m/s²], or increments [rad, m/s] when `increments`.
  std::array<double, 6> values{};
  std::optional<double> temperature_degc;  ///< [°C], when the sample carried one
};

/// Where the six columns of a snapshot come from in the message (ImuSampleColumns'
/// source_fields and source_units): one set for rates, one for increments.
struct ImuSampleFields {
  std::array<std::string, 6> rate_fields, rate_units;
  std::array<std::string, 6> increment_fields, increment_units;
  std::string temperature_field;
};

/// The bounds of the window and the analysis cadence.
struct LiveWindowLimits {
  double window_s = 0.0;         ///< longest span of data time kept [s], > 0
  std::int64_t max_samples = 0;  ///< most samples kept (memory bound), ≥ 1
  double every_s = 0.0;          ///< data time between analyses (also the least analysed) [s], > 0
};

/// What arrived, and what was done with it. Every message is counted once in `received` and
/// once as accepted or as one kind of rejection (a gap is an accepted sample).
struct LiveWindowCounts {
  std::int64_t received = 0;        ///< messages on the channel
  std::int64_t accepted = 0;        ///< samples added to the window
  std::int64_t undecodable = 0;     ///< wrong type, truncated or corrupt
  std::int64_t non_finite = 0;      ///< NaN/Inf in a used field
  std::int64_t out_of_order = 0;    ///< utime ≤ the last accepted one (incl. duplicates)
  std::int64_t mode_changes = 0;    ///< increments differing from the window's samples
  std::int64_t gaps = 0;            ///< intervals > kGapFactor × the nominal period
  std::int64_t trimmed_by_cap = 0;  ///< oldest samples dropped by LiveWindowLimits::max_samples
  std::int64_t restarts = 0;        ///< window restarted after a run of rejected samples
};

/// Rejected samples in a row (out of order or switching between rates and increments) after
/// which the stream counts as restarted: the window starts again from the next such sample.
inline constexpr std::int64_t kRestartAfterRejections = 100;

/// The rolling window. Not thread-safe: one thread adds and takes snapshots.
class LiveWindow {
 public:
  /// @throws ContractViolation when a limit is outside its documented range.
  LiveWindow(const LiveWindowLimits& limits, ImuSampleFields fields);

  /// Counts a message that could not be decoded.
  void add_undecodable();

  /// Adds SAMPLE, or counts why not: a non-finite value, a stamp ≤ the last accepted one,
  /// a switch between rates and increments (after kRestartAfterRejections such rejections in a
  /// row the window restarts from SAMPLE). An accepted sample more than kGapFactor × the
  /// nominal period after the last one counts as a gap. Then the oldest samples are dropped
  /// while the window spans more than window_s, and while it holds more than max_samples
  /// (those are counted).
  void add(const ImuSample& sample);

  /// The nominal sample period [s] of the gap count (the analysis's τ0); none before it is set.
  void set_nominal_period_s(double period_s);

  /// Span of the window in data time [s]: last − first stamp (0 below two samples).
  double span_s() const;
  /// Stamp of the newest sample [µs] (0 when empty).
  std::int64_t last_utime() const;
  /// Samples accepted since the last snapshot.
  std::int64_t new_samples() const { return new_samples_; }
  std::size_t size() const { return window_.size(); }
  const LiveWindowCounts& counts() const { return counts_; }

  /// Whether to analyse now: new samples since the last snapshot, the window spans ≥ every_s,
  /// and every_s of data time passed since the data of the last snapshot (or the stamps went
  /// back before it, after a restart).
  bool analysis_due() const;
  /// Whether a last analysis at the end has something to add: new samples since the last
  /// snapshot and a window that spans more than 0 s.
  bool has_unanalysed_data() const;

  /// The window as columns for recording_from_imu_samples (cheap: the conversion, with its
  /// sampling checks, can run on another thread). Marks the data as analysed: resets
  /// new_samples() and remembers last_utime() for analysis_due().
  ImuSampleColumns snapshot();

 private:
  double window_us_;
  std::int64_t max_samples_;
  double every_s_;
  ImuSampleFields fields_;
  std::deque<ImuSample> window_;
  std::int64_t new_samples_ = 0;
  std::int64_t analysed_until_us_ = 0;  ///< data time of the last snapshot
  std::int64_t nominal_period_us_ = 0;
  std::int64_t consecutive_rejections_ = 0;
  LiveWindowCounts counts_;
};

}  // namespace imunoise::pipeline
