/// @file
/// @brief `imunoise simulate`: a synthetic stationary IMU recording (CSV, SI units) from a
/// YAML noise model and/or per-term flags, generated in blocks (constant memory).
///
/// Model file schema (every key carries its unit; unknown keys are errors):
/// @code{.yaml}
/// name: demo consumer MEMS IMU        # optional, echoed in the CSV header
/// sample_rate_hz: 100                 # optional default for --rate
/// flicker_band_s: [0.01, 7200]        # optional; default [1/rate, duration]
/// gyro:                               # terms shared by x, y, z ...
///   arw_rad_per_sqrt_s: 1.16355e-4
///   bias_instability_rad_per_s: 1.22173e-4
///   rrw_rad_per_s_sqrt_s: 6.80678e-6
///   gauss_markov: [{sigma_rad_per_s: 1e-4, tau_c_s: 30}]
///   x: {bias_rad_per_s: 2e-3}         # ... and per-axis overrides
/// accel:
///   vrw_m_per_s_sqrt_s: 1.471e-3
///   z: {specific_force_m_per_s2: -9.80665}
/// @endcode
/// The term keys of each sensor are listed in kGyroKeys / kAccelKeys below.
#include <yaml-cpp/yaml.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/units.h"
#include "io/atomic_output.h"
#include "models/noise_simulator.h"
#include "tools/commands.h"

namespace imunoise::tools {

namespace {

/// One axis as written in the model file; bias and true signal are both folded into
/// ChannelNoiseModel::constant at the end.
struct AxisSpec {
  double quantization = 0.0;
  double white_noise = 0.0;
  double bias_instability = 0.0;
  double random_walk = 0.0;
  double ramp = 0.0;
  double bias = 0.0;
  double signal = 0.0;
  double output_lsb = 0.0;
  std::vector<models::GaussMarkovTerm> gauss_markov;
  std::vector<models::SinusoidTerm> sinusoids;
};

/// A scalar term key: its name in the file, the field it sets, and whether it may be < 0.
struct ScalarKey {
  std::string_view name;
  double AxisSpec::*field;
  bool signed_value;
};

/// Key names of one sensor (they differ only in units).
struct SensorKeys {
  std::string_view sensor;  ///< "gyro" or "accel"
  std::array<ScalarKey, 8> scalars;
  std::string_view gm_sigma;        ///< key of σ inside a gauss_markov item
  std::string_view sine_amplitude;  ///< key of the amplitude inside a sinusoids item
};

constexpr SensorKeys kGyroKeys{"gyro",
                               {{{"quantization_rad", &AxisSpec::quantization, false},
                                 {"arw_rad_per_sqrt_s", &AxisSpec::white_noise, false},
                                 {"bias_instability_rad_per_s", &AxisSpec::bias_instability, false},
                                 {"rrw_rad_per_s_sqrt_s", &AxisSpec::random_walk, false},
                                 {"ramp_rad_per_s2", &AxisSpec::ramp, true},
                                 {"bias_rad_per_s", &AxisSpec::bias, true},
                                 {"angular_rate_rad_per_s", &AxisSpec::signal, true},
                                 {"output_lsb_rad_per_s", &AxisSpec::output_lsb, false}}},
                               "sigma_rad_per_s",
                               "amplitude_rad_per_s"};

constexpr SensorKeys kAccelKeys{"accel",
                                {{{"quantization_m_per_s", &AxisSpec::quantization, false},
                                  {"vrw_m_per_s_sqrt_s", &AxisSpec::white_noise, false},
                                  {"bias_instability_m_per_s2", &AxisSpec::bias_instability, false},
                                  {"rw_m_per_s2_sqrt_s", &AxisSpec::random_walk, false},
                                  {"ramp_m_per_s3", &AxisSpec::ramp, true},
                                  {"bias_m_per_s2", &AxisSpec::bias, true},
                                  {"specific_force_m_per_s2", &AxisSpec::signal, true},
                                  {"output_lsb_m_per_s2", &AxisSpec::output_lsb, false}}},
                                "sigma_m_per_s2",
                                "amplitude_m_per_s2"};

constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};

/// Everything `simulate` needs, after the model file and the flags are merged.
struct SimulationSetup {
  std::string model_source = "command-line flags";
  std::string name;
  std::optional<double> sample_rate_hz;
  std::optional<std::array<double, 2>> flicker_band_s;
  std::array<AxisSpec, 3> gyro;
  std::array<AxisSpec, 3> accel;
};

std::string number_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// Reads a YAML model file with located, key-naming errors.
class ModelReader {
 public:
  explicit ModelReader(std::string path) : path_(std::move(path)) {}

