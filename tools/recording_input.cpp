#include "tools/recording_input.h"

#include <CLI/CLI.hpp>
#include <vector>

#include "common/errors.h"
#include "io/lcm_fingerprint.h"
#include "io/lcm_log.h"
#include "io/lcm_user_imu_decoder.h"
#include "io/recording_input.h"

namespace imunoise::tools {

namespace {

/// With --lcm-type and no --channel: the log's only channel carrying that type.
std::string channel_of_type(const std::string& path, const io::LcmUserImuDecoder& decoder) {
  std::vector<std::string> found;
  for (const io::LcmLogChannel& c : io::list_lcm_log_channels(path)) {
    if (c.fingerprint == decoder.fingerprint()) found.push_back(c.name);
  }
  if (found.size() == 1) return found.front();
  throw InputError(located_message(
      path, 0, 0,
      (found.empty() ? "no channel" : std::to_string(found.size()) + " channels") +
          std::string(" of type ") + decoder.type_name() + " (fingerprint " +
          io::lcm_fingerprint_text(decoder.fingerprint()) + ") in this LCM log; give --channel"));
}

/// The user's IMU type from --lcm-type/--lcm-struct, its fields named by the column flags
/// (--time-col default utime in µs, --gyro-cols and --accel-cols required) in the units of
/// --time-unit, --gyro-unit and --accel-unit.
io::LcmUserType user_type_of(const LogInputFlags& lcm, const io::InputConfig& config) {
  if (config.gyro_columns.empty() || config.accel_columns.empty()) {
    throw InputError("--lcm-type " + lcm.type_path +
                     ": name the fields with --gyro-cols and --accel-cols (one 3-element array "
                     "each, e.g. --gyro-cols gyro, or three fields, e.g. --gyro-cols gx,gy,gz)");
  }
  const io::GyroUnit gyro = config.gyro_unit.value_or(io::GyroUnit::kRadPerS);
  const io::AccelUnit accel = config.accel_unit.value_or(io::AccelUnit::kMPerS2);
  if (io::is_increment(gyro) != io::is_increment(accel)) {
    throw InputError("--gyro-unit " + std::string(io::to_string(gyro)) + " and --accel-unit " +
                     std::string(io::to_string(accel)) +
                     ": a message type holds either rates or increments for both sensors");
  }
  return io::lcm_user_type(lcm.type_path, lcm.struct_name, config);
}

/// The CSV/TXT-only flags given in CONFIG, in the order they are checked: --delimiter, --rate,
/// extra_columns, then (with COLUMN_FLAGS) the column and unit flags.
std::vector<const char*> table_flags_given(const io::InputConfig& config, bool column_flags) {
  std::vector<const char*> given;
  const auto check = [&](bool is_given, const char* flag) {
    if (is_given) given.push_back(flag);
  };
  check(config.delimiter.has_value(), "--delimiter");
  check(config.rate_hz.has_value(), "--rate");
  check(!config.extra_columns.empty(), "extra_columns");
  if (column_flags) {
    check(!config.time_column.empty(), "--time-col");
    check(config.time_unit.has_value(), "--time-unit");
    check(!config.gyro_columns.empty(), "--gyro-cols");
    check(config.gyro_unit.has_value(), "--gyro-unit");
    check(!config.accel_columns.empty(), "--accel-cols");
    check(config.accel_unit.has_value(), "--accel-unit");
  }
  return given;
}

/// Table-only flags that mean nothing for an LCM log of imu_sample_t (with --lcm-type, the
/// column and unit flags name the user's fields and are allowed).
void reject_table_flags(const std::string& path, const io::InputConfig& config, bool user_type) {
  const std::vector<const char*> given = table_flags_given(config, !user_type);
  if (given.empty()) return;
  throw InputError(path + ": " + given.front() +
                   " applies to CSV/TXT tables; this file is an LCM log" +
                   (user_type ? "" : " (imu_sample_t fields are SI by definition)"));
}

/// The LCM flags given, in the order they are checked.
std::vector<const char*> lcm_flags_given(const LogInputFlags& flags) {
  std::vector<const char*> given;
  if (!flags.channel.empty()) given.push_back("--channel");
  if (!flags.type_path.empty()) given.push_back("--lcm-type");
  if (!flags.struct_name.empty()) given.push_back("--lcm-struct");
  return given;
}

/// The robotics-log flags given, in the order they are checked.
std::vector<const char*> robotics_flags_given(const LogInputFlags& flags) {
  std::vector<const char*> given;
  if (!flags.topic.empty()) given.push_back("--topic");
  if (flags.instance) given.push_back("--instance");
  if (!flags.time_source.empty()) given.push_back("--time-source");
  return given;
}

/// Robotics-log flags on another format: an InputError naming the first.
void reject_robotics_flags(const std::string& path, const LogInputFlags& flags,
                           io::RecordingFormat format) {
  const std::vector<const char*> given = robotics_flags_given(flags);
  if (given.empty()) return;
  throw InputError(path + ": " + given.front() +
                   " applies to robotics logs (ROS bags, MCAP, rosbag2, ULog); this file is read "
                   "as " +
                   std::string(io::recording_format_name(format)));
}

/// Table and LCM flags mean nothing for a binary recording, whose header carries rate and units.
void reject_flags_for_binary(const std::string& path, const io::InputConfig& config,
                             const LogInputFlags& lcm) {
  std::vector<const char*> given = lcm_flags_given(lcm);
  for (const char* flag : table_flags_given(config, true)) given.push_back(flag);
  if (given.empty()) return;
  throw InputError(path + ": " + given.front() +
                   " does not apply to an imunoise binary recording (the binary header carries "
                   "rate and units)");
}

/// The robotics-log read of PATH (FORMAT) with FLAGS: table and LCM flags are refused.
pipeline::Recording read_robotics_log(const std::string& path, io::RecordingFormat format,
                                      const io::InputConfig& config, const LogInputFlags& flags) {
  std::vector<const char*> given = lcm_flags_given(flags);
  for (const char* flag : table_flags_given(config, true)) given.push_back(flag);
  if (!given.empty()) {
    throw InputError(path + ": " + given.front() + " does not apply to this " +
                     std::string(io::recording_format_name(format)) +
                     " (its messages carry stamps and SI units; choose the topic with --topic)");
  }
  io::LogReadOptions options;
  options.topic = flags.topic;
  options.instance = flags.instance;
  options.drop_non_finite = config.drop_non_finite.value_or(false);
  if (!flags.time_source.empty()) {
    const auto source = io::parse_time_source(flags.time_source);
    if (!source) {
      throw InputError("--time-source '" + flags.time_source + "': expected header or log");
    }
    options.time_source = *source;
  }
  return io::read_robotics_log_as(format, path, options);
}

}  // namespace

void add_log_input_options(CLI::App& cmd, LogInputFlags& flags) {
  const std::string group = "LCM log input (files written by lcm-logger)";
  cmd.add_option("--channel", flags.channel,
                 "IMU channel of an LCM log (default: the log's only imunoise.imu_sample_t "
                 "channel)")
      ->group(group);
  cmd.add_option("--lcm-type", flags.type_path,
                 "your own IMU message type: its .lcm definition; --time-col, --gyro-cols, "
                 "--accel-cols and their units then name its fields (e.g. --gyro-cols gyro "
                 "--gyro-unit deg/s)")
      ->check(CLI::ExistingFile)
      ->group(group);
  cmd.add_option("--lcm-struct", flags.struct_name,
                 "struct of --lcm-type to use, 'package.name' or 'name' (default: the only one)")
      ->group(group);
  const std::string robotics = "Robotics logs (ROS 1 bags, MCAP, rosbag2 .db3, PX4 ULog)";
  cmd.add_option("--topic", flags.topic,
                 "IMU topic of a robotics log (default: its only sensor_msgs/Imu topic)")
      ->group(robotics);
  cmd.add_option("--instance", flags.instance,
                 "instance (multi_id) of a PX4 ULog topic, e.g. --topic sensor_gyro --instance 1")
      ->group(robotics);
  cmd.add_option("--time-source", flags.time_source,
                 "stamps of a robotics log: header (the message's header.stamp, default) or log "
                 "(when the recorder received it)")
      ->group(robotics);
}

pipeline::Recording read_input_recording(const std::string& path, const io::InputConfig& config,
                                         const LogInputFlags& lcm, const ProgressCallback& progress,
                                         unsigned threads) {
  const io::RecordingFormat format = io::detect_recording_format(path);
  if (io::is_robotics_log(format)) return read_robotics_log(path, format, config, lcm);
  reject_robotics_flags(path, lcm, format);
  io::LcmImuSource source;
  if (format == io::RecordingFormat::kBinary) {
    reject_flags_for_binary(path, config, lcm);
  } else if (format == io::RecordingFormat::kTable) {
    if (!lcm.channel.empty() || !lcm.type_path.empty() || !lcm.struct_name.empty()) {
      throw InputError(path +
                       ": --channel, --lcm-type and --lcm-struct apply to LCM logs; this file "
                       "does not start with the LCM log sync word (read as CSV/TXT without them)");
    }
  } else {
    const bool user_type = !lcm.type_path.empty();
    if (!lcm.struct_name.empty() && !user_type) {
      throw InputError("--lcm-struct needs --lcm-type (the .lcm file that defines the struct)");
    }
    reject_table_flags(path, config, user_type);
    if (user_type) source.user_type = user_type_of(lcm, config);
    source.channel = lcm.channel;
    if (source.channel.empty()) {
      source.channel = source.user_type
                           ? channel_of_type(path, io::LcmUserImuDecoder(*source.user_type))
                           : io::only_imu_sample_channel(
                                 path,
                                 "give --channel NAME (and --lcm-type FILE.lcm for an IMU "
                                 "message type of your own)");
    }
  }
  return io::read_recording_as(format, path, config, source, progress, threads);
}

}  // namespace imunoise::tools
