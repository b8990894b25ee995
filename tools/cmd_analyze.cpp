/// @file
/// @brief `imunoise analyze`: the whole job on one recording — sampling report, OADEV/OHDEV
/// with intervals, Welch PSD, the weighted NNLS fit with bootstrap intervals, read-offs and
/// B → GM conversions for each of the six channels (in parallel) — written to DIR as
/// model.yaml (native schema, docs/model-yaml.md), allan.csv and psd.csv, with a summary table
/// in datasheet units on stdout.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
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
#include "common/number_text.h"
#include "common/units.h"
#include "io/atomic_output.h"
#include "io/csv_reader.h"
#include "io/noise_model_yaml.h"
#include "io/simulation_model.h"
#include "models/noise_model.h"
#include "pipeline/axis_analysis.h"
#include "tools/commands.h"
#include "tools/input_options.h"

namespace imunoise::tools {

namespace {

using io::kImuChannelNames;

struct AnalyzeArgs {
  std::string file;
  io::InputConfig flags;
  std::string config_path;
  std::string output_dir;
  std::string taus = "log:10";
  double confidence = 0.95;
  int bootstrap = 50;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  bool gauss_markov = false;
  bool no_low_pass_check = false;
  double tau_min_s = 0.0;
  double tau_max_s = 0.0;
  std::string truth_path;
  std::vector<double> sinusoid_hz;
  bool quiet = false;
};

std::string fixed(double value, int digits = 4) {
  std::ostringstream out;
  out.precision(digits);
  out << value;
  return out.str();
}

/// Data-quality findings from the sampling report, one line each (empty = nothing to say).
std::vector<std::string> quality_findings(const io::SamplingReport& report) {
  std::vector<std::string> out;
  const io::TimingReport& t = report.timing;
  if (t.gap_count > 0) {
    out.push_back(std::to_string(t.gap_count) + " time-stamp gap(s), longest " +
                  fixed(t.longest_gap_s) + " s, about " + std::to_string(t.missing_samples) +
                  " samples missing; the analysis assumes uniform sampling");
  }
  if (t.non_monotonic_count > 0) {
    out.push_back(std::to_string(t.non_monotonic_count) + " non-monotonic time stamp(s)");
  }
  if (t.duplicate_count > 0) {
    out.push_back(std::to_string(t.duplicate_count) + " duplicate time stamp(s)");
  }
  if (t.has_timestamps && t.median_interval_s > 0.0 &&
      t.jitter_rms_s > 0.01 * t.median_interval_s) {
    out.push_back("time-stamp jitter " + fixed(t.jitter_rms_s) + " s RMS (" +
                  fixed(100.0 * t.jitter_rms_s / t.median_interval_s, 3) + " % of the interval)");
  }
  if (report.rows_dropped > 0) {
    out.push_back(std::to_string(report.rows_dropped) + " row(s) with NaN/Inf dropped");
  }
  for (const io::ChannelReport& c : report.channels) {
    if (c.saturated_samples > 0) {
      out.push_back(c.name + ": " + std::to_string(c.saturated_samples) +
                    " samples in saturation runs at the range limits");
    }
    if (c.beyond_full_scale > 0) {
      out.push_back(c.name + ": " + std::to_string(c.beyond_full_scale) +
                    " samples at or beyond the full scale");
    }
    if (c.lsb)
      out.push_back(c.name + ": output quantized, LSB " + shortest_number_text(*c.lsb) + " " +
                    c.unit);
  }
  return out;
}

/// A coefficient in the unit people read on datasheets, with that unit's name.
struct DisplayUnit {
  double factor;  ///< SI value × factor = display value
  const char* name;
};

DisplayUnit display_unit(models::Term term, bool gyro) {
  using models::Term;
  const double sqrt_hour = std::sqrt(units::kHour);
  if (gyro) {
    switch (term) {
      case Term::quantization:
        return {1e6, "urad"};
      case Term::white_noise:
        return {1.0 / units::kDegPerSqrtHour, "deg/sqrt(h)"};
      case Term::bias_instability:
        return {1.0 / units::kDegPerHour, "deg/h"};
      case Term::random_walk:
        return {1.0 / units::kDegPerHourPerSqrtHour, "deg/h/sqrt(h)"};
      case Term::ramp:
        return {units::kHour * units::kHour / units::kDeg, "deg/h^2"};
    }
  }
  switch (term) {
    case Term::quantization:
      return {1e3, "mm/s"};
    case Term::white_noise:
      return {1.0 / units::kMicroG, "ug/sqrt(Hz)"};
    case Term::bias_instability:
      return {1.0 / units::kMicroG, "ug"};
    case Term::random_walk:
      return {units::kHour * sqrt_hour, "m/s/h/sqrt(h)"};
    case Term::ramp:
      return {units::kHour / units::kMicroG, "ug/h"};
  }
  return {1.0, ""};
}

std::string unit_suffix(bool gyro) { return gyro ? "rad_per_s" : "m_per_s2"; }
std::string psd_unit_suffix(bool gyro) { return gyro ? "rad2_per_s2_per_hz" : "m2_per_s4_per_hz"; }

/// allan.csv: one row per averaging factor (union of the OADEV and OHDEV grids), per axis the
/// OADEV with its interval, EDF and identified α, the fitted model ADEV, and the OHDEV.
void write_allan_csv(const std::string& path, const std::vector<pipeline::AxisAnalysis>& axes,
                     double tau0_s) {
  std::map<std::int64_t, std::size_t> rows;
  for (const auto& a : axes) {
    for (const auto& p : a.oadev.points) rows.emplace(p.m, 0);
    for (const auto& p : a.ohdev.points) rows.emplace(p.m, 0);
  }
  io::AtomicOutputFile file(path);
  std::ostream& out = file.stream();
  out << "m,tau_s";
  for (const auto& a : axes) {
    const std::string n = a.model.name;
    const std::string u = unit_suffix(a.model.gyro);
    out << "," << n << "_oadev_" << u << "," << n << "_oadev_ci_low_" << u << "," << n
        << "_oadev_ci_high_" << u << "," << n << "_oadev_edf," << n << "_oadev_alpha," << n
        << "_model_adev_" << u << "," << n << "_ohdev_" << u << "," << n << "_ohdev_ci_low_" << u
        << "," << n << "_ohdev_ci_high_" << u;
  }
  out << "\n";
  for (const auto& [m, unused] : rows) {
    (void)unused;
    const double tau = static_cast<double>(m) * tau0_s;
    out << m << "," << shortest_number_text(tau);
    for (const auto& a : axes) {
      const auto find =
          [m = m](const analysis::DeviationCurve& c) -> const analysis::DeviationPoint* {
        for (const auto& p : c.points) {
          if (p.m == m) return &p;
        }
        return nullptr;
      };
      if (const auto* p = find(a.oadev)) {
        out << "," << shortest_number_text(p->value) << "," << shortest_number_text(p->ci_low)
            << "," << shortest_number_text(p->ci_high) << "," << shortest_number_text(p->edf) << ","
            << p->alpha;
      } else {
        out << ",,,,,";
      }
      out << "," << shortest_number_text(std::sqrt(analysis::model_avar(a.fit.coefficients, tau)));
      if (const auto* p = find(a.ohdev)) {
        out << "," << shortest_number_text(p->value) << "," << shortest_number_text(p->ci_low)
            << "," << shortest_number_text(p->ci_high);
      } else {
        out << ",,,";
      }
    }
    out << "\n";
  }
  file.commit();
}

/// psd.csv: one row per log bin (every axis has the same bins: same length, rate and Welch
/// settings), per axis the one-sided PSD, its dof and the fitted model's PSD, with the unit
/// in every column name as in allan.csv.
void write_psd_csv(const std::string& path, const std::vector<pipeline::AxisAnalysis>& axes,
                   double tau0_s) {
  std::map<double, std::size_t> rows;  // frequency → row; a bin an axis lacks stays empty
  for (const auto& a : axes) {
    for (double f : a.psd.frequency_hz) rows.emplace(f, 0);
  }
  io::AtomicOutputFile file(path);
  std::ostream& out = file.stream();
  out << "frequency_hz";
  for (const auto& a : axes) {
    const std::string n = a.model.name;
    const std::string u = psd_unit_suffix(a.model.gyro);
    out << "," << n << "_psd_" << u << "," << n << "_psd_dof," << n << "_model_psd_" << u;
  }
  out << "\n";
  for (const auto& [f, unused] : rows) {
    (void)unused;
    out << shortest_number_text(f);
    for (const auto& a : axes) {
      const auto& freq = a.psd.frequency_hz;
      const auto it = std::find(freq.begin(), freq.end(), f);
      if (it == freq.end()) {
        out << ",,,";
        continue;
      }
      const auto i = static_cast<std::size_t>(it - freq.begin());
      out << "," << shortest_number_text(a.psd.density[i]) << ","
          << shortest_number_text(a.psd.dof[i]) << ","
          << shortest_number_text(analysis::model_psd_one_sided(a.fit.coefficients, f, tau0_s));
    }
    out << "\n";
  }
  file.commit();
}

/// "1.234e-02 [1.1e-02, 1.4e-02]" or "not identified (< 3e-4)".
std::string estimate_text(const models::Estimate& e, const DisplayUnit& unit) {
  if (!e.identified) {
    if (e.ci_high > 0.0) return "- (< " + fixed(e.ci_high * unit.factor, 2) + ")";
    return "-";
  }
  return fixed(e.value * unit.factor, 4) + " [" + fixed(e.ci_low * unit.factor, 3) + ", " +
         fixed(e.ci_high * unit.factor, 3) + "]";
}

void print_summary(const models::NoiseModel& model,
                   const std::optional<std::array<NoiseCoefficients, 6>>& truth) {
  std::cout << "imunoise analyze: " << model.source << " — " << model.samples << " samples at "
            << fixed(model.sample_rate_hz, 6) << " Hz (" << fixed(model.duration_s / 3600.0, 4)
            << " h); coefficients with " << fixed(100.0 * model.confidence, 3)
            << " % intervals, '-' = not identified (upper bound);\n"
            << "ieee952 = the graphical slope read-off of the OADEV curve, for traceability\n";
  for (bool gyro : {true, false}) {
    std::cout << "\n" << (gyro ? "gyro" : "accel") << "\n";
    for (models::Term term : models::kTerms) {
      const DisplayUnit unit = display_unit(term, gyro);
      std::cout << "  " << models::term_name(term) << " [" << unit.name << "]\n";
      for (std::size_t i = 0; i < model.axes.size(); ++i) {
        const models::AxisModel& axis = model.axes[i];
        if (axis.gyro != gyro) continue;
        const models::Estimate& e = axis.terms[static_cast<std::size_t>(term)];
        std::cout << "    " << axis.name << ": " << estimate_text(e, unit);
        const double slope = axis.readoff.slope[static_cast<std::size_t>(term)];
        if (slope > 0.0) std::cout << "   ieee952 " << fixed(slope * unit.factor, 4);
        if (truth) {
          const std::size_t channel = static_cast<std::size_t>(
              std::find(kImuChannelNames.begin(), kImuChannelNames.end(), axis.name) -
              kImuChannelNames.begin());
          if (channel < 6) {
            const double true_value = models::coefficient((*truth)[channel], term);
            const bool inside = true_value >= e.ci_low && true_value <= e.ci_high;
            std::cout << "   true " << fixed(true_value * unit.factor, 4)
                      << (inside ? "  (inside)" : "  (OUTSIDE)");
          }
        }
        std::cout << "\n";
      }
    }
  }
  for (const models::AxisModel& axis : model.axes) {
    if (axis.psd_check_pass && !*axis.psd_check_pass) {
      std::cout << "\nPSD cross-check FAILED for " << axis.name << ": " << axis.psd_check_note
                << "\n";
    }
  }
  if (!model.data_quality.empty()) {
    std::cout << "\ndata quality:\n";
    for (const std::string& line : model.data_quality) std::cout << "  - " << line << "\n";
  }
}

void run_analyze(const AnalyzeArgs& args) {
  const io::InputConfig config = resolve_input_config(args.flags, args.config_path);
  if (!(args.confidence > 0.0 && args.confidence < 1.0)) {
    throw InputError("--confidence: expected a level in (0, 1), got " +
                     shortest_number_text(args.confidence));
  }
  if (args.bootstrap == 1 || args.bootstrap < 0) {
    throw InputError("--bootstrap: expected 0 (off) or at least 2 replicates");
  }
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
  const bool progress = !args.quiet && isatty(STDERR_FILENO);

  const io::Recording recording = io::read_recording(args.file, config);
  const double tau0_s = recording.sample_period_s;
  std::vector<std::pair<std::size_t, const io::Channel*>> channels;
  for (std::size_t c = 0; c < kImuChannelNames.size(); ++c) {
    if (const io::Channel* channel = recording.find_channel(kImuChannelNames[c])) {
      channels.emplace_back(c, channel);
    }
  }
  if (channels.empty()) {
    throw InputError(args.file + ": no gyro or accelerometer channels to analyse");
  }

  pipeline::AxisAnalysisOptions options;
  options.confidence = args.confidence;
  options.grid = analysis::parse_tau_grid(args.taus);
  options.bootstrap_replicates = args.bootstrap;
  options.seed = args.seed;
  options.fit.gauss_markov =
      args.gauss_markov ? analysis::GaussMarkovMode::on : analysis::GaussMarkovMode::off;
  options.fit.tau_min_s = args.tau_min_s;
  for (double f : args.sinusoid_hz) {
    if (!(f > 0.0) || !(f < 0.5 / tau0_s)) {
      throw InputError("--sinusoid-hz: " + shortest_number_text(f) +
                       " Hz is not in (0, Nyquist = " + shortest_number_text(0.5 / tau0_s) +
                       " Hz)");
    }
  }
  options.fit.sinusoid_frequencies_hz = args.sinusoid_hz;
  options.fit.tau_max_s = args.tau_max_s;
  options.auto_low_pass = !args.no_low_pass_check;

  // Axes in parallel: each worker takes the next axis (one thread per axis; the bootstrap of
  // an axis runs in that thread, so the total never exceeds --threads).
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const unsigned threads = std::min<unsigned>(args.threads == 0 ? hardware : args.threads,
                                              static_cast<unsigned>(channels.size()));
  std::vector<std::optional<pipeline::AxisAnalysis>> results(channels.size());
  std::vector<std::exception_ptr> errors(channels.size());
  std::atomic<std::size_t> next{0};
  std::mutex print_mutex;
  const auto worker = [&] {
    for (std::size_t i = next++; i < channels.size(); i = next++) {
      const auto [index, channel] = channels[i];
      try {
        results[i] = pipeline::analyze_axis(channel->name, index < 3, channel->values, tau0_s,
                                            static_cast<int>(index), options);
        if (progress) {
          std::lock_guard<std::mutex> lock(print_mutex);
          std::cerr << "  " << channel->name << " done\n";
        }
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  if (progress) {
    std::cerr << "imunoise analyze: " << channels.size() << " channels on " << threads
              << " thread(s), bootstrap " << args.bootstrap << " replicates\n";
  }
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  for (std::size_t i = 0; i < channels.size(); ++i) {
    if (errors[i]) std::rethrow_exception(errors[i]);
  }

  models::NoiseModel model;
  model.source = args.file;
  model.sensor_name = std::filesystem::path(args.file).filename().string();
  model.sample_rate_hz = 1.0 / tau0_s;
  model.samples = static_cast<std::int64_t>(recording.sample_count());
  model.duration_s = static_cast<double>(model.samples) * tau0_s;
  model.confidence = args.confidence;
  model.data_quality = quality_findings(recording.report);
  std::vector<pipeline::AxisAnalysis> axes;
  for (auto& r : results) {
    model.axes.push_back(r->model);
    axes.push_back(std::move(*r));
  }

  std::filesystem::create_directories(args.output_dir);
  const std::filesystem::path dir(args.output_dir);
  io::write_model_yaml(model, (dir / "model.yaml").string());
  write_allan_csv((dir / "allan.csv").string(), axes, tau0_s);
  write_psd_csv((dir / "psd.csv").string(), axes, tau0_s);
  print_summary(model, truth);
  std::cout << "\nwrote " << (dir / "model.yaml").string() << ", allan.csv, psd.csv\n";
}

}  // namespace

void register_analyze_command(CLI::App& app) {
  auto args = std::make_shared<AnalyzeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "analyze",
      "Fit the stochastic error model of every gyro and accelerometer axis of a stationary "
      "recording (OADEV + OHDEV with intervals, PSD, weighted NNLS fit with bootstrap "
      "intervals) and write DIR/model.yaml, allan.csv and psd.csv");
  cmd->add_option("REC", args->file, "recording (CSV/TXT; see 'imunoise check --help')")
      ->required();
  add_input_options(*cmd, args->flags, args->config_path);
  cmd->add_option("-o,--output", args->output_dir, "output directory (created if needed)")
      ->required();
  cmd->add_option("--taus", args->taus, "tau grid: octave, decade, log:N (default log:10)");
  cmd->add_option("--confidence", args->confidence, "interval level (default 0.95)");
  cmd->add_option("--bootstrap", args->bootstrap,
                  "parametric bootstrap replicates per axis (default 50; 0 = least-squares "
                  "intervals, which ignore the correlation between tau points)");
  cmd->add_option("--seed", args->seed, "bootstrap seed (default 1)");
  cmd->add_option("--threads", args->threads, "worker threads (0 = all cores)");
  cmd->add_flag("--gauss-markov", args->gauss_markov,
                "also fit first-order Gauss-Markov terms (grid of correlation times, refined)");
  cmd->add_option("--sinusoid-hz", args->sinusoid_hz,
                  "candidate sinusoid frequencies F1,F2,... [Hz] (e.g. lines seen in psd.csv); "
                  "each amplitude is fitted and kept only if the data support it")
      ->delimiter(',');
  cmd->add_option("--tau-min", args->tau_min_s, "fit only tau >= this [s]");
  cmd->add_option("--tau-max", args->tau_max_s, "fit only tau <= this [s]");
  cmd->add_flag("--no-low-pass-check", args->no_low_pass_check,
                "keep the shortest tau even where the curve bends below the white-noise line");
  cmd->add_option("--truth", args->truth_path,
                  "simulator model file (e.g. the one given to 'imunoise simulate'): print the "
                  "true coefficients next to the recovered ones");
  cmd->add_flag("-q,--quiet", args->quiet, "no progress messages");
  cmd->footer(
      "Examples:\n"
      "  imunoise simulate configs/reference-imu.yaml --duration 8h --rate 50 --seed 1 -o rec.csv\n"
      "  imunoise analyze rec.csv -o out --truth configs/reference-imu.yaml\n"
      "  imunoise analyze imu.txt --config configs/example_input.yaml -o out --bootstrap 0\n"
      "Outputs: model.yaml (SI units named in every key, docs/model-yaml.md), allan.csv\n"
      "(OADEV/OHDEV with intervals and the model ADEV, per axis), psd.csv (log-binned one-sided\n"
      "PSD with dof and the model PSD, per axis); units are part of every column name.");
  cmd->callback([args] { run_analyze(*args); });
}

}  // namespace imunoise::tools
