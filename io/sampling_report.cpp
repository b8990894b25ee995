#include "io/sampling_report.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/sampling_gap.h"
#include "common/sensor_kind.h"
#include "common/units.h"
#include "io/atomic_output.h"

namespace imunoise::io {

namespace {

std::string printf_string(const char* format, ...) __attribute__((format(printf, 1, 2)));

std::string printf_string(const char* format, ...) {
  char buffer[512];
  va_list args;
  va_start(args, format);
  const int len = std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  if (len < 0) return {};
  return std::string(buffer,
                     std::min<std::size_t>(static_cast<std::size_t>(len), sizeof buffer - 1));
}

std::string where(const std::optional<pipeline::SampleLocation>& loc) {
  if (!loc) return {};
  if (loc->line) return printf_string(" (first at line %" PRId64 ")", *loc->line);
  return printf_string(" (first at sample %" PRId64 ")", loc->index);
}

/// The same value in the unit people read off datasheets, for gyro and accel channels (the
/// channel's unit as the report spells it: "rad/s", "m/s^2"; none for other units).
std::string human_value(double v, const std::string& unit) {
  const std::optional<SensorKind> kind = parse_si_rate_unit(unit);
  if (!kind) return {};
  if (*kind == SensorKind::gyro) return printf_string("%.4g deg/s", v / units::kDegPerS);
  return printf_string("%.4g mg", v / units::kMilliG);
}

nlohmann::ordered_json location_json(const std::optional<pipeline::SampleLocation>& loc) {
  if (!loc) return nullptr;
  nlohmann::ordered_json j;
  j["index"] = loc->index;
  j["line"] = loc->line ? nlohmann::ordered_json(*loc->line) : nlohmann::ordered_json(nullptr);
  return j;
}

}  // namespace

std::string format_sampling_report(const pipeline::SamplingReport& report,
                                   std::string_view source_path) {
  const pipeline::TimingReport& t = report.timing;
  std::string out;
  out += "file:       " + std::string(source_path) + "\n";
  out += printf_string("samples:    %" PRId64 "\n", report.samples);
  if (report.rows_dropped > 0 || report.non_finite_dropped > 0) {
    out += printf_string("dropped:    %" PRId64 " rows holding %" PRId64 " NaN/Inf values\n",
                         report.rows_dropped, report.non_finite_dropped);
  }
  if (!t.has_timestamps) {
    out += printf_string("rate:       %.6g Hz (given; no time stamps to check)\n", t.rate_hz);
    out += "duration:   " + duration_text(t.duration_s) + "\n";
  } else {
    if (t.period_from_mean) {
      out +=
          printf_string("rate:       %.6g Hz from the mean regular interval ", t.rate_hz) +
          duration_text(t.mean_interval_s) + " (median " + duration_text(t.median_interval_s) +
          printf_string("; quantized or alternating stamps; mean rate %.6g Hz)\n", t.mean_rate_hz);
    } else {
      out += printf_string("rate:       %.6g Hz from the median interval ", t.rate_hz) +
             duration_text(t.median_interval_s) +
             printf_string(" (mean rate %.6g Hz)\n", t.mean_rate_hz);
    }
    out += "duration:   " + duration_text(t.duration_s) + "\n";
    out += printf_string("gaps:       %" PRId64, t.gap_count);
    if (t.gap_count > 0) {
      out += " (longest " + duration_text(t.longest_gap_s) +
             printf_string(", about %" PRId64 " samples missing)", t.missing_samples) +
             where(t.first_gap);
    }
    out += "\n";
    out += printf_string("order:      %" PRId64 " non-monotonic", t.non_monotonic_count) +
           where(t.first_non_monotonic) +
           printf_string(", %" PRId64 " duplicate", t.duplicate_count) + where(t.first_duplicate) +
           " time stamps\n";
    out += "jitter:     RMS " + duration_text(t.jitter_rms_s) + ", max " +
           duration_text(t.jitter_max_s) + " (interval - median, gaps excluded)\n";
  }
  for (const pipeline::ChannelReport& c : report.channels) {
    const std::string unit = c.unit.empty() ? "" : " " + c.unit;
    out += "\n" + c.name + " [" + (c.unit.empty() ? "as in file" : c.unit) + "]\n";
    out += printf_string("  range:      %.9g .. %.9g%s, mean %.9g, std %.4g\n", c.min, c.max,
                         unit.c_str(), c.mean, c.std_dev);
    if (c.lsb) {
      const std::string human = human_value(*c.lsb, c.unit);
      out += printf_string("  LSB:        %.6g%s", *c.lsb, unit.c_str()) +
             (human.empty() ? "" : " (" + human + ")") +
             printf_string(", %.0f codes span the range\n", (c.max - c.min) / *c.lsb);
    } else {
      out += "  LSB:        none detected\n";
    }
    if (c.constant) {
      out += "  saturation: constant channel (every sample equal)\n";
    } else if (c.saturation_runs > 0) {
      out += printf_string("  saturation: %" PRId64 " runs at min/max (%" PRId64
                           " samples, longest %" PRId64 ")",
                           c.saturation_runs, c.saturated_samples, c.longest_saturation_run) +
             where(c.first_saturation) + "\n";
    } else {
      out += "  saturation: none\n";
    }
    if (c.full_scale) {
      out += printf_string("  full scale: +/-%.6g%s, %" PRId64 " samples at or beyond",
                           *c.full_scale, unit.c_str(), c.beyond_full_scale) +
             where(c.first_beyond_full_scale) + "\n";
    }
  }
  return out;
}

nlohmann::ordered_json sampling_report_to_json(const pipeline::SamplingReport& report,
                                               std::string_view source_path) {
  const pipeline::TimingReport& t = report.timing;
  nlohmann::ordered_json j;
  j["file"] = std::string(source_path);
  j["samples"] = report.samples;
  j["has_timestamps"] = t.has_timestamps;
  j["rate_hz"] = t.rate_hz;
  j["median_interval_s"] = t.median_interval_s;
  j["mean_interval_s"] = t.mean_interval_s;
  j["sample_period_s"] = t.sample_period_s;
  j["period_from_mean"] = t.period_from_mean;
  j["mean_rate_hz"] = t.mean_rate_hz;
  j["duration_s"] = t.duration_s;
  j["gap_count"] = t.gap_count;
  j["longest_gap_s"] = t.longest_gap_s;
  j["missing_samples"] = t.missing_samples;
  j["first_gap"] = location_json(t.first_gap);
  j["non_monotonic_count"] = t.non_monotonic_count;
  j["first_non_monotonic"] = location_json(t.first_non_monotonic);
  j["duplicate_count"] = t.duplicate_count;
  j["first_duplicate"] = location_json(t.first_duplicate);
  j["jitter_rms_s"] = t.jitter_rms_s;
  j["jitter_max_s"] = t.jitter_max_s;
  j["interval_histogram"] = {{"bin_low_s", t.interval_histogram.bin_low_s},
                             {"bin_high_s", t.interval_histogram.bin_high_s},
                             {"counts", t.interval_histogram.counts}};
  nlohmann::ordered_json gaps = nlohmann::ordered_json::array();
  for (const pipeline::GapRecord& g : t.gaps) {
    gaps.push_back(
        {{"after", location_json(g.after)}, {"start_s", g.start_s}, {"length_s", g.length_s}});
  }
  j["gaps"] = std::move(gaps);
  j["non_finite_dropped"] = report.non_finite_dropped;
  j["rows_dropped"] = report.rows_dropped;
  nlohmann::ordered_json channels = nlohmann::ordered_json::array();
  for (const pipeline::ChannelReport& c : report.channels) {
    nlohmann::ordered_json cj;
    cj["name"] = c.name;
    cj["unit"] = c.unit;
    cj["min"] = c.min;
    cj["max"] = c.max;
    cj["mean"] = c.mean;
    cj["std"] = c.std_dev;
    cj["constant"] = c.constant;
    cj["lsb"] = c.lsb ? nlohmann::ordered_json(*c.lsb) : nlohmann::ordered_json(nullptr);
    cj["saturation_runs"] = c.saturation_runs;
    cj["saturated_samples"] = c.saturated_samples;
    cj["longest_saturation_run"] = c.longest_saturation_run;
    cj["first_saturation"] = location_json(c.first_saturation);
    cj["full_scale"] =
        c.full_scale ? nlohmann::ordered_json(*c.full_scale) : nlohmann::ordered_json(nullptr);
    cj["beyond_full_scale"] = c.beyond_full_scale;
    cj["first_beyond_full_scale"] = location_json(c.first_beyond_full_scale);
    channels.push_back(std::move(cj));
  }
  j["channels"] = std::move(channels);
  return j;
}

// --- Reading back ------------------------------------------------------------------------------

namespace {

using Json = nlohmann::ordered_json;

/// Where a value sits, for messages: the source (a path) and the place in it ("channels[2]").
struct Place {
  std::string_view where;
  std::string path;  ///< empty at the top level

