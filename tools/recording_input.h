/// @file
/// @brief Reading the recording a subcommand analyses: a CSV/TXT table (io/csv_reader.h), an
/// LCM log written by lcm-logger (io/lcm_log.h) or an imunoise binary recording
/// (io/binary_recording.h), told apart by the log's sync word and the binary magic, with the
/// LCM flags (--channel, --lcm-type, --lcm-struct).
#pragma once

#include <string>

#include "common/progress.h"
#include "io/input_config.h"
#include "pipeline/recording.h"

namespace CLI {
class App;
}

namespace imunoise::tools {

/// The LCM-log flags as given.
struct LcmInputFlags {
  std::string channel;      ///< --channel: the IMU channel of the log
  std::string type_path;    ///< --lcm-type: the user's own .lcm definition of the IMU message
  std::string struct_name;  ///< --lcm-struct: which struct of that file (default: the only one)
};

/// Adds --channel, --lcm-type and --lcm-struct to `cmd` (values land in `flags`).
void add_lcm_input_options(CLI::App& cmd, LcmInputFlags& flags);

/// True when `path` starts with the LCM event-log sync word (0xEDA1DA01).
bool is_lcm_log_file(const std::string& path);

/// The recording at `path`: an imunoise binary recording (any table or LCM flag is an
/// InputError naming the flag: the header carries rate and units; --drop-non-finite changes
/// nothing, binary files hold finite values only), an LCM log (channel from --channel; without it,
/// the log's only imunoise.imu_sample_t channel, else an error listing the channels) or a CSV/TXT
/// table read with `config`. LCM flags on a table are an InputError, as are table-only flags
/// (--rate, --delimiter, ...) on a log; with --lcm-type, the column/unit flags map the user's
/// fields. PROGRESS (optional) follows the bytes read of a table (io::read_recording), which
/// parses on THREADS threads (0 = all cores; --threads).
pipeline::Recording read_input_recording(const std::string& path, const io::InputConfig& config,
                                         const LcmInputFlags& lcm,
                                         const ProgressCallback& progress = {},
                                         unsigned threads = 0);

}  // namespace imunoise::tools
