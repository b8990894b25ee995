/// @file
/// @brief `imunoise allan`: one Allan-family deviation curve of one series, with confidence
/// intervals, as a table or as one JSON object.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "analysis/deviation.h"
#include "analysis/tau_grid.h"
#include "common/errors.h"
#include "io/binary_recording.h"
#include "io/csv_reader.h"
#include "io/sampling_report.h"
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
  LcmInputFlags lcm;
  CLI::Option* tau0_option = nullptr;  // to tell a given --tau0 from the default
  Verbosity verbosity;
};

/// Which EDF model the interval uses, for the table header.
const char* edf_model(analysis::DeviationType type) {
  using analysis::DeviationType;
  switch (type) {
    case DeviationType::totdev:
      return "of SP 1065 (TOTDEV)";
    case DeviationType::mtotdev:
    case DeviationType::ttotdev:
      return "of SP 1065 Table 8 (MTOT)";
    case DeviationType::htotdev:
      return "by Greenhall-Riley (OHDEV model)";
    case DeviationType::theo1:
      return "of SP 1065 (Theo1)";
    default:
      return "by Greenhall-Riley";
  }
}

/// One channel of an LCM log (--channel) or of an imunoise binary recording as a series:
/// --column names the recording channel (gyro_x … accel_z, temperature), with its time stamps.
io::Series recording_series(const AllanArgs& args, const io::SeriesReadOptions& read_options,
                            bool lcm_log) {
  io::InputConfig config;
  config.drop_non_finite = read_options.drop_non_finite;
  pipeline::Recording recording = read_input_recording(args.file, config, args.lcm);
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
void run_allan(const AllanArgs& args, StageTimes& times) {
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
  const bool lcm_log = is_lcm_log_file(args.file);
  const io::Series series = lcm_log || io::is_binary_recording_file(args.file)
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
    tau0_s = timing.median_interval_s;
    tau0_source = "median interval of time column '" + series.time_column + "'";
    // The estimators assume uniform sampling: say so when the stamps disagree.
    if (timing.gap_count > 0 || timing.non_monotonic_count > 0 || timing.duplicate_count > 0) {
      std::cerr << fmt::format(
          "imunoise: warning: {}: time column '{}' shows {} gap(s), {} non-monotonic and {} "
          "duplicate stamp(s); deviations assume uniform sampling (see 'imunoise check')\n",
          args.file, series.time_column, timing.gap_count, timing.non_monotonic_count,
          timing.duplicate_count);
    }
  }

  const bool is_phase = args.data == "phase";
  const std::size_t needed = is_phase ? 2 : 1;
  if (series.values.size() < needed) {
    throw AnalysisError(located_message(args.file, 0, 0,
                                        "too few samples: " + std::to_string(series.values.size()) +
                                            " value(s) in column '" + series.column_name + "'"));
  }
  // SI inside means: the phase is the integral of the input in input-unit·s.
  const std::vector<double> phase = is_phase ? analysis::detrended_phase(series.values)
                                             : analysis::phase_from_rate(series.values, tau0_s);
  std::vector<std::int64_t> factors;
  try {
    factors = analysis::averaging_factors(grid, *type, static_cast<std::int64_t>(phase.size()));
  } catch (const AnalysisError& e) {
    throw AnalysisError(located_message(args.file, 0, 0, e.what()));
  }

  times.mark("read");
  analysis::DeviationOptions options;
  options.type = *type;
  options.confidence = args.confidence;
  if (args.alpha != 99) options.alpha = args.alpha;
  options.threads = args.threads;
  options.bias_corrected = args.bias_corrected;
  const analysis::DeviationCurve curve =
      analysis::compute_deviation(phase, tau0_s, factors, options);
  times.mark("deviations");

  if (args.json) {
    nlohmann::ordered_json out;
    out["type"] = std::string(analysis::to_string(curve.type));
    out["data"] = args.data;
    out["tau0_s"] = curve.tau0_s;
    out["n_samples"] = series.values.size();
    out["confidence"] = curve.confidence;
    out["tau0_source"] = tau0_source;
    out["source"] = args.file;
    out["column"] = series.column_name;
    out["n_phase"] = curve.n_phase;
    out["non_finite_dropped"] = series.non_finite_dropped;
    const bool time_statistic = curve.type == analysis::DeviationType::tdev ||
                                curve.type == analysis::DeviationType::ttotdev;
    out["value_unit"] = time_statistic ? "input unit * s" : "input unit";
    out["bias_corrected"] = options.bias_corrected && analysis::cost_grows_with_m(curve.type);
    auto& points = out["points"] = nlohmann::ordered_json::array();
    for (const auto& p : curve.points) {
      points.push_back({{"m", p.m},
                        {"tau_s", p.tau_s},
                        {"value", p.value},
                        {"n_terms", p.n_terms},
                        {"alpha", p.alpha},
                        {"edf", p.edf},
                        {"ci_low", p.ci_low},
                        {"ci_high", p.ci_high}});
    }
    std::cout << out.dump() << "\n";
    return;
  }
  std::cout << fmt::format(
      "# {} of {} column '{}' ({} data, tau0 = {} s from {}, {} samples, {} phase points)\n"
      "# confidence interval: {:.1f} % two-sided chi-square, EDF {}{}\n",
      analysis::to_string(curve.type), args.file, series.column_name, args.data, tau0_s,
      tau0_source, series.values.size(), curve.n_phase, 100.0 * curve.confidence,
      edf_model(curve.type),
      options.alpha ? fmt::format(", alpha fixed at {}", *options.alpha)
                    : ", alpha identified per tau (lag-1 ACF)");
  if (series.non_finite_dropped > 0) {
    std::cout << fmt::format("# {} NaN/Inf values dropped\n", series.non_finite_dropped);
  }
  std::cout << fmt::format("{:>10} {:>13} {:>10} {:>5} {:>11} {:>13} {:>13} {:>13}\n", "m", "tau_s",
                           "n_terms", "alpha", "edf", "ci_low", "value", "ci_high");
  for (const auto& p : curve.points) {
    std::cout << fmt::format(
        "{:>10} {:>13.6e} {:>10} {:>5} {:>11.4g} {:>13.6e} {:>13.6e} {:>13.6e}\n", p.m, p.tau_s,
        p.n_terms, p.alpha, p.edf, p.ci_low, p.value, p.ci_high);
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
  add_lcm_input_options(*cmd, args->lcm);
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
    StageTimes times;
    run_allan(*args, times);
    times.mark("output");
    print_timings(args->verbosity, "allan", times);
  });
}

}  // namespace imunoise::tools
