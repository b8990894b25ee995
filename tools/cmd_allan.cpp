/// @file
/// @brief `imunoise allan`: the flags of one Allan-family deviation curve of one series
/// (analysis/series_deviation.h), with confidence intervals, printed as a table or as one JSON
/// object (io/deviation_curve_text.h).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "analysis/series_deviation.h"
#include "common/errors.h"
#include "io/csv_reader.h"
#include "io/deviation_curve_text.h"
#include "io/recording_input.h"
#include "pipeline/sampling_checks.h"
#include "tools/commands.h"
#include "tools/recording_input.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

struct AllanArgs {
  std::string file;
  std::string column;
  std::string data = "rate";
  double tau0_s = 1.0;
  std::string type = "oadev";
  std::string taus = "octave";
  double confidence = 0.683;
  int alpha = 99;  // 99 = identify per τ
  bool json = false;
  bool drop_non_finite = false;
  bool bias_corrected = false;
  unsigned threads = 0;
  LogInputFlags log;
  CLI::Option* tau0_option = nullptr;  // to tell a given --tau0 from the default
  Verbosity verbosity;
};

/// One channel of an LCM log (--channel) or of an imunoise binary recording as a series:
/// --column names the recording channel (gyro_x … accel_z, temperature), with its time stamps.
io::Series recording_series(const AllanArgs& args, const io::SeriesReadOptions& read_options,
                            bool lcm_log) {
  io::InputConfig config;
  config.drop_non_finite = read_options.drop_non_finite;
  pipeline::Recording recording = read_input_recording(args.file, config, args.log);
  std::string names;
  for (const pipeline::Channel& c : recording.channels)
    names += (names.empty() ? "" : ", ") + c.name;
  if (args.column.empty()) {
    throw InputError(args.file + ": give --column, one of " + names);
  }
  const pipeline::Channel* channel = recording.find_channel(args.column);
  if (channel == nullptr) {
    throw InputError(args.file + ": --column '" + args.column + "' is not a channel of the " +
                     (lcm_log ? "log" : "recording") + " (" + names + ")");
  }
  io::Series series;
  series.source_path = args.file;
  series.column_name = channel->source_column;
  series.values = channel->values;
  series.non_finite_dropped = recording.report.non_finite_dropped;
  if (read_options.read_time) {
    series.time_column = lcm_log ? "utime" : "time_s";
    series.time_s = std::move(recording.time_s);
  }
  return series;
}

/// TIMES gets the wall time of reading and of the deviation.
void run_allan(const AllanArgs& args, io::StageTimes& times) {
  const auto type = analysis::parse_deviation_type(args.type);
  if (!type) throw InputError("unknown --type '" + args.type + "'");
  const bool tau0_given = args.tau0_option != nullptr && args.tau0_option->count() > 0;
  if (!(args.tau0_s > 0.0) || !std::isfinite(args.tau0_s)) {
    throw InputError("--tau0 must be a positive number of seconds");
  }
  const analysis::TauGridSpec grid = analysis::parse_tau_grid(args.taus);

  io::SeriesReadOptions read_options;
  read_options.column = args.column;
  read_options.drop_non_finite = args.drop_non_finite;
  read_options.read_time = !tau0_given;
  read_options.threads = args.threads;
  const io::RecordingFormat format = io::detect_recording_format(args.file);
  const bool lcm_log = format == io::RecordingFormat::kLcmLog;
  const io::Series series = format != io::RecordingFormat::kTable
                                ? recording_series(args, read_options, lcm_log)
                                : io::read_series(args.file, read_options);

  // τ0: --tau0, else the median interval of the file's time column, else 1 s — and say which.
  double tau0_s = args.tau0_s;
  std::string tau0_source = tau0_given ? "--tau0" : "default (no --tau0, no time column)";
  if (!tau0_given && series.time_s.size() >= 2) {
    const pipeline::TimingReport timing = pipeline::analyze_timing(series.time_s);
    if (!(timing.median_interval_s > 0.0)) {
      throw InputError(located_message(
          args.file, 0, 0,
          "time column '" + series.time_column + "' has no positive interval; give --tau0"));
    }
    tau0_s = timing.sample_period_s;
    tau0_source = std::string(timing.period_from_mean ? "mean regular interval (quantized or "
                                                        "alternating stamps)"
                                                      : "median interval") +
                  " of time column '" + series.time_column + "'";
    // The estimators assume uniform sampling: say so when the stamps disagree.
    if (timing.gap_count > 0 || timing.non_monotonic_count > 0 || timing.duplicate_count > 0) {
      std::cerr << fmt::format(
          "imunoise: warning: {}: time column '{}' shows {} gap(s), {} non-monotonic and {} "
          "duplicate stamp(s); deviations assume uniform sampling (see 'imunoise check')\n",
          args.file, series.time_column, timing.gap_count, timing.non_monotonic_count,
          timing.duplicate_count);
    }
  }

  const analysis::SeriesKind kind =
      args.data == "phase" ? analysis::SeriesKind::kPhase : analysis::SeriesKind::kRate;
  if (series.values.size() < analysis::min_series_values(kind)) {
    throw AnalysisError(located_message(args.file, 0, 0,
                                        "too few samples: " + std::to_string(series.values.size()) +
                                            " value(s) in column '" + series.column_name + "'"));
  }
  times.mark("read");
  analysis::DeviationOptions options;
  options.type = *type;
  options.confidence = args.confidence;
  if (args.alpha != 99) options.alpha = args.alpha;
  options.threads = args.threads;
  options.bias_corrected = args.bias_corrected;
  const analysis::DeviationCurve curve =
      analysis::series_deviation(series.values, kind, tau0_s, grid, options, args.file);
  times.mark("deviations");

  io::SeriesCurveInfo info;
  info.data = args.data;
  info.source = args.file;
  info.column = series.column_name;
  info.n_samples = series.values.size();
  info.tau0_source = tau0_source;
  info.non_finite_dropped = series.non_finite_dropped;
  info.alpha = options.alpha;
  info.bias_corrected = options.bias_corrected;
  if (args.json) {
    std::cout << io::series_curve_json(curve, info).dump() << "\n";
  } else {
    std::cout << io::series_curve_table(curve, info);
  }
}

}  // namespace

