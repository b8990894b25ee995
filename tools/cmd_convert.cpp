/// @file
/// @brief `imunoise convert`: one recording (anything `analyze` reads: CSV/TXT, LCM log,
/// imunoise binary) to another format: the binary recording (io/binary_recording.h), a CSV in
/// the columns `imunoise simulate` writes (values that read back bit for bit), or an lcm-logger
/// file of imunoise.imu_sample_t. One output file, written atomically.
#include <CLI/CLI.hpp>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <imunoise/imu_sample_t.hpp>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/binary_recording.h"
#include "io/lcm_log_writer.h"
#include "tools/commands.h"
#include "tools/input_options.h"
#include "tools/progress.h"
#include "tools/recording_input.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

enum class OutputFormat { kCsv, kBinary, kLcm };

struct ConvertArgs {
  std::string input;
  std::string output;
  std::string to;  ///< csv|binary|lcm; empty = from the output's extension
  std::string lcm_channel = "IMU";
  LcmInputFlags lcm;
  io::InputConfig flags;
  std::string config_path;
  Verbosity verbosity;
};

std::string_view format_name(OutputFormat f) {
  switch (f) {
    case OutputFormat::kCsv:
      return "CSV";
    case OutputFormat::kBinary:
      return "binary";
    case OutputFormat::kLcm:
      return "LCM log";
  }
  return "?";
}

