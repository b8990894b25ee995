#include "tools/verbosity.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "common/number_text.h"

namespace imunoise::tools {

void add_verbosity_options(CLI::App& cmd, Verbosity& verbosity) {
  const std::string group = "Messages";
  CLI::Option* quiet =
      cmd.add_flag("-q,--quiet", verbosity.quiet,
                   "no progress bar and no informational messages on stderr (results, "
                   "warnings and errors still appear)")
          ->group(group);
  CLI::Option* verbose = cmd.add_flag("-v,--verbose", verbosity.verbose,
                                      "extra detail on stderr (e.g. the wall time of each stage)")
                             ->group(group);
  quiet->excludes(verbose);
}

bool progress_wanted(const Verbosity& verbosity) {
  return !verbosity.quiet && ::isatty(STDERR_FILENO) == 1;
}

void print_info(const Verbosity& verbosity, std::string_view command, std::string_view line) {
  if (verbosity.quiet) return;
  std::cerr << "imunoise " << command << ": " << line << "\n";
}

void print_detail(const Verbosity& verbosity, std::string_view command, std::string_view line) {
  if (!verbosity.verbose) return;
  std::cerr << "imunoise " << command << ": " << line << "\n";
}

StageTimes::StageTimes() : start_(std::chrono::steady_clock::now()), last_mark_(start_) {}

void StageTimes::add(std::string_view stage, double seconds) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [name, total] : stages_) {
    if (name == stage) {
      total += seconds;
      return;
    }
  }
  stages_.emplace_back(std::string(stage), seconds);
}

void StageTimes::mark(std::string_view stage) {
  const auto now = std::chrono::steady_clock::now();
  double seconds = 0.0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    seconds = std::chrono::duration<double>(now - last_mark_).count();
    last_mark_ = now;
  }
  add(stage, seconds);
}

double StageTimes::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string StageTimes::text() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string out;
  for (const auto& [name, seconds] : stages_) {
    if (!out.empty()) out.append(", ");
    out.append(name).append(" ").append(significant_number_text(seconds, 3)).append(" s");
  }
  return out;
}

void print_timings(const Verbosity& verbosity, std::string_view command, const StageTimes& times) {
  const std::string stages = times.text();
  if (stages.empty()) return;
  print_detail(verbosity, command,
               std::string("wall time: ")
                   .append(stages)
                   .append(" (total ")
                   .append(significant_number_text(times.elapsed_s(), 3))
                   .append(" s)"));
}

}  // namespace imunoise::tools
