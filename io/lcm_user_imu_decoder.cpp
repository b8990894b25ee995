/// @file
/// @brief The mapping of a user's IMU message onto imunoise's six channels (see
/// lcm_user_imu_decoder.h): fields resolved once, then each message decoded, scaled to SI and
/// stamped in integer µs.
#include "io/lcm_user_imu_decoder.h"

#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/sensor_kind.h"
#include "io/lcm_type_definition_internal.h"

namespace imunoise::io {
namespace {

using detail::is_integer_valued;

LcmFieldDecoder user_type_decoder(const LcmUserType& user_type) {
  LcmTypeFile file = read_lcm_type_definition(user_type.definition_path);
  const std::size_t index = file.find_struct(user_type.type_name);
  return LcmFieldDecoder(std::move(file), index);
}

/// "rad/s", or "0.017453292519943295 rad/s" for a field in deg/s: the source unit in SI.
std::string unit_text(double scale_to_si, std::string_view si_unit) {
  if (scale_to_si == 1.0) return std::string(si_unit);
  std::string text = shortest_number_text(scale_to_si);
  text.append(" ").append(si_unit);
  return text;
}

/// llround semantics (half away from zero) for an integer quotient.
std::int64_t divide_rounded(std::int64_t value, std::int64_t divisor) {
  std::int64_t quotient = value / divisor;
  const std::int64_t remainder = value % divisor;
  if (remainder != 0 && static_cast<std::uint64_t>(remainder < 0 ? -remainder : remainder) * 2 >=
                            static_cast<std::uint64_t>(divisor)) {
    quotient += value < 0 ? -1 : 1;
  }
  return quotient;
}

/// `value` × `us_per_unit` as an integer when that factor is an integer or the inverse of one
/// (ns, ms, s stamps): exact, unlike the double product for stamps beyond 2^53.
std::optional<std::int64_t> exact_integer_stamp_us(std::int64_t value, double us_per_unit,
                                                   bool* overflow) {
  *overflow = false;
  const double multiplier = std::round(us_per_unit);
  if (multiplier >= 1.0 && multiplier < 9e15 &&
      std::abs(us_per_unit - multiplier) <= 1e-9 * multiplier) {
    std::int64_t out = 0;
    *overflow = __builtin_mul_overflow(value, static_cast<std::int64_t>(multiplier), &out);
    return out;
  }
  const double divisor = std::round(1.0 / us_per_unit);
  if (divisor >= 2.0 && divisor < 9e15 && std::abs(1.0 / us_per_unit - divisor) <= 1e-9 * divisor) {
    return divide_rounded(value, static_cast<std::int64_t>(divisor));
  }
  return std::nullopt;
}

}  // namespace

LcmUserImuDecoder::LcmUserImuDecoder(const LcmUserType& user_type)
    : definition_path_(user_type.definition_path),
      decoder_(user_type_decoder(user_type)),
      time_unit_s_(user_type.time_unit_s),
      increments_(user_type.increments) {
  const auto fail = [&](const std::string& problem) {
    return InputError(located_message(definition_path_, 0, 0, problem));
  };
  if (!(std::isfinite(time_unit_s_) && time_unit_s_ > 0.0)) {
    throw fail("time unit " + shortest_number_text(time_unit_s_) + " s is not a positive number");
  }
  const std::vector<std::size_t> time_slots = decoder_.add_field(user_type.time_field);
  if (time_slots.size() != 1) {
    throw fail("time field '" + user_type.time_field + "' must be one number, not an array");
  }
  time_slot_ = time_slots.front();

  const auto add_group = [&](const std::vector<std::string>& fields, double scale,
                             const char* group, std::size_t first) {
    if (!(std::isfinite(scale) && scale != 0.0)) {
      throw fail(std::string(group) + " scale " + shortest_number_text(scale) +
                 " is not a finite non-zero factor");
    }
    if (fields.empty()) {
      throw fail(std::string("no ") + group + " fields given: name one array of 3 or three " +
                 "fields (both gyro and accel fields are needed)");
    }
    std::vector<std::size_t> slots;
    for (const std::string& f : fields) {
      const std::vector<std::size_t> s = decoder_.add_field(f);
      if (fields.size() > 1 && s.size() != 1) {
        throw fail(std::string(group) + " field '" + f + "' is an array; with several " + group +
                   " fields each must be one number");
      }
      slots.insert(slots.end(), s.begin(), s.end());
    }
    if (slots.size() != 3) {
      throw fail(std::string(group) + " fields give " + std::to_string(slots.size()) +
                 " value(s); x, y, z need 3 (one array of 3 or three fields)");
    }
    for (std::size_t a = 0; a < 3; ++a) {
      value_slots_[first + a] = slots[a];
      scale_to_si_[first + a] = scale;
    }
  };
  add_group(user_type.gyro_fields, user_type.gyro_scale_to_si, "gyro", 0);
  add_group(user_type.accel_fields, user_type.accel_scale_to_si, "accel", 3);
}

pipeline::ImuSampleColumns LcmUserImuDecoder::make_columns() const {
  pipeline::ImuSampleColumns columns;
  columns.increments = increments_;
  for (std::size_t c = 0; c < 6; ++c) {
    columns.source_fields[c] = decoder_.slot_path(value_slots_[c]);
    const SensorKind kind = pipeline::kImuChannelKinds[c];
    // An increment is an angle [rad] or a velocity change [m/s]; a rate is in the kind's unit.
    const std::string_view si = !increments_               ? si_rate_unit(kind)
                                : kind == SensorKind::gyro ? "rad"
                                                           : "m/s";
    columns.source_units[c] = unit_text(scale_to_si_[c], si);
  }
  return columns;
}

bool LcmUserImuDecoder::stamp_us(std::int64_t* out, std::string& error) const {
  const double us_per_unit = time_unit_s_ * 1e6;
  const std::string& field = decoder_.slot_path(time_slot_);
  if (is_integer_valued(decoder_.slot_type(time_slot_))) {
    bool overflow = false;
    const auto exact =
        exact_integer_stamp_us(slot_values_.integers[time_slot_], us_per_unit, &overflow);
    if (exact && !overflow) {
      *out = *exact;
      return true;
    }
    if (overflow) {
      error = "time stamp " + field + " = " + std::to_string(slot_values_.integers[time_slot_]) +
              " is beyond the int64 µs range";
      return false;
    }
  }
  const double us = slot_values_.values[time_slot_] * us_per_unit;
  if (!(std::abs(us) < 9.2e18)) {
    error = "time stamp " + field + " = " + shortest_number_text(slot_values_.values[time_slot_]) +
            " is beyond the int64 µs range";
    return false;
  }
  *out = std::llround(us);
  return true;
}

bool LcmUserImuDecoder::append(std::span<const unsigned char> message, bool drop_non_finite,
                               pipeline::ImuSampleColumns& samples, std::string& error) {
  if (!decoder_.decode(message, slot_values_, error)) {
    error =
        "the message does not decode as " + type_name() + " (" + definition_path_ + "): " + error;
    return false;
  }
  // The used values in SI (a finite value times its scale may still overflow) and the stamp.
  std::array<double, 6> si{};
  std::int64_t non_finite = 0;
  std::string first_bad;
  const auto check = [&](double v, std::size_t slot) {
    if (std::isfinite(v)) return;
    if (non_finite++ == 0) {
      first_bad = decoder_.slot_path(slot) + (std::isnan(v) ? " (NaN)" : " (Inf)");
      if (std::isfinite(slot_values_.values[slot])) first_bad += " after scaling to SI";
    }
  };
  check(slot_values_.values[time_slot_], time_slot_);
  for (std::size_t c = 0; c < 6; ++c) {
    si[c] = slot_values_.values[value_slots_[c]] * scale_to_si_[c];
    check(si[c], value_slots_[c]);
  }
  if (non_finite > 0) {
    if (!drop_non_finite) {
      error = "non-finite value in " + first_bad;
      return false;
    }
    samples.non_finite_dropped += non_finite;
    ++samples.rows_dropped;
    return true;
  }
  std::int64_t utime_us = 0;
  if (!stamp_us(&utime_us, error)) return false;
  samples.utime_us.push_back(utime_us);
  for (std::size_t c = 0; c < 6; ++c) samples.values[c].push_back(si[c]);
  return true;
}

}  // namespace imunoise::io
