/// @file
/// @brief Reader of rosbag2 bags in the sqlite3 storage (the .db3 files of `ros2 bag record`
/// before Iron made MCAP the default), through libsqlite3: the topics with their types and
/// message counts, and a sensor_msgs/msg/Imu topic (CDR, io/ros_imu_message.h) into a Recording.
///
/// The layout is rosbag2_storage_sqlite3's (every version from Eloquent to Jazzy): a table
/// topics(id, name, type, serialization_format, …) and a table messages(id, topic_id,
/// timestamp, data), timestamp the receive time [ns], data the serialized message. Messages are
/// taken in the order of their row id (the order the recorder inserted them). The file is
/// opened read-only. A file that is not such a database, a corrupt one, or a message that does
/// not decode is an InputError naming the file and, for a message, its row id in the table
/// messages (a database has no byte offsets that mean anything to the user).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "io/log_topics.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// The 16 bytes every SQLite 3 database starts with.
inline constexpr std::string_view kSqliteMagic{"SQLite format 3\0", 16};

/// True when the file at PATH starts with kSqliteMagic.
bool is_sqlite_file(const std::string& path);

/// The topics of the rosbag2 database at PATH in order of their id, with types and message
/// counts (is_imu for sensor_msgs/msg/Imu in cdr). Throws InputError for a file that is not
/// one.
std::vector<LogTopic> list_rosbag2_sqlite_topics(const std::string& path);

/// The Imu messages of OPTIONS.topic (or of the database's only Imu topic) as a Recording in
/// SI, stamps from header.stamp or, with TimeSource::kLog, the timestamp column. A wrong or
/// ambiguous topic is an InputError listing the topics (select_imu_topic).
pipeline::Recording read_rosbag2_sqlite_imu(const std::string& path, const LogReadOptions& options);

}  // namespace imunoise::io
