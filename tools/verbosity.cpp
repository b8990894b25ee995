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

void print_timings(const Verbosity& verbosity, std::string_view command,
                   const io::StageTimes& times) {
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
