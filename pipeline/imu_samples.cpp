#include "pipeline/imu_samples.h"

#include <optional>
#include <utility>

#include "common/errors.h"
#include "pipeline/sampling_checks.h"

namespace imunoise::pipeline {

namespace {

/// Time since the first stamp [s], exact in integer µs unless the difference overflows.
double relative_seconds(std::int64_t utime, std::int64_t first) {
  std::int64_t diff = 0;
  if (__builtin_sub_overflow(utime, first, &diff)) {
    return (static_cast<double>(utime) - static_cast<double>(first)) * 1e-6;
  }
  return static_cast<double>(diff) * 1e-6;
}

}  // namespace

void ImuSampleColumns::clear() {
  utime_us.clear();
  for (auto& v : values) v.clear();
  temperature_degc.clear();
  non_finite_dropped = 0;
  rows_dropped = 0;
}

void append_sample_temperature(ImuSampleColumns& samples, std::optional<double> temperature_degc) {
  IMUNOISE_EXPECT(samples.size() > 0, "append_sample_temperature: append the sample's stamp first");
  // Every sample so far had one exactly when the column is one shorter than the stamps.
  if (temperature_degc && samples.temperature_degc.size() == samples.size() - 1) {
    samples.temperature_degc.push_back(*temperature_degc);
  }
}

Recording recording_from_imu_samples(ImuSampleColumns samples, const std::string& source_path,
                                     const std::string& channel) {
  const std::size_t n = samples.size();
  require_min_samples(source_path, n, 2, "a sample rate from time stamps");

  Recording rec;
  rec.source_path = source_path;
  rec.start_time_s = static_cast<double>(samples.utime_us.front()) * 1e-6;
  rec.time_s.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    rec.time_s[i] = relative_seconds(samples.utime_us[i], samples.utime_us.front());
  }
  const SamplingOptions sampling;
  const TimingReport timing = analyze_timing(rec.time_s, sampling);
  if (!(timing.median_interval_s > 0.0)) {
    throw InputError(located_message(source_path, 0, 0,
                                     "cannot estimate the sample rate: the utime stamps on "
                                     "channel '" +
                                         channel + "' never increase"));
  }
  rec.sample_period_s = timing.sample_period_s;

  const auto add_channel = [&](std::string name, std::optional<SensorKind> kind,
                               std::string source_unit, const std::string& field,
                               std::vector<double> v, bool from_inc) {
    Channel ch;
    ch.name = std::move(name);
    ch.kind = kind;
    ch.source_unit = std::move(source_unit);
    ch.source_column = channel + "." + field;
    ch.from_increments = from_inc;
    ch.values = std::move(v);
    if (from_inc) {
      for (double& x : ch.values) x /= rec.sample_period_s;  // as csv_reader: increment / Δt
    }
    rec.channels.push_back(std::move(ch));
  };
  for (std::size_t c = 0; c < 6; ++c) {
    add_channel(kImuChannelNames[c], kImuChannelKinds[c], samples.source_units[c],
                samples.source_fields[c], std::move(samples.values[c]), samples.increments);
  }
  if (samples.temperature_degc.size() == n) {
    // An extra channel, as a CSV extra column: no kind, unit "" (as in the source), here °C.
    add_channel("temperature", std::nullopt, "degC", samples.temperature_field,
                std::move(samples.temperature_degc), false);
  }

  rec.report.samples = static_cast<std::int64_t>(n);
  rec.report.timing = timing;
  rec.report.non_finite_dropped = samples.non_finite_dropped;
  rec.report.rows_dropped = samples.rows_dropped;
  rec.report.channels = check_channels(rec.channels, std::nullopt, std::nullopt, sampling);
  return rec;
}

}  // namespace imunoise::pipeline