void register_allan_command(CLI::App& app) {
  auto args = std::make_shared<AllanArgs>();
  CLI::App* cmd = app.add_subcommand(
      "allan",
      "Allan-family deviation of one series (ADEV, OADEV, MDEV, TDEV, HDEV, OHDEV, TOTDEV, "
      "MTOTDEV, TTOTDEV, HTOTDEV, Theo1)");
  cmd->footer(
      "Examples:\n"
      "  imunoise allan gyro_x.txt --tau0 0.01 --type oadev --taus log:10\n"
      "  imunoise allan PHASE.DAT --data phase --type mdev --taus octave --json\n"
      "  imunoise allan rec.csv --column gyro_z_rad_per_s --tau0 0.0025 --taus decade\n"
      "  imunoise allan imu.lcmlog --channel IMU --column gyro_z --taus log:10\n"
      "Values are in the unit of the input (rate data) or input unit per second (phase data);\n"
      "TDEV and TTOTDEV are in phase units. mtotdev, ttotdev, htotdev and theo1 cost O(M*m)\n"
      "per tau; theo1 uses even m with tau = 0.75*m*tau0.");
  cmd->add_option("file", args->file,
                  "CSV/TXT file: one value per line, or columns (see --column); or an LCM log")
      ->required();
  cmd->add_option("--column", args->column,
                  "column name (header) or 1-based index; needed when the file has several. For "
                  "an LCM log: the channel, gyro_x … accel_z");
  add_log_input_options(*cmd, args->log);
  cmd->add_option("--data", args->data, "the series is rate ('frequency') or integrated ('phase')")
      ->check(CLI::IsMember({"rate", "phase"}))
      ->capture_default_str();
  args->tau0_option =
      cmd->add_option("--tau0", args->tau0_s,
                      "sample period [s]; default: median interval of a time_s/time_ms/time_us/"
                      "time_ns column, else 1")
          ->capture_default_str();
  cmd->add_option("--type", args->type, "statistic")
      ->check(CLI::IsMember({"adev", "oadev", "mdev", "tdev", "hdev", "ohdev", "totdev", "mtotdev",
                             "ttotdev", "htotdev", "theo1"}))
      ->capture_default_str();
  cmd->add_option("--taus", args->taus, "tau grid: octave, decade, all, log:N, or m1,m2,...")
      ->capture_default_str();
  cmd->add_option("--confidence", args->confidence, "two-sided confidence level of the interval")
      ->check(CLI::Range(1e-6, 1.0 - 1e-9))
      ->capture_default_str();
  cmd->add_option("--alpha", args->alpha,
                  "force the power-law noise type for the EDF (2 white PM .. -2 RW FM); "
                  "default: identified per tau")
      ->check(CLI::Range(-4, 2));
  cmd->add_flag("--json", args->json, "print exactly one JSON object on stdout");
  cmd->add_flag("--bias-correction", args->bias_corrected,
                "mtotdev, ttotdev, htotdev, theo1: apply the SP 1065 bias removal for the "
                "per-tau noise type (default: plain estimator, as Stable32 without correction)");
  cmd->add_flag("--drop-non-finite", args->drop_non_finite,
                "drop NaN/Inf values instead of failing (the count is reported)");
  cmd->add_option("--threads", args->threads, "worker threads (0 = all cores)")
      ->capture_default_str();
  add_verbosity_options(*cmd, args->verbosity);
  cmd->callback([args] {
    io::StageTimes times;
    run_allan(*args, times);
    times.mark("output");
    print_timings(args->verbosity, "allan", times);
  });
}

}  // namespace imunoise::tools
