// imunoise._core: the Recording (pipeline::Recording, SI channels with the sampling report),
// read from a file by the readers every command uses (io::read_recording_as, by content), made
// from numpy arrays at a fixed rate, or simulated (models::ImuSimulator, `imunoise simulate`).
#include <pybind11/stl.h>

#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/input_config.h"
#include "io/lcm_log.h"
#include "io/log_topics.h"
#include "io/recording_input.h"
#include "io/sampling_report.h"
#include "io/simulation_output.h"
#include "io/simulation_setup.h"
#include "models/noise_simulator.h"
#include "pipeline/recording.h"
#include "pipeline/sampling_checks.h"
#include "python/core_bindings.h"

namespace imunoise::python {
namespace {

using RecordingPtr = std::shared_ptr<pipeline::Recording>;

/// The column mapping of a table: the input config file CONFIG (io/input_config.h), then the
/// arguments given (the CLI's --time-col, --time-unit, --gyro-cols, … under Python names).
struct TableOptions {
  std::optional<std::string> config, time_col, time_unit, gyro_unit, accel_unit;
  std::vector<std::string> gyro_cols, accel_cols;
  bool given() const {
    return config || time_col || time_unit || gyro_unit || accel_unit || !gyro_cols.empty() ||
           !accel_cols.empty();
  }
};

io::InputConfig table_config(const TableOptions& t) {
  io::InputConfig c = t.config ? io::load_input_config(*t.config) : io::InputConfig{};
  if (t.time_col) c.time_column = *t.time_col;
  if (t.time_unit) {
    c.time_unit = io::parse_time_unit(*t.time_unit);
    if (!c.time_unit)
      throw InputError("time_unit: expected s, ms, us or ns, got '" + *t.time_unit + "'");
  }
  if (t.gyro_unit) {
    c.gyro_unit = io::parse_gyro_unit(*t.gyro_unit);
    if (!c.gyro_unit) {
      throw InputError("gyro_unit: expected rad/s, deg/s, deg/h, rad or deg, got '" + *t.gyro_unit +
                       "'");
    }
  }
  if (t.accel_unit) {
    c.accel_unit = io::parse_accel_unit(*t.accel_unit);
    if (!c.accel_unit) {
      throw InputError("accel_unit: expected m/s^2, g, mg or m/s, got '" + *t.accel_unit + "'");
    }
  }
  if (!t.gyro_cols.empty()) c.gyro_columns = t.gyro_cols;
  if (!t.accel_cols.empty()) c.accel_columns = t.accel_cols;
  return c;
}

RecordingPtr read_recording(const std::string& path, const std::optional<std::string>& topic,
                            std::optional<int> instance,
                            const std::optional<std::string>& time_source,
                            const std::optional<std::string>& lcm_channel,
                            std::optional<double> rate_hz, bool drop_non_finite, unsigned threads,
                            const TableOptions& table) {
  py::gil_scoped_release unlocked;
  const io::RecordingFormat format = io::detect_recording_format(path);
  if (table.given() && format != io::RecordingFormat::kTable) {
    throw InputError(path +
                     ": config and the column/unit arguments apply to CSV/TXT tables; "
                     "this file is read as " +
                     std::string(io::recording_format_name(format)));
  }
  const bool log_options = topic || instance || time_source;
  if (io::is_robotics_log(format)) {
    if (lcm_channel || rate_hz) {
      throw InputError(path + ": " + (lcm_channel ? "lcm_channel" : "rate_hz") +
                       " does not apply to this " + std::string(io::recording_format_name(format)) +
                       " (choose the topic)");
    }
    io::LogReadOptions options;
    options.topic = topic.value_or("");
    options.instance = instance;
    options.drop_non_finite = drop_non_finite;
    if (time_source && *time_source != "header" && *time_source != "log") {
      throw InputError("time_source: expected 'header' or 'log', got '" + *time_source + "'");
    }
    options.time_source = time_source == "log" ? io::TimeSource::kLog : io::TimeSource::kHeader;
    return std::make_shared<pipeline::Recording>(io::read_robotics_log_as(format, path, options));
  }
  if (log_options) {
    throw InputError(path +
                     ": topic, instance and time_source apply to robotics logs (ROS "
                     "bags, MCAP, rosbag2, ULog); this file is read as " +
                     std::string(io::recording_format_name(format)));
  }
  io::InputConfig config = table_config(table);
  if (rate_hz) config.rate_hz = rate_hz;
  if (drop_non_finite) config.drop_non_finite = true;
  io::LcmImuSource lcm;
  if (format == io::RecordingFormat::kLcmLog) {
    lcm.channel =
        lcm_channel ? *lcm_channel : io::only_imu_sample_channel(path, "give lcm_channel=NAME");
  } else if (lcm_channel) {
    throw InputError(path + ": lcm_channel applies to LCM logs; this file is read as " +
                     std::string(io::recording_format_name(format)));
  }
  return std::make_shared<pipeline::Recording>(
      io::read_recording_as(format, path, config, lcm, {}, threads));
}

/// The report of a recording sampled at exactly RATE_HZ, as the CSV reader gives one read with
/// --rate: fixed-rate timing and the checks of every channel.
void fill_fixed_rate_report(pipeline::Recording& r, double rate_hz) {
  r.sample_period_s = 1.0 / rate_hz;
  r.report.samples = static_cast<std::int64_t>(r.sample_count());
  r.report.timing = pipeline::fixed_rate_timing(rate_hz, r.report.samples);
  r.report.channels = pipeline::check_channels(r.channels, std::nullopt, std::nullopt, {});
}

RecordingPtr recording_from_arrays(double rate_hz, const py::dict& channels,
                                   const std::string& source) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw InputError("rate: expected a sample rate > 0 Hz, got " + shortest_number_text(rate_hz));
  }
  auto r = std::make_shared<pipeline::Recording>();
  r->source_path = source;
  // In kImuChannelNames order, whatever the order of the dict.
  std::map<std::string, py::handle> given;
  for (const auto& [key, value] : channels) {
    const std::string name = py::str(key);
    std::size_t k = 0;
    while (k < pipeline::kImuChannelNames.size() && name != pipeline::kImuChannelNames[k]) ++k;
    if (k == pipeline::kImuChannelNames.size()) {
      throw InputError("channels: unknown channel '" + name +
                       "' (gyro_x, gyro_y, gyro_z [rad/s], accel_x, accel_y, accel_z [m/s^2])");
    }
    given[name] = value;
  }
  if (given.empty()) throw InputError("channels: no IMU channel given");
  for (std::size_t k = 0; k < pipeline::kImuChannelNames.size(); ++k) {
    const auto it = given.find(pipeline::kImuChannelNames[k]);
    if (it == given.end()) continue;
    const auto array = py::cast<DoubleArray>(it->second);
    const std::span<const double> values = finite_values(array, "channels['" + it->first + "']");
    if (!r->channels.empty() && values.size() != r->sample_count()) {
      throw InputError("channels['" + it->first + "']: " + std::to_string(values.size()) +
                       " values, the other channels " + std::to_string(r->sample_count()));
    }
    pipeline::Channel c;
    c.name = it->first;
    c.kind = pipeline::kImuChannelKinds[k];
    c.values.assign(values.begin(), values.end());
    c.source_column = it->first;
    c.source_unit = std::string(c.unit());
    r->channels.push_back(std::move(c));
  }
  fill_fixed_rate_report(*r, rate_hz);
  return r;
}

