#include "io/simulation_output.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <optional>
#include <span>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/recording_csv_writer.h"
#include "io/recording_lcm_writer.h"
#include "io/simulation_setup.h"
#include "pipeline/sampling_checks.h"

namespace imunoise::io {

namespace {

constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};

bool ends_with(const std::string& path, std::string_view suffix) {
  return path.size() > suffix.size() &&
         path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The median of a stream of intervals, from a histogram of the distinct values (a handful per
/// binade of t for stamps k / rate), as pipeline::analyze_timing takes it.
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

}  // namespace

SimulationOutputFormat simulation_output_format(const std::string& path) {
  if (ends_with(path, kBinaryRecordingExtension)) return SimulationOutputFormat::kBinary;
  if (ends_with(path, ".lcmlog")) return SimulationOutputFormat::kLcmLog;
  return SimulationOutputFormat::kCsv;
}

SimulationRun simulation_run(const SimulationModelFile& setup, double rate_hz, double duration_s,
                             std::int64_t samples, std::uint64_t seed) {
  SimulationRun run;
  run.sample_rate_hz = rate_hz;
  run.duration_s = duration_s;
  run.samples = samples;
  run.seed = seed;
  run.flicker_band = setup.flicker_band.value_or(
      models::FlickerBand{1.0 / rate_hz, std::max(duration_s, 2.0 / rate_hz)});
  return run;
}

models::ImuSimulator make_simulator(const SimulationModelFile& setup, const SimulationRun& run) {
  const models::ImuNoiseModel model = imu_noise_model(setup);
  models::SimulationOptions options;
  options.sample_rate_hz = run.sample_rate_hz;
  options.seed = run.seed;
  options.flicker_band = run.flicker_band;
  return models::ImuSimulator(model, options);
}

double simulated_sample_period_s(double rate_hz, std::int64_t samples) {
  IntervalMedian median;
  // The decimal grids every stamp is on so far (bit d: pipeline::on_decimal_grid(t, d)).
  unsigned grids = (1u << (pipeline::kMaxGridDigits + 1)) - 1;
  double previous = 0.0;
  for (std::int64_t k = 1; k < samples; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    median.add(t - previous);
    previous = t;
    for (unsigned g = grids; g != 0; g &= g - 1) {
      const int d = std::countr_zero(g);
      if (!pipeline::on_decimal_grid(t, d)) grids &= ~(1u << d);
    }
  }
  const std::optional<double> m = median.median();
  if (!m) return 1.0 / rate_hz;
  // As analyze_timing: the median on the stamps' decimal grid, when there is one.
  return grids != 0 ? pipeline::snap_to_decimal_grid(*m, std::countr_zero(grids)) : *m;
}

BinaryRecordingHeader simulation_binary_header(const SimulationModelFile& setup,
                                               const SimulationRun& run) {
  BinaryRecordingHeader h;
  h.source_path = setup.source;
  h.created_by = std::string(kBinaryCreatedBy);
  h.sample_period_s = simulated_sample_period_s(run.sample_rate_hz, run.samples);
  h.has_time = true;
  h.sample_count = static_cast<std::uint64_t>(run.samples);
  for (std::size_t c = 0; c < models::kImuChannels; ++c) {
    pipeline::Channel channel;
    channel.name = pipeline::kImuChannelNames[c];
    channel.kind = pipeline::kImuChannelKinds[c];
    channel.source_column = csv_column_name(channel);
    channel.source_unit = channel.unit();
    h.channels.push_back(std::move(channel));
  }
  return h;
}

void write_simulation_csv_header(std::ostream& out, const SimulationModelFile& setup,
                                 const SimulationRun& run) {
  out << "# imunoise simulate: synthetic stationary IMU recording, SI units\n";
  out << "# model: " << setup.source;
  if (!setup.name.empty()) out << " (" << setup.name << ")";
  out << "\n# seed: " << run.seed
      << "\n# sample_rate_hz: " << shortest_number_text(run.sample_rate_hz)
      << "\n# duration_s: " << shortest_number_text(run.duration_s)
      << "\n# samples: " << run.samples << "\n# flicker_band_s: ["
      << shortest_number_text(run.flicker_band.tau_min_s) << ", "
      << shortest_number_text(run.flicker_band.tau_max_s) << "]\n";
  const auto write_sensor = [&](SensorKind kind, const std::array<SimulationAxis, 3>& axes) {
    for (std::size_t a = 0; a < 3; ++a) {
      out << "# " << sensor_name(kind) << "_" << kAxes[a] << ":" << si_terms_text(axes[a], kind)
          << "\n";
    }
  };
  write_sensor(SensorKind::gyro, setup.gyro);
  write_sensor(SensorKind::accel, setup.accel);
  out << "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,"
         "accel_x_m_per_s2,accel_y_m_per_s2,accel_z_m_per_s2\n";
}

void write_simulation(models::ImuSimulator& simulator, const SimulationModelFile& setup,
                      const SimulationRun& run, const std::string& path,
                      const std::string& lcm_channel, const ProgressCallback& progress) {
  // A binary output goes column by column through its own writer; CSV and LCM through a
  // stream.
  const SimulationOutputFormat format = simulation_output_format(path);
  const bool binary = format == SimulationOutputFormat::kBinary;
  std::optional<BinaryRecordingWriter> binary_writer;
  std::optional<AtomicOutputFile> file;
  if (binary) {
    binary_writer.emplace(path, simulation_binary_header(setup, run));
  } else {
    file.emplace(path);
  }
  std::ostringstream no_stream;  // the binary writer has its own file
  std::ostream& out = file ? file->stream() : no_stream;
  if (format == SimulationOutputFormat::kCsv) write_simulation_csv_header(out, setup, run);
  ImuSampleLogWriter log_writer(out, lcm_channel);

  constexpr std::size_t kBlock = 4096;
  constexpr std::size_t kChannels = models::kImuChannels;
  std::vector<double> values(kChannels * kBlock);
  std::vector<char> text(binary ? 0 : kBlock * (kChannels + 1) * kCsvFieldChars);
  std::vector<double> block_time(binary ? kBlock : 0);
  std::array<std::span<double>, kChannels> spans;
  const double rate_hz = run.sample_rate_hz;
  for (std::int64_t done = 0; done < run.samples;) {
    report_progress(progress, "generating", done, run.samples);
    const std::size_t n = static_cast<std::size_t>(
        std::min<std::int64_t>(static_cast<std::int64_t>(kBlock), run.samples - done));
    for (std::size_t c = 0; c < kChannels; ++c) {
      spans[c] = std::span<double>(values).subspan(c * kBlock, n);
    }
    simulator.next_block(spans);
    const auto time_of = [&](std::size_t i) {
      return static_cast<double>(done + static_cast<std::int64_t>(i)) / rate_hz;
    };
    switch (format) {
      case SimulationOutputFormat::kBinary: {
        std::span<double> time = std::span<double>(block_time).first(n);
        for (std::size_t i = 0; i < n; ++i) time[i] = time_of(i);
        binary_writer->append(0, time);
        for (std::size_t c = 0; c < kChannels; ++c) binary_writer->append(1 + c, spans[c]);
        break;
      }
      case SimulationOutputFormat::kLcmLog:
        // imu_sample_t in SI, stamped in whole µs from 0 (the same stamp as the log event).
        for (std::size_t i = 0; i < n; ++i) {
          const auto k = static_cast<double>(done + static_cast<std::int64_t>(i));
          log_writer.write(std::llround(k * 1e6 / rate_hz), {spans[0][i], spans[1][i], spans[2][i]},
                           {spans[3][i], spans[4][i], spans[5][i]});
        }
        break;
      case SimulationOutputFormat::kCsv: {
        char* p = text.data();
        std::array<double, kChannels> row{};
        for (std::size_t i = 0; i < n; ++i) {
          for (std::size_t c = 0; c < kChannels; ++c) row[c] = spans[c][i];
          p = append_csv_row(p, time_of(i), row);
        }
        out.write(text.data(), p - text.data());
        break;
      }
    }
    done += static_cast<std::int64_t>(n);
  }
  if (binary_writer) binary_writer->commit();
  if (file) file->commit();
}

}  // namespace imunoise::io
