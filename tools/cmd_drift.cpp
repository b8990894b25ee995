/// @file
/// @brief `imunoise drift`: what the fitted noise model means in metres, checked against the
/// recording (theory.md §7.6–7.7): segments of the recording aligned and free-run through the
/// strapdown navigator, the covariance prediction of the model with the same protocol, a
/// Monte Carlo envelope of the model, and the consistency statistics — CSV + JSON in DIR.
/// Here: the flags, reading the model and the recording, the printed summary; the job is
/// pipeline/drift_run.h, the files io/drift_files.h.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "common/errors.h"
#include "common/progress_callback.h"
#include "common/units.h"
#include "io/drift_files.h"
#include "io/duration_parser.h"
#include "io/noise_model_yaml.h"
#include "io/terminal_progress_bar.h"
#include "pipeline/drift_run.h"
#include "report/drift_summary_text.h"
#include "report/write_report.h"
#include "tools/commands.h"
#include "tools/gm_convention_option.h"
#include "tools/input_options.h"
#include "tools/invocation.h"
#include "tools/recording_input.h"
#include "tools/verbosity.h"

namespace imunoise::tools {
namespace {

struct DriftArgs {
  std::string file;
  LogInputFlags log;
  io::InputConfig flags;
  std::string config_path;
  std::string model_path;
  std::string align = "60s";
  std::string segment = "10min";
  std::string warmup = "0s";
  std::string output_step = "1s";
  std::vector<double> location{45.0, 0.0, 0.0};
  bool location_given = false;
  std::optional<double> heading_deg;
  double heading_sigma_deg = 0.0;
  /// Those within --segment are used: 1, 5 and 10 min by default; 30 min and 1 h with
  /// segments that long.
  std::vector<double> report_times_s{60.0, 300.0, 600.0, 1800.0, 3600.0};
  int monte_carlo = 100;
  std::uint64_t seed = 1;
  std::string gm_convention = "peak_match";
  bool force = false;
  std::string holdout = "none";
  std::string output;
  Verbosity verbosity;
};

/// The flag that gets past a refusal of the drift analysis, appended to its message.
std::string how_to_proceed(pipeline::DriftRefusal reason) {
  switch (reason) {
    case pipeline::DriftRefusal::missing_channel:
      return " (map it with --config or the column flags)";
    case pipeline::DriftRefusal::time_gaps:
      return " (use --force to run anyway)";
    case pipeline::DriftRefusal::not_stationary:
      return " — use --force to run it anyway";
    case pipeline::DriftRefusal::too_few_segments:
      return " — shorten --segment or --align";
  }
  return "";
}

/// The flags as run_drift's options (durations parsed, report times beyond the segment left
/// out: the default 60,300,600 with a shorter --segment).
pipeline::DriftRunOptions drift_options(const DriftArgs& a) {
  pipeline::DriftRunOptions o;
  o.location = {a.location[0], a.location[1], a.location[2], a.location_given};
  if (a.heading_deg) o.heading_rad = *a.heading_deg * units::kDeg;
  o.heading_sigma_rad = a.heading_sigma_deg * units::kDeg;
  o.heading_setting = "--heading DEG";
  o.align_s = io::parse_duration_s(a.align, "--align");
  o.navigation_s = io::parse_duration_s(a.segment, "--segment");
  o.warmup_s = io::parse_duration_s(a.warmup, "--warmup", /*allow_zero=*/true);
  o.output_step_s = io::parse_duration_s(a.output_step, "--output-step");
  o.report_times_s.clear();
  for (double t : a.report_times_s)
    if (t <= o.navigation_s) o.report_times_s.push_back(t);
  if (o.report_times_s.empty()) o.report_times_s.push_back(o.navigation_s);
  o.gm_convention = gm_conventions().at(a.gm_convention);
  o.monte_carlo_runs = a.monte_carlo;
  o.seed = a.seed;
  o.force = a.force;
  o.model_path = a.model_path;
  o.holdout_half = a.holdout == "half";
  return o;
}

/// TIMES gets the wall time of each computing stage (the caller adds the outputs).
void run_drift(const DriftArgs& a, io::StageTimes& times) {
  io::ProgressBar bar("drift", progress_wanted(a.verbosity));
  if (a.location.size() != 3)
    throw InputError("--location: expected LAT,LON,H (deg, deg, m), got " +
                     std::to_string(a.location.size()) + " values");
  const models::NoiseModel model = io::load_model_yaml(a.model_path);
  const pipeline::DriftRunOptions options = drift_options(a);
  const io::InputConfig config = resolve_input_config(a.flags, a.config_path);
  const pipeline::Recording recording = read_input_recording(a.file, config, a.log, bar.callback());
  times.mark("read");
  // The Monte Carlo starts once the segments and the prediction are done.
  const ProgressCallback draw = bar.callback();
  bool monte_carlo_started = false;
  const ProgressCallback progress = [&](std::string_view stage, std::int64_t done,
                                        std::int64_t total) {  // single-threaded stages
    if (stage == "Monte Carlo" && !monte_carlo_started) {
      monte_carlo_started = true;
      times.mark("segments and prediction");
    }
    if (draw) draw(stage, done, total);
  };
  pipeline::DriftResult result;
  try {
    result = pipeline::run_drift(recording, model, options, progress);
  } catch (const pipeline::DriftRefused& e) {
    throw InputError(e.what() + how_to_proceed(e.reason()));
  }
  times.mark(monte_carlo_started ? "Monte Carlo" : "segments and prediction");
  bar.finish();  // before any other output: it starts on a clean line

  std::error_code ec;
  std::filesystem::create_directories(a.output, ec);
  if (ec) throw InputError(a.output + ": cannot create the directory: " + ec.message());
  const std::filesystem::path dir(a.output);
  io::write_drift_segments_csv((dir / "drift_segments.csv").string(), result.segments);
  io::write_drift_envelope_csv((dir / "drift_envelope.csv").string(), result.series);
  io::write_drift_summary_json((dir / "drift_summary.json").string(), result.summary);
  io::write_drift_budget_csv((dir / "drift_budget.csv").string(), result.budget);

  std::cout << report::drift_summary_text(result.summary)
            << report::drift_budget_text(result.budget);
  write_command_file(dir.string());
  const report::ReportOutput report = report::write_report(dir.string());
  std::cout << "\nwrote " << (dir / "drift_segments.csv").string()
            << ", drift_envelope.csv, drift_summary.json, drift_budget.csv, plots/\nreport: "
            << report.html_path << "\n";
}

}  // namespace

void register_drift_command(CLI::App& app) {
  auto args = std::make_shared<DriftArgs>();
  CLI::App* cmd = app.add_subcommand(
      "drift",
      "Free-inertial drift of a stationary recording vs the drift the fitted model predicts: "
      "segments aligned and mechanized, covariance prediction, Monte Carlo envelope, NEES and "
      "coverage.\n"
      "Example: imunoise drift rec.csv --model out/model.yaml --location 45,7,300 --heading 0 "
      "-o out/drift");
  cmd->add_option("REC", args->file, "recording (CSV/TXT; see 'imunoise check --help')")
      ->required();
  add_input_options(*cmd, args->flags, args->config_path);
  add_log_input_options(*cmd, args->log);
  cmd->add_option("--model", args->model_path, "fitted model.yaml (imunoise analyze)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--align", args->align, "alignment window per segment (default 60s)");
  cmd->add_option("--segment", args->segment, "navigation time per segment (default 10min)");
  cmd->add_option("--warmup", args->warmup, "skip this much at the start (default 0s)");
  cmd->add_option("--output-step", args->output_step, "time step of the series (default 1s)");
  CLI::Option* location =
      cmd->add_option("--location", args->location, "LAT,LON,H [deg, deg, m] (default 45,0,0)")
          ->delimiter(',')
          ->expected(3);
  cmd->add_option("--heading", args->heading_deg,
                  "heading of the IMU's x axis from north [deg]; without it each segment "
                  "gyrocompasses, which a MEMS gyro usually cannot");
  cmd->add_option("--heading-sigma", args->heading_sigma_deg, "1-sigma of --heading [deg]")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--report-times", args->report_times_s,
                  "times for the statistics [s], those within --segment (default "
                  "60,300,600,1800,3600)")
      ->delimiter(',');
  cmd->add_option("--monte-carlo", args->monte_carlo,
                  "Monte Carlo runs of the model through the same protocol (default 100; 0 = off)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--seed", args->seed, "Monte Carlo seed (default 1)");
  cmd->add_option("--gm-convention", args->gm_convention,
                  "B as one GM in the prediction (theory.md §4.4): min_adev_at_tau_min, "
                  "peak_match (default), sigma_equals_b")
      ->check(CLI::IsMember(gm_conventions()));
  cmd->add_flag("--force", args->force, "run even if the IMU moves or the record has gaps");
  cmd->add_option("--holdout", args->holdout,
                  "split-sample check: 'half' fits a model on the first half of REC (as "
                  "'imunoise analyze' does) and judges the segments of the second half with it, "
                  "beside the numbers of --model (default none)")
      ->check(CLI::IsMember({"none", "half"}));
  cmd->add_option("-o,--output", args->output, "output directory (created if needed)")->required();
  add_verbosity_options(*cmd, args->verbosity);
  cmd->callback([args, location] {
    args->location_given = location->count() > 0;
    io::StageTimes times;
    run_drift(*args, times);
    times.mark("outputs");
    print_timings(args->verbosity, "drift", times);
  });
}

}  // namespace imunoise::tools
