#include "pipeline/imu_samples.h"

#include <array>
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

namespace {

/// The six channels of `values` (+ the temperature when TEMPERATURE has one value per sample)
/// and the sampling report, on REC whose time_s and source_path are set. The error for stamps
/// that never increase is "cannot estimate the sample rate: " + NEVER_INCREASE.
void add_channels_and_report(Recording& rec, std::array<std::vector<double>, 6>& values,
                             const std::array<std::string, 6>& source_fields,
                             const std::array<std::string, 6>& source_units, bool increments,
                             std::vector<double>* temperature, const std::string& temperature_field,
                             const std::string& channel, const std::string& never_increase) {
  const std::size_t n = rec.time_s.size();
  const SamplingOptions sampling;
  const TimingReport timing = analyze_timing(rec.time_s, sampling);
  if (!(timing.median_interval_s > 0.0)) {
    throw InputError(located_message(rec.source_path, 0, 0,
                                     "cannot estimate the sample rate: " + never_increase));
  }
  rec.sample_period_s = timing.sample_period_s;

  const auto add_channel = [&](std::string name, std::optional<SensorKind> kind,
                               std::string source_unit, const std::string& field,
                               std::vector<double> v, bool from_inc) {
    Channel ch;
    ch.name = std::move(name);
    ch.kind = kind;
    ch.source_unit = std::move(source_unit);
    ch.source_column = channel.empty() ? field : channel + "." + field;
    ch.from_increments = from_inc;
    ch.values = std::move(v);
    if (from_inc) {
      for (double& x : ch.values) x /= rec.sample_period_s;  // as csv_reader: increment / Δt
    }
    rec.channels.push_back(std::move(ch));
  };
  for (std::size_t c = 0; c < 6; ++c) {
    add_channel(kImuChannelNames[c], kImuChannelKinds[c], source_units[c], source_fields[c],
                std::move(values[c]), increments);
  }
  if (temperature != nullptr && temperature->size() == n) {
    // An extra channel, as a CSV extra column: no kind, unit "" (as in the source), here °C.
    add_channel("temperature", std::nullopt, "degC", temperature_field, std::move(*temperature),
                false);
  }

  rec.report.samples = static_cast<std::int64_t>(n);
  rec.report.timing = timing;
  rec.report.channels = check_channels(rec.channels, std::nullopt, std::nullopt, sampling);
}

}  // namespace

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
  add_channels_and_report(rec, samples.values, samples.source_fields, samples.source_units,
                          samples.increments, &samples.temperature_degc, samples.temperature_field,
                          channel, "the utime stamps on channel '" + channel + "' never increase");
  rec.report.non_finite_dropped = samples.non_finite_dropped;
  rec.report.rows_dropped = samples.rows_dropped;
  return rec;
}

Recording recording_from_stamped_samples(StampedImuColumns samples, const std::string& source_path,
                                         const std::string& topic, const std::string& stamp_name) {
  const std::size_t n = samples.size();
  require_min_samples(source_path, n, 2, "a sample rate from time stamps");
  for (const std::vector<double>& v : samples.values) {
    IMUNOISE_EXPECT(v.size() == n, "recording_from_stamped_samples: a column's size differs");
  }
  Recording rec;
  rec.source_path = source_path;
  const std::int64_t first = samples.stamp_ns.front();
  rec.start_time_s = static_cast<double>(first) * 1e-9;
  rec.time_s.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t diff = 0;
    rec.time_s[i] =
        __builtin_sub_overflow(samples.stamp_ns[i], first, &diff)
            ? (static_cast<double>(samples.stamp_ns[i]) - static_cast<double>(first)) * 1e-9
            : static_cast<double>(diff) * 1e-9;
  }
  add_channels_and_report(
      rec, samples.values, samples.source_fields, samples.source_units, false, nullptr, "", topic,
      "the " + stamp_name + " stamps" +
          (topic.empty() ? std::string() : " of topic '" + topic + "'") + " never increase");
  rec.report.non_finite_dropped = samples.non_finite_dropped;
  rec.report.rows_dropped = samples.rows_dropped;
  return rec;
}

}  // namespace imunoise::pipeline
