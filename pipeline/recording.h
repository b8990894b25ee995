/// @file
/// @brief A recording in SI: nominal sample period, time stamps and named channels
/// (`gyro_x` … `accel_z`, plus extra mapped columns) with the sampling report of the read.
/// Pure data: the readers of io/ (CSV, binary, LCM log) fill it; pipeline/ analyses it.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.h"
#include "common/sensor_kind.h"
#include "pipeline/sampling_checks.h"

namespace imunoise::pipeline {

/// The six standard channel names of a recording, gyro then accelerometer, x, y, z (body FRD).
inline constexpr std::array<const char*, 6> kImuChannelNames{"gyro_x",  "gyro_y",  "gyro_z",
                                                             "accel_x", "accel_y", "accel_z"};
/// The sensor kind of each of kImuChannelNames.
inline constexpr std::array<SensorKind, 6> kImuChannelKinds{SensorKind::gyro,  SensorKind::gyro,
                                                            SensorKind::gyro,  SensorKind::accel,
                                                            SensorKind::accel, SensorKind::accel};

/// One named channel, in SI.
struct Channel {
  std::string name;  ///< gyro_x, gyro_y, gyro_z, accel_x, accel_y, accel_z, or an extra name
  /// gyro (`values` in rad/s) or accelerometer (m/s²); empty for extra (as-in-file) columns
  std::optional<SensorKind> kind;
  std::vector<double> values;
  std::string source_column;     ///< where it came from: header name or "column N"
  std::string source_unit;       ///< unit in the file, e.g. "deg/h", or "rad" for angle increments
  bool from_increments = false;  ///< the file held increments per sample, divided here by Δt

  /// The SI unit of `values` as every output writes it: "rad/s", "m/s^2", or "" (extra).
  std::string_view unit() const { return kind ? si_rate_unit(*kind) : std::string_view(); }
};

/// A stationary IMU recording, SI inside.
struct Recording {
  std::string source_path;
  /// Nominal Δt = τ0 [s]: 1 / the given rate, else the median time-stamp interval. Increments
  /// were divided by this value.
  double sample_period_s = 0.0;
  /// Time since the first sample [s] (so ns integer stamps keep full precision); empty when a
  /// fixed rate was given instead of a time column.
  std::vector<double> time_s;
  double start_time_s = 0.0;  ///< first time stamp as written in the file, in s (0 if none)
  std::vector<Channel> channels;
  SamplingReport report;

  std::size_t sample_count() const { return channels.empty() ? 0 : channels.front().values.size(); }

  /// The channel called `name`, or nullptr.
  const Channel* find_channel(std::string_view name) const {
    for (const Channel& c : channels) {
      if (c.name == name) return &c;
    }
    return nullptr;
  }
};

/// Time of sample I of RECORDING since its first sample [s]: its stamp, or I / rate for a
/// recording read at a fixed rate (the report's rate, else 1 / sample_period_s).
inline double sample_time_s(const Recording& recording, std::size_t i) {
  if (!recording.time_s.empty()) return recording.time_s[i];
  const double rate = recording.report.timing.rate_hz > 0.0 ? recording.report.timing.rate_hz
                                                            : 1.0 / recording.sample_period_s;
  return static_cast<double>(i) / rate;
}

/// The inputs of the sampling report's channel checks: the gyro channels (rad/s) against
/// GYRO_FULL_SCALE, the accelerometer channels (m/s^2) against ACCEL_FULL_SCALE.
inline std::vector<ChannelSamples> channel_checks(const std::vector<Channel>& channels,
                                                  std::optional<double> gyro_full_scale_rad_per_s,
                                                  std::optional<double> accel_full_scale_m_per_s2) {
  std::vector<ChannelSamples> checks;
  for (const Channel& ch : channels) {
    ChannelSamples samples{ch.name, ch.unit(), ch.values, std::nullopt};
    if (ch.kind == SensorKind::gyro) samples.full_scale = gyro_full_scale_rad_per_s;
    if (ch.kind == SensorKind::accel) samples.full_scale = accel_full_scale_m_per_s2;
    checks.push_back(samples);
  }
  return checks;
}

/// The sampling report's checks of every channel (analyze_channels of channel_checks) — what
/// every reader puts in Recording::report.channels.
inline std::vector<ChannelReport> check_channels(const std::vector<Channel>& channels,
                                                 std::optional<double> gyro_full_scale_rad_per_s,
                                                 std::optional<double> accel_full_scale_m_per_s2,
                                                 const SamplingOptions& options) {
  return analyze_channels(
      channel_checks(channels, gyro_full_scale_rad_per_s, accel_full_scale_m_per_s2), options);
}

/// Throws InputError "PATH: too few samples: N (need at least MIN for PURPOSE)" when
/// `count < min_samples`.
inline void require_min_samples(const std::string& path, std::size_t count, std::size_t min_samples,
                                std::string_view purpose) {
  if (count >= min_samples) return;
  throw InputError(located_message(path, 0, 0,
                                   "too few samples: " + std::to_string(count) +
                                       " (need at least " + std::to_string(min_samples) + " for " +
                                       std::string(purpose) + ")"));
}

/// require_min_samples over a recording's sample count.
inline void require_min_samples(const Recording& recording, std::size_t min_samples,
                                std::string_view purpose) {
  require_min_samples(recording.source_path, recording.sample_count(), min_samples, purpose);
}

}  // namespace imunoise::pipeline
