/// @file
/// @brief LCM logs of imunoise.imu_sample_t (the format lcm-logger writes; replay with
/// lcm-logplayer): a writer of single samples, shared by `imunoise simulate` (io/
/// simulation_output) and `imunoise convert` (a Recording as a log).
#pragma once

#include <array>
#include <cstdint>
#include <imunoise/imu_sample_t.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "io/lcm_log_writer.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// Appends imunoise.imu_sample_t events on one channel to an LCM log on a stream.
class ImuSampleLogWriter {
 public:
  /// Events go to OUT on CHANNEL (1 to 4096 bytes).
  ImuSampleLogWriter(std::ostream& out, std::string channel);

  /// One sample, stamped UTIME_US both in the message and as the log event: rates
  /// [rad/s] and specific forces [m/s²] about x, y, z, and the temperature [°C] when given
  /// (has_temperature false and 0 °C otherwise).
  void write(std::int64_t utime_us, const std::array<double, 3>& angular_rate_rad_per_s,
             const std::array<double, 3>& specific_force_m_per_s2,
             std::optional<double> temperature_degc = std::nullopt);

 private:
  LcmLogWriter writer_;
  std::string channel_;
  imunoise::imu_sample_t message_{};
  std::vector<unsigned char> encoded_;
};

/// Writes RECORDING to PATH atomically as an LCM log of imunoise.imu_sample_t on CHANNEL: the
/// six IMU channels as rates, and the "temperature" channel when there is one; utime = start +
/// time since the first sample, in whole µs.
/// @throws InputError "SOURCE: an LCM log of imu_sample_t needs all six channels gyro_x ...
/// accel_z; missing: …", "SOURCE: start_time_s does not fit a 64-bit µs stamp", or naming
/// PATH when it cannot be written.
void write_recording_lcm(const pipeline::Recording& recording, const std::string& path,
                         const std::string& channel);

}  // namespace imunoise::io
