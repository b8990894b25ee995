/// @file
/// @brief IMU samples as they arrive in messages (an LCM log, a live LCM subscription), and
/// their conversion to a Recording. One conversion for every message source, so `imunoise
/// live` and `imunoise analyze` on a log of the same messages see the same numbers. Pure
/// computation: io/ fills the columns from a log, pipeline/live_window from a subscription.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/recording.h"

namespace imunoise::pipeline {

/// One stream of samples in SI, column by column (gyro x y z, accel x y z).
struct ImuSampleColumns {
  std::vector<std::int64_t> utime_us;  ///< sample stamps [µs], any epoch
  /// Rates [rad/s, m/s²], or increments per sample [rad, m/s] when `increments` is true.
  std::array<std::vector<double>, 6> values;
  bool increments = false;
  /// One temperature per sample [°C], or empty when not every sample carried one.
  std::vector<double> temperature_degc;
  /// Where each column came from, e.g. "angular_rate_rad_per_s[0]", and the unit it had there.
  std::array<std::string, 6> source_fields;
  std::array<std::string, 6> source_units;
  std::string temperature_field;
  std::int64_t non_finite_dropped = 0;  ///< NaN/Inf values in dropped samples
  std::int64_t rows_dropped = 0;        ///< samples dropped because they held NaN/Inf

  std::size_t size() const { return utime_us.size(); }
  void clear();
};

/// Adds the temperature of the sample last appended to SAMPLES (its stamp is in: size() counts
/// it) by the one rule for the temperature channel of message samples: temperature is a channel
/// only if every sample carries one, so the column grows while every sample so far had one and
/// stops at the first without (it then stays shorter than the others and
/// recording_from_imu_samples leaves it out). Used by io::append_imu_sample (LCM logs) and
/// LiveWindow::snapshot (live), so both give the same channels.
/// @param[in,out] samples          the columns, with the sample's stamp already appended
/// @param[in]     temperature_degc the sample's temperature [°C], or none when it carried none
/// @throws ContractViolation when SAMPLES holds no sample.
void append_sample_temperature(ImuSampleColumns& samples, std::optional<double> temperature_degc);

/// The Recording of `samples`: time_s from utime relative to the first sample, sample period =
/// the median interval, increments divided by it (as the CSV reader does), channels gyro_x …
/// accel_z (+ "temperature" when present) with source_column "CHANNEL.FIELD", and the sampling
/// report. Non-monotonic stamps are reported, not fatal. Throws InputError (naming
/// `source_path`) for fewer than 2 samples or stamps that never increase.
Recording recording_from_imu_samples(ImuSampleColumns samples, const std::string& source_path,
                                     const std::string& channel);

/// The samples of one topic of a robotics log (a ROS bag, an MCAP or rosbag2 file, a PX4 ULog),
/// rates in SI with integer nanosecond stamps.
struct StampedImuColumns {
  std::vector<std::int64_t> stamp_ns;         ///< sample stamps [ns], any epoch
  std::array<std::vector<double>, 6> values;  ///< gyro x y z [rad/s], accel x y z [m/s²]
  /// Where each column came from, e.g. "angular_velocity.x", and the unit it had there.
  std::array<std::string, 6> source_fields;
  std::array<std::string, 6> source_units;
  std::int64_t non_finite_dropped = 0;  ///< NaN/Inf values in dropped samples
  std::int64_t rows_dropped = 0;        ///< samples dropped because they held NaN/Inf

  std::size_t size() const { return stamp_ns.size(); }
};

/// The Recording of `samples`, built as recording_from_imu_samples builds it (time_s relative to
/// the first stamp, exact to the ns; sample period from the intervals; channels gyro_x …
/// accel_z with source_column "TOPIC.FIELD", or FIELD when TOPIC is empty; the sampling report).
/// STAMP_NAME names the stamps in the error for stamps that never increase ("header.stamp", "log
/// time"). Throws InputError (naming `source_path`) for fewer than 2 samples or stamps that never
/// increase.
Recording recording_from_stamped_samples(StampedImuColumns samples, const std::string& source_path,
                                         const std::string& topic, const std::string& stamp_name);

}  // namespace imunoise::pipeline
