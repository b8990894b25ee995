/// @file
/// @brief `imunoise simulate`: a synthetic stationary IMU recording (CSV, SI units) from a
/// YAML noise model (io/simulation_model.h; keys in datasheet units, docs/simulation-model.md)
/// and/or per-term flags, generated in blocks (constant memory).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <imunoise/imu_sample_t.hpp>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/units.h"
#include "io/atomic_output.h"
#include "io/binary_recording.h"
#include "io/lcm_log_writer.h"
#include "io/noise_model_yaml.h"
#include "io/simulation_model.h"
#include "models/noise_simulator.h"
#include "tools/commands.h"
#include "tools/duration.h"
#include "tools/progress.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};

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

/// An output path that asks for an LCM log.
bool is_lcm_log_path(const std::string& path) {
  const std::string suffix = ".lcmlog";
  return path.size() > suffix.size() &&
         path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// An output path that asks for the binary recording format (io/binary_recording.h).
bool is_binary_path(const std::string& path) {
  const std::string_view suffix = io::kBinaryRecordingExtension;
  return path.size() > suffix.size() &&
         path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The median of the intervals t[k+1] − t[k] of the stamps t[k] = k / rate (k < samples),
/// computed as pipeline::analyze_timing does (mean of the two middle values for an even count) from
/// a histogram of the distinct intervals — a handful per binade of t — so that the header of a
/// binary output holds the sample period a read of the CSV output finds.
class IntervalMedian {
 public:
  void add(double interval) {
    if (last_ < counts_.size() && counts_[last_].first == interval) {
      ++counts_[last_].second;
      return;
    }
    for (last_ = 0; last_ < counts_.size(); ++last_) {
      if (counts_[last_].first == interval) {
        ++counts_[last_].second;
        return;
      }
    }
    counts_.emplace_back(interval, 1);
  }

  /// The median, or nullopt without intervals.
  std::optional<double> median() {
    std::sort(counts_.begin(), counts_.end());
    std::int64_t total = 0;
    for (const auto& c : counts_) total += c.second;
    if (total == 0) return std::nullopt;
    const auto nth = [&](std::int64_t index) {
      for (const auto& [value, count] : counts_) {
        if (index < count) return value;
        index -= count;
      }
      return counts_.back().first;
    };
    const double upper = nth(total / 2);
    return total % 2 == 1 ? upper : 0.5 * (nth(total / 2 - 1) + upper);
  }

 private:
  std::vector<std::pair<double, std::int64_t>> counts_;
  std::size_t last_ = 0;
};

/// The sample period of a simulated recording as the CSV reader would find it from the time
/// column (its median interval); 1 / rate for a single sample.
double simulated_sample_period_s(double rate_hz, std::int64_t samples) {
  IntervalMedian median;
  double previous = 0.0;
  for (std::int64_t k = 1; k < samples; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    median.add(t - previous);
    previous = t;
  }
  return median.median().value_or(1.0 / rate_hz);
}

/// Header of a binary output: what converting the CSV output would give (columns named as the
/// CSV's, SI source units), with the model as source.
io::BinaryRecordingHeader binary_header(const SimulationSetup& setup, double rate_hz,
                                        std::int64_t samples) {
  io::BinaryRecordingHeader h;
  h.source_path = setup.source;
  h.created_by = std::string(io::kBinaryCreatedBy);
  h.sample_period_s = simulated_sample_period_s(rate_hz, samples);
  h.has_time = true;
  h.sample_count = static_cast<std::uint64_t>(samples);
  for (std::size_t c = 0; c < models::kImuChannels; ++c) {
    const bool gyro = c < 3;
    pipeline::Channel channel;
    channel.name = pipeline::kImuChannelNames[c];
    channel.unit = gyro ? "rad/s" : "m/s^2";
    channel.source_column = channel.name + (gyro ? "_rad_per_s" : "_m_per_s2");
    channel.source_unit = channel.unit;
    h.channels.push_back(std::move(channel));
  }
  return h;
}

/// Writes the '#' header: source, seed, rate, and every non-zero term per channel (SI keys).
void write_header(std::ostream& out, const SimulationSetup& setup, const SimulateArgs& args,
                  double rate_hz, double duration_s, std::int64_t samples,
                  const std::array<double, 2>& band) {
  out << "# imunoise simulate: synthetic stationary IMU recording, SI units\n";
  out << "# model: " << setup.source;
  if (!setup.name.empty()) out << " (" << setup.name << ")";
  out << "\n# seed: " << args.seed << "\n# sample_rate_hz: " << shortest_number_text(rate_hz)
      << "\n# duration_s: " << shortest_number_text(duration_s) << "\n# samples: " << samples
      << "\n# flicker_band_s: [" << shortest_number_text(band[0]) << ", "
      << shortest_number_text(band[1]) << "]\n";
  const auto write_sensor = [&](std::string_view sensor_name, io::Sensor sensor,
                                const std::array<io::SimulationAxis, 3>& axes) {
    for (std::size_t a = 0; a < 3; ++a) {
      out << "# " << sensor_name << "_" << kAxes[a] << ":" << io::si_terms_text(axes[a], sensor)
          << "\n";
    }
  };
  write_sensor("gyro", io::Sensor::kGyro, setup.gyro);
  write_sensor("accel", io::Sensor::kAccel, setup.accel);
  out << "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,"
         "accel_x_m_per_s2,accel_y_m_per_s2,accel_z_m_per_s2\n";
}

models::ChannelNoiseModel to_channel_model(const io::SimulationAxis& axis,
                                           const std::string& where) {
  models::ChannelNoiseModel model = io::channel_model(axis);
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

/// True when PATH is a fitted model.yaml (native schema) rather than a simulator model file.
bool is_native_model_file(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int i = 0; i < 64 && std::getline(in, line); ++i) {
    if (line.rfind("format:", 0) == 0) return line.find(io::kModelYamlFormat) != std::string::npos;
  }
  return false;
}

/// A fitted model.yaml as a simulation set-up: each of gyro_x … accel_z simulated with its
/// point estimates (terms not identified are 0; fitted GM terms and sinusoids included). No
/// bias or gravity: the fitted model describes the noise only.
SimulationSetup setup_from_fitted_model(const std::string& path) {
  const models::NoiseModel fitted = io::load_model_yaml(path);
  SimulationSetup setup;
  setup.source = path;
  setup.name = "fitted model of " + fitted.source;
  setup.sample_rate_hz = fitted.sample_rate_hz;
  for (std::size_t a = 0; a < 3; ++a) {
    for (const bool gyro : {true, false}) {
      const std::string name = std::string(gyro ? "gyro_" : "accel_") + std::string(kAxes[a]);
      const models::AxisModel* axis = fitted.find_axis(name);
      if (axis == nullptr) continue;
      (gyro ? setup.gyro : setup.accel)[a].coefficients = axis->coefficients();
    }
  }
  return setup;
}

/// TIMES gets the wall time of the set-up and of generating + writing.
void run_simulate(const SimulateArgs& args, StageTimes& times) {
  // 1. Load and merge; every check happens before the output file is opened.
  SimulationSetup setup;
  setup.source = "command-line flags";
  if (!args.model_path.empty()) {
    setup = is_native_model_file(args.model_path) ? setup_from_fitted_model(args.model_path)
                                                  : io::load_simulation_model(args.model_path);
  }
  for (const auto& [option, apply] : args.overrides) {
    if (option->count() > 0) apply(setup);
  }
  const double duration_s = parse_duration_s(args.duration, "--duration");
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
  const auto samples = static_cast<std::int64_t>(count);
  const models::FlickerBand flicker_band = setup.flicker_band.value_or(
      models::FlickerBand{1.0 / rate_hz, std::max(duration_s, 2.0 / rate_hz)});
  const std::array<double, 2> band{flicker_band.tau_min_s, flicker_band.tau_max_s};

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
  times.mark("setup");

  // 2. Generate and write block by block: memory stays constant for any duration. A binary
  // output goes column by column through its own writer; CSV and LCM through a stream.
  const bool binary = is_binary_path(args.output);
  std::optional<io::BinaryRecordingWriter> binary_writer;
  std::optional<io::AtomicOutputFile> file;
  if (binary) {
    binary_writer.emplace(args.output, binary_header(setup, rate_hz, samples));
  } else {
    file.emplace(args.output);
  }
  std::ostringstream no_stream;  // the binary writer has its own file
  std::ostream& out = file ? file->stream() : no_stream;
  const bool lcm_log = is_lcm_log_path(args.output);
  if (!lcm_log && !binary) write_header(out, setup, args, rate_hz, duration_s, samples, band);
  io::LcmLogWriter log_writer(out);
  imunoise::imu_sample_t message{};
  std::vector<unsigned char> encoded(static_cast<std::size_t>(message.getEncodedSize()));

  constexpr std::size_t kBlock = 4096;
  constexpr std::size_t kMaxRowChars = 7 * 25;  // 7 fields, each ≤ 24 chars plus separator
  std::vector<double> values(models::kImuChannels * kBlock);
  std::vector<char> text(binary ? 0 : kBlock * kMaxRowChars);
  std::vector<double> block_time(binary ? kBlock : 0);
  std::array<std::span<double>, models::kImuChannels> spans;
  ProgressBar bar("simulate", progress_wanted(args.verbosity));
  for (std::int64_t done = 0; done < samples;) {
    bar.update("generating", done, samples);  // per block; the bar throttles its redraws
    const std::size_t n = static_cast<std::size_t>(
        std::min<std::int64_t>(static_cast<std::int64_t>(kBlock), samples - done));
    for (std::size_t c = 0; c < models::kImuChannels; ++c) {
      spans[c] = std::span<double>(values).subspan(c * kBlock, n);
    }
    simulator.next_block(spans);
    if (binary) {
      std::span<double> time = std::span<double>(block_time).first(n);
      for (std::size_t i = 0; i < n; ++i) {
        time[i] = static_cast<double>(done + static_cast<std::int64_t>(i)) / rate_hz;
      }
      binary_writer->append(0, time);
      for (std::size_t c = 0; c < models::kImuChannels; ++c) binary_writer->append(1 + c, spans[c]);
      done += static_cast<std::int64_t>(n);
      continue;
    }
    if (lcm_log) {
      // imu_sample_t in SI, stamped in whole µs from 0 (the same stamp as the log event).
      for (std::size_t i = 0; i < n; ++i) {
        const auto k = static_cast<double>(done + static_cast<std::int64_t>(i));
        message.utime = std::llround(k * 1e6 / rate_hz);
        for (std::size_t a = 0; a < 3; ++a) {
          message.angular_rate_rad_per_s[a] = spans[a][i];
          message.specific_force_m_per_s2[a] = spans[3 + a][i];
        }
        message.encode(encoded.data(), 0, static_cast<int>(encoded.size()));
        log_writer.write(args.lcm_channel, message.utime, encoded);
      }
      done += static_cast<std::int64_t>(n);
      continue;
    }
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
  if (binary_writer) binary_writer->commit();
  if (file) file->commit();
  bar.finish();
  times.mark("generate and write");
  std::cout << "imunoise simulate: wrote " << samples << " samples ("
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
    StageTimes times;
    run_simulate(*args, times);
    print_timings(args->verbosity, "simulate", times);
  });
}

}  // namespace imunoise::tools