  SimulationSetup read() {
    try {
      return read_root();
    } catch (const YAML::Exception& e) {  // e.g. a key that is not a scalar
      throw InputError(located_message(path_, e.mark.line + 1, e.mark.column + 1, e.msg));
    }
  }

 private:
  SimulationSetup read_root() {
    YAML::Node root;
    try {
      root = YAML::LoadFile(path_);
    } catch (const YAML::BadFile&) {
      throw InputError(located_message(path_, 0, 0, "cannot open the model file"));
    } catch (const YAML::Exception& e) {
      throw InputError(
          located_message(path_, e.mark.line + 1, e.mark.column + 1, "YAML syntax: " + e.msg));
    }
    SimulationSetup setup;
    setup.model_source = path_;
    if (!root.IsMap()) fail(root, "model", "expected a mapping of keys (name, gyro, accel, …)");
    for (const auto& entry : root) {
      const std::string key = key_text(entry.first, "model");
      const YAML::Node& value = entry.second;
      if (key == "name") {
        if (!value.IsScalar()) fail(value, key, "expected a string");
        setup.name = value.Scalar();
        std::replace(setup.name.begin(), setup.name.end(), '\n', ' ');  // one header line
      } else if (key == "sample_rate_hz") {
        setup.sample_rate_hz = positive(value, key);
      } else if (key == "flicker_band_s") {
        if (!value.IsSequence() || value.size() != 2) {
          fail(value, key, "expected [tau_min_s, tau_max_s]");
        }
        const double low = positive(value[0], key + "[0]");
        const double high = positive(value[1], key + "[1]");
        if (!(high > low)) fail(value, key, "expected tau_min_s < tau_max_s");
        setup.flicker_band_s = std::array<double, 2>{low, high};
      } else if (key == "gyro") {
        read_sensor(value, kGyroKeys, setup.gyro);
      } else if (key == "accel") {
        read_sensor(value, kAccelKeys, setup.accel);
      } else {
        fail(entry.first, key,
             "unknown key (expected name, sample_rate_hz, flicker_band_s, gyro, accel)");
      }
    }
    return setup;
  }

  /// The text of a mapping key, which must be a plain scalar.
  std::string key_text(const YAML::Node& key, const std::string& where) const {
    if (!key.IsScalar()) fail(key, where, "keys must be plain names");
    return key.Scalar();
  }

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key,
                         const std::string& what) const {
    const YAML::Mark mark = node.Mark();
    throw InputError(located_message(path_, mark.line + 1, mark.column + 1, key + ": " + what));
  }