RecordingPtr simulate(const std::string& model_path, double duration_s,
                      std::optional<double> rate_hz, std::uint64_t seed) {
  py::gil_scoped_release unlocked;
  const io::SimulationModelFile setup = io::load_simulation_setup(model_path);
  double rate = rate_hz.value_or(0.0);
  if (!rate_hz) {
    if (!setup.sample_rate_hz) {
      throw InputError("rate_hz is required (the model file has no sample_rate_hz)");
    }
    rate = *setup.sample_rate_hz;
  }
  if (!(rate > 0.0) || !std::isfinite(rate)) {
    throw InputError("rate_hz: expected > 0, got " + shortest_number_text(rate));
  }
  const double count = std::round(duration_s * rate);
  if (!(count >= 1.0) || count > 1e10) {
    throw InputError("duration_s × rate_hz gives " + shortest_number_text(count) +
                     " samples; expected 1 to 1e10");
  }
  const auto n = static_cast<std::int64_t>(count);
  const io::SimulationRun run = io::simulation_run(setup, rate, duration_s, n, seed);
  models::ImuSimulator simulator = io::make_simulator(setup, run);
  auto r = std::make_shared<pipeline::Recording>();
  r->source_path = model_path;
  for (std::size_t k = 0; k < pipeline::kImuChannelNames.size(); ++k) {
    pipeline::Channel c;
    c.name = pipeline::kImuChannelNames[k];
    c.kind = pipeline::kImuChannelKinds[k];
    c.values.resize(static_cast<std::size_t>(n));
    c.source_column = c.name;
    c.source_unit = std::string(c.unit());
    r->channels.push_back(std::move(c));
  }
  // The simulator's blocks, written straight into the channels.
  constexpr std::size_t kBlock = 1 << 16;
  for (std::size_t at = 0; at < static_cast<std::size_t>(n); at += kBlock) {
    const std::size_t len = std::min(kBlock, static_cast<std::size_t>(n) - at);
    std::array<std::span<double>, models::kImuChannels> out;
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = {r->channels[k].values.data() + at, len};
    simulator.next_block(out);
  }
  fill_fixed_rate_report(*r, rate);
  return r;
}

}  // namespace

