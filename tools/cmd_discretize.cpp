/// @file
/// @brief `imunoise discretize`: the state models of a fitted model.yaml and their exact
/// discretization at a step dt (theory.md §6): per-axis sensor error states, or the 15/21-state
/// INS error-state model at a stationary nominal, written as Φ and Q_d (with F, G, Q_c and P₀)
/// to YAML and JSON, every state labelled with its unit.
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
#include "ins/error_state_model.h"
#include "ins/noise_from_model.h"
#include "io/atomic_output.h"
#include "io/noise_model_yaml.h"
#include "models/filter_parameters.h"
#include "models/state_space.h"
#include "pipeline/recording.h"
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

/// Renames the states of BLOCK: NAME → NAME_UNIT (state_space labels carry no unit).
models::ContinuousStateModel with_units(models::ContinuousStateModel block,
                                        const std::vector<std::string>& units) {
  for (std::size_t i = 0; i < block.state_names.size() && i < units.size(); ++i)
    block.state_names[i] += "_" + units[i];
  return block;
}

/// White-noise lines reported beside the states (white noise is an input, not a state).
struct WhiteNoise {
  std::string axis;
  double density = 0.0;  ///< N [rad/√s | m/s/√s]
  bool gyro = true;
};

/// Per-axis sensor error states of every axis (theory.md §6.1): RW bias, GM biases (fitted
/// GM terms and B as one GM by the convention), ramp [bias, slope].
models::ContinuousStateModel sensor_states(const models::NoiseModel& model, const DiscretizeArgs& a,
                                           const models::FilterParameterOptions& options,
                                           std::vector<WhiteNoise>& white,
                                           std::vector<std::string>& notes) {
  std::vector<models::ContinuousStateModel> blocks;
  const bool rw = a.bias != "gm", gm = a.bias != "rw";
  for (const auto& axis : model.axes) {
    const auto p = models::axis_filter_parameters(axis, options);
    const std::string rate_unit = axis.gyro ? "rad_per_s" : "m_per_s2";
    const std::string ramp_unit = axis.gyro ? "rad_per_s2" : "m_per_s3";
    white.push_back({axis.name, p.white_noise, axis.gyro});
    if (rw && p.random_walk > 0.0)
      blocks.push_back(with_units(models::random_walk_state(p.random_walk, axis.name + "_bias_rw"),
                                  {rate_unit}));
    if (!rw && p.random_walk > 0.0)
      notes.push_back(axis.name + ": random walk K not represented (--bias gm)");
    if (gm) {
      for (std::size_t j = 0; j < axis.gauss_markov.size(); ++j) {
        const auto& g = axis.gauss_markov[j].value;
        const double sigma =
            a.conservative ? std::max(g.sigma, axis.gauss_markov[j].sigma_ci_high) : g.sigma;
        blocks.push_back(
            with_units(models::gauss_markov_state(sigma, g.tau_c_s,
                                                  axis.name + "_bias_gm" + std::to_string(j + 1)),
                       {rate_unit}));
      }
      if (p.bias_instability > 0.0)
        blocks.push_back(with_units(models::gauss_markov_state(p.bias_gm.sigma, p.bias_gm.tau_c_s,
                                                               axis.name + "_bias_instability_gm"),
                                    {rate_unit}));
    } else if (p.bias_instability > 0.0 || !axis.gauss_markov.empty()) {
      notes.push_back(axis.name +
                      ": bias instability / GM terms not represented (--bias rw; "
                      "use --bias gm or both)");
    }
    if (p.ramp > 0.0)
      blocks.push_back(
          with_units(models::ramp_state(p.ramp, axis.name + "_ramp"), {rate_unit, ramp_unit}));
  }
  return models::block_diagonal(blocks);
}

