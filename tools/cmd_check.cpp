/// @file
/// @brief `imunoise check`: reads a recording and prints its sampling report (rate, gaps,
/// time-stamp order and jitter, saturation and quantization step per channel).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "io/csv_reader.h"
#include "io/sampling_report.h"
#include "io/terminal_progress_bar.h"
#include "tools/commands.h"
#include "tools/input_options.h"
#include "tools/recording_input.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

struct CheckArgs {
  std::string file;
  LogInputFlags log;
  io::InputConfig flags;
  std::string config_path;
  bool json = false;
  Verbosity verbosity;
};

void run_check(const CheckArgs& args) {
  const io::InputConfig config = resolve_input_config(args.flags, args.config_path);
  io::StageTimes times;
  io::ProgressBar bar("check", progress_wanted(args.verbosity));
  const pipeline::Recording recording =
      read_input_recording(args.file, config, args.log, bar.callback());
  bar.finish();
  times.mark("read");
  if (args.json) {
    std::cout << io::sampling_report_to_json(recording.report, args.file).dump(2) << "\n";
  } else {
    std::cout << io::format_sampling_report(recording.report, args.file);
  }
  print_timings(args.verbosity, "check", times);
}

}  // namespace

void register_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Sampling report of a recording: rate (median interval), gaps, non-monotonic and duplicate "
      "time stamps, jitter, and per channel range, saturation runs and quantization step (LSB)");
  cmd->footer(
      "Examples:\n"
      "  imunoise check rec.csv                      # columns as written by 'imunoise simulate'\n"
      "  imunoise check imu.txt --time-col 1 --time-unit ns --gyro-cols 2,3,4 \\\n"
      "      --accel-cols 5,6,7 --full-scale-gyro 2000 --full-scale-accel 16 --json\n"
      "  imunoise check log.csv --rate 400 --gyro-cols dtheta_x,dtheta_y,dtheta_z --gyro-unit rad\n"
      "  imunoise check log.csv --config configs/example_input.yaml\n"
      "Problems with the file (bad number, wrong column count, NaN without --drop-non-finite)\n"
      "stop with FILE:LINE:COL and a non-zero exit; timing anomalies are reported, not fatal.");
  cmd->add_option("REC", args->file, "recording: CSV/TXT with a header row, or headerless")
      ->required();
  add_input_options(*cmd, args->flags, args->config_path);
  add_log_input_options(*cmd, args->log);
  cmd->add_flag("--json", args->json,
                "print one JSON object (keys carry units: rate_hz, longest_gap_s, jitter_rms_s)");
  add_verbosity_options(*cmd, args->verbosity);
  cmd->callback([args] { run_check(*args); });
}

}  // namespace imunoise::tools
