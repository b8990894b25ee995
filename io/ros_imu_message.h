/// @file
/// @brief The sensor_msgs/Imu message of ROS 1 and ROS 2, decoded from its serialized bytes:
/// the stamp of its header and the angular velocity and linear acceleration vectors (the
/// orientation and the three covariance arrays are skipped).
///
/// ROS 1 serialization (wiki.ros.org/msg, "Message serialization"; sensor_msgs/Imu.msg of
/// common_msgs): little-endian, packed, no alignment — header (uint32 seq, time stamp as uint32
/// sec + uint32 nsec, string frame_id as uint32 length + bytes), orientation (4 float64),
/// float64[9], angular_velocity (3 float64), float64[9], linear_acceleration (3 float64),
/// float64[9].
/// ROS 2 (CDR, io/cdr_decoder.h; sensor_msgs/msg/Imu.msg of common_interfaces): header
/// (builtin_interfaces/Time stamp as int32 sec + uint32 nanosec, string frame_id), then the same
/// fields, every float64 aligned.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace imunoise::io {

/// ROS 1's type name and MD5 sum of sensor_msgs/Imu (rosmsg md5 sensor_msgs/Imu).
inline constexpr std::string_view kRos1ImuType = "sensor_msgs/Imu";
inline constexpr std::string_view kRos1ImuMd5 = "6a62c6daae103f4ff57a132d6f95cec2";
/// ROS 2's type name of sensor_msgs/msg/Imu.
inline constexpr std::string_view kRos2ImuType = "sensor_msgs/msg/Imu";

/// True for "sensor_msgs/Imu" and "sensor_msgs/msg/Imu".
bool is_ros_imu_type(std::string_view type);

/// The field names of the six values, in imunoise's channel order (gyro x y z, accel x y z):
/// "angular_velocity.x" … "linear_acceleration.z".
const std::array<std::string, 6>& ros_imu_fields();

/// What imunoise reads of one sensor_msgs/Imu message, in SI.
struct ImuMessage {
  std::int64_t stamp_ns = 0;       ///< header.stamp [ns since the epoch of the stamps]
  std::array<double, 6> values{};  ///< angular velocity [rad/s], linear acceleration [m/s²]
};

/// Decodes BYTES as a ROS 1 sensor_msgs/Imu into OUT. False (ERROR says why) when the bytes
/// run out or do not end with the message (trailing bytes).
bool decode_ros1_imu(std::span<const std::uint8_t> bytes, ImuMessage& out, std::string& error);

/// Decodes BYTES as a CDR sensor_msgs/msg/Imu into OUT. False (ERROR says why) for an
/// unsupported encapsulation or bytes that run out (trailing bytes are allowed: CDR pads).
bool decode_cdr_imu(std::span<const std::uint8_t> bytes, ImuMessage& out, std::string& error);

}  // namespace imunoise::io