  Place child(const std::string& key) const {
    return {where, path.empty() ? key : path + "." + key};
  }
  Place element(const char* key, std::size_t i) const {
    return child(std::string(key) + "[" + std::to_string(i) + "]");
  }
};

[[noreturn]] void fail(const Place& p, const std::string& problem) {
  std::string message(p.where);
  message += ": ";
  if (!p.path.empty()) message += p.path + ": ";
  throw InputError(message + problem);
}

[[noreturn]] void not_a(const Place& p, const char* key, const char* what) {
  fail(p, std::string("key '") + key + "' not " + what);
}

/// The value of KEY in the object O (checked to be one by the caller).
const Json& at(const Json& o, const Place& p, const char* key) {
  const auto it = o.find(key);
  if (it == o.end()) fail(p, std::string("key '") + key + "' missing");
  return *it;
}

const Json& object_at(const Json& o, const Place& p, const char* key) {
  const Json& v = at(o, p, key);
  if (!v.is_object()) not_a(p, key, "an object");
  return v;
}

const Json& array_at(const Json& o, const Place& p, const char* key) {
  const Json& v = at(o, p, key);
  if (!v.is_array()) not_a(p, key, "an array");
  return v;
}

/// A real written by the writer: a number, or null for one JSON cannot hold (NaN, ±inf).
double real_of(const Json& v, const Place& p, const char* key) {
  if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!v.is_number()) not_a(p, key, "a number");
  return v.get<double>();
}

double real_at(const Json& o, const Place& p, const char* key) {
  return real_of(at(o, p, key), p, key);
}

/// An optional real: null = empty.
std::optional<double> optional_real_at(const Json& o, const Place& p, const char* key) {
  const Json& v = at(o, p, key);
  if (v.is_null()) return std::nullopt;
  if (!v.is_number()) not_a(p, key, "a number or null");
  return v.get<double>();
}

std::int64_t integer_of(const Json& v, const Place& p, const char* key) {
  if (!v.is_number_integer() ||
      (v.is_number_unsigned() &&
       v.get<std::uint64_t>() >
           static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))) {
    not_a(p, key, "an integer");
  }
  return v.get<std::int64_t>();
}

