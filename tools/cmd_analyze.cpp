/// @file
/// @brief `imunoise analyze`: the whole job on one recording — sampling report, OADEV/OHDEV
/// with intervals, Welch PSD, the weighted NNLS fit with bootstrap intervals, read-offs and
/// B → GM conversions for each of the six channels (in parallel) — written to DIR as
/// model.yaml (native schema, docs/model-yaml.md), allan.csv and psd.csv, with a summary table
/// in datasheet units on stdout.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <array>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "analysis/noise_terms.h"
#include "analysis/psd_model.h"
#include "common/errors.h"
#include "common/units.h"
#include "io/allan_csv.h"
#include "io/atomic_output.h"
#include "io/csv_reader.h"
#include "io/noise_model_yaml.h"
#include "io/psd_csv.h"
#include "io/sampling_report.h"
#include "io/simulation_model.h"
#include "io/terminal_progress_bar.h"
#include "models/noise_model.h"
#include "pipeline/axis_analysis.h"
#include "pipeline/gap_policy.h"
#include "report/summary_text.h"
#include "report/write_report.h"
#include "tools/analysis_options.h"
#include "tools/commands.h"
#include "tools/input_options.h"
#include "tools/invocation.h"
#include "tools/lcm_bus.h"
#include "tools/recording_input.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

struct AnalyzeArgs {
  std::string file;
  io::InputConfig flags;
  std::string config_path;
  LogInputFlags log;
  std::string output_dir;
  AnalysisSettings analysis;
  std::string truth_path;
  Verbosity verbosity;
  bool publish = false;
  std::string lcm_url = kDefaultLcmUrl;
  std::string model_channel = "NOISE_MODEL";
  std::string curves_channel = "ALLAN_CURVE";
};

/// TIMES gets the wall time of reading, the analysis, the output files and the report (the
/// caller adds what follows: the summary and publishing, as "outputs").
void run_analyze(const AnalyzeArgs& args, io::StageTimes& times) {
  (void)gap_policy_option(args.analysis);    // a bad --gaps fails before the read
  import_fftw_wisdom_option(args.analysis);  // so does a bad wisdom file
  const io::InputConfig config = resolve_input_config(args.flags, args.config_path);
  std::optional<std::array<NoiseCoefficients, 6>> truth;
  if (!args.truth_path.empty()) {
    const io::SimulationModelFile file = io::load_simulation_model(args.truth_path);
    std::array<NoiseCoefficients, 6> values;
    for (std::size_t a = 0; a < 3; ++a) {
      values[a] = file.gyro[a].coefficients;
      values[3 + a] = file.accel[a].coefficients;
    }
    truth = values;
  }
  io::ProgressBar bar("analyze", progress_wanted(args.verbosity));
  // Open the bus before the work: a bad --lcm-url fails in a second, not after the analysis.
  std::optional<LcmBus> bus;
  if (args.publish) bus.emplace(args.lcm_url);

  pipeline::Recording recording =
      read_input_recording(args.file, config, args.log, bar.callback(), args.analysis.threads);
  times.mark("read");
  io::StageTimes channel_times;
  pipeline::RecordingAnalysis result = analyze_recording_freeing_time_stamps(
      recording, args.file, args.analysis,
      {&bar, args.verbosity.verbose ? &channel_times : nullptr});
  bar.finish();  // before anything else is written: the next output starts on a clean line
  times.mark("analysis");
  print_detail(args.verbosity, "analyze",
               std::to_string(result.axes.size()) + " channels, " +
                   (args.analysis.bootstrap
                        ? "bootstrap " + std::to_string(*args.analysis.bootstrap)
                        : "interval draws " + std::to_string(args.analysis.interval_draws)) +
                   " replicates; per stage, summed over the channels: " + channel_times.text());
  if (args.verbosity.verbose)
    print_detail(args.verbosity, "analyze", pipeline::psd_plan_text(result));
  const models::NoiseModel& model = result.model;
  const std::vector<pipeline::AxisAnalysis>& axes = result.axes;
  const double tau0_s = result.tau0_s;

  io::create_output_directory(args.output_dir);
  const std::filesystem::path dir(args.output_dir);
  io::write_model_yaml(model, (dir / "model.yaml").string());
  io::write_allan_csv((dir / "allan.csv").string(), io::allan_table(axes, tau0_s));
  io::write_psd_csv((dir / "psd.csv").string(), io::psd_table(axes, tau0_s));
  io::write_sampling_report_json((dir / "sampling_report.json").string(), recording.report,
                                 args.file);
  write_command_file(dir.string());
  times.mark("outputs");
  const report::ReportOutput report = report::write_report(dir.string());
  times.mark("report");
  std::cout << report::summary_text(model, truth, (dir / "model.yaml").string());
  std::cout << "\nwrote " << (dir / "model.yaml").string()
            << ", allan.csv, psd.csv, sampling_report.json, plots/\nreport: " << report.html_path
            << "\n";
  if (bus) {
    const std::int64_t utime = now_utime_us();
    bus->publish(args.model_channel, io::noise_model_message(model, utime));
    for (const pipeline::AxisAnalysis& a : axes) {
      bus->publish(args.curves_channel, io::allan_curve_message(a.model.name, a.oadev, utime));
    }
    std::cout << "published the model on '" << args.model_channel << "' and " << axes.size()
              << " OADEV curves on '" << args.curves_channel << "' (" << args.lcm_url << ")\n";
  }
}

}  // namespace

