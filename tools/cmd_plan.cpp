/// @file
/// @brief `imunoise plan MODEL [--target K:20%,B:10%] [--rate HZ] [--duration D] [-o plan.csv]`:
/// how long to record. From a datasheet model (the simulator's YAML, io/simulation_model.h) or
/// a fitted model.yaml (io/simulation_setup.h reads both), the recording length that
/// identifies each term and that brings each target term's 95 % interval to the target
/// relative half-width (pipeline/recording_plan.h); with --duration the inverse: the expected
/// precision of that recording. Text on stdout (report/plan_text.h), the table in plan.csv
/// (io/recording_plan_csv.h).
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/parallel_for.h"
#include "io/duration_parser.h"
#include "io/recording_plan_csv.h"
#include "io/simulation_setup.h"
#include "pipeline/recording_plan.h"
#include "report/plan_text.h"
#include "tools/commands.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

struct PlanArgs {
  std::string model_path;
  std::string targets;
  double rate_hz = 0.0;
  std::string duration;
  std::string max_duration = "720h";
  std::string output;
  unsigned threads = 0;
  Verbosity verbosity;
};

/// The axes of SETUP that carry noise (an axis with every coefficient 0 has nothing to plan).
std::vector<pipeline::PlanAxis> noisy_axes(const io::SimulationModelFile& setup) {
  std::vector<pipeline::PlanAxis> axes;
  const char* names[] = {"x", "y", "z"};
  for (int sensor = 0; sensor < 2; ++sensor) {
    const auto& list = sensor == 0 ? setup.gyro : setup.accel;
    for (std::size_t k = 0; k < 3; ++k) {
      const NoiseCoefficients& c = list[k].coefficients;
      bool any = !c.gauss_markov.empty() || !c.sinusoids.empty();
      for (NoiseTerm t : kNoiseTerms) any = any || coefficient(c, t) > 0.0;
      if (any) axes.push_back({std::string(sensor == 0 ? "gyro_" : "accel_") + names[k], c});
    }
  }
  return axes;
}

void run_plan(const PlanArgs& args) {
  const io::SimulationModelFile setup = io::load_simulation_setup(args.model_path);
  double rate_hz = args.rate_hz;
  if (rate_hz == 0.0) {
    if (!setup.sample_rate_hz) {
      throw InputError(args.model_path + ": no sample_rate_hz in the model; give --rate HZ");
    }
    rate_hz = *setup.sample_rate_hz;
  }
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw InputError("--rate: expected a rate > 0 Hz, got " + shortest_number_text(rate_hz));
  }
  const std::vector<pipeline::PlanAxis> axes = noisy_axes(setup);
  if (axes.empty()) {
    throw InputError(args.model_path + ": every axis has zero noise; nothing to plan");
  }
  const std::vector<pipeline::PlanTarget> targets =
      pipeline::parse_plan_targets(args.targets, "--target");
  pipeline::RecordingPlanOptions options;
  options.threads = resolve_threads(args.threads);
  options.max_duration_s = io::parse_duration_s(args.max_duration, "--max-duration");
  if (!(options.max_duration_s >= 2.0 * options.min_duration_s)) {
    throw InputError("--max-duration: expected at least 2 min, got " + args.max_duration);
  }
  pipeline::RecordingPlan plan;
  std::string text;
  if (!args.duration.empty()) {
    const double duration_s = io::parse_duration_s(args.duration, "--duration");
    if (!(duration_s * rate_hz >= 16.0)) {
      throw InputError("--duration: " + args.duration + " at " + shortest_number_text(rate_hz) +
                       " Hz is fewer than the 16 samples an analysis needs");
    }
    plan = pipeline::precision_at(axes, rate_hz, duration_s, targets, options);
    text = report::precision_text(plan, args.model_path);
  } else {
    print_info(args.verbosity, "plan", "computing the expected intervals (a few seconds per axis)");
    plan = pipeline::plan_recording(axes, rate_hz, targets, options, "--target");
    text = report::plan_text(plan, args.model_path);
  }
  if (!args.output.empty()) io::write_plan_csv(plan, args.output);
  std::cout << text;
  if (!args.output.empty()) std::cout << "plan.csv: " << args.output << "\n";
}

}  // namespace

void register_plan_command(CLI::App& app) {
  auto args = std::make_shared<PlanArgs>();
  CLI::App* sub = app.add_subcommand(
      "plan",
      "how long to record: the duration that identifies each term and meets each interval "
      "target, or (--duration) the expected precision of a recording");
  sub->add_option("model", args->model_path,
                  "datasheet model (simulator YAML, docs/simulation-model.md) or a fitted "
                  "model.yaml")
      ->required();
  sub->add_option("--target", args->targets,
                  "relative half-width of the 95 % interval per term, e.g. K:20%,B:10% "
                  "(terms Q N B K R)");
  sub->add_option("--rate", args->rate_hz,
                  "sample rate of the recording [Hz] (default: the model's sample_rate_hz)");
  sub->add_option("--duration", args->duration,
                  "instead of planning: the expected precision of a recording this long "
                  "(2h, 30min, 600s)");
  sub->add_option("--max-duration", args->max_duration,
                  "longest duration searched (default 720h = 30 days)");
  sub->add_option("-o,--output", args->output, "also write the plan as CSV (plan.csv)");
  sub->add_option("--threads", args->threads, "worker threads (default 0 = all cores)");
  add_verbosity_options(*sub, args->verbosity);
  sub->callback([args] { run_plan(*args); });
}

}  // namespace imunoise::tools