  double number(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, key, "expected a number");
    const std::string& text = node.Scalar();
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
      fail(node, key, "expected a finite number, got '" + text + "'");
    }
    return value;
  }

  double non_negative(const YAML::Node& node, const std::string& key) const {
    const double value = number(node, key);
    if (value < 0.0) fail(node, key, "must be >= 0, got " + node.Scalar());
    return value;
  }

  double positive(const YAML::Node& node, const std::string& key) const {
    const double value = number(node, key);
    if (!(value > 0.0)) fail(node, key, "must be > 0, got " + node.Scalar());
    return value;
  }

  void read_sensor(const YAML::Node& node, const SensorKeys& keys, std::array<AxisSpec, 3>& axes) {
    const std::string where(keys.sensor);
    if (!node.IsMap()) fail(node, where, "expected a mapping of term keys");
    AxisSpec shared;
    read_terms(node, keys, where, shared, true);
    for (std::size_t a = 0; a < 3; ++a) {
      axes[a] = shared;
      const YAML::Node axis = node[std::string(kAxes[a])];
      if (!axis) continue;
      const std::string axis_where = where + "." + std::string(kAxes[a]);
      if (!axis.IsMap()) fail(axis, axis_where, "expected a mapping of term keys");
      read_terms(axis, keys, axis_where, axes[a], false);
    }
  }

  /// Sets the terms present in NODE on SPEC (later keys override earlier values).
  void read_terms(const YAML::Node& node, const SensorKeys& keys, const std::string& where,
                  AxisSpec& spec, bool allow_axes) {
    for (const auto& entry : node) {
      const std::string key = key_text(entry.first, where);
      const std::string path = where + "." + key;
      const YAML::Node& value = entry.second;
      if (allow_axes && (key == "x" || key == "y" || key == "z")) continue;
      bool found = false;
      for (const ScalarKey& scalar : keys.scalars) {
        if (key == scalar.name) {
          spec.*scalar.field =
              scalar.signed_value ? number(value, path) : non_negative(value, path);
          found = true;
        }
      }
      if (found) continue;
      if (key == "gauss_markov") {
        spec.gauss_markov = read_list<models::GaussMarkovTerm>(
            value, path, {std::string(keys.gm_sigma), "tau_c_s"},
            [&](const YAML::Node& item, const std::string& item_path) {
              const std::string sigma_key(keys.gm_sigma);
              return models::GaussMarkovTerm{
                  non_negative(required(item, sigma_key, item_path), item_path + "." + sigma_key),
                  positive(required(item, "tau_c_s", item_path), item_path + ".tau_c_s")};
            });
      } else if (key == "sinusoids") {
        spec.sinusoids = read_list<models::SinusoidTerm>(
            value, path, {std::string(keys.sine_amplitude), "frequency_hz", "phase_rad"},
            [&](const YAML::Node& item, const std::string& item_path) {
              const std::string amplitude_key(keys.sine_amplitude);
              models::SinusoidTerm term;
              term.amplitude =
                  number(required(item, amplitude_key, item_path), item_path + "." + amplitude_key);
              term.frequency_hz = non_negative(required(item, "frequency_hz", item_path),
                                               item_path + ".frequency_hz");
              if (item["phase_rad"])
                term.phase_rad = number(item["phase_rad"], item_path + ".phase_rad");
              return term;
            });
      } else {
        std::string expected;
        for (const ScalarKey& scalar : keys.scalars) expected += std::string(scalar.name) + ", ";
        expected += "gauss_markov, sinusoids";
        if (allow_axes) expected += ", x, y, z";
        fail(entry.first, path, "unknown key (expected one of: " + expected + ")");
      }
    }
  }

  YAML::Node required(const YAML::Node& item, const std::string& key,
                      const std::string& item_path) const {
    const YAML::Node value = item[key];
    if (!value) fail(item, item_path, "missing key '" + key + "'");
    return value;
  }

  template <typename Term, typename ReadItem>
  std::vector<Term> read_list(const YAML::Node& node, const std::string& path,
                              const std::vector<std::string>& allowed, ReadItem read_item) const {
    if (!node.IsSequence()) fail(node, path, "expected a list of mappings");
    std::vector<Term> terms;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node item = node[i];
      const std::string item_path = path + "[" + std::to_string(i) + "]";
      if (!item.IsMap()) fail(item, item_path, "expected a mapping");
      for (const auto& entry : item) {
        const std::string key = key_text(entry.first, item_path);
        bool known = false;
        for (const std::string& name : allowed) known = known || key == name;
        if (!known) {
          std::string list;
          for (const std::string& name : allowed) list += (list.empty() ? "" : ", ") + name;
          fail(entry.first, item_path + "." + key, "unknown key (expected " + list + ")");
        }
      }
      terms.push_back(read_item(item, item_path));
    }
    return terms;
  }

  std::string path_;
};

