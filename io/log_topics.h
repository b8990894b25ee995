/// @file
/// @brief What the readers of robotics logs share (ROS 1 bags, MCAP, rosbag2 .db3, PX4 ULog):
/// the options of a read (which topic, which instance, which time stamps), the listing of a
/// file's topics with their types and message counts, the choice of the IMU topic with the one
/// error that lists them, and the collection of decoded messages into a Recording.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/ros_imu_message.h"
#include "pipeline/imu_samples.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// Which stamp a sample gets.
enum class TimeSource {
  kHeader,  ///< the message's own stamp: ROS header.stamp, ULog timestamp_sample / timestamp
  kLog,     ///< when the recorder received it: the bag record time, MCAP log_time, .db3 timestamp
};

/// "header", "log".
std::string_view time_source_name(TimeSource source);
/// The TimeSource called TEXT ("header" or "log"), or none.
std::optional<TimeSource> parse_time_source(std::string_view text);

/// Options of the readers of robotics logs.
struct LogReadOptions {
  std::string topic;            ///< the topic to read; empty: the file's only IMU topic
  std::optional<int> instance;  ///< ULog multi-instance: which one; none: the only one
  TimeSource time_source = TimeSource::kHeader;
  /// false: a NaN/Inf value is an InputError; true: the message is dropped and counted.
  bool drop_non_finite = false;
};

/// One topic of a log.
struct LogTopic {
  std::string name;  ///< "/imu/data", or the ULog message name "sensor_combined"
  std::string type;  ///< "sensor_msgs/Imu", "sensor_msgs/msg/Imu", ULog format name
  std::int64_t message_count = 0;
  std::optional<int> instance;  ///< the ULog multi_id
  bool is_imu = false;          ///< a type this reader decodes into the six channels
};

/// "the bag holds '/imu' (sensor_msgs/Imu, 400 messages), '/tf' (tf2_msgs/TFMessage, 12
/// messages)"; FILE_KIND is "bag", "MCAP file", … .
std::string describe_log_topics(const std::vector<LogTopic>& topics, std::string_view file_kind);

/// The topic of TOPICS to read: the one named OPTIONS.topic (and of OPTIONS.instance when
/// given), or, without a name, the only one with is_imu and messages. Throws InputError "PATH:
/// problem; give
/// --topic NAME; <describe_log_topics>" when the name is not found, names a topic of another
/// type or without messages, or when no name is given and the IMU topics are not exactly one.
const LogTopic& select_imu_topic(const std::string& path, const std::vector<LogTopic>& topics,
                                 const LogReadOptions& options, std::string_view file_kind);

/// The decoded messages of one topic gathered into columns, then into a Recording.
class ImuSampleCollector {
 public:
  /// FIELDS and UNITS name each column's source (ros_imu_fields(), "rad/s", "m/s^2").
  ImuSampleCollector(const LogReadOptions& options, const std::array<std::string, 6>& fields,
                     const std::array<std::string, 6>& units);

  /// Appends MESSAGE with the stamp the options ask for (its own or LOG_TIME_NS). Returns the
  /// field name of its first NaN/Inf value when it has one and such messages are not dropped
  /// (the caller then throws, naming where); else nullptr (a non-finite message is counted and
  /// dropped).
  const std::string* add(const ImuMessage& message, std::int64_t log_time_ns);

  std::size_t size() const { return columns_.size(); }
  /// Room for COUNT samples (the count a file's index states), so that the columns do not grow
  /// past it; at most FILE_BYTES / 16, since that count is the file's word, unchecked, and no
  /// IMU message, even compressed, takes fewer bytes.
  void reserve(std::int64_t count, std::uint64_t file_bytes);

  /// The Recording of the samples (pipeline::recording_from_stamped_samples), the source of
  /// each channel "TOPIC.FIELD". Throws InputError for fewer than two samples or stamps that
  /// never increase.
  pipeline::Recording finish(const std::string& path, const std::string& topic);

 private:
  pipeline::StampedImuColumns columns_;
  TimeSource time_source_;
  bool drop_non_finite_;
};

/// The unit names of the six channels as ROS and PX4 state them: "rad/s" ×3, "m/s^2" ×3.
const std::array<std::string, 6>& si_imu_units();

}  // namespace imunoise::io
