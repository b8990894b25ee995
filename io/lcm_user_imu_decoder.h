/// @file
/// @brief A user's own IMU message type (LcmUserType, for read_lcm_imu_log) and its decoder
/// into imunoise's six channels in SI with integer µs stamps (LcmUserImuDecoder), built on the
/// generic decoder of lcm_field_decoder.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pipeline/imu_samples.h"
#include "io/lcm_field_decoder.h"

namespace imunoise::io {

/// A user's own IMU message type, for read_lcm_imu_log (LcmReadOptions::user_type).
struct LcmUserType {
  std::string definition_path;  ///< the `.lcm` file defining the type
  std::string type_name;        ///< struct to use ("pkg.name" or "name"); empty = the only one
  /// Field holding the sample stamp and its unit in seconds (1e-6 µs, 1e-9 ns, 1 s). The stamp
  /// becomes integer µs = llround(value × time_unit_s × 1e6); integer fields are converted
  /// exactly when the unit is an integer multiple or fraction of 1 µs (e.g. int64 ns).
  std::string time_field = "utime";
  double time_unit_s = 1e-6;
  /// One name of a numeric array of 3 (x, y, z), or three names of numeric fields. Both are
  /// required.
  std::vector<std::string> gyro_fields, accel_fields;
  /// Factors to SI: the field's unit in rad/s (rad for increments) and m/s² (m/s), e.g.
  /// π/180 for deg/s, 9.80665 for g.
  double gyro_scale_to_si = 1.0, accel_scale_to_si = 1.0;
  bool increments = false;  ///< the fields are angle / velocity increments per sample
};

/// Decodes a user's IMU messages into ImuSampleColumns (SI, stamps in µs).
class LcmUserImuDecoder {
 public:
  /// Reads the definition and resolves the fields; throws InputError for a bad definition,
  /// an unknown struct or field, fewer or more than 3 gyro or accel values, a bad unit or scale.
  explicit LcmUserImuDecoder(const LcmUserType& user_type);

  std::uint64_t fingerprint() const { return decoder_.fingerprint(); }
  /// "package.name" of the struct used.
  std::string type_name() const { return decoder_.type().full_name(); }
  const std::string& definition_path() const { return definition_path_; }

  /// Empty columns carrying the increments flag and the source fields and units.
  pipeline::ImuSampleColumns make_columns() const;

  /// Decodes one message and appends it to `samples`. A NaN/Inf among the used fields drops
  /// the message (counted in `samples`) when `drop_non_finite`, else fails. False, with the
  /// problem in `error`, when the message does not decode, has a non-finite value (and
  /// !drop_non_finite) or a stamp beyond the int64 µs range.
  bool append(std::span<const unsigned char> message, bool drop_non_finite,
              pipeline::ImuSampleColumns& samples, std::string& error);

 private:
  bool stamp_us(std::int64_t* out, std::string& error) const;

  std::string definition_path_;
  LcmFieldDecoder decoder_;
  std::size_t time_slot_ = 0;
  std::size_t value_slots_[6] = {};
  double scale_to_si_[6] = {};
  double time_unit_s_ = 1e-6;
  bool increments_ = false;
  LcmSlotValues slot_values_;
};

}  // namespace imunoise::io
