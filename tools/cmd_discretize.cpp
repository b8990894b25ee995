/// @file
/// @brief `imunoise discretize`: the state models of a fitted model.yaml and their exact
/// discretization at a step dt (theory.md §6): per-axis sensor error states, or the 15/21-state
/// INS error-state model at a stationary nominal, written as Φ and Q_d (with F, G, Q_c and P₀)
/// to YAML and JSON, every state labelled with its unit.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "ins/error_state_model.h"
#include "ins/noise_from_model.h"
#include "io/discrete_model_file.h"
#include "io/noise_model_yaml.h"
#include "models/filter_parameters.h"
#include "models/state_space.h"
#include "pipeline/sensor_states.h"
#include "tools/commands.h"
#include "tools/gm_convention_option.h"
#include "tools/invocation.h"
#include "tools/verbosity.h"

namespace imunoise::tools {
namespace {

struct DiscretizeArgs {
  std::string model_path;
  double dt_s = 0.0;
  std::string states = "sensor";
  std::string bias = "rw";
  bool conservative = false;
  std::string gm_convention = "peak_match";
  double latitude_deg = 45.0;
  double height_m = 0.0;
  double heading_deg = 0.0;
  bool height_hold = false;
  double gyro_scale_sigma_ppm = 0.0;
  double accel_scale_sigma_ppm = 0.0;
  std::string output;
  Verbosity verbosity;
};

const std::map<std::string, ins::BiasModel> kBiasModels{{"rw", ins::BiasModel::random_walk},
                                                        {"gm", ins::BiasModel::gauss_markov},
                                                        {"both", ins::BiasModel::both}};

/// The note of the file for a term the states leave out, naming the flag that left it out.
std::string dropped_term_note(const pipeline::DroppedTerm& d, bool sensor_states) {
  if (d.kind == pipeline::DroppedTerm::Kind::random_walk)
    return d.axis + ": random walk K not represented (--bias gm)";
  return d.axis + (sensor_states ? ": bias instability / GM terms not represented (--bias rw; "
                                   "use --bias gm or both)"
                                 : ": bias instability / GM not represented (--bias rw)");
}

void run_discretize(const DiscretizeArgs& a) {
  if (!(a.dt_s > 0.0) || !std::isfinite(a.dt_s))
    throw InputError("--dt must be a finite step > 0 s, got " + shortest_number_text(a.dt_s));
  const auto model = io::load_model_yaml(a.model_path);
  models::FilterParameterOptions options;
  options.axis = models::AxisChoice::each;
  options.conservative = a.conservative;
  options.gm_convention = gm_conventions().at(a.gm_convention);
  options.filter_rate_hz = 1.0 / a.dt_s;
  // The messages have always named export's flags, which discretize does not have (it uses
  // each axis's tau of the ADEV minimum); kept so that its errors read as before.
  options.setting_names = {"--axis", "--correction-interval"};
  const ins::BiasModel bias = kBiasModels.at(a.bias);

  const bool sensor = a.states == "sensor";
  pipeline::SensorStates states;
  if (sensor) {
    states = pipeline::sensor_states(model, bias, options, a.dt_s);
  } else {
    ins::InsNoiseOptions noise_options;
    noise_options.conservative = a.conservative;
    noise_options.gm_convention = options.gm_convention;
    noise_options.setting_names = options.setting_names;
    ins::InsSensorNoise noise;
    try {
      noise = ins::ins_sensor_noise(model, noise_options);
    } catch (const InputError& e) {
      throw InputError(a.model_path + ": --states " + a.states + ": " + e.what());
    }
    pipeline::InsStateOptions o;
    o.error_state.scale_factors = a.states == "21";
    o.error_state.bias = bias;
    o.error_state.height_hold = a.height_hold;
    o.latitude_deg = a.latitude_deg;
    o.height_m = a.height_m;
    o.heading_deg = a.heading_deg;
    o.gyro_scale_factor_sigma = a.gyro_scale_sigma_ppm * 1e-6;
    o.accel_scale_factor_sigma = a.accel_scale_sigma_ppm * 1e-6;
    o.dt_s = a.dt_s;
    states = pipeline::ins_states(std::move(noise), o);
  }

  io::DiscreteModelFile file;
  file.discrete = models::discretize(states.continuous, a.dt_s);
  file.source_model = a.model_path;
  file.description = states.description;
  for (const pipeline::DroppedTerm& d : states.dropped)
    file.notes.push_back(dropped_term_note(d, sensor));
  file.conservative = a.conservative;
  file.bias_model = a.bias;
  file.gm_convention = a.gm_convention;
  file.continuous = std::move(states.continuous);
  file.white_noise = std::move(states.white_noise);
  const std::string base = io::write_discrete_model(file, a.output);
  write_command_file(a.output);
  std::cout << base << ".yaml\n" << base << ".json\n";
}

}  // namespace

void register_discretize_command(CLI::App& app) {
  auto args = std::make_shared<DiscretizeArgs>();
  CLI::App* sub = app.add_subcommand(
      "discretize",
      "Exact discrete state models (Phi, Qd) of a fitted model.yaml at a step dt: per-axis "
      "sensor error states, or the 15/21-state INS error state.\n"
      "Example: imunoise discretize out/model.yaml --dt 0.005 --states 15 --bias both -o disc");
  sub->add_option("model", args->model_path, "fitted model.yaml (from imunoise analyze)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--dt", args->dt_s, "step [s]")->required()->check(CLI::PositiveNumber);
  sub->add_option("--states", args->states,
                  "sensor (per-axis error states, default), 15 (INS: attitude, velocity, "
                  "position, accel bias, gyro bias) or 21 (+ scale factors)")
      ->check(CLI::IsMember({"sensor", "15", "21"}));
  sub->add_option("--bias", args->bias,
                  "bias states: rw (random walk K, default), gm (Gauss-Markov: fitted GM terms "
                  "and B as one GM), both (augmented)")
      ->check(CLI::IsMember(kBiasModels));
  sub->add_flag("--conservative", args->conservative, "upper interval ends instead of estimates");
  sub->add_option("--gm-convention", args->gm_convention,
                  "B as one GM (theory.md §4.4): min_adev_at_tau_min, peak_match (default), "
                  "sigma_equals_b")
      ->check(CLI::IsMember(gm_conventions()));
  sub->add_option("--latitude", args->latitude_deg, "INS nominal latitude [deg] (default 45)")
      ->check(CLI::Range(-89.9, 89.9));
  sub->add_option("--height", args->height_m, "INS nominal height [m] (default 0)");
  sub->add_option("--heading", args->heading_deg, "INS nominal heading [deg] (default 0)");
  sub->add_flag("--height-hold", args->height_hold,
                "INS: hold the vertical channel (stationary-analysis convention)");
  sub->add_option("--gyro-scale-sigma-ppm", args->gyro_scale_sigma_ppm,
                  "21 states: gyro scale-factor sigma [ppm] (not observable from a stationary "
                  "record; default 0)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--accel-scale-sigma-ppm", args->accel_scale_sigma_ppm,
                  "21 states: accel scale-factor sigma [ppm] (default 0)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("-o,--output", args->output,
                  "output directory: discrete_model.yaml and discrete_model.json")
      ->required();
  add_verbosity_options(*sub, args->verbosity);
  sub->callback([args] {
    io::StageTimes times;
    run_discretize(*args);
    times.mark("load, discretize and write");
    print_timings(args->verbosity, "discretize", times);
  });
}

}  // namespace imunoise::tools
