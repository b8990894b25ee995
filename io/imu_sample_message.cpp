#include "io/imu_sample_message.h"

#include <climits>

#include "io/lcm_messages.h"

namespace imunoise::io {

pipeline::ImuSample imu_sample_of(const imunoise::imu_sample_t& m) {
  pipeline::ImuSample s;
  s.utime_us = m.utime;
  s.increments = m.has_increments != 0;
  const double* gyro = s.increments ? m.delta_angle_rad : m.angular_rate_rad_per_s;
  const double* accel = s.increments ? m.delta_velocity_m_per_s : m.specific_force_m_per_s2;
  for (std::size_t a = 0; a < 3; ++a) {
    s.values[a] = gyro[a];
    s.values[3 + a] = accel[a];
  }
  if (m.has_temperature) s.temperature_degc = m.temperature_degc;
  return s;
}

std::optional<pipeline::ImuSample> decode_imu_sample(const void* data, std::size_t size) {
  imunoise::imu_sample_t m{};
  if (size > static_cast<std::size_t>(INT32_MAX) ||
      m.decode(data, 0, static_cast<int>(size)) != static_cast<int>(size)) {
    return std::nullopt;
  }
  return imu_sample_of(m);
}

pipeline::ImuSampleFields imu_sample_fields() {
  // The names are append_imu_sample's (the one place they are written): read them off the
  // columns it makes of one sample of each kind.
  const auto columns_of = [](bool increments) {
    imunoise::imu_sample_t m{};
    m.has_increments = increments;
    pipeline::ImuSampleColumns columns;
    append_imu_sample(m, columns);
    return columns;
  };
  const pipeline::ImuSampleColumns rates = columns_of(false), increments = columns_of(true);
  pipeline::ImuSampleFields fields;
  fields.rate_fields = rates.source_fields;
  fields.rate_units = rates.source_units;
  fields.increment_fields = increments.source_fields;
  fields.increment_units = increments.source_units;
  fields.temperature_field = rates.temperature_field;
  return fields;
}

}  // namespace imunoise::io