/// Parses "2h", "30min", "600s" or "600" (seconds) into seconds.
double parse_duration_s(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  const std::string_view unit(ptr, static_cast<std::size_t>(end - ptr));
  double scale = 0.0;
  if (unit.empty() || unit == "s") {
    scale = 1.0;
  } else if (unit == "min") {
    scale = 60.0;
  } else if (unit == "h") {
    scale = units::kHour;
  }
  if (ec != std::errc() || scale == 0.0 || !std::isfinite(value) || !(value > 0.0)) {
    throw InputError(
        "--duration: expected a positive number with unit s, min or h (e.g. 2h, "
        "30min, 600s), got '" +
        text + "'");
  }
  return value * scale;
}

/// Command-line values, in the units their flag names state.
struct SimulateArgs {
  std::string model_path;
  std::string duration = "";
  double rate_hz = 0.0;
  std::uint64_t seed = 1;
  std::string output;
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
  /// Options whose presence decides whether they override the model file.
  std::vector<std::pair<CLI::Option*, std::function<void(SimulationSetup&)>>> overrides;
};

/// Writes the '#' header: source, seed, rate, and every non-zero term per channel (SI keys).
void write_header(std::ostream& out, const SimulationSetup& setup, const SimulateArgs& args,
                  double rate_hz, double duration_s, std::int64_t samples,
                  const std::array<double, 2>& band) {
  out << "# imunoise simulate: synthetic stationary IMU recording, SI units\n";
  out << "# model: " << setup.model_source;
  if (!setup.name.empty()) out << " (" << setup.name << ")";
  out << "\n# seed: " << args.seed << "\n# sample_rate_hz: " << number_text(rate_hz)
      << "\n# duration_s: " << number_text(duration_s) << "\n# samples: " << samples
      << "\n# flicker_band_s: [" << number_text(band[0]) << ", " << number_text(band[1]) << "]\n";
  const auto write_sensor = [&](const SensorKeys& keys, const std::array<AxisSpec, 3>& axes) {
    for (std::size_t a = 0; a < 3; ++a) {
      out << "# " << keys.sensor << "_" << kAxes[a] << ":";
      bool any = false;
      for (const ScalarKey& scalar : keys.scalars) {
        const double value = axes[a].*scalar.field;
        if (value == 0.0) continue;
        out << " " << scalar.name << "=" << number_text(value);
        any = true;
      }
      for (const auto& gm : axes[a].gauss_markov) {
        out << " gauss_markov{" << keys.gm_sigma << "=" << number_text(gm.sigma)
            << " tau_c_s=" << number_text(gm.tau_c_s) << "}";
        any = true;
      }
      for (const auto& s : axes[a].sinusoids) {
        out << " sinusoid{" << keys.sine_amplitude << "=" << number_text(s.amplitude)
            << " frequency_hz=" << number_text(s.frequency_hz)
            << " phase_rad=" << number_text(s.phase_rad) << "}";
        any = true;
      }
      if (!any) out << " (no terms)";
      out << "\n";
    }
  };
  write_sensor(kGyroKeys, setup.gyro);
  write_sensor(kAccelKeys, setup.accel);
  out << "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,"
         "accel_x_m_per_s2,accel_y_m_per_s2,accel_z_m_per_s2\n";
}

models::ChannelNoiseModel to_channel_model(const AxisSpec& spec, const std::string& where) {
  models::ChannelNoiseModel model;
  model.quantization = spec.quantization;
  model.white_noise = spec.white_noise;
  model.bias_instability = spec.bias_instability;
  model.random_walk = spec.random_walk;
  model.ramp = spec.ramp;
  model.constant = spec.bias + spec.signal;
  model.output_lsb = spec.output_lsb;
  model.gauss_markov = spec.gauss_markov;
  model.sinusoids = spec.sinusoids;
  models::validate_channel_model(model, where);
  return model;
}

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