bool ends_with(std::string_view text, std::string_view suffix) {
  return text.size() > suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

/// --to, else the output's extension; an InputError when neither decides.
OutputFormat output_format(const ConvertArgs& args) {
  if (args.to == "csv") return OutputFormat::kCsv;
  if (args.to == "binary") return OutputFormat::kBinary;
  if (args.to == "lcm") return OutputFormat::kLcm;
  if (!args.to.empty()) {
    throw InputError("--to '" + args.to + "': expected csv, binary or lcm");
  }
  const std::string& out = args.output;
  if (ends_with(out, io::kBinaryRecordingExtension)) return OutputFormat::kBinary;
  if (ends_with(out, ".csv") || ends_with(out, ".txt")) return OutputFormat::kCsv;
  if (ends_with(out, ".lcm") || ends_with(out, ".log") || ends_with(out, ".lcmlog")) {
    return OutputFormat::kLcm;
  }
  throw InputError(out +
                   ": cannot tell the output format from the file name; use the extension "
                   ".imnb (binary), .csv/.txt (CSV) or .lcm/.log/.lcmlog (LCM log), or give "
                   "--to csv|binary|lcm");
}

/// The CSV column of a channel: the standard channels with their SI unit suffix (as `simulate`
/// writes them, so a default read maps them back), other channels by name.
std::string csv_column_name(const pipeline::Channel& channel) {
  if (channel.unit == "rad/s") return channel.name + "_rad_per_s";
  if (channel.unit == "m/s^2") return channel.name + "_m_per_s2";
  return channel.name;
}

/// Time of sample I since the first [s]: the stamps, or I / rate for a fixed rate.
double sample_time_s(const pipeline::Recording& rec, std::size_t i) {
  if (!rec.time_s.empty()) return rec.time_s[i];
  const double rate =
      rec.report.timing.rate_hz > 0.0 ? rec.report.timing.rate_hz : 1.0 / rec.sample_period_s;
  return static_cast<double>(i) / rate;
}

/// CSV: '#' lines with the provenance, the column line, then rows of shortest round-trip
/// numbers (std::to_chars), time_s relative to the first sample.
void write_csv(const pipeline::Recording& rec, const std::string& path) {
  io::AtomicOutputFile file(path);
  std::ostream& out = file.stream();
  out << "# imunoise convert: " << rec.source_path << ", SI units\n"
      << "# sample_period_s: " << shortest_number_text(rec.sample_period_s) << "\n"
      << "# start_time_s: " << shortest_number_text(rec.start_time_s) << "\n"
      << "# samples: " << rec.sample_count() << "\n";
  if (rec.time_s.empty()) {
    out << "# time_s: k / " << shortest_number_text(rec.report.timing.rate_hz)
        << " Hz (the input had a fixed rate)\n";
  }
  for (const pipeline::Channel& c : rec.channels) {
    out << "# " << c.name << ": from " << c.source_column
        << (c.source_unit.empty() ? "" : " [" + c.source_unit + "]")
        << (c.from_increments ? " (increments divided by the sample period)" : "") << "\n";
  }
  out << "time_s";
  for (const pipeline::Channel& c : rec.channels) out << "," << csv_column_name(c);
  out << "\n";

  constexpr std::size_t kBlockRows = 4096;
  const std::size_t row_chars = (rec.channels.size() + 1) * 25;
  std::vector<char> text(kBlockRows * row_chars);
  const std::size_t n = rec.sample_count();
  for (std::size_t first = 0; first < n; first += kBlockRows) {
    const std::size_t last = std::min(n, first + kBlockRows);
    char* p = text.data();
    for (std::size_t i = first; i < last; ++i) {
      p = std::to_chars(p, p + 24, sample_time_s(rec, i)).ptr;
      for (const pipeline::Channel& c : rec.channels) {
        *p++ = ',';
        p = std::to_chars(p, p + 24, c.values[i]).ptr;
      }
      *p++ = '\n';
    }
    out.write(text.data(), p - text.data());
  }
  file.commit();
}

/// LCM log of imunoise.imu_sample_t: the six IMU channels (required) as rates, and the
/// "temperature" channel when there is one; utime = start + time since the first sample [µs].
void write_lcm(const pipeline::Recording& rec, const std::string& path,
               const std::string& channel) {
  std::array<const pipeline::Channel*, 6> imu{};
  std::string missing;
  for (std::size_t c = 0; c < imu.size(); ++c) {
    imu[c] = rec.find_channel(pipeline::kImuChannelNames[c]);
    if (imu[c] == nullptr)
      missing += std::string(missing.empty() ? "" : ", ") + pipeline::kImuChannelNames[c];
  }
  if (!missing.empty()) {
    throw InputError(rec.source_path +
                     ": an LCM log of imu_sample_t needs all six channels "
                     "gyro_x ... accel_z; missing: " +
                     missing);
  }
  const pipeline::Channel* temperature = rec.find_channel("temperature");
  const double start_us = std::round(rec.start_time_s * 1e6);
  if (!(std::fabs(start_us) < 9.2e18)) {
    throw InputError(rec.source_path + ": start_time_s does not fit a 64-bit µs stamp");
  }
  const auto start = static_cast<std::int64_t>(start_us);

  io::AtomicOutputFile file(path);
  io::LcmLogWriter writer(file.stream());
  imunoise::imu_sample_t message{};
  std::vector<unsigned char> encoded(static_cast<std::size_t>(message.getEncodedSize()));
  const std::size_t n = rec.sample_count();
  for (std::size_t i = 0; i < n; ++i) {
    message.utime = start + std::llround(sample_time_s(rec, i) * 1e6);
    for (std::size_t a = 0; a < 3; ++a) {
      message.angular_rate_rad_per_s[a] = imu[a]->values[i];
      message.specific_force_m_per_s2[a] = imu[3 + a]->values[i];
    }
    message.has_temperature = temperature != nullptr;
    message.temperature_degc = temperature != nullptr ? temperature->values[i] : 0.0;
    message.encode(encoded.data(), 0, static_cast<int>(encoded.size()));
    writer.write(channel, message.utime, encoded);
  }
  file.commit();
}

void run_convert(const ConvertArgs& args) {
  const OutputFormat format = output_format(args);  // before reading: a typo fails fast
  if (format == OutputFormat::kLcm && args.lcm_channel.empty()) {
    throw InputError("--lcm-channel must not be empty");
  }
  const io::InputConfig config = resolve_input_config(args.flags, args.config_path);
  StageTimes times;
  ProgressBar bar("convert", progress_wanted(args.verbosity));
  const pipeline::Recording recording =
      read_input_recording(args.input, config, args.lcm, bar.callback());
  bar.finish();
  times.mark("read");
  switch (format) {
    case OutputFormat::kBinary:
      io::write_binary_recording(args.output, recording);
      break;
    case OutputFormat::kCsv:
      write_csv(recording, args.output);
      break;
    case OutputFormat::kLcm:
      write_lcm(recording, args.output, args.lcm_channel);
      break;
  }
  times.mark("write");
  std::cout << "imunoise convert: wrote " << recording.sample_count() << " samples × "
            << recording.channels.size() << " channels of " << args.input << " to " << args.output
            << " (" << format_name(format) << ")\n";
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
  add_lcm_input_options(*cmd, args->lcm);
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
