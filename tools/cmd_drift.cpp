/// @file
/// @brief `imunoise drift`: what the fitted noise model means in metres, checked against the
/// recording (theory.md §7.6–7.7): segments of the recording aligned and free-run through the
/// strapdown navigator, the covariance prediction of the model with the same protocol, a
/// Monte Carlo envelope of the model, and the consistency statistics — CSV + JSON in DIR.
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/units.h"
#include "ins/noise_from_model.h"
#include "io/atomic_output.h"
#include "io/csv_reader.h"
#include "io/noise_model_yaml.h"
#include "models/noise_simulator.h"
#include "pipeline/drift_analysis.h"
#include "tools/commands.h"
#include "tools/duration.h"
#include "tools/gm_convention_option.h"
#include "tools/input_options.h"
#include "tools/invocation.h"
#include "tools/progress.h"
#include "tools/recording_input.h"
#include "tools/report_job.h"
#include "tools/verbosity.h"

namespace imunoise::tools {
namespace {

struct DriftArgs {
  std::string file;
  LcmInputFlags lcm;
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
  std::vector<double> report_times_s{60.0, 300.0, 600.0};
  int monte_carlo = 100;
  std::uint64_t seed = 1;
  std::string gm_convention = "peak_match";
  bool force = false;
  std::string output;
  Verbosity verbosity;
};

/// TIMES gets the wall time of each computing stage (the caller adds the outputs).
void run_drift(DriftArgs a, StageTimes& times) {
  ProgressBar bar("drift", progress_wanted(a.verbosity));
  if (a.location.size() != 3)
    throw InputError("--location: expected LAT,LON,H (deg, deg, m), got " +
                     std::to_string(a.location.size()) + " values");
  const auto model = io::load_model_yaml(a.model_path);
  ins::InsNoiseOptions noise_options;
  noise_options.gm_convention = gm_conventions().at(a.gm_convention);
  const auto noise = ins::ins_sensor_noise(model, noise_options);

  pipeline::DriftOptions o;
  o.latitude_rad = a.location[0] * units::kDeg;
  o.longitude_rad = a.location[1] * units::kDeg;
  o.height_m = a.location[2];
  if (a.heading_deg) o.heading_rad = *a.heading_deg * units::kDeg;
  o.heading_sigma_rad = a.heading_sigma_deg * units::kDeg;
  o.align_s = parse_duration_s(a.align, "--align");
  o.navigation_s = parse_duration_s(a.segment, "--segment");
  o.warmup_s = parse_duration_s(a.warmup, "--warmup", /*allow_zero=*/true);
  o.output_step_s = parse_duration_s(a.output_step, "--output-step");
  o.report_times_s.clear();
  for (double t : a.report_times_s)
    if (t <= o.navigation_s) o.report_times_s.push_back(t);
  if (o.report_times_s.empty()) o.report_times_s.push_back(o.navigation_s);

  const io::InputConfig config = resolve_input_config(a.flags, a.config_path);
  const pipeline::Recording recording = read_input_recording(a.file, config, a.lcm, bar.callback());
  times.mark("read");
  pipeline::ImuSeries series;
  series.sample_period_s = recording.sample_period_s;
  for (int c = 0; c < 6; ++c) {
    const pipeline::Channel* channel = recording.find_channel(pipeline::kImuChannelNames[c]);
    if (channel == nullptr)
      throw InputError(a.file + ": drift needs all six channels; " + pipeline::kImuChannelNames[c] +
                       " is missing (map it with --config or the column flags)");
    series.channels[c] = channel->values;
  }
  if (recording.report.timing.gap_count > 0 && !a.force)
    throw InputError(a.file + ": the recording has " +
                     std::to_string(recording.report.timing.gap_count) +
                     " time gap(s); segments across a gap would navigate through missing data "
                     "(use --force to run anyway)");

  const auto motion = pipeline::check_stationary(series, noise);
  if (!motion.stationary && !a.force)
    throw InputError(a.file + ": the IMU is not stationary (" + motion.reason +
                     "); drift analysis compares free-inertial drift at rest with the noise "
                     "model — use --force to run it anyway");

  o.progress = bar.callback();
  const auto drift = pipeline::analyze_drift(series, noise, o);
  times.mark("segments and prediction");
  std::optional<pipeline::MonteCarloEnvelope> mc;
  if (a.monte_carlo > 0) {
    models::ImuNoiseModel simulation;
    for (int i = 0; i < 3; ++i) {
      if (const auto* g = model.find_axis(pipeline::kImuChannelNames[i]))
        simulation.gyro[i] = models::channel_model_from(g->coefficients());
      if (const auto* f = model.find_axis(pipeline::kImuChannelNames[3 + i]))
        simulation.accel[i] = models::channel_model_from(f->coefficients());
    }
    models::FlickerBand band;
    band.tau_max_s = std::max(1e4, 10.0 * (o.align_s + o.navigation_s));
    mc = pipeline::monte_carlo_drift(simulation, band, noise, series.sample_period_s, o,
                                     a.monte_carlo, a.seed);
    times.mark("Monte Carlo");
  }
  bar.finish();  // before any other output: it starts on a clean line

  std::error_code ec;
  std::filesystem::create_directories(a.output, ec);
  if (ec) throw InputError(a.output + ": cannot create the directory: " + ec.message());
  const std::filesystem::path dir(a.output);

  std::ostringstream seg;
  seg << "segment,start_s,time_s,north_error_m,east_error_m,horizontal_error_m,"
         "horizontal_velocity_error_m_per_s,attitude_error_north_deg,attitude_error_east_deg,"
         "attitude_error_down_deg\n";
  for (std::size_t k = 0; k < drift.segments.size(); ++k) {
    const auto& s = drift.segments[k];
    for (std::size_t i = 0; i < drift.time_s.size(); ++i) {
      const auto& e = s.position_error_ne_m[i];
      seg << k << ',' << shortest_number_text(s.start_s) << ','
          << shortest_number_text(drift.time_s[i]) << ',' << shortest_number_text(e(0)) << ','
          << shortest_number_text(e(1)) << ',' << shortest_number_text(e.norm()) << ','
          << shortest_number_text(s.velocity_error_horizontal_m_per_s[i]);
      for (int a = 0; a < 3; ++a)
        seg << ',' << shortest_number_text(s.attitude_error_ned_rad[i](a) / units::kDeg);
      seg << '\n';
    }
  }
  io::write_file_atomically((dir / "drift_segments.csv").string(), seg.str());

  std::ostringstream env;
  env << "time_s,predicted_north_sigma_m,predicted_east_sigma_m,predicted_horizontal_drms_m,"
         "predicted_horizontal_velocity_drms_m_per_s,predicted_roll_sigma_deg,"
         "predicted_pitch_sigma_deg,predicted_heading_sigma_deg,actual_rms_horizontal_error_m";
  if (mc) env << ",mc_radial_p50_m,mc_radial_p68_m,mc_radial_p95_m,mc_radial_rms_m";
  env << '\n';
  const auto& p = drift.prediction;
  for (std::size_t i = 0; i < drift.time_s.size(); ++i) {
    double ss = 0.0;
    for (const auto& s : drift.segments) ss += s.position_error_ne_m[i].squaredNorm();
    env << shortest_number_text(drift.time_s[i]) << ',' << shortest_number_text(p.north_sigma_m[i])
        << ',' << shortest_number_text(p.east_sigma_m[i]) << ','
        << shortest_number_text(p.horizontal_drms_m[i]) << ','
        << shortest_number_text(p.velocity_horizontal_drms_m_per_s[i]) << ','
        << shortest_number_text(p.roll_sigma_rad[i] / units::kDeg) << ','
        << shortest_number_text(p.pitch_sigma_rad[i] / units::kDeg) << ','
        << shortest_number_text(p.heading_sigma_rad[i] / units::kDeg) << ','
        << shortest_number_text(std::sqrt(ss / drift.segments.size()));
    if (mc)
      env << ',' << shortest_number_text(mc->radial_p50_m[i]) << ','
          << shortest_number_text(mc->radial_p68_m[i]) << ','
          << shortest_number_text(mc->radial_p95_m[i]) << ','
          << shortest_number_text(mc->radial_rms_m[i]);
    env << '\n';
  }
  io::write_file_atomically((dir / "drift_envelope.csv").string(), env.str());

  nlohmann::json j;
  j["recording"] = a.file;
  j["model"] = a.model_path;
  j["location"] = {{"latitude_deg", a.location[0]},
                   {"longitude_deg", a.location[1]},
                   {"height_m", a.location[2]},
                   {"given", a.location_given}};
  j["protocol"] = {{"align_s", o.align_s},
                   {"navigation_s", o.navigation_s},
                   {"warmup_s", o.warmup_s},
                   {"segments", drift.segments.size()},
                   {"vertical_channel", "height hold (theory.md §7.2): horizontal errors only"},
                   {"gyro_bias", "estimated over each alignment window and removed (§7.3)"},
                   {"heading", drift.heading_note},
                   {"bias_instability_as_gm", a.gm_convention}};
  j["motion_check"] = {{"stationary", motion.stationary},
                       {"reason", motion.reason},
                       {"forced", a.force && !motion.stationary},
                       {"max_gyro_std_ratio", motion.max_gyro_std_ratio},
                       {"max_accel_std_ratio", motion.max_accel_std_ratio},
                       {"max_force_deviation_m_per_s2", motion.max_force_deviation_m_per_s2},
                       {"max_tilt_change_deg", motion.max_tilt_change_rad / units::kDeg},
                       {"max_rotation_deg_per_s", motion.max_rotation_rad_per_s / units::kDeg}};
  nlohmann::json stats = nlohmann::json::array();
  for (const auto& c : drift.consistency) {
    nlohmann::json s = {{"time_s", c.time_s},
                        {"predicted_north_sigma_m", c.predicted_north_sigma_m},
                        {"predicted_east_sigma_m", c.predicted_east_sigma_m},
                        {"predicted_horizontal_drms_m", c.predicted_drms_m},
                        {"actual_rms_horizontal_error_m", c.actual_rms_m},
                        {"mean_nees", c.mean_nees},
                        {"mean_nees_band_95", {c.nees_band_low, c.nees_band_high}},
                        {"nees_inside_band", c.nees_inside},
                        {"coverage_1_2_3_sigma", c.coverage},
                        {"expected_coverage_1_2_3_sigma", {0.3935, 0.8647, 0.9889}},
                        {"rms_ratio", c.rms_ratio},
                        {"rms_ratio_ci_95", {c.rms_ratio_ci_low, c.rms_ratio_ci_high}}};
    if (mc) {
      const auto i = static_cast<std::size_t>(std::llround(c.time_s / o.output_step_s)) - 1;
      s["monte_carlo_radial_rms_m"] = mc->radial_rms_m[i];
      s["monte_carlo_radial_p95_m"] = mc->radial_p95_m[i];
    }
    stats.push_back(s);
  }
  j["consistency"] = stats;
  if (mc) j["monte_carlo"] = {{"runs", mc->runs}, {"seed", a.seed}};
  io::write_file_atomically((dir / "drift_summary.json").string(), j.dump(2) + "\n");

  std::cout << "drift: " << drift.segments.size() << " segments of "
            << significant_number_text(o.align_s) << " s alignment + "
            << significant_number_text(o.navigation_s) << " s navigation, height hold\n";
  if (!a.location_given)
    std::cout << "location not given: assumed 45 deg N, 0 deg E, 0 m (--location LAT,LON,H)\n";
  std::cout << "heading: " << drift.heading_note << "\n";
  if (!motion.stationary)
    std::cout << "WARNING: not stationary (" << motion.reason << "), forced\n";
  std::cout << "\n  time   predicted DRMS   actual RMS   ratio [95% CI]        mean NEES [95% band]"
               "     coverage 1/2/3 sigma (exp. 39/86/99 %)"
            << (mc ? "   MC RMS" : "") << "\n";
  for (const auto& c : drift.consistency) {
    std::cout << "  " << significant_number_text(c.time_s) << " s   "
              << significant_number_text(c.predicted_drms_m) << " m   "
              << significant_number_text(c.actual_rms_m) << " m   "
              << significant_number_text(c.rms_ratio, 3) << " ["
              << significant_number_text(c.rms_ratio_ci_low, 3) << ", "
              << significant_number_text(c.rms_ratio_ci_high, 3) << "]   "
              << significant_number_text(c.mean_nees, 3) << " ["
              << significant_number_text(c.nees_band_low, 3) << ", "
              << significant_number_text(c.nees_band_high, 3) << "] "
              << (c.nees_inside ? "inside" : "OUTSIDE") << "   "
              << significant_number_text(100 * c.coverage[0], 3) << "/"
              << significant_number_text(100 * c.coverage[1], 3) << "/"
              << significant_number_text(100 * c.coverage[2], 3) << " %";
    if (mc) {
      const auto i = static_cast<std::size_t>(std::llround(c.time_s / o.output_step_s)) - 1;
      std::cout << "   " << significant_number_text(mc->radial_rms_m[i]) << " m";
    }
    std::cout << "\n";
  }
  write_command_file(dir.string());
  const ReportOutput report = write_report(dir.string());
  std::cout << "\nwrote " << (dir / "drift_segments.csv").string()
            << ", drift_envelope.csv, drift_summary.json, plots/\nreport: " << report.html_path
            << "\n";
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
  add_lcm_input_options(*cmd, args->lcm);
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
                  "times for the statistics [s] (default 60,300,600)")
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
  cmd->add_option("-o,--output", args->output, "output directory (created if needed)")->required();
  add_verbosity_options(*cmd, args->verbosity);
  cmd->callback([args, location] {
    args->location_given = location->count() > 0;
    StageTimes times;
    run_drift(*args, times);
    times.mark("outputs");
    print_timings(args->verbosity, "drift", times);
  });
}

}  // namespace imunoise::tools