void run_simulate(const SimulateArgs& args) {
  // 1. Load and merge; every check happens before the output file is opened.
  SimulationSetup setup =
      args.model_path.empty() ? SimulationSetup{} : ModelReader(args.model_path).read();
  for (const auto& [option, apply] : args.overrides) {
    if (option->count() > 0) apply(setup);
  }
  const double duration_s = parse_duration_s(args.duration);
  double rate_hz = args.rate_hz;
  if (rate_hz == 0.0) {
    if (!setup.sample_rate_hz) {
      throw InputError("--rate is required (the model file has no sample_rate_hz)");
    }
    rate_hz = *setup.sample_rate_hz;
  }
  const double count = std::round(duration_s * rate_hz);
  if (!(count >= 1.0) || count > 1e11) {
    throw InputError("--duration × --rate gives " + number_text(count) +
                     " samples; expected 1 to 1e11");
  }
  const auto samples = static_cast<std::int64_t>(count);
  const std::array<double, 2> band = setup.flicker_band_s.value_or(
      std::array<double, 2>{1.0 / rate_hz, std::max(duration_s, 2.0 / rate_hz)});

  models::ImuNoiseModel model;
  for (std::size_t a = 0; a < 3; ++a) {
    model.gyro[a] = to_channel_model(setup.gyro[a], "gyro." + std::string(kAxes[a]));
    model.accel[a] = to_channel_model(setup.accel[a], "accel." + std::string(kAxes[a]));
  }
  models::SimulationOptions options;
  options.sample_rate_hz = rate_hz;
  options.seed = args.seed;
  options.flicker_band = {band[0], band[1]};
  models::ImuSimulator simulator(model, options);

  // 2. Generate and write block by block: memory stays constant for any duration.
  io::AtomicOutputFile file(args.output);
  std::ostream& out = file.stream();
  write_header(out, setup, args, rate_hz, duration_s, samples, band);

  constexpr std::size_t kBlock = 4096;
  constexpr std::size_t kMaxRowChars = 7 * 25;  // 7 fields, each ≤ 24 chars plus separator
  std::vector<double> values(models::kImuChannels * kBlock);
  std::vector<char> text(kBlock * kMaxRowChars);
  std::array<std::span<double>, models::kImuChannels> spans;
  for (std::int64_t done = 0; done < samples;) {
    const std::size_t n = static_cast<std::size_t>(
        std::min<std::int64_t>(static_cast<std::int64_t>(kBlock), samples - done));
    for (std::size_t c = 0; c < models::kImuChannels; ++c) {
      spans[c] = std::span<double>(values).subspan(c * kBlock, n);
    }
    simulator.next_block(spans);
    char* p = text.data();
    for (std::size_t i = 0; i < n; ++i) {
      const double t = static_cast<double>(done + static_cast<std::int64_t>(i)) / rate_hz;
      p = std::to_chars(p, p + 24, t).ptr;
      for (std::size_t c = 0; c < models::kImuChannels; ++c) {
        *p++ = ',';
        p = std::to_chars(p, p + 24, spans[c][i]).ptr;
      }
      *p++ = '\n';
    }
    out.write(text.data(), p - text.data());
    done += static_cast<std::int64_t>(n);
  }
  file.commit();
  std::cout << "imunoise simulate: wrote " << samples << " samples (" << number_text(duration_s)
            << " s at " << number_text(rate_hz) << " Hz, seed " << args.seed << ") to "
            << args.output << "\n";
}

}  // namespace

