/// @file
/// @brief `-q,--quiet` and `-v,--verbose`, shared by every subcommand: quiet = no progress bar
/// and no informational stderr lines (results still go to stdout and files; warnings and
/// errors still go to stderr); verbose = extra detail on stderr, such as the wall time of each
/// stage. Stdout never changes with either flag.
#pragma once

#include <chrono>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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

/// Wall seconds per named stage, in the order first seen. Thread-safe (add() may come from
/// worker threads; the lock is held only to add a number).
class StageTimes {
 public:
  StageTimes();
  /// Adds `seconds` to `stage`.
  void add(std::string_view stage, double seconds);
  /// Adds the wall time since the previous mark (or construction) to `stage`.
  void mark(std::string_view stage);
  /// Seconds since construction.
  double elapsed_s() const;
  /// "read 0.52 s, deviations 3.1 s" (empty when nothing was added).
  std::string text() const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::pair<std::string, double>> stages_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_mark_;
};

/// With --verbose: "imunoise COMMAND: wall time: read 0.5 s, … (total 4.6 s)".
void print_timings(const Verbosity& verbosity, std::string_view command, const StageTimes& times);

}  // namespace imunoise::tools
