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
#include "io/lcm_messages.h"
#include "io/noise_model_yaml.h"
#include "io/recording.h"
#include "tools/commands.h"
#include "tools/duration.h"
#include "tools/lcm_bus.h"

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
};

/// A CSV file written by imunoise (allan.csv, drift_envelope.csv): a header row and numbers,
/// empty cells allowed (a point that one curve lacks).
struct NumericTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::optional<double>>> rows;

  std::optional<std::size_t> find(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (columns[i] == name) return i;
    }
    return std::nullopt;
  }
};

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(
        line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

NumericTable read_numeric_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(located_message(path, 0, 0, "cannot open for reading"));
  NumericTable table;
  std::string line;
  std::int64_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> cells = split_commas(line);
    if (table.columns.empty()) {
      table.columns = std::move(cells);
      continue;
    }
    if (cells.size() != table.columns.size()) {
      throw InputError(located_message(path, line_number, 0,
                                       std::to_string(cells.size()) + " fields, the header has " +
                                           std::to_string(table.columns.size())));
    }
    std::vector<std::optional<double>> row;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells[c].empty()) {
        row.emplace_back();
        continue;
      }
      double v = 0.0;
      const char* first = cells[c].data();
      const char* last = first + cells[c].size();
      const auto [end, ec] = std::from_chars(first, last, v);
      if (ec != std::errc() || end != last || !std::isfinite(v)) {
        throw InputError(located_message(
            path, line_number, 0,
            "column '" + table.columns[c] + "': '" + cells[c] + "' is not a finite number"));
      }
      row.emplace_back(v);
    }
    table.rows.push_back(std::move(row));
  }
  if (table.columns.empty()) throw InputError(located_message(path, 0, 0, "empty file"));
  return table;
}

std::size_t require_column(const NumericTable& t, const std::string& path, const std::string& name,
                           const char* what) {
  if (const auto i = t.find(name)) return *i;
  throw InputError(located_message(
      path, 1, 0, "no column '" + name + "' (is this " + what + " written by imunoise?)"));
}

/// The OADEV and OHDEV curves of allan.csv (imunoise analyze), one series per axis and
/// statistic, at the rows where the statistic has a value.
std::vector<io::DeviationSeries> read_allan_csv(const std::string& path, double confidence) {
  const NumericTable t = read_numeric_table(path);
  const std::size_t tau = require_column(t, path, "tau_s", "an allan.csv");
  std::vector<io::DeviationSeries> out;
  for (const char* axis : io::kImuChannelNames) {
    const bool gyro = std::string(axis).rfind("gyro", 0) == 0;
    const std::string unit_suffix = gyro ? "rad_per_s" : "m_per_s2";
    for (const char* statistic : {"oadev", "ohdev"}) {
      const std::string base = std::string(axis) + "_" + statistic + "_";
      const auto value = t.find(base + unit_suffix);
      if (!value) continue;  // an axis that was not analysed
      const std::size_t low = require_column(t, path, base + "ci_low_" + unit_suffix, "allan.csv");
      const std::size_t high =
          require_column(t, path, base + "ci_high_" + unit_suffix, "allan.csv");
      io::DeviationSeries s;
      s.axis_name = axis;
      s.statistic = statistic;
      s.unit = gyro ? "rad/s" : "m/s^2";
      s.confidence = confidence;
      for (const auto& row : t.rows) {
        if (!row[*value] || !row[tau]) continue;
        s.tau_s.push_back(*row[tau]);
        s.deviation.push_back(*row[*value]);
        s.ci_low.push_back(row[low].value_or(0.0));
        s.ci_high.push_back(row[high].value_or(0.0));
      }
      out.push_back(std::move(s));
    }
  }
  if (out.empty()) {
    throw InputError(located_message(path, 1, 0, "no <axis>_oadev_/_ohdev_ columns found"));
  }
  return out;
}

/// drift_envelope.csv (imunoise drift): predicted 1σ and the measured RMS drift.
io::DriftSeries read_drift_csv(const std::string& path) {
  const NumericTable t = read_numeric_table(path);
  const char* what = "a drift_envelope.csv";
  const std::size_t time = require_column(t, path, "time_s", what);
  const std::size_t drms = require_column(t, path, "predicted_horizontal_drms_m", what);
  const std::size_t roll = require_column(t, path, "predicted_roll_sigma_deg", what);
  const std::size_t pitch = require_column(t, path, "predicted_pitch_sigma_deg", what);
  const std::size_t heading = require_column(t, path, "predicted_heading_sigma_deg", what);
  const auto actual = t.find("actual_rms_horizontal_error_m");
  io::DriftSeries d;
  d.height_hold = true;  // imunoise drift always holds the height (theory.md §7.2)
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    for (std::size_t c : {time, drms, roll, pitch, heading}) {
      if (!row[c]) {
        throw InputError(located_message(path, static_cast<std::int64_t>(r) + 2, 0,
                                         "empty cell in column '" + t.columns[c] + "'"));
      }
    }
    d.time_s.push_back(*row[time]);
    d.horizontal_sigma_m.push_back(*row[drms]);
    d.vertical_sigma_m.push_back(0.0);
    d.attitude_sigma_rad.push_back(units::kDeg *
                                   std::sqrt(*row[roll] * *row[roll] + *row[pitch] * *row[pitch] +
                                             *row[heading] * *row[heading]));
    if (actual && row[*actual]) d.actual_horizontal_m.push_back(*row[*actual]);
  }
  if (d.actual_horizontal_m.size() != d.time_s.size()) d.actual_horizontal_m.clear();
  return d;
}

void run_publish(const PublishArgs& args) {
  if (args.repeat < 1) throw InputError("--repeat: expected at least 1");
  const double interval_s = parse_duration_s(args.interval, "--interval", true);
  // Read everything before opening the bus: a bad file publishes nothing.
  const models::NoiseModel model = io::load_model_yaml(args.model_path);
  std::vector<io::DeviationSeries> curves;
  if (!args.curves_path.empty()) curves = read_allan_csv(args.curves_path, model.confidence);
  std::optional<io::DriftSeries> drift;
  if (!args.drift_path.empty()) drift = read_drift_csv(args.drift_path);

  LcmBus bus(args.url);
  for (int k = 0; k < args.repeat; ++k) {
    if (k > 0) std::this_thread::sleep_for(std::chrono::duration<double>(interval_s));
    const std::int64_t utime = now_utime_us();
    bus.publish(args.model_channel, io::noise_model_message(model, utime));
    for (const io::DeviationSeries& c : curves) {
      bus.publish(args.curves_channel, io::allan_curve_message(c, utime));
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
  cmd->callback([args] { run_publish(*args); });
}

}  // namespace imunoise::tools
