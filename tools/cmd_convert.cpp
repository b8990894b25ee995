/// @file
/// @brief `imunoise convert`: one recording (anything `analyze` reads: CSV/TXT, LCM log,
/// imunoise binary) to another format: the binary recording (io/binary_recording.h), a CSV in
/// the columns `imunoise simulate` writes (io/recording_csv_writer.h: values that read back bit
/// for bit), or an lcm-logger file of imunoise.imu_sample_t (io/recording_lcm_writer.h). One
/// output file, written atomically.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <string>

#include "common/errors.h"
#include "io/binary_recording.h"
#include "io/recording_csv_writer.h"
#include "io/recording_input.h"
#include "io/recording_lcm_writer.h"
#include "io/terminal_progress_bar.h"
#include "tools/commands.h"
#include "tools/input_options.h"
#include "tools/recording_input.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

struct ConvertArgs {
  std::string input;
  std::string output;
  std::string to;  ///< csv|binary|lcm; empty = from the output's extension
  std::string lcm_channel = "IMU";
  LogInputFlags log;
  io::InputConfig flags;
  std::string config_path;
  Verbosity verbosity;
};

/// --to, else the output's extension; an InputError when neither decides.
io::RecordingFormat output_format(const ConvertArgs& args) {
  if (args.to == "csv") return io::RecordingFormat::kTable;
  if (args.to == "binary") return io::RecordingFormat::kBinary;
  if (args.to == "lcm") return io::RecordingFormat::kLcmLog;
  if (!args.to.empty()) {
    throw InputError("--to '" + args.to + "': expected csv, binary or lcm");
  }
  if (const auto format = io::recording_format_of_file_name(args.output)) return *format;
  throw InputError(args.output +
                   ": cannot tell the output format from the file name; use the extension "
                   ".imnb (binary), .csv/.txt (CSV) or .lcm/.log/.lcmlog (LCM log), or give "
                   "--to csv|binary|lcm");
}

void run_convert(const ConvertArgs& args) {
  const io::RecordingFormat format = output_format(args);  // before reading: a typo fails fast
  if (format == io::RecordingFormat::kLcmLog && args.lcm_channel.empty()) {
    throw InputError("--lcm-channel must not be empty");
  }
  const io::InputConfig config = resolve_input_config(args.flags, args.config_path);
  io::StageTimes times;
  io::ProgressBar bar("convert", progress_wanted(args.verbosity));
  const pipeline::Recording recording =
      read_input_recording(args.input, config, args.log, bar.callback());
  bar.finish();
  times.mark("read");
  switch (format) {
    case io::RecordingFormat::kBinary:
      io::write_binary_recording(args.output, recording);
      break;
    case io::RecordingFormat::kTable:
      io::write_recording_csv(recording, args.output);
      break;
    case io::RecordingFormat::kLcmLog:
      io::write_recording_lcm(recording, args.output, args.lcm_channel);
      break;
    default:  // robotics logs are inputs only: output_format never gives one
      throw ContractViolation("convert: no writer for the output format");
  }
  times.mark("write");
  std::cout << "imunoise convert: wrote " << recording.sample_count() << " samples × "
            << recording.channels.size() << " channels of " << args.input << " to " << args.output
            << " (" << io::recording_format_name(format) << ")\n";
  print_timings(args.verbosity, "convert", times);
}

}  // namespace

void register_convert_command(CLI::App& app) {
  auto args = std::make_shared<ConvertArgs>();
  CLI::App* cmd = app.add_subcommand(
      "convert",
      "Convert a recording (CSV/TXT, LCM log or imunoise binary) to the compact binary format "
      "(.imnb), a CSV in the columns 'simulate' writes, or an LCM log of imu_sample_t");
  cmd->add_option("INPUT", args->input, "recording to read (anything 'analyze' reads)")->required();
  cmd->add_option("-o,--output", args->output,
                  "output file; its extension picks the format: .imnb binary, .csv/.txt CSV, "
                  ".lcm/.log/.lcmlog LCM log")
      ->required();
  cmd->add_option("--to", args->to, "output format, overriding the extension: csv|binary|lcm");
  cmd->add_option("--lcm-channel", args->lcm_channel, "channel of the samples in an LCM output")
      ->capture_default_str();
  add_input_options(*cmd, args->flags, args->config_path);
  add_log_input_options(*cmd, args->log);
  add_verbosity_options(*cmd, args->verbosity);
  cmd->footer(
      "The CSV output reads back with default options and gives the same values bit for bit\n"
      "(shortest round-trip numbers); the LCM output holds the six IMU channels only (and\n"
      "temperature), CSV and binary keep extra channels. The output is written atomically.\n"
      "Examples:\n"
      "  imunoise convert rec.csv -o rec.imnb\n"
      "  imunoise convert imu.txt --time-col 1 --time-unit ns --gyro-cols 2,3,4 \\\n"
      "      --accel-cols 5,6,7 -o imu.imnb\n"
      "  imunoise convert rec.imnb -o rec.lcmlog --lcm-channel IMU\n");
  cmd->callback([args] { run_convert(*args); });
}

}  // namespace imunoise::tools
