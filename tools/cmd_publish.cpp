/// @file
/// @brief `imunoise publish`: a fitted model (model.yaml), and optionally its deviation curves
/// (allan.csv) and drift prediction (drift_envelope.csv), as LCM messages
/// (lcmtypes/imunoise_*.lcm) on a bus.
#include <CLI/CLI.hpp>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/errors.h"
#include "common/units.h"
#include "io/allan_csv.h"
#include "io/drift_files.h"
#include "io/duration_parser.h"
#include "io/lcm_messages.h"
#include "io/noise_model_yaml.h"
#include "io/result_files.h"
#include "pipeline/recording.h"
#include "tools/commands.h"
#include "tools/lcm_bus.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

struct PublishArgs {
  std::string model_path;
  std::string url = kDefaultLcmUrl;
  std::string model_channel = "NOISE_MODEL";
  std::string curves_path;
  std::string curves_channel = "ALLAN_CURVE";
  std::string drift_path;
  std::string drift_channel = "DRIFT_PREDICTION";
  int repeat = 1;
  std::string interval = "1s";
  Verbosity verbosity;
};

void run_publish(const PublishArgs& args) {
  if (args.repeat < 1) throw InputError("--repeat: expected at least 1");
  const double interval_s = io::parse_duration_s(args.interval, "--interval", true);
  // Read everything before opening the bus: a bad file publishes nothing.
  const models::NoiseModel model = io::load_model_yaml(args.model_path);
  std::vector<std::pair<std::string, analysis::DeviationCurve>> curves;  // axis, curve
  if (!args.curves_path.empty()) {
    for (io::AllanAxis& a : io::read_allan_csv(args.curves_path, model.confidence).axes) {
      curves.emplace_back(a.name, std::move(a.oadev));
      curves.emplace_back(a.name, std::move(a.ohdev));
    }
  }
  std::optional<pipeline::DriftSeries> drift;
  if (!args.drift_path.empty()) drift = io::read_drift_envelope_csv(args.drift_path);

  LcmBus bus(args.url);
  for (int k = 0; k < args.repeat; ++k) {
    if (k > 0) std::this_thread::sleep_for(std::chrono::duration<double>(interval_s));
    const std::int64_t utime = now_utime_us();
    bus.publish(args.model_channel, io::noise_model_message(model, utime));
    for (const auto& [axis_name, curve] : curves) {
      bus.publish(args.curves_channel, io::allan_curve_message(axis_name, curve, utime));
    }
    if (drift) bus.publish(args.drift_channel, io::drift_prediction_message(*drift, utime));
  }
  std::cout << "published " << args.model_path << " on '" << args.model_channel << "'";
  if (!curves.empty()) {
    std::cout << ", " << curves.size() << " curves on '" << args.curves_channel << "'";
  }
  if (drift) std::cout << ", the drift prediction on '" << args.drift_channel << "'";
  std::cout << " (" << args.repeat << (args.repeat == 1 ? " time" : " times") << ", " << args.url
            << ")\n";
}

}  // namespace

void register_publish_command(CLI::App& app) {
  auto args = std::make_shared<PublishArgs>();
  CLI::App* cmd = app.add_subcommand(
      "publish",
      "Publish a fitted model (imunoise.noise_model_t), and optionally its Allan curves "
      "(imunoise.allan_curve_t) and drift prediction (imunoise.drift_prediction_t), on LCM");
  cmd->add_option("MODEL", args->model_path, "model.yaml written by 'imunoise analyze'")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--lcm-url", args->url, "LCM provider URL")->capture_default_str();
  cmd->add_option("--channel", args->model_channel, "channel of the noise model")
      ->capture_default_str();
  cmd->add_option("--curves", args->curves_path,
                  "allan.csv of the same analysis: publish each axis's OADEV and OHDEV")
      ->check(CLI::ExistingFile);
  cmd->add_option("--curves-channel", args->curves_channel, "channel of the curves")
      ->capture_default_str();
  cmd->add_option("--drift", args->drift_path,
                  "drift_envelope.csv written by 'imunoise drift': publish the prediction")
      ->check(CLI::ExistingFile);
  cmd->add_option("--drift-channel", args->drift_channel, "channel of the drift prediction")
      ->capture_default_str();
  cmd->add_option("--repeat", args->repeat, "publish N times (for late subscribers)")
      ->capture_default_str();
  cmd->add_option("--interval", args->interval, "time between repeats (e.g. 1s, 500ms is 0.5s)")
      ->capture_default_str();
  cmd->footer(
      "Examples:\n"
      "  imunoise publish out/model.yaml\n"
      "  imunoise publish out/model.yaml --curves out/allan.csv --lcm-url "
      "'udpm://239.255.76.67:7667?ttl=0'\n"
      "  imunoise publish out/model.yaml --lcm-url 'file:///tmp/model.lcmlog?mode=w'\n"
      "Subscribers decode with the generated type of lcmtypes/imunoise_noise_model_t.lcm "
      "(README: LCM).");
  add_verbosity_options(*cmd, args->verbosity);
  cmd->callback([args] {
    io::StageTimes times;
    run_publish(*args);
    times.mark("load and publish");
    print_timings(args->verbosity, "publish", times);
  });
}

}  // namespace imunoise::tools