void register_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* sub = app.add_subcommand(
      "simulate",
      "Simulate a stationary IMU recording (CSV, SI units) from a YAML noise model and/or "
      "per-term flags. Deterministic for a seed.");
  sub->add_option("model", args->model_path,
                  "YAML noise model (keys carry SI units; see configs/demo_imu.yaml)")
      ->check(CLI::ExistingFile);
  sub->add_option("--duration", args->duration, "record length with unit: 2h, 30min, 600s")
      ->required();
  sub->add_option("--rate", args->rate_hz, "sample rate [Hz] (default: the model's sample_rate_hz)")
      ->check(number_check(true));
  sub->add_option("--seed", args->seed, "random seed (default 1)");
  sub->add_option("-o,--output", args->output, "output CSV file")->required();

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
  const auto all_gyro = [](double AxisSpec::*field, double factor) {
    return [field, factor](SimulationSetup& s, double v) {
      for (auto& axis : s.gyro) axis.*field = v * factor;
    };
  };
  const auto all_accel = [](double AxisSpec::*field, double factor) {
    return [field, factor](SimulationSetup& s, double v) {
      for (auto& axis : s.accel) axis.*field = v * factor;
    };
  };
  const double m_per_s_per_sqrt_hour = 1.0 / std::sqrt(units::kHour);  // m/s/√h → m/s/√s
  add_term("--gyro-arw-deg-per-sqrt-h", args->gyro_arw_deg_per_sqrt_h, "gyro ARW N [deg/√h]",
           all_gyro(&AxisSpec::white_noise, units::kDegPerSqrtHour));
  add_term("--gyro-bias-instability-deg-per-h", args->gyro_bias_instability_deg_per_h,
           "gyro bias instability B [deg/h] (ADEV floor 0.664·B)",
           all_gyro(&AxisSpec::bias_instability, units::kDegPerHour));
  add_term("--gyro-rrw-deg-per-h-per-sqrt-h", args->gyro_rrw_deg_per_h_per_sqrt_h,
           "gyro rate random walk K [deg/h/√h]",
           all_gyro(&AxisSpec::random_walk, units::kDegPerHourPerSqrtHour));
  add_term("--gyro-bias-deg-per-h", args->gyro_bias_deg_per_h, "gyro constant bias [deg/h]",
           all_gyro(&AxisSpec::bias, units::kDegPerHour), true);
  add_term("--gyro-lsb-deg-per-s", args->gyro_lsb_deg_per_s,
           "gyro output quantizer step [deg/s] (0 = off)",
           all_gyro(&AxisSpec::output_lsb, units::kDegPerS));
  CLI::Option* vrw_h =
      add_term("--accel-vrw-m-per-s-per-sqrt-h", args->accel_vrw_m_per_s_per_sqrt_h,
               "accel velocity random walk N [m/s/√h]",
               all_accel(&AxisSpec::white_noise, m_per_s_per_sqrt_hour));
  CLI::Option* vrw_hz = add_term("--accel-vrw-ug-per-sqrt-hz", args->accel_vrw_ug_per_sqrt_hz,
                                 "accel VRW N as a two-sided density [µg/√Hz]",
                                 all_accel(&AxisSpec::white_noise, units::kMicroG));
  vrw_h->excludes(vrw_hz);
  add_term("--accel-bias-instability-ug", args->accel_bias_instability_ug,
           "accel bias instability B [µg]", all_accel(&AxisSpec::bias_instability, units::kMicroG));
  add_term("--accel-rw-m-per-s-per-h-per-sqrt-h", args->accel_rw_m_per_s_per_h_per_sqrt_h,
           "accel random walk K [(m/s/h)/√h]",
           all_accel(&AxisSpec::random_walk, 1.0 / (units::kHour * std::sqrt(units::kHour))));
  add_term("--accel-bias-mg", args->accel_bias_mg, "accel constant bias [mg]",
           all_accel(&AxisSpec::bias, units::kMilliG), true);
  add_term("--accel-lsb-mg", args->accel_lsb_mg, "accel output quantizer step [mg] (0 = off)",
           all_accel(&AxisSpec::output_lsb, units::kMilliG));
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
  sub->callback([args] { run_simulate(*args); });
}

}  // namespace imunoise::tools
