/// @file
/// @brief `imunoise simulate`: the flags of a synthetic stationary IMU recording from a YAML
/// noise model or a fitted model.yaml (io/simulation_setup.h; keys in datasheet units,
/// docs/simulation-model.md) and/or per-term flags; io/simulation_output.h generates and
/// writes it (CSV, LCM log or binary).
#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/units.h"
#include "io/duration_parser.h"
#include "io/simulation_output.h"
#include "io/simulation_setup.h"
#include "io/terminal_progress_bar.h"
#include "models/noise_simulator.h"
#include "tools/commands.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

/// Everything `simulate` needs, after the model file and the flags are merged; `source` is the
/// model file, or "command-line flags" without one.
using SimulationSetup = io::SimulationModelFile;

/// Command-line values, in the units their flag names state.
struct SimulateArgs {
  std::string model_path;
  std::string duration = "";
  double rate_hz = 0.0;
  std::uint64_t seed = 1;
  std::string output;
  std::string lcm_channel = "IMU";
  double gyro_arw_deg_per_sqrt_h = 0.0;
  double gyro_bias_instability_deg_per_h = 0.0;
  double gyro_rrw_deg_per_h_per_sqrt_h = 0.0;
  double gyro_bias_deg_per_h = 0.0;
  double gyro_lsb_deg_per_s = 0.0;
  double accel_vrw_m_per_s_per_sqrt_h = 0.0;
  double accel_vrw_ug_per_sqrt_hz = 0.0;
  double accel_bias_instability_ug = 0.0;
  double accel_rw_m_per_s_per_h_per_sqrt_h = 0.0;
  double accel_bias_mg = 0.0;
  double accel_lsb_mg = 0.0;
  std::vector<double> specific_force_m_per_s2;
  Verbosity verbosity;
  /// Options whose presence decides whether they override the model file.
  std::vector<std::pair<CLI::Option*, std::function<void(SimulationSetup&)>>> overrides;
};

/// CLI11 validator: a finite number, optionally required to be > 0 or ≥ 0 (CLI11's own range
/// validators print the full double range in their message).
CLI::Validator number_check(bool strictly_positive) {
  return CLI::Validator(
      [strictly_positive](std::string& text) -> std::string {
        double value = 0.0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, value);
        if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
          return "expected a finite number, got '" + text + "'";
        }
        if (strictly_positive && !(value > 0.0)) return "must be > 0, got " + text;
        if (!strictly_positive && value < 0.0) return "must be >= 0, got " + text;
        return {};
      },
      strictly_positive ? "NUMBER>0" : "NUMBER>=0");
}

/// TIMES gets the wall time of the set-up and of generating + writing.
void run_simulate(const SimulateArgs& args, io::StageTimes& times) {
  // 1. Load and merge; every check happens before the output file is opened.
  SimulationSetup setup;
  setup.source = "command-line flags";
  if (!args.model_path.empty()) {
    setup = io::load_simulation_setup(args.model_path);
  }
  for (const auto& [option, apply] : args.overrides) {
    if (option->count() > 0) apply(setup);
  }
  const double duration_s = io::parse_duration_s(args.duration, "--duration");
  double rate_hz = args.rate_hz;
  if (rate_hz == 0.0) {
    if (!setup.sample_rate_hz) {
      throw InputError("--rate is required (the model file has no sample_rate_hz)");
    }
    rate_hz = *setup.sample_rate_hz;
  }
  const double count = std::round(duration_s * rate_hz);
  if (!(count >= 1.0) || count > 1e11) {
    throw InputError("--duration × --rate gives " + shortest_number_text(count) +
                     " samples; expected 1 to 1e11");
  }
  const io::SimulationRun run =
      io::simulation_run(setup, rate_hz, duration_s, static_cast<std::int64_t>(count), args.seed);
  models::ImuSimulator simulator = io::make_simulator(setup, run);
  times.mark("setup");

  // 2. Generate and write block by block: memory stays constant for any duration.
  io::ProgressBar bar("simulate", progress_wanted(args.verbosity));
  io::write_simulation(simulator, setup, run, args.output, args.lcm_channel, bar.callback());
  bar.finish();
  times.mark("generate and write");
  std::cout << "imunoise simulate: wrote " << run.samples << " samples ("
            << shortest_number_text(duration_s) << " s at " << shortest_number_text(rate_hz)
            << " Hz, seed " << args.seed << ") to " << args.output << "\n";
}

}  // namespace

