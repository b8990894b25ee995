/// @file
/// @brief Reader of MCAP files (the format of ROS 2's default bag storage and of Foxglove;
/// specification mcap.dev/spec, format version 0), parsed here without the MCAP library: the
/// topics with their types and message counts, and a sensor_msgs/msg/Imu topic (CDR, or ROS 1
/// serialization for message encoding "ros1"; io/ros_imu_message.h) read into a Recording.
///
/// An MCAP file is the magic "\x89MCAP0\r\n", records (uint8 opcode, uint64 length, content;
/// little-endian), the magic again. The data section holds the header (0x01), schemas (0x03),
/// channels (0x04), messages (0x05: channel id, sequence, log time, publish time, data) either
/// directly or in chunks (0x06: compression "", "zstd" or "lz4", uncompressed size, records),
/// message indexes (0x07), attachments and metadata, and ends with a data end record (0x0F);
/// the optional summary section (schemas, channels, statistics 0x0B, chunk indexes 0x08) is
/// found through the footer (0x02) before the closing magic.
///
/// With a summary holding statistics, the topics and counts come from it and chunks whose index
/// shows no message of the topic are skipped; without one (or for a file cut short) the data
/// section is scanned. Messages are taken in file order. Unknown record opcodes are skipped, as
/// the specification asks. Every malformed byte sequence is an InputError "FILE: byte offset N:
/// problem" (a truncated record or chunk, an impossible length, an unknown compression, a
/// message that does not decode); lengths are checked against the file or chunk before
/// anything is allocated. Chunk CRCs are not checked (the decoders' own checks remain).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "io/log_topics.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// The 8 bytes every MCAP file starts and ends with.
inline constexpr std::string_view kMcapMagic{"\x89MCAP0\r\n", 8};

/// True when the file at PATH starts with kMcapMagic.
bool is_mcap_file(const std::string& path);

/// The topics of the MCAP file at PATH in order of their first channel, with their types (the
/// schema name) and message counts (is_imu for sensor_msgs/msg/Imu in CDR, or sensor_msgs/Imu in
/// ROS 1 encoding). Throws InputError for a malformed file.
std::vector<LogTopic> list_mcap_topics(const std::string& path);

/// The Imu messages of OPTIONS.topic (or of the file's only Imu topic) as a Recording in SI:
/// angular_velocity → gyro_x … gyro_z [rad/s], linear_acceleration → accel_x … accel_z [m/s²],
/// stamps from header.stamp or, with TimeSource::kLog, the log time of each message. A wrong
/// or ambiguous topic is an InputError listing the topics (select_imu_topic).
pipeline::Recording read_mcap_imu(const std::string& path, const LogReadOptions& options);

}  // namespace imunoise::io
