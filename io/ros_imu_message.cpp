/// @file
/// @brief sensor_msgs/Imu decoding (see ros_imu_message.h for the layouts).
#include "io/ros_imu_message.h"

#include <cstring>

#include "io/binary_file.h"
#include "io/cdr_decoder.h"

namespace imunoise::io {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;
// After frame_id: orientation 4, covariance 9, angular_velocity 3, covariance 9,
// linear_acceleration 3, covariance 9 float64 values.
constexpr std::size_t kRos1BodyBytes = (4 + 9 + 3 + 9 + 3 + 9) * 8;

double load_le_double(const std::uint8_t* p) {
  const std::uint64_t u = load_le64(p);
  double d = 0.0;
  std::memcpy(&d, &u, sizeof d);
  return d;
}

}  // namespace

bool is_ros_imu_type(std::string_view type) { return type == kRos1ImuType || type == kRos2ImuType; }

const std::array<std::string, 6>& ros_imu_fields() {
  static const std::array<std::string, 6> fields{"angular_velocity.x",    "angular_velocity.y",
                                                 "angular_velocity.z",    "linear_acceleration.x",
                                                 "linear_acceleration.y", "linear_acceleration.z"};
  return fields;
}

bool decode_ros1_imu(std::span<const std::uint8_t> bytes, ImuMessage& out, std::string& error) {
  // seq, stamp.sec, stamp.nsec, frame_id length
  if (bytes.size() < 16) {
    error = "a " + std::to_string(bytes.size()) +
            "-byte message, shorter than the 16 bytes of a std_msgs/Header";
    return false;
  }
  const std::uint8_t* p = bytes.data();
  const std::uint32_t sec = load_le32(p + 4);
  const std::uint32_t nsec = load_le32(p + 8);
  const std::uint32_t frame_length = load_le32(p + 12);
  const std::size_t body = 16 + static_cast<std::size_t>(frame_length);
  if (frame_length > bytes.size() - 16 || bytes.size() - body != kRos1BodyBytes) {
    error = "a " + std::to_string(bytes.size()) + "-byte message with a " +
            std::to_string(frame_length) + "-byte frame_id is not a sensor_msgs/Imu (it needs " +
            std::to_string(kRos1BodyBytes) + " bytes after the frame_id)";
    return false;
  }
  out.stamp_ns = static_cast<std::int64_t>(sec) * kNsPerS + static_cast<std::int64_t>(nsec);
  const std::uint8_t* q = p + body + (4 + 9) * 8;
  for (std::size_t i = 0; i < 3; ++i) out.values[i] = load_le_double(q + 8 * i);
  q += (3 + 9) * 8;
  for (std::size_t i = 0; i < 3; ++i) out.values[3 + i] = load_le_double(q + 8 * i);
  return true;
}

bool decode_cdr_imu(std::span<const std::uint8_t> bytes, ImuMessage& out, std::string& error) {
  CdrReader cdr(bytes);
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  const bool ok =
      cdr.read_i32(sec, "header.stamp.sec") && cdr.read_u32(nanosec, "header.stamp.nanosec") &&
      cdr.skip_string("header.frame_id") && cdr.read_f64s(nullptr, 4 + 9, "orientation") &&
      cdr.read_f64s(out.values.data(), 3, "angular_velocity") &&
      cdr.read_f64s(nullptr, 9, "angular_velocity_covariance") &&
      cdr.read_f64s(out.values.data() + 3, 3, "linear_acceleration") &&
      cdr.read_f64s(nullptr, 9, "linear_acceleration_covariance");
  if (!ok) {
    error = cdr.error();
    return false;
  }
  out.stamp_ns = static_cast<std::int64_t>(sec) * kNsPerS + static_cast<std::int64_t>(nanosec);
  return true;
}

}  // namespace imunoise::io
