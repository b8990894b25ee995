/// @file
/// @brief `-q,--quiet` and `-v,--verbose`, shared by every subcommand: quiet = no progress bar
/// and no informational stderr lines (results still go to stdout and files; warnings and
/// errors still go to stderr); verbose = extra detail on stderr, such as the wall time of each
/// stage. Stdout never changes with either flag.
#pragma once

#include <string_view>

#include "io/stage_progress.h"

namespace CLI {
class App;
}

namespace imunoise::tools {

/// The two flags as given (they exclude each other).
struct Verbosity {
  bool quiet = false;
  bool verbose = false;
};

/// Adds -q,--quiet and -v,--verbose to `cmd`; values land in `verbosity` (which must outlive
/// the parse).
void add_verbosity_options(CLI::App& cmd, Verbosity& verbosity);

/// True when a progress bar should be drawn: not --quiet and stderr is a terminal.
bool progress_wanted(const Verbosity& verbosity);

/// "imunoise COMMAND: LINE" on stderr unless --quiet (informational messages).
void print_info(const Verbosity& verbosity, std::string_view command, std::string_view line);

/// "imunoise COMMAND: LINE" on stderr with --verbose only (extra detail).
void print_detail(const Verbosity& verbosity, std::string_view command, std::string_view line);

/// With --verbose: "imunoise COMMAND: wall time: read 0.5 s, … (total 4.6 s)".
void print_timings(const Verbosity& verbosity, std::string_view command,
                   const io::StageTimes& times);

}  // namespace imunoise::tools