/// Notes for the terms of one INS axis that BIAS cannot carry (ins_error_state_model drops them).
void note_dropped_terms(const ins::SensorAxisNoise& n, ins::BiasModel bias, const std::string& name,
                        std::vector<std::string>& notes) {
  if (bias == ins::BiasModel::random_walk && n.bias_gm.sigma > 0.0)
    notes.push_back(name + ": bias instability / GM not represented (--bias rw)");
  if (bias == ins::BiasModel::gauss_markov && n.random_walk > 0.0)
    notes.push_back(name + ": random walk K not represented (--bias gm)");
}

nlohmann::json matrix_json(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}

std::string matrix_yaml(const Eigen::MatrixXd& m, const std::string& indent) {
  if (m.rows() == 0) return " []\n";
  std::ostringstream out;
  out << "\n";
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    out << indent << "- [";
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      out << (c ? ", " : "") << shortest_number_text(m(r, c));
    out << "]\n";
  }
  return out.str();
}

std::string names_yaml(const std::vector<std::string>& names) {
  std::string s = "[";
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s + "]";
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

  std::vector<WhiteNoise> white;
  std::vector<std::string> notes;
  models::ContinuousStateModel continuous;
  std::string description;
  if (a.states == "sensor") {
    continuous = sensor_states(model, a, options, white, notes);
    description = "per-axis sensor error states (theory.md §6.1); white noise is an input";
  } else {
    ins::InsNoiseOptions noise_options;
    noise_options.conservative = a.conservative;
    noise_options.gm_convention = options.gm_convention;
    ins::InsSensorNoise noise;
    try {
      noise = ins::ins_sensor_noise(model, noise_options);
    } catch (const InputError& e) {
      throw InputError(a.model_path + ": --states " + a.states + ": " + e.what());
    }
    const auto bias = kBiasModels.at(a.bias);
    for (int i = 0; i < 3; ++i) {
      noise.gyro[i].scale_factor_sigma = a.gyro_scale_sigma_ppm * 1e-6;
      noise.accel[i].scale_factor_sigma = a.accel_scale_sigma_ppm * 1e-6;
      note_dropped_terms(noise.gyro[i], bias, pipeline::kImuChannelNames[i], notes);
      note_dropped_terms(noise.accel[i], bias, pipeline::kImuChannelNames[3 + i], notes);
    }
    for (int i = 0; i < 3; ++i)
      white.push_back({pipeline::kImuChannelNames[i], noise.gyro[i].white_noise, true});
    for (int i = 0; i < 3; ++i)
      white.push_back({pipeline::kImuChannelNames[3 + i], noise.accel[i].white_noise, false});
    ins::ErrorStateOptions o;
    o.scale_factors = a.states == "21";
    o.bias = bias;
    o.height_hold = a.height_hold;
    const auto nominal = ins::stationary_nominal(a.latitude_deg * units::kDeg, a.height_m,
                                                 a.heading_deg * units::kDeg);
    continuous = ins::ins_error_state_model(nominal, noise, o);
    description = "INS error state (theory.md §6.3, §7.4), stationary at latitude " +
                  shortest_number_text(a.latitude_deg) + " deg, height " +
                  shortest_number_text(a.height_m) + " m, heading " +
                  shortest_number_text(a.heading_deg) + " deg" +
                  (a.height_hold ? ", vertical channel held" : "");
  }
  const auto discrete = models::discretize(continuous, a.dt_s);

  // YAML: the same content as the JSON, with a comment header for people.
  std::ostringstream y;
  y << "# imunoise discrete state model from " << a.model_path << "\n";
  y << "# " << description << "\n";
  y << "# x_{k+1} = phi x_k + w_k, cov(w_k) = qd; continuous xdot = F x + G w, E[w w'] = Qc "
       "delta\n";
  y << "# discretization: " << discrete.method << " (exact: Van Loan, theory.md §6.2)\n";
  y << "# values: " << (a.conservative ? "conservative (upper interval ends)" : "best estimates")
    << "; bias model: " << a.bias << "; B as GM by convention " << a.gm_convention << "\n";
  for (const auto& n : notes) y << "# note: " << n << "\n";
  y << "# " << discrete.state_names.size() << " states\n";
  y << "format: imunoise-discrete-model\nformat_version: 1\n";
  y << "source_model: \"" << a.model_path << "\"\n";
  y << "dt_s: " << shortest_number_text(a.dt_s) << "\n";
  y << "states: " << names_yaml(discrete.state_names) << "\n";
  y << "noises: " << names_yaml(continuous.noise_names) << "\n";
  y << "phi:" << matrix_yaml(discrete.Phi, "  ");
  y << "qd:" << matrix_yaml(discrete.Qd, "  ");
  y << "initial_variance: [";
  for (Eigen::Index i = 0; i < continuous.initial_variance.size(); ++i)
    y << (i ? ", " : "") << shortest_number_text(continuous.initial_variance(i));
  y << "]\n";
  y << "continuous:\n  F:" << matrix_yaml(continuous.F, "    ");
  y << "  G:" << matrix_yaml(continuous.G, "    ");
  y << "  Qc:" << matrix_yaml(continuous.Qc, "    ");
  y << "white_noise:  # inputs, not states: per-sample sigma for rates and for increments\n";
  nlohmann::json white_json = nlohmann::json::array();
  for (const auto& w : white) {
    const std::string u = w.gyro ? "rad" : "m_per_s";
    const double rate_sigma = models::white_noise_rate_sigma(w.density, a.dt_s);
    const double increment_sigma = models::white_noise_increment_sigma(w.density, a.dt_s);
    y << "  - {axis: " << w.axis << ", density_" << (w.gyro ? "rad_per_sqrt_s" : "m_per_s_sqrt_s")
      << ": " << shortest_number_text(w.density) << ", rate_sigma_"
      << (w.gyro ? "rad_per_s" : "m_per_s2") << ": " << shortest_number_text(rate_sigma)
      << ", increment_sigma_" << u << ": " << shortest_number_text(increment_sigma) << "}\n";
    white_json.push_back({{"axis", w.axis},
                          {w.gyro ? "density_rad_per_sqrt_s" : "density_m_per_s_sqrt_s", w.density},
                          {w.gyro ? "rate_sigma_rad_per_s" : "rate_sigma_m_per_s2", rate_sigma},
                          {"increment_sigma_" + u, increment_sigma}});
  }
  nlohmann::json j;
  j["format"] = "imunoise-discrete-model";
  j["format_version"] = 1;
  j["source_model"] = a.model_path;
  j["description"] = description;
  j["discretization"] = discrete.method;
  j["notes"] = notes;
  j["dt_s"] = a.dt_s;
  j["states"] = discrete.state_names;
  j["noises"] = continuous.noise_names;
  j["phi"] = matrix_json(discrete.Phi);
  j["qd"] = matrix_json(discrete.Qd);
  j["initial_variance"] =
      std::vector<double>(continuous.initial_variance.data(),
                          continuous.initial_variance.data() + continuous.initial_variance.size());
  j["continuous"] = {{"F", matrix_json(continuous.F)},
                     {"G", matrix_json(continuous.G)},
                     {"Qc", matrix_json(continuous.Qc)}};
  j["white_noise"] = white_json;

  std::error_code ec;
  std::filesystem::create_directories(a.output, ec);
  if (ec) throw InputError(a.output + ": cannot create the directory: " + ec.message());
  const auto base = std::filesystem::path(a.output) / "discrete_model";
  io::write_file_atomically(base.string() + ".yaml", y.str());
  io::write_file_atomically(base.string() + ".json", j.dump(2) + "\n");
  write_command_file(a.output);
  std::cout << base.string() << ".yaml\n" << base.string() << ".json\n";
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
    StageTimes times;
    run_discretize(*args);
    times.mark("load, discretize and write");
    print_timings(args->verbosity, "discretize", times);
  });
}

}  // namespace imunoise::tools