std::int64_t integer_at(const Json& o, const Place& p, const char* key) {
  return integer_of(at(o, p, key), p, key);
}

bool boolean_at(const Json& o, const Place& p, const char* key) {
  const Json& v = at(o, p, key);
  if (!v.is_boolean()) not_a(p, key, "a boolean");
  return v.get<bool>();
}

std::string string_at(const Json& o, const Place& p, const char* key) {
  const Json& v = at(o, p, key);
  if (!v.is_string()) not_a(p, key, "a string");
  return v.get<std::string>();
}

/// A location as location_json writes it: {"index": 0-based sample, "line": line or null}.
pipeline::SampleLocation location_of(const Json& v, const Place& p, const char* key) {
  if (!v.is_object()) not_a(p, key, "an object");
  const Place in = p.child(key);
  pipeline::SampleLocation loc;
  loc.index = integer_at(v, in, "index");
  const Json& line = at(v, in, "line");
  if (!line.is_null()) loc.line = integer_of(line, in, "line");
  return loc;
}

/// An optional location: null = none.
std::optional<pipeline::SampleLocation> optional_location_at(const Json& o, const Place& p,
                                                             const char* key) {
  const Json& v = at(o, p, key);
  if (v.is_null()) return std::nullopt;
  return location_of(v, p, key);
}

std::vector<double> reals_at(const Json& o, const Place& p, const char* key) {
  std::vector<double> out;
  const Json& a = array_at(o, p, key);
  for (std::size_t i = 0; i < a.size(); ++i) out.push_back(real_of(a[i], p, key));
  return out;
}

std::vector<std::int64_t> integers_at(const Json& o, const Place& p, const char* key) {
  std::vector<std::int64_t> out;
  const Json& a = array_at(o, p, key);
  for (std::size_t i = 0; i < a.size(); ++i) out.push_back(integer_of(a[i], p, key));
  return out;
}

pipeline::IntervalHistogram histogram_of(const Json& h, const Place& p) {
  pipeline::IntervalHistogram out;
  out.bin_low_s = reals_at(h, p, "bin_low_s");
  out.bin_high_s = reals_at(h, p, "bin_high_s");
  out.counts = integers_at(h, p, "counts");
  if (out.bin_low_s.size() != out.counts.size() || out.bin_high_s.size() != out.counts.size()) {
    fail(p, "bin_low_s, bin_high_s and counts differ in length");
  }
  return out;
}

