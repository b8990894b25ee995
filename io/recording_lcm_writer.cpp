#include "io/recording_lcm_writer.h"

#include <cmath>
#include <utility>

#include "common/errors.h"
#include "io/atomic_output.h"

namespace imunoise::io {

ImuSampleLogWriter::ImuSampleLogWriter(std::ostream& out, std::string channel)
    : writer_(out),
      channel_(std::move(channel)),
      encoded_(static_cast<std::size_t>(message_.getEncodedSize())) {}

void ImuSampleLogWriter::write(std::int64_t utime_us,
                               const std::array<double, 3>& angular_rate_rad_per_s,
                               const std::array<double, 3>& specific_force_m_per_s2,
                               std::optional<double> temperature_degc) {
  message_.utime = utime_us;
  for (std::size_t a = 0; a < 3; ++a) {
    message_.angular_rate_rad_per_s[a] = angular_rate_rad_per_s[a];
    message_.specific_force_m_per_s2[a] = specific_force_m_per_s2[a];
  }
  message_.has_temperature = temperature_degc.has_value();
  message_.temperature_degc = temperature_degc.value_or(0.0);
  message_.encode(encoded_.data(), 0, static_cast<int>(encoded_.size()));
  writer_.write(channel_, message_.utime, encoded_);
}

void write_recording_lcm(const pipeline::Recording& rec, const std::string& path,
                         const std::string& channel) {
  std::array<const pipeline::Channel*, 6> imu{};
  std::string missing;
  for (std::size_t c = 0; c < imu.size(); ++c) {
    imu[c] = rec.find_channel(pipeline::kImuChannelNames[c]);
    if (imu[c] == nullptr)
      missing += std::string(missing.empty() ? "" : ", ") + pipeline::kImuChannelNames[c];
  }
  if (!missing.empty()) {
    throw InputError(rec.source_path +
                     ": an LCM log of imu_sample_t needs all six channels "
                     "gyro_x ... accel_z; missing: " +
                     missing);
  }
  const pipeline::Channel* temperature = rec.find_channel("temperature");
  const double start_us = std::round(rec.start_time_s * 1e6);
  if (!(std::fabs(start_us) < 9.2e18)) {
    throw InputError(rec.source_path + ": start_time_s does not fit a 64-bit µs stamp");
  }
  const auto start = static_cast<std::int64_t>(start_us);

  AtomicOutputFile file(path);
  ImuSampleLogWriter writer(file.stream(), channel);
  const std::size_t n = rec.sample_count();
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<double, 3> rate{imu[0]->values[i], imu[1]->values[i], imu[2]->values[i]};
    const std::array<double, 3> force{imu[3]->values[i], imu[4]->values[i], imu[5]->values[i]};
    writer.write(
        start + std::llround(pipeline::sample_time_s(rec, i) * 1e6), rate, force,
        temperature != nullptr ? std::optional<double>(temperature->values[i]) : std::nullopt);
  }
  file.commit();
}

}  // namespace imunoise::io
