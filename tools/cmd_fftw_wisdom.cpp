/// @file
/// @brief `imunoise fftw-wisdom`: measures FFTW r2c plans for the PSD segment lengths that
/// `analyze` will use and saves them as FFTW wisdom, so that `analyze --fftw-wisdom FILE` (or
/// IMUNOISE_FFTW_WISDOM=FILE) runs its PSD transforms with a measured plan without measuring.
/// Prints, per length, the planning time and the time of one transform with the wisdom plan
/// and with the FFTW_ESTIMATE plan analyze uses otherwise.
#include <CLI/CLI.hpp>
#include <climits>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/multirate_psd.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/duration_parser.h"
#include "io/fftw_wisdom.h"
#include "io/fftw_wisdom_planning.h"
#include "tools/commands.h"
#include "tools/verbosity.h"

namespace imunoise::tools {
namespace {

struct WisdomArgs {
  std::vector<std::size_t> samples;
  std::vector<std::size_t> lengths;
  std::string effort = "measure";
  std::string time_limit;  // empty = no limit
  std::string output;
  bool merge = false;
  Verbosity verbosity;
};

void run_fftw_wisdom(const WisdomArgs& args) {
  if (args.samples.empty() && args.lengths.empty()) {
    throw InputError(
        "fftw-wisdom: give the record lengths (--samples N) or the segment "
        "lengths (--length L) to plan for");
  }
  const io::PlannerEffort effort =
      args.effort == "patient" ? io::PlannerEffort::kPatient : io::PlannerEffort::kMeasure;
  const double time_limit_s =
      args.time_limit.empty() ? 0.0 : io::parse_duration_s(args.time_limit, "--time-limit");

  // Each length once, with the first record length that asked for it.
  std::map<std::size_t, std::string> lengths;
  for (std::size_t n : args.samples) {
    if (n < 16) {
      throw InputError("--samples: " + std::to_string(n) +
                       " samples is too short for a Welch PSD (at least 16)");
    }
    // The one FFT length analyze's multi-rate PSD uses for a record of n samples.
    lengths.emplace(analysis::multirate_plan(n).segment_length,
                    "the PSD length for " + std::to_string(n) + " samples");
  }
  for (std::size_t l : args.lengths) {
    if (l < 2 || l > static_cast<std::size_t>(INT_MAX)) {
      throw InputError("--length: " + std::to_string(l) + " is not a segment length (2 to " +
                       std::to_string(INT_MAX) + ")");
    }
    lengths.emplace(l, "--length");
  }

  // Fail in a second, not after minutes of planning, when FILE cannot be written.
  { const io::AtomicOutputFile probe(args.output); }
  if (args.merge) {
    if (std::filesystem::exists(args.output)) {
      io::import_fftw_wisdom(args.output);
      print_info(args.verbosity, "fftw-wisdom", "merging with the wisdom in " + args.output);
    } else {
      print_info(args.verbosity, "fftw-wisdom",
                 args.output + " does not exist yet: nothing to merge");
    }
  }

  std::size_t unusable = 0;
  for (const auto& [length, origin] : lengths) {
    print_detail(args.verbosity, "fftw-wisdom",
                 "planning L = " + std::to_string(length) + " (" + args.effort + ")…");
    const io::LengthPlanResult r = io::plan_fft_length(length, effort, time_limit_s);
    std::ostringstream line;
    line << "L = " << length << " (" << origin << "): ";
    if (r.already_known) {
      line << "already in the merged wisdom";
    } else {
      line << args.effort << " planning " << duration_text(r.planning_s);
    }
    line << "; one transform " << duration_text(r.wisdom_s) << " with the wisdom plan vs "
         << duration_text(r.estimate_s) << " with FFTW_ESTIMATE (" << std::fixed
         << std::setprecision(2) << r.estimate_s / r.wisdom_s << "x)";
    std::cout << line.str() << std::endl;
    if (!r.usable) {
      ++unusable;
      std::cerr << "imunoise fftw-wisdom: warning: L = " << length
                << (time_limit_s > 0.0
                        ? ": planning stopped at the --time-limit, and FFTW keeps no reusable "
                          "wisdom from an interrupted search"
                        : ": FFTW kept no reusable wisdom for this length")
                << "; analyze will use FFTW_ESTIMATE for it"
                << (time_limit_s > 0.0 ? " (raise or drop --time-limit)\n" : "\n");
    }
  }
  io::export_fftw_wisdom(args.output);
  std::cout << "wrote " << args.output;
  if (unusable > 0) std::cout << " (" << unusable << " length(s) without usable wisdom)";
  std::cout << "; use it with 'imunoise analyze REC --fftw-wisdom " << args.output
            << "' or IMUNOISE_FFTW_WISDOM=" << args.output << "\n";
}

}  // namespace

void register_fftw_wisdom_command(CLI::App& app) {
  auto args = std::make_shared<WisdomArgs>();
  CLI::App* cmd = app.add_subcommand(
      "fftw-wisdom",
      "Measure FFTW plans for the PSD segment lengths of 'analyze' and save them as FFTW "
      "wisdom (FILE), so that 'analyze --fftw-wisdom FILE' uses a measured plan without "
      "measuring; prints the planning time and the transform time with and without it");
  cmd->add_option("--samples", args->samples,
                  "record lengths [samples] to plan for (repeat or N1,N2,...): each gives the "
                  "FFT length of analyze's PSD (the largest power of two <= N/8, at least 16, "
                  "capped at 4096: longer records are decimated, not transformed longer)")
      ->delimiter(',');
  cmd->add_option("--length", args->lengths, "explicit segment lengths L (repeat or L1,L2,...)")
      ->delimiter(',');
  cmd->add_option("--effort", args->effort,
                  "planner rigour: measure (default) or patient (slower to plan, sometimes a "
                  "faster plan)")
      ->check(CLI::IsMember({"measure", "patient"}));
  cmd->add_option("--time-limit", args->time_limit,
                  "stop FFTW's search for one length after this long (600, 10min; default: no "
                  "limit); a length cut short keeps no reusable wisdom (a warning says so)");
  cmd->add_option("-o,--output", args->output, "wisdom file to write (atomically)")->required();
  cmd->add_flag("--merge", args->merge,
                "import FILE first, if it exists, and keep its wisdom (lengths already in it are "
                "not measured again)");
  add_verbosity_options(*cmd, args->verbosity);
  cmd->footer(
      "Examples:\n"
      "  imunoise fftw-wisdom --samples 86400000 -o imu.wisdom    # 24 h at 1 kHz: L = 2^23, ~5 "
      "min\n"
      "  imunoise fftw-wisdom --length 1048576,4096 --merge -o imu.wisdom\n"
      "  imunoise analyze rec.imnb -o out --fftw-wisdom imu.wisdom\n"
      "  IMUNOISE_FFTW_WISDOM=imu.wisdom imunoise analyze rec.imnb -o out\n"
      "Wisdom holds for this machine and this FFTW build only; analyze plans from it without\n"
      "measuring, and falls back to FFTW_ESTIMATE for a length it does not cover.");
  cmd->callback([args] {
    io::StageTimes times;
    run_fftw_wisdom(*args);
    times.mark("plan, time and write");
    print_timings(args->verbosity, "fftw-wisdom", times);
  });
}

}  // namespace imunoise::tools