void add_recording_functions(py::module_& m) {
  py::class_<pipeline::Recording, RecordingPtr>(m, "Recording")
      .def_property_readonly("source_path",
                             [](const pipeline::Recording& r) { return r.source_path; })
      .def_property_readonly("sample_period_s",
                             [](const pipeline::Recording& r) { return r.sample_period_s; })
      .def_property_readonly("rate_hz",
                             [](const pipeline::Recording& r) { return r.report.timing.rate_hz; })
      .def_property_readonly("start_time_s",
                             [](const pipeline::Recording& r) { return r.start_time_s; })
      .def_property_readonly("sample_count", &pipeline::Recording::sample_count)
      .def_property_readonly("time_s",
                             [](py::object self) {
                               return array_view(self.cast<const pipeline::Recording&>().time_s,
                                                 self);
                             })
      .def_property_readonly("channel_names",
                             [](const pipeline::Recording& r) {
                               std::vector<std::string> names;
                               for (const auto& c : r.channels) names.push_back(c.name);
                               return names;
                             })
      .def(
          "channel",
          [](py::object self, const std::string& name) {
            const auto* c = self.cast<const pipeline::Recording&>().find_channel(name);
            if (c == nullptr) throw InputError("no channel '" + name + "' in this recording");
            return array_view(c->values, self);
          },
          py::arg("name"))
      .def(
          "unit",
          [](const pipeline::Recording& r, const std::string& name) {
            const auto* c = r.find_channel(name);
            if (c == nullptr) throw InputError("no channel '" + name + "' in this recording");
            return std::string(c->unit());
          },
          py::arg("name"))
      .def_property_readonly("sampling_report_json",
                             [](const pipeline::Recording& r) {
                               return io::sampling_report_to_json(r.report, r.source_path).dump();
                             })
      .def_property_readonly("sampling_report_text", [](const pipeline::Recording& r) {
        return io::format_sampling_report(r.report, r.source_path);
      });
  m.def(
      "read_recording",
      [](const std::string& path, const std::optional<std::string>& topic,
         std::optional<int> instance, const std::optional<std::string>& time_source,
         const std::optional<std::string>& lcm_channel, std::optional<double> rate_hz,
         bool drop_non_finite, unsigned threads, std::optional<std::string> config,
         std::optional<std::string> time_col, std::optional<std::string> time_unit,
         std::vector<std::string> gyro_cols, std::optional<std::string> gyro_unit,
         std::vector<std::string> accel_cols, std::optional<std::string> accel_unit) {
        TableOptions table{std::move(config),    std::move(time_col),   std::move(time_unit),
                           std::move(gyro_unit), std::move(accel_unit), std::move(gyro_cols),
                           std::move(accel_cols)};
        return read_recording(path, topic, instance, time_source, lcm_channel, rate_hz,
                              drop_non_finite, threads, table);
      },
      py::arg("path"), py::kw_only(), py::arg("topic") = py::none(),
      py::arg("instance") = py::none(), py::arg("time_source") = py::none(),
      py::arg("lcm_channel") = py::none(), py::arg("rate_hz") = py::none(),
      py::arg("drop_non_finite") = false, py::arg("threads") = 0u, py::arg("config") = py::none(),
      py::arg("time_col") = py::none(), py::arg("time_unit") = py::none(),
      py::arg("gyro_cols") = std::vector<std::string>{}, py::arg("gyro_unit") = py::none(),
      py::arg("accel_cols") = std::vector<std::string>{}, py::arg("accel_unit") = py::none());
  m.def("recording_from_arrays", &recording_from_arrays, py::arg("rate_hz"), py::arg("channels"),
        py::arg("source") = "arrays");
  m.def("simulate", &simulate, py::arg("model_path"), py::arg("duration_s"),
        py::arg("rate_hz") = py::none(), py::arg("seed") = 1);
}

}  // namespace imunoise::python
