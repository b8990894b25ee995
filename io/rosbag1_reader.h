/// @file
/// @brief Reader of ROS 1 bags (format version 2.0, wiki.ros.org/Bags/Format/2.0), parsed here
/// without ROS: the topics with their types and message counts, and a sensor_msgs/Imu topic
/// (io/ros_imu_message.h) read into a Recording.
///
/// A bag is the line "#ROSBAG V2.0\n", then records: int32 header length, header fields
/// (int32 length, "name=value", the field "op" a byte naming the record), int32 data length,
/// data. The bag header record (op 0x03: index_pos, conn_count, chunk_count) comes first;
/// chunks (0x05: compression "none", "bz2" or "lz4" — roslz4's LZ4 frames —, size) hold the
/// connection (0x07) and message data (0x02: conn, time) records, each chunk followed by its
/// index data records (0x04); at index_pos the connection records and the chunk info records
/// (0x06: chunk_pos, per connection the message count) close the bag.
///
/// With a valid index (index_pos inside the file) the topics and counts come from it and only
/// the chunks that hold the topic are read; without one (index_pos 0: a bag still being
/// recorded, or one whose index is past the end of the file) every chunk is scanned. Messages
/// are taken in file order. Every malformed byte sequence is an InputError "FILE: byte offset
/// N: problem" (a truncated record or chunk, an impossible length, an unknown compression or
/// record, a message that is not a sensor_msgs/Imu); every length is checked against the file
/// or chunk before anything is allocated.
#pragma once

#include <string>
#include <vector>

#include "io/log_topics.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// The first bytes of every ROS 1 bag of format 2.0.
inline constexpr std::string_view kRosbag1Magic = "#ROSBAG V2.0\n";

/// True when the file at PATH starts with kRosbag1Magic.
bool is_rosbag1_file(const std::string& path);

/// The topics of the bag at PATH in order of their first connection, with their types and
/// message counts (is_imu for sensor_msgs/Imu). Throws InputError for a malformed bag.
std::vector<LogTopic> list_rosbag1_topics(const std::string& path);

/// The sensor_msgs/Imu messages of OPTIONS.topic (or of the bag's only sensor_msgs/Imu topic)
/// as a Recording in SI: angular_velocity → gyro_x … gyro_z [rad/s], linear_acceleration →
/// accel_x … accel_z [m/s²], stamps from header.stamp or, with TimeSource::kLog, from the
/// record time of each message. A wrong or ambiguous topic is an InputError listing the topics
/// (select_imu_topic).
pipeline::Recording read_rosbag1_imu(const std::string& path, const LogReadOptions& options);

}  // namespace imunoise::io
