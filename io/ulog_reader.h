/// @file
/// @brief Reader of PX4 ULog files (docs.px4.io, "ULog File Format"), parsed here without
/// PX4's tools: the logged topics (message name and multi-instance id) with their counts, and
/// the IMU topics read into a Recording.
///
/// A ULog file is a 16-byte header ("ULog" 0x01 0x12 0x35, version, start time [µs]), then
/// messages (uint16 size, uint8 type, content): the definitions (flag bits 'B', formats 'F',
/// information 'I'/'M', parameters 'P'/'Q') and the data (subscriptions 'A' naming a format
/// and a multi_id for a msg_id, data 'D' of a msg_id, logged strings 'L'/'C', sync 'S',
/// dropouts 'O', unsubscriptions 'R'). Formats are self-describing: fields are found by name.
///
/// IMU topics read, in SI (PX4 logs rad/s and m/s²), stamps in µs turned into ns:
/// - sensor_combined: gyro_rad and accelerometer_m_s2; the stamp is `timestamp` (the gyro's
///   sample time; both time sources);
/// - sensor_gyro with sensor_accel of the same instance: x, y, z of each, paired by
///   timestamp_sample (each gyro sample with the accelerometer sample nearest in time, within
///   half the median gyro interval; unpaired samples dropped); stamps timestamp_sample
///   (header) or timestamp (log);
/// - sensor_gyro_fifo with sensor_accel_fifo of the same instance: `samples` values of x, y, z
///   (int16) × scale per message, sample k of n at timestamp_sample − (n − 1 − k)·dt, paired as
///   above.
/// Without --topic: sensor_combined when the file has it, else the only gyro topic (sensor_gyro
/// or sensor_gyro_fifo, one instance) with messages. --topic sensor_accel(_fifo) means its pair.
/// Every malformed byte sequence is an InputError "FILE: byte offset N: problem".
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "io/log_topics.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// The first 7 bytes of every ULog file.
inline constexpr std::string_view kUlogMagic{"ULog\x01\x12\x35", 7};

/// True when the file at PATH starts with kUlogMagic.
bool is_ulog_file(const std::string& path);

/// The logged topics of the ULog file at PATH in order of subscription: name = message name,
/// instance = multi_id, type = format name, counts of data messages; is_imu for
/// sensor_combined, sensor_gyro and sensor_gyro_fifo. Throws InputError for a malformed file.
std::vector<LogTopic> list_ulog_topics(const std::string& path);

/// The IMU samples of the topic OPTIONS choose (see above) as a Recording in SI. A wrong or
/// ambiguous topic is an InputError listing the topics; a gyro topic without its accelerometer
/// counterpart, or with no sample times in common, is an InputError too.
pipeline::Recording read_ulog_imu(const std::string& path, const LogReadOptions& options);

}  // namespace imunoise::io