void register_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* sub = app.add_subcommand("simulate",
                                     "Simulate a stationary IMU recording (CSV, LCM log or .imnb "
                                     "binary, SI units) from a YAML noise model and/or "
                                     "per-term flags. Deterministic for a seed.");
  sub->add_option("model", args->model_path,
                  "YAML noise model (each key names its unit; see configs/demo_imu.yaml and "
                  "docs/simulation-model.md)")
      ->check(CLI::ExistingFile);
  sub->add_option("--duration", args->duration, "record length with unit: 2h, 30min, 600s")
      ->required();
  sub->add_option("--rate", args->rate_hz, "sample rate [Hz] (default: the model's sample_rate_hz)")
      ->check(number_check(true));
  sub->add_option("--seed", args->seed, "random seed (default 1)");
  sub->add_option("-o,--output", args->output,
                  "output file: CSV; an LCM log of imunoise.imu_sample_t when it ends in "
                  ".lcmlog (as lcm-logger writes; replay with lcm-logplayer); an imunoise binary "
                  "recording when it ends in .imnb (docs/binary-format.md)")
      ->required();
  sub->add_option("--lcm-channel", args->lcm_channel, "channel of the samples in a .lcmlog output")
      ->capture_default_str();

  // Per-term flags: human units at the edge, converted once here (common/units.h); each one
  // sets that term on all three axes, overriding the model file.
  const auto add_term = [&](const std::string& flag, double& value, const std::string& help,
                            std::function<void(SimulationSetup&, double)> apply,
                            bool may_be_negative = false) {
    CLI::Option* option = sub->add_option(flag, value, help);
    if (!may_be_negative) option->check(number_check(false));
    args->overrides.emplace_back(option, [&value, apply](SimulationSetup& s) { apply(s, value); });
    return option;
  };
  // A field of a SimulationAxis, as a captureless lambda.
  using AxisField = double& (*)(io::SimulationAxis&);
  const AxisField white = [](io::SimulationAxis& a) -> double& {
    return a.coefficients.white_noise;
  };
  const AxisField bias_instability = [](io::SimulationAxis& a) -> double& {
    return a.coefficients.bias_instability;
  };
  const AxisField random_walk = [](io::SimulationAxis& a) -> double& {
    return a.coefficients.random_walk;
  };
  const AxisField bias = [](io::SimulationAxis& a) -> double& { return a.bias; };
  const AxisField output_lsb = [](io::SimulationAxis& a) -> double& { return a.output_lsb; };
  const auto all_gyro = [](AxisField field, double factor) {
    return [field, factor](SimulationSetup& s, double v) {
      for (auto& axis : s.gyro) field(axis) = v * factor;
    };
  };
  const auto all_accel = [](AxisField field, double factor) {
    return [field, factor](SimulationSetup& s, double v) {
      for (auto& axis : s.accel) field(axis) = v * factor;
    };
  };
  add_term("--gyro-arw-deg-per-sqrt-h", args->gyro_arw_deg_per_sqrt_h, "gyro ARW N [deg/√h]",
           all_gyro(white, units::kDegPerSqrtHour));
  add_term("--gyro-bias-instability-deg-per-h", args->gyro_bias_instability_deg_per_h,
           "gyro bias instability B [deg/h] (ADEV floor 0.664·B)",
           all_gyro(bias_instability, units::kDegPerHour));
  add_term("--gyro-rrw-deg-per-h-per-sqrt-h", args->gyro_rrw_deg_per_h_per_sqrt_h,
           "gyro rate random walk K [deg/h/√h]",
           all_gyro(random_walk, units::kDegPerHourPerSqrtHour));
  add_term("--gyro-bias-deg-per-h", args->gyro_bias_deg_per_h, "gyro constant bias [deg/h]",
           all_gyro(bias, units::kDegPerHour), true);
  add_term("--gyro-lsb-deg-per-s", args->gyro_lsb_deg_per_s,
           "gyro output quantizer step [deg/s] (0 = off)", all_gyro(output_lsb, units::kDegPerS));
  CLI::Option* vrw_h =
      add_term("--accel-vrw-m-per-s-per-sqrt-h", args->accel_vrw_m_per_s_per_sqrt_h,
               "accel velocity random walk N [m/s/√h]", all_accel(white, units::kMPerSPerSqrtHour));
  CLI::Option* vrw_hz = add_term("--accel-vrw-ug-per-sqrt-hz", args->accel_vrw_ug_per_sqrt_hz,
                                 "accel VRW N as a two-sided density [µg/√Hz]",
                                 all_accel(white, units::kMicroGPerSqrtHz));
  vrw_h->excludes(vrw_hz);
  add_term("--accel-bias-instability-ug", args->accel_bias_instability_ug,
           "accel bias instability B [µg]", all_accel(bias_instability, units::kMicroG));
  add_term("--accel-rw-m-per-s-per-h-per-sqrt-h", args->accel_rw_m_per_s_per_h_per_sqrt_h,
           "accel random walk K [(m/s/h)/√h]",
           all_accel(random_walk, units::kMPerSPerHourPerSqrtHour));
  add_term("--accel-bias-mg", args->accel_bias_mg, "accel constant bias [mg]",
           all_accel(bias, units::kMilliG), true);
  add_term("--accel-lsb-mg", args->accel_lsb_mg, "accel output quantizer step [mg] (0 = off)",
           all_accel(output_lsb, units::kMilliG));
  CLI::Option* force =
      sub->add_option("--specific-force-m-per-s2", args->specific_force_m_per_s2,
                      "true specific force X,Y,Z [m/s²], e.g. 0,0,-9.80665 for a level FRD IMU")
          ->expected(3)
          ->delimiter(',');
  args->overrides.emplace_back(force, [a = args.get()](SimulationSetup& s) {
    for (std::size_t i = 0; i < 3; ++i) s.accel[i].signal = a->specific_force_m_per_s2[i];
  });

  sub->footer(
      "Per-term flags (units in their names) set that term on all three axes of the sensor,\n"
      "overriding the model file. Output: a '#' header with the model and seed, then columns\n"
      "time_s,gyro_x_rad_per_s,...,accel_z_m_per_s2 (SI).\n"
      "Examples:\n"
      "  imunoise simulate configs/demo_imu.yaml --duration 2h --rate 100 --seed 7 -o rec.csv\n"
      "  imunoise simulate --duration 30min --rate 200 --gyro-arw-deg-per-sqrt-h 0.4 \\\n"
      "      --gyro-bias-instability-deg-per-h 25 --specific-force-m-per-s2 0,0,-9.80665 \\\n"
      "      -o rec.csv\n");
  add_verbosity_options(*sub, args->verbosity);
  sub->callback([args] {
    io::StageTimes times;
    run_simulate(*args, times);
    print_timings(args->verbosity, "simulate", times);
  });
}

}  // namespace imunoise::tools
