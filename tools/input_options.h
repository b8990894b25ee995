/// @file
/// @brief The recording-input flags shared by every subcommand that reads a recording
/// (--config, --time-col, --rate, --gyro-cols, …) and their merge with a YAML input config.
#pragma once

#include <string>

#include "io/input_config.h"

namespace CLI {
class App;
}

namespace imunoise::tools {

/// Adds the input flags to `cmd`. Parsed values land in `config` (only flags given are set)
/// and the --config path in `config_path`; both must outlive the parse.
/// Full-scale flags are in deg/s and g (datasheet units) and stored in SI.
void add_input_options(CLI::App& cmd, io::InputConfig& config, std::string& config_path);

/// The YAML config at `config_path` (none if empty) overridden by the flags.
io::InputConfig resolve_input_config(const io::InputConfig& flags, const std::string& config_path);

}  // namespace imunoise::tools
