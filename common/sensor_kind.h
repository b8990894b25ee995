/// @file
/// @brief The one sensor kind of every layer: a channel, an axis model or a curve is a gyro's
/// (rad/s) or an accelerometer's (m/s²). Its names and SI units are written here once.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace imunoise {

/// Gyro (angular rate) or accelerometer (specific force).
enum class SensorKind { gyro, accel };

/// Both kinds, gyro first (the order of kImuChannelNames and of every output).
inline constexpr std::array<SensorKind, 2> kSensorKinds{SensorKind::gyro, SensorKind::accel};

/// "gyro" or "accel": the prefix of the channel names and the `sensor:` value of model.yaml.
constexpr std::string_view sensor_name(SensorKind kind) {
  return kind == SensorKind::gyro ? "gyro" : "accel";
}

/// SI unit of the rate values: "rad/s" or "m/s^2" (ASCII, as in every output).
constexpr std::string_view si_rate_unit(SensorKind kind) {
  return kind == SensorKind::gyro ? "rad/s" : "m/s^2";
}

/// The unit as it ends a column name or key: "rad_per_s" or "m_per_s2".
constexpr std::string_view rate_unit_suffix(SensorKind kind) {
  return kind == SensorKind::gyro ? "rad_per_s" : "m_per_s2";
}

/// The one-sided PSD unit as it ends a column name: "rad2_per_s2_per_hz" or "m2_per_s4_per_hz".
constexpr std::string_view psd_unit_suffix(SensorKind kind) {
  return kind == SensorKind::gyro ? "rad2_per_s2_per_hz" : "m2_per_s4_per_hz";
}

/// The kind sensor_name() spells NAME ("gyro" or "accel", exactly); empty for any other text.
constexpr std::optional<SensorKind> parse_sensor_name(std::string_view name) {
  if (name == sensor_name(SensorKind::gyro)) return SensorKind::gyro;
  if (name == sensor_name(SensorKind::accel)) return SensorKind::accel;
  return std::nullopt;
}

/// The kind whose si_rate_unit() is UNIT ("rad/s" or "m/s^2", exactly); empty for other text.
constexpr std::optional<SensorKind> parse_si_rate_unit(std::string_view unit) {
  if (unit == si_rate_unit(SensorKind::gyro)) return SensorKind::gyro;
  if (unit == si_rate_unit(SensorKind::accel)) return SensorKind::accel;
  return std::nullopt;
}

/// The kind of a channel named "gyro…" or "accel…" (gyro_x … accel_z); empty for other names.
constexpr std::optional<SensorKind> sensor_kind_of_channel(std::string_view channel_name) {
  if (channel_name.starts_with("gyro")) return SensorKind::gyro;
  if (channel_name.starts_with("accel")) return SensorKind::accel;
  return std::nullopt;
}

}  // namespace imunoise