void register_analyze_command(CLI::App& app) {
  auto args = std::make_shared<AnalyzeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "analyze",
      "Fit the stochastic error model of every gyro and accelerometer axis of a stationary "
      "recording (OADEV + OHDEV with intervals, PSD, weighted NNLS fit with bootstrap "
      "intervals) and write DIR/model.yaml, allan.csv and psd.csv");
  cmd->add_option("REC", args->file,
                  "recording: CSV/TXT (see 'imunoise check --help'), an lcm-logger log, a ROS bag, "
                  "MCAP or rosbag2 .db3 (docs/inputs.md)")
      ->required();
  add_input_options(*cmd, args->flags, args->config_path);
  add_log_input_options(*cmd, args->log);
  cmd->add_option("-o,--output", args->output_dir, "output directory (created if needed)")
      ->required();
  add_analysis_options(*cmd, args->analysis);
  cmd->add_option("--truth", args->truth_path,
                  "simulator model file (e.g. the one given to 'imunoise simulate'): print the "
                  "true coefficients next to the recovered ones");
  add_verbosity_options(*cmd, args->verbosity);
  const std::string lcm_group = "Publishing on LCM";
  cmd->add_flag("--publish", args->publish,
                "at the end, publish the model (imunoise.noise_model_t) and the OADEV curves "
                "(imunoise.allan_curve_t) on LCM")
      ->group(lcm_group);
  cmd->add_option("--lcm-url", args->lcm_url, "LCM provider URL for --publish")
      ->capture_default_str()
      ->group(lcm_group);
  cmd->add_option("--model-channel", args->model_channel, "channel of the model")
      ->capture_default_str()
      ->group(lcm_group);
  cmd->add_option("--curves-channel", args->curves_channel, "channel of the curves")
      ->capture_default_str()
      ->group(lcm_group);
  cmd->footer(
      "Examples:\n"
      "  imunoise simulate configs/reference-imu.yaml --duration 8h --rate 50 --seed 1 -o rec.csv\n"
      "  imunoise analyze rec.csv -o out --truth configs/reference-imu.yaml\n"
      "  imunoise analyze imu.txt --config configs/example_input.yaml -o out --bootstrap 0\n"
      "  imunoise analyze imu.lcmlog --channel IMU -o out --publish\n"
      "  imunoise analyze rec.imnb -o out --fftw-wisdom imu.wisdom   # see 'fftw-wisdom --help'\n"
      "Outputs: model.yaml (SI units named in every key, docs/model-yaml.md), allan.csv\n"
      "(OADEV/OHDEV with intervals and the model ADEV, per axis), psd.csv (log-binned one-sided\n"
      "PSD with dof and the model PSD, per axis); units are part of every column name.");
  cmd->callback([args] {
    io::StageTimes times;
    run_analyze(*args, times);
    times.mark("outputs");
    print_timings(args->verbosity, "analyze", times);
  });
}

}  // namespace imunoise::tools
