/// @file
/// @brief Reading a recording whatever its format: a CSV/TXT table (io/csv_reader.h), an LCM
/// log written by lcm-logger (io/lcm_log.h), an imunoise binary recording
/// (io/binary_recording.h) or a robotics log — a ROS 1 bag (io/rosbag1_reader.h), an MCAP file
/// (io/mcap_reader.h), a rosbag2 .db3 (io/rosbag2_sqlite_reader.h), a PX4 ULog
/// (io/ulog_reader.h) — told apart by content (the log's sync word, the binary magic, the bag's
/// first line, the MCAP magic, the SQLite header, the ULog magic) or, for an output, by the file
/// name. Which settings apply to which
/// format is the caller's to check (the CLI refuses the flags that do not apply, naming them).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/progress_callback.h"
#include "io/input_config.h"
#include "io/lcm_user_imu_decoder.h"
#include "io/log_topics.h"
#include "pipeline/recording.h"

namespace imunoise::io {

/// The recording formats: imunoise's own three, and the robotics logs it reads.
enum class RecordingFormat {
  kTable,          ///< CSV/TXT
  kLcmLog,         ///< lcm-logger event log
  kBinary,         ///< imunoise binary recording (.imnb)
  kRosbag1,        ///< ROS 1 bag (format 2.0)
  kMcap,           ///< MCAP (ROS 2's default bag storage)
  kRosbag2Sqlite,  ///< rosbag2 sqlite3 storage (.db3)
  kUlog,           ///< PX4 ULog (.ulg)
};

/// "CSV", "LCM log", "binary", "ROS 1 bag", "MCAP file", "rosbag2 .db3", "ULog file".
std::string_view recording_format_name(RecordingFormat format);

/// True for the robotics logs (ROS bags, ...), whose topics --topic selects.
bool is_robotics_log(RecordingFormat format);

/// True when PATH starts with the LCM event-log sync word (0xEDA1DA01).
bool is_lcm_log_file(const std::string& path);

/// The format of the file at PATH by its first bytes: kBinary when it starts with
/// kBinaryMagic, kLcmLog with the LCM sync word, kRosbag1 with "#ROSBAG V" (any version: the
/// reader names the one it does not read), kMcap with the MCAP magic, kRosbag2Sqlite with the
/// SQLite header, kUlog with the ULog magic, else kTable.
RecordingFormat detect_recording_format(const std::string& path);

/// The format a file name asks for: kBinary for .imnb, kTable for .csv/.txt, kLcmLog for
/// .lcm/.log/.lcmlog; nullopt for any other name.
std::optional<RecordingFormat> recording_format_of_file_name(std::string_view path);

/// A user's IMU message type (io/lcm_user_imu_decoder.h) mapped by the column and unit fields
/// of CONFIG: the stamp in time_column (default "utime") in time_unit (default µs), the gyro
/// and accelerometer fields in gyro_columns / accel_columns in gyro_unit / accel_unit (default
/// rad/s and m/s²), from the struct STRUCT_NAME (empty: the only one) of DEFINITION_PATH.
/// Contract (the caller checks it with its own message): both column lists are given, and
/// both units are rates or both increments; ContractViolation otherwise.
LcmUserType lcm_user_type(const std::string& definition_path, const std::string& struct_name,
                          const InputConfig& config);

/// Where the IMU samples of an LCM log are.
struct LcmImuSource {
  std::string channel;                   ///< the channel to read (not empty)
  std::optional<LcmUserType> user_type;  ///< the user's own type, else imunoise.imu_sample_t
};

/// The recording at PATH, read as FORMAT (detect_recording_format): a robotics log's only IMU
/// topic (read_robotics_log_as with default options but CONFIG.drop_non_finite); a binary
/// recording with
/// CONFIG's full-scale values; an LCM log on LCM.channel (NaN/Inf dropped with
/// CONFIG.drop_non_finite; with a user type, the channels' source units named as CONFIG spells
/// them, e.g. "deg/s"); or a table read with CONFIG (io::read_recording). PROGRESS (optional)
/// follows the bytes read of a table or a binary recording; THREADS parse or read them (0 =
/// all cores; the result does not depend on it). Throws as the reader of FORMAT.
pipeline::Recording read_recording_as(RecordingFormat format, const std::string& path,
                                      const InputConfig& config, const LcmImuSource& lcm,
                                      const ProgressCallback& progress = {}, unsigned threads = 0);

/// The topics of the robotics log at PATH (FORMAT: is_robotics_log), with types and counts.
std::vector<LogTopic> list_log_topics(RecordingFormat format, const std::string& path);

/// The IMU topic of the robotics log at PATH (FORMAT: is_robotics_log) chosen by OPTIONS, as a
/// Recording (read_rosbag1_imu, ...). Throws as that reader.
pipeline::Recording read_robotics_log_as(RecordingFormat format, const std::string& path,
                                         const LogReadOptions& options);

}  // namespace imunoise::io
