#include "io/recording_input.h"

#include <array>
#include <fstream>

#include "common/errors.h"
#include "common/sensor_kind.h"
#include "io/binary_recording.h"
#include "io/csv_reader.h"
#include "io/lcm_log.h"
#include "io/mcap_reader.h"
#include "io/rosbag1_reader.h"
#include "io/rosbag2_sqlite_reader.h"
#include "io/ulog_reader.h"

namespace imunoise::io {

namespace {

bool ends_with(std::string_view text, std::string_view suffix) {
  return text.size() > suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

}  // namespace

std::string_view recording_format_name(RecordingFormat format) {
  switch (format) {
    case RecordingFormat::kTable:
      return "CSV";
    case RecordingFormat::kBinary:
      return "binary";
    case RecordingFormat::kLcmLog:
      return "LCM log";
    case RecordingFormat::kRosbag1:
      return "ROS 1 bag";
    case RecordingFormat::kMcap:
      return "MCAP file";
    case RecordingFormat::kRosbag2Sqlite:
      return "rosbag2 .db3";
    case RecordingFormat::kUlog:
      return "ULog file";
  }
  return "?";
}

bool is_robotics_log(RecordingFormat format) {
  return format == RecordingFormat::kRosbag1 || format == RecordingFormat::kMcap ||
         format == RecordingFormat::kRosbag2Sqlite || format == RecordingFormat::kUlog;
}

bool is_lcm_log_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 4> head{};
  if (!in.read(reinterpret_cast<char*>(head.data()), 4)) return false;
  return head[0] == 0xED && head[1] == 0xA1 && head[2] == 0xDA && head[3] == 0x01;
}

RecordingFormat detect_recording_format(const std::string& path) {
  if (is_binary_recording_file(path)) return RecordingFormat::kBinary;
  if (is_lcm_log_file(path)) return RecordingFormat::kLcmLog;
  std::ifstream in(path, std::ios::binary);
  std::string head(16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.starts_with("#ROSBAG V")) return RecordingFormat::kRosbag1;
  if (head.starts_with(kMcapMagic)) return RecordingFormat::kMcap;
  if (head.starts_with(kSqliteMagic)) return RecordingFormat::kRosbag2Sqlite;
  if (head.starts_with(kUlogMagic)) return RecordingFormat::kUlog;
  return RecordingFormat::kTable;
}

std::optional<RecordingFormat> recording_format_of_file_name(std::string_view path) {
  if (ends_with(path, kBinaryRecordingExtension)) return RecordingFormat::kBinary;
  if (ends_with(path, ".csv") || ends_with(path, ".txt")) return RecordingFormat::kTable;
  if (ends_with(path, ".lcm") || ends_with(path, ".log") || ends_with(path, ".lcmlog")) {
    return RecordingFormat::kLcmLog;
  }
  return std::nullopt;
}

LcmUserType lcm_user_type(const std::string& definition_path, const std::string& struct_name,
                          const InputConfig& config) {
  const GyroUnit gyro = config.gyro_unit.value_or(GyroUnit::kRadPerS);
  const AccelUnit accel = config.accel_unit.value_or(AccelUnit::kMPerS2);
  IMUNOISE_EXPECT(!config.gyro_columns.empty() && !config.accel_columns.empty(),
                  "lcm_user_type: the gyro and accelerometer fields must be named");
  IMUNOISE_EXPECT(is_increment(gyro) == is_increment(accel),
                  "lcm_user_type: both units must be rates or both increments");
  LcmUserType t;
  t.definition_path = definition_path;
  t.type_name = struct_name;
  if (!config.time_column.empty()) t.time_field = config.time_column;
  t.time_unit_s = config.time_unit ? si_factor(*config.time_unit) : 1e-6;
  t.gyro_fields = config.gyro_columns;
  t.accel_fields = config.accel_columns;
  t.gyro_scale_to_si = si_factor(gyro);
  t.accel_scale_to_si = si_factor(accel);
  t.increments = is_increment(gyro);
  return t;
}

pipeline::Recording read_recording_as(RecordingFormat format, const std::string& path,
                                      const InputConfig& config, const LcmImuSource& lcm,
                                      const ProgressCallback& progress, unsigned threads) {
  switch (format) {
    case RecordingFormat::kBinary: {
      BinaryReadOptions options;
      options.gyro_full_scale_rad_per_s = config.gyro_full_scale_rad_per_s;
      options.accel_full_scale_m_per_s2 = config.accel_full_scale_m_per_s2;
      options.threads = threads;
      return read_binary_recording(path, options, progress);
    }
    case RecordingFormat::kTable:
      return read_recording(path, config, progress, threads);
    case RecordingFormat::kRosbag1:
    case RecordingFormat::kMcap:
    case RecordingFormat::kRosbag2Sqlite:
    case RecordingFormat::kUlog: {
      LogReadOptions options;
      options.drop_non_finite = config.drop_non_finite.value_or(false);
      return read_robotics_log_as(format, path, options);
    }
    case RecordingFormat::kLcmLog:
      break;
  }
  LcmReadOptions options;
  options.drop_non_finite = config.drop_non_finite.value_or(false);
  options.user_type = lcm.user_type;
  pipeline::Recording recording = read_lcm_imu_log(path, lcm.channel, options);
  if (options.user_type) {
    // Name the source units as the user wrote them ("deg/s", not a factor).
    const std::string gyro(to_string(config.gyro_unit.value_or(GyroUnit::kRadPerS)));
    const std::string accel(to_string(config.accel_unit.value_or(AccelUnit::kMPerS2)));
    for (pipeline::Channel& c : recording.channels) {
      if (c.kind == SensorKind::gyro) c.source_unit = gyro;
      if (c.kind == SensorKind::accel) c.source_unit = accel;
    }
  }
  return recording;
}

std::vector<LogTopic> list_log_topics(RecordingFormat format, const std::string& path) {
  IMUNOISE_EXPECT(is_robotics_log(format), "list_log_topics: not a robotics log format");
  if (format == RecordingFormat::kMcap) return list_mcap_topics(path);
  if (format == RecordingFormat::kRosbag2Sqlite) return list_rosbag2_sqlite_topics(path);
  if (format == RecordingFormat::kUlog) return list_ulog_topics(path);
  return list_rosbag1_topics(path);
}

pipeline::Recording read_robotics_log_as(RecordingFormat format, const std::string& path,
                                         const LogReadOptions& options) {
  IMUNOISE_EXPECT(is_robotics_log(format), "read_robotics_log_as: not a robotics log format");
  if (format == RecordingFormat::kMcap) return read_mcap_imu(path, options);
  if (format == RecordingFormat::kRosbag2Sqlite) return read_rosbag2_sqlite_imu(path, options);
  if (format == RecordingFormat::kUlog) return read_ulog_imu(path, options);
  return read_rosbag1_imu(path, options);
}

}  // namespace imunoise::io
