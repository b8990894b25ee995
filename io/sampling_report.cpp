#include "io/sampling_report.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/number_text.h"
#include "common/sampling_gap.h"
#include "common/units.h"

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

/// The same value in the unit people read off datasheets, for gyro and accel channels.
std::string human_value(double v, const std::string& unit) {
  if (unit == "rad/s") return printf_string("%.4g deg/s", v / units::kDegPerS);
  if (unit == "m/s^2") return printf_string("%.4g mg", v / units::kMilliG);
  return {};
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
    out += printf_string("rate:       %.6g Hz from the median interval ", t.rate_hz) +
           duration_text(t.median_interval_s) +
           printf_string(" (mean rate %.6g Hz)\n", t.mean_rate_hz);
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

}  // namespace imunoise::io