pipeline::ChannelReport channel_of(const Json& c, const Place& p) {
  pipeline::ChannelReport out;
  out.name = string_at(c, p, "name");
  out.unit = string_at(c, p, "unit");
  out.min = real_at(c, p, "min");
  out.max = real_at(c, p, "max");
  out.mean = real_at(c, p, "mean");
  out.std_dev = real_at(c, p, "std");
  out.constant = boolean_at(c, p, "constant");
  out.lsb = optional_real_at(c, p, "lsb");
  out.saturation_runs = integer_at(c, p, "saturation_runs");
  out.saturated_samples = integer_at(c, p, "saturated_samples");
  out.longest_saturation_run = integer_at(c, p, "longest_saturation_run");
  out.first_saturation = optional_location_at(c, p, "first_saturation");
  out.full_scale = optional_real_at(c, p, "full_scale");
  out.beyond_full_scale = integer_at(c, p, "beyond_full_scale");
  out.first_beyond_full_scale = optional_location_at(c, p, "first_beyond_full_scale");
  return out;
}

/// The keys of sampling_report_to_json, in its order.
SamplingReportFile report_of(const Json& j, std::string_view where) {
  const Place top{where, {}};
  if (!j.is_object()) fail(top, "not a JSON object");
  SamplingReportFile file;
  file.source_path = string_at(j, top, "file");
  pipeline::SamplingReport& r = file.report;
  pipeline::TimingReport& t = r.timing;
  r.samples = integer_at(j, top, "samples");
  t.has_timestamps = boolean_at(j, top, "has_timestamps");
  t.rate_hz = real_at(j, top, "rate_hz");
  t.median_interval_s = real_at(j, top, "median_interval_s");
  // Written since the sample period may be the mean interval; older files: the median.
  if (j.contains("sample_period_s")) {
    t.mean_interval_s = real_at(j, top, "mean_interval_s");
    t.sample_period_s = real_at(j, top, "sample_period_s");
    t.period_from_mean = boolean_at(j, top, "period_from_mean");
  } else {
    t.mean_interval_s = t.median_interval_s;
    t.sample_period_s = t.median_interval_s;
  }
  t.mean_rate_hz = real_at(j, top, "mean_rate_hz");
  t.duration_s = real_at(j, top, "duration_s");
  t.gap_count = integer_at(j, top, "gap_count");
  t.longest_gap_s = real_at(j, top, "longest_gap_s");
  t.missing_samples = integer_at(j, top, "missing_samples");
  t.first_gap = optional_location_at(j, top, "first_gap");
  t.non_monotonic_count = integer_at(j, top, "non_monotonic_count");
  t.first_non_monotonic = optional_location_at(j, top, "first_non_monotonic");
  t.duplicate_count = integer_at(j, top, "duplicate_count");
  t.first_duplicate = optional_location_at(j, top, "first_duplicate");
  t.jitter_rms_s = real_at(j, top, "jitter_rms_s");
  t.jitter_max_s = real_at(j, top, "jitter_max_s");
  t.interval_histogram =
      histogram_of(object_at(j, top, "interval_histogram"), top.child("interval_histogram"));
  const Json& gaps = array_at(j, top, "gaps");
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    const Place in = top.element("gaps", i);
    if (!gaps[i].is_object()) fail(in, "not an object");
    pipeline::GapRecord g;
    g.after = location_of(at(gaps[i], in, "after"), in, "after");
    g.start_s = real_at(gaps[i], in, "start_s");
    g.length_s = real_at(gaps[i], in, "length_s");
    t.gaps.push_back(g);
  }
  r.non_finite_dropped = integer_at(j, top, "non_finite_dropped");
  r.rows_dropped = integer_at(j, top, "rows_dropped");
  const Json& channels = array_at(j, top, "channels");
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const Place in = top.element("channels", i);
    if (!channels[i].is_object()) fail(in, "not an object");
    r.channels.push_back(channel_of(channels[i], in));
  }
  return file;
}

}  // namespace

pipeline::SamplingReport sampling_report_from_json(const nlohmann::ordered_json& j,
                                                   std::string_view where) {
  return report_of(j, where).report;
}

void write_sampling_report_json(const std::string& path, const pipeline::SamplingReport& report,
                                std::string_view source_path) {
  write_file_atomically(path, sampling_report_to_json(report, source_path).dump(2) + "\n");
}

SamplingReportFile read_sampling_report_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open for reading");
  Json j;
  try {
    j = Json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path + ": not valid JSON (" + e.what() + ")");
  }
  return report_of(j, path);
}

}  // namespace imunoise::io
