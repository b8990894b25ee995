/// @file
/// @brief The flags of the recording a subcommand analyses: the LCM flags (--channel,
/// --lcm-type, --lcm-struct), the robotics-log flags (--topic, --instance, --time-source), their
/// checks against the format io/recording_input.h finds by content (a CSV/TXT table, an LCM
/// log, an imunoise binary recording, a ROS bag), and the read.
#pragma once

#include <optional>
#include <string>

#include "common/progress_callback.h"
#include "io/input_config.h"
#include "pipeline/recording.h"

namespace CLI {
class App;
}

namespace imunoise::tools {

/// The flags of message logs (LCM logs and robotics logs) as given.
struct LogInputFlags {
  std::string channel;      ///< --channel: the IMU channel of an LCM log
  std::string type_path;    ///< --lcm-type: the user's own .lcm definition of the IMU message
  std::string struct_name;  ///< --lcm-struct: which struct of that file (default: the only one)
  std::string topic;        ///< --topic: the IMU topic of a robotics log (default: the only one)
  std::optional<int> instance;  ///< --instance: the multi-instance of a ULog topic
  std::string time_source;      ///< --time-source header|log (empty: header)
};

/// Adds --channel, --lcm-type, --lcm-struct, --topic, --instance and --time-source to `cmd`
/// (values land in `flags`).
void add_log_input_options(CLI::App& cmd, LogInputFlags& flags);

/// The recording at `path`: a robotics log (its topic from --topic, else its only IMU topic;
/// table and LCM flags are an InputError naming the flag), an imunoise binary recording (any
/// table, LCM or robotics-log flag is an
/// InputError naming the flag: the header carries rate and units; --drop-non-finite changes
/// nothing, binary files hold finite values only), an LCM log (channel from --channel; without it,
/// the log's only imunoise.imu_sample_t channel, else an error listing the channels) or a CSV/TXT
/// table read with `config`. LCM flags on a table are an InputError, as are table-only flags
/// (--rate, --delimiter, ...) on a log; with --lcm-type, the column/unit flags map the user's
/// fields. PROGRESS (optional) follows the bytes read of a table (io::read_recording), which
/// parses on THREADS threads (0 = all cores; --threads).
pipeline::Recording read_input_recording(const std::string& path, const io::InputConfig& config,
                                         const LogInputFlags& flags,
                                         const ProgressCallback& progress = {},
                                         unsigned threads = 0);

}  // namespace imunoise::tools
