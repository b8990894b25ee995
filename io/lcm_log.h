/// @file
/// @brief Reader of LCM event logs (the files `lcm-logger` and `lcm::LogFile` write), parsed
/// here without the LCM runtime: list the channels and their message types, and read an
/// `imunoise.imu_sample_t` channel into a Recording (lcmtypes/imunoise_imu_sample_t.lcm).
///
/// Event format (LCM's eventlog.c; every integer big-endian):
///   uint32 sync word 0xEDA1DA01, int64 event number, int64 timestamp [µs],
///   int32 channel length, int32 data length, channel bytes (no NUL), data bytes.
/// The data of every LCM message starts with the 8-byte big-endian fingerprint of its type
/// (equal to the generated `T::getHash()`), which is how a channel's type is recognised.
///
/// Every malformed input is an InputError "FILE: byte offset N: problem": a truncated event, a
/// bad sync word, a channel or data length beyond the file, the channel not found (the message
/// lists the channels and types present), a wrong type on the channel (expected and found
/// fingerprints). No byte sequence crashes the reader.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/lcm_user_imu_decoder.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// One channel of an LCM log.
struct LcmLogChannel {
  std::string name;              ///< channel name as published
  std::int64_t event_count = 0;  ///< events on this channel
  /// Fingerprint (first 8 data bytes, big-endian) of the channel's first message; empty when
  /// that message is shorter than 8 bytes.
  std::optional<std::uint64_t> fingerprint;
  /// "imunoise.imu_sample_t" etc. when `fingerprint` is one of our types; empty otherwise.
  std::string type_name;
  /// Events whose fingerprint differs from the first one's (0 for a well-formed log).
  std::int64_t other_fingerprint_count = 0;
};

/// The channels of the log at `path`, in order of first appearance. Throws InputError when
/// the file cannot be read or is malformed anywhere.
std::vector<LcmLogChannel> list_lcm_log_channels(const std::string& path);

/// "the log holds 'IMU' (imunoise.imu_sample_t, 100 events), 'X' (unknown type, fingerprint
/// 0x…, 2 events)" — how error messages list a log's channels.
std::string describe_lcm_log_channels(const std::vector<LcmLogChannel>& channels);

/// The log's only imunoise.imu_sample_t channel, the default of every reader of PATH; else
/// InputError "PATH: no (several) imunoise.imu_sample_t channel(s) in this LCM log; HINT; " and
/// the channels (describe_lcm_log_channels). HINT names the caller's setting ("give --channel
/// NAME").
std::string only_imu_sample_channel(const std::string& path, std::string_view hint);

/// Options of read_lcm_imu_log.
struct LcmReadOptions {
  /// false: a NaN/Inf in a used field is an InputError; true: the message is dropped and
  /// counted in the sampling report.
  bool drop_non_finite = false;
  /// A user's own IMU message type (io/lcm_user_imu_decoder.h) instead of imu_sample_t: the
  /// channel must carry that type's fingerprint; the mapped fields are scaled to SI.
  std::optional<LcmUserType> user_type = std::nullopt;
};

/// Reads the `imunoise.imu_sample_t` messages on `channel` into a Recording in SI: channels
/// gyro_x … gyro_z [rad/s] and accel_x … accel_z [m/s²] from the rates, or, when the messages
/// carry increments (has_increments), from delta_angle_rad / delta_velocity_m_per_s divided by
/// the sample period; a "temperature" channel [°C] when every message has one. time_s from
/// utime (relative to the first message), sample_period_s = the median interval; sampling
/// report as for CSV input (non-monotonic stamps are reported, not fatal). Throws InputError
/// for a malformed log, an unknown channel, a message of another type on the channel, mixed
/// has_increments, fewer than 2 samples or stamps that never increase.
/// With `options.user_type`: that type's messages instead, decoded by LcmUserImuDecoder (stamp
/// and six values from the mapped fields, scaled to SI; increments divided by the period); a
/// bad definition or mapping, another type on the channel (both fingerprints named) or a
/// message that does not decode is an InputError.
pipeline::Recording read_lcm_imu_log(const std::string& path, const std::string& channel,
                                     const LcmReadOptions& options = {});

}  // namespace imunoise::io
