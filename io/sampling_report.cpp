#include "io/sampling_report.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/parallel_for.h"
#include "common/sampling_gap.h"
#include "common/units.h"

namespace imunoise::io {

namespace {

SampleLocation locate(std::size_t index, const SamplingOptions& options) {
  SampleLocation loc;
  loc.index = static_cast<std::int64_t>(index);
  if (options.line_of_sample) loc.line = options.line_of_sample(index);
  return loc;
}

/// The median of V, reordering V (nth_element): callers that need the order keep their own.
double median_in_place(std::vector<double>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  // Even count: mean of the two middle values; the lower one is the max of the left half.
  const double upper = *mid;
  const double lower = *std::max_element(v.begin(), mid);
  return 0.5 * (lower + upper);
}

/// Euclid's algorithm on reals with a relative tolerance: stops when the remainder is within
/// 10 % of the divisor, which absorbs decimal printing and float rounding of scaled codes.
double approximate_gcd(double a, double b) {
  if (a < b) std::swap(a, b);
  for (int i = 0; i < 64 && b > 0.0; ++i) {
    const double r = std::fabs(a - b * std::nearbyint(a / b));
    if (r <= 0.1 * b) return b;
    a = b;
    b = r;
  }
  return 0.0;
}

}  // namespace

namespace {

/// The histogram of the regular intervals (see IntervalHistogram); at least one exists.
IntervalHistogram interval_histogram(const std::vector<double>& intervals, double median,
                                     double gap_limit) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (double d : intervals) {
    if (d > 0.0 && d <= gap_limit) {
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
  IntervalHistogram h;
  // Stamps parsed as decimal seconds differ from the true step by ~1e-14 s: not jitter.
  const bool one_bin = hi - lo <= 1e-9 * median;
  const int bins = one_bin ? 1 : kIntervalHistogramBins;
  const double width = one_bin ? 1e-6 * median : (hi - lo) / bins;
  const double first = one_bin ? median - 0.5 * width : lo;
  h.counts.assign(static_cast<std::size_t>(bins), 0);
  for (int b = 0; b < bins; ++b) {
    h.bin_low_s.push_back(first + b * width);
    h.bin_high_s.push_back(b + 1 == bins ? (one_bin ? first + width : hi)
                                         : first + (b + 1) * width);
  }
  for (double d : intervals) {
    if (!(d > 0.0 && d <= gap_limit)) continue;
    // Clamped as a double: with stamps near the double range an interval is inf and the
    // bin position NaN, which no integer conversion may see.
    const double x = one_bin ? 0.0 : std::floor((d - lo) / width);
    const int b = !(x > 0.0) ? 0 : x >= bins - 1 ? bins - 1 : static_cast<int>(x);
    ++h.counts[static_cast<std::size_t>(b)];
  }
  return h;
}

}  // namespace

TimingReport analyze_timing(std::span<const double> time_s, const SamplingOptions& options) {
  TimingReport t;
  t.has_timestamps = true;
  const std::size_t n = time_s.size();
  if (n < 2) return t;

  // One interval array, reordered by the median search: the histogram does not need the
  // order, and the scan below takes each interval from the stamps again (a copy of 8 bytes
  // per sample is what a 24 h record at 1 kHz cannot afford twice).
  std::vector<double> intervals(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) intervals[i] = time_s[i + 1] - time_s[i];
  double median = median_in_place(intervals);
  if (!(median > 0.0)) {
    // Mostly duplicated stamps: the positive intervals still tell the step.
    std::vector<double> positive;
    for (double d : intervals) {
      if (d > 0.0) positive.push_back(d);
    }
    median = positive.empty() ? 0.0 : median_in_place(positive);
  }
  t.median_interval_s = median;
  t.rate_hz = median > 0.0 ? 1.0 / median : 0.0;
  t.duration_s = time_s[n - 1] - time_s[0];
  t.mean_rate_hz = t.duration_s > 0.0 ? static_cast<double>(n - 1) / t.duration_s : 0.0;

  const double gap_limit = options.gap_factor * median;
  double sum_sq = 0.0;
  std::int64_t jitter_count = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double d = time_s[i + 1] - time_s[i];
    if (d < 0.0) {
      if (t.non_monotonic_count++ == 0) t.first_non_monotonic = locate(i + 1, options);
    } else if (d == 0.0) {
      if (t.duplicate_count++ == 0) t.first_duplicate = locate(i + 1, options);
    } else if (median > 0.0 && d > gap_limit) {
      if (t.gap_count++ == 0) t.first_gap = locate(i + 1, options);
      if (t.gaps.size() < kMaxListedGaps) {
        t.gaps.push_back(GapRecord{locate(i + 1, options), time_s[i] - time_s[0], d});
      }
      t.longest_gap_s = std::max(t.longest_gap_s, d);
      if (__builtin_add_overflow(t.missing_samples, missing_samples_in_gap(d, median),
                                 &t.missing_samples)) {
        t.missing_samples = std::numeric_limits<std::int64_t>::max();
      }
    } else {
      const double dev = d - median;
      sum_sq += dev * dev;
      t.jitter_max_s = std::max(t.jitter_max_s, std::fabs(dev));
      ++jitter_count;
    }
  }
  if (jitter_count > 0) t.jitter_rms_s = std::sqrt(sum_sq / static_cast<double>(jitter_count));
  if (jitter_count > 0) t.interval_histogram = interval_histogram(intervals, median, gap_limit);
  return t;
}

TimingReport fixed_rate_timing(double rate_hz, std::int64_t samples) {
  TimingReport t;
  t.has_timestamps = false;
  t.rate_hz = rate_hz;
  t.mean_rate_hz = rate_hz;
  t.median_interval_s = rate_hz > 0.0 ? 1.0 / rate_hz : 0.0;
  t.duration_s = samples > 1 ? static_cast<double>(samples - 1) * t.median_interval_s : 0.0;
  return t;
}

std::vector<ChannelReport> analyze_channels(std::span<const ChannelSamples> channels,
                                            const SamplingOptions& options, unsigned threads) {
  std::vector<ChannelReport> reports(channels.size());
  parallel_for(channels.size(), threads,
               [&](std::size_t i) { reports[i] = analyze_channel(channels[i], options); });
  return reports;
}

std::optional<double> estimate_lsb(std::span<const double> values) {
  const std::size_t n = values.size();
  if (n < 3) return std::nullopt;
  double lo = values[0], hi = values[0];
  for (double v : values) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  const double range = hi - lo;
  const double scale = std::max(std::fabs(lo), std::fabs(hi));
  if (!(range > 0.0) || !std::isfinite(range)) return std::nullopt;
  // Steps below this are float rounding of equal codes, not a change of code.
  const double noise_floor = scale * 1e-12;
  constexpr double kMaxLevels = 16777216.0;  // 2^24: no IMU ADC has a finer code grid
  constexpr double kTolerance = 0.1;         // |step − k·q| allowed, as a fraction of q

  double q0 = std::numeric_limits<double>::infinity();
  std::int64_t steps = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double d = std::fabs(values[i + 1] - values[i]);
    if (d > noise_floor) {
      q0 = std::min(q0, d);
      ++steps;
    }
  }
  if (steps < 8) return std::nullopt;

  // The common divisor is searched among small steps (≤ 64 smallest steps): Euclid on a large
  // step would multiply q's rounding error by the step's multiple.
  std::vector<double> small;
  for (std::size_t i = 0; i + 1 < n && small.size() < 4096; ++i) {
    const double d = std::fabs(values[i + 1] - values[i]);
    if (d > noise_floor && d <= 64.0 * q0) small.push_back(d);
  }
  const auto is_multiple = [&](double d, double q) {
    const double k = std::nearbyint(d / q);
    return k >= 1.0 && std::fabs(d - k * q) <= kTolerance * q;
  };
  // Least squares q = Σd / Σk over the small steps that fit the grid: averages the decimal
  // printing error of each value down, so large steps are judged against an accurate q.
  const auto refine = [&](double q) {
    double sum_d = 0.0, sum_k = 0.0;
    for (double d : small) {
      if (!is_multiple(d, q)) continue;
      sum_d += d;
      sum_k += std::nearbyint(d / q);
    }
    return sum_k > 0.0 ? sum_d / sum_k : q;
  };

  double q = q0;
  for (int round = 0; round < 16; ++round) {
    if (!(q > noise_floor) || range / q > kMaxLevels) return std::nullopt;
    // First make q divide every small step; q is then still a difference of data values,
    // accurate to their rounding, so refining it cannot pull it off the grid.
    const auto small_offender =
        std::find_if_not(small.begin(), small.end(), [&](double d) { return is_multiple(d, q); });
    if (small_offender != small.end()) {
      q = approximate_gcd(q, *small_offender);
      continue;
    }
    q = refine(q);
    double offender = 0.0;
    for (std::size_t i = 0; offender == 0.0 && i + 1 < n; ++i) {
      const double d = std::fabs(values[i + 1] - values[i]);
      if (d > noise_floor && !is_multiple(d, q)) offender = d;
    }
    if (offender == 0.0) return q;
    q = approximate_gcd(q, offender);
  }
  return std::nullopt;
}

ChannelReport analyze_channel(const ChannelSamples& channel, const SamplingOptions& options) {
  ChannelReport r;
  r.name = std::string(channel.name);
  r.unit = std::string(channel.unit);
  r.full_scale = channel.full_scale;
  const auto v = channel.values;
  const std::size_t n = v.size();
  if (n == 0) return r;

  double lo = v[0], hi = v[0], sum = 0.0;
  for (double x : v) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    sum += x;
  }
  r.min = lo;
  r.max = hi;
  r.mean = sum / static_cast<double>(n);
  r.constant = lo == hi;

  double sum_sq = 0.0;
  std::size_t run_start = 0;
  const auto close_run = [&](std::size_t end) {  // run is [run_start, end)
    const auto len = static_cast<std::int64_t>(end - run_start);
    const double value = v[run_start];
    if (!r.constant && len >= options.saturation_min_run && (value == lo || value == hi)) {
      if (r.saturation_runs++ == 0) r.first_saturation = locate(run_start, options);
      r.saturated_samples += len;
      r.longest_saturation_run = std::max(r.longest_saturation_run, len);
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double dev = v[i] - r.mean;
    sum_sq += dev * dev;
    if (i > 0 && v[i] != v[run_start]) {
      close_run(i);
      run_start = i;
    }
    if (channel.full_scale && std::fabs(v[i]) >= *channel.full_scale) {
      if (r.beyond_full_scale++ == 0) r.first_beyond_full_scale = locate(i, options);
    }
  }
  close_run(n);
  r.std_dev = n > 1 ? std::sqrt(sum_sq / static_cast<double>(n - 1)) : 0.0;
  r.lsb = estimate_lsb(v);
  return r;
}

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

std::string where(const std::optional<SampleLocation>& loc) {
  if (!loc) return {};
  if (loc->line) return printf_string(" (first at line %" PRId64 ")", *loc->line);
  return printf_string(" (first at sample %" PRId64 ")", loc->index);
}

/// A duration with a readable unit.
std::string seconds(double s) {
  const double a = std::fabs(s);
  if (a == 0.0) return "0 s";
  if (a < 1e-6) return printf_string("%.3g ns", s * 1e9);
  if (a < 1e-3) return printf_string("%.3g us", s * 1e6);
  if (a < 1.0) return printf_string("%.4g ms", s * 1e3);
  return printf_string("%.6g s", s);
}

/// The same value in the unit people read off datasheets, for gyro and accel channels.
std::string human_value(double v, const std::string& unit) {
  if (unit == "rad/s") return printf_string("%.4g deg/s", v / units::kDegPerS);
  if (unit == "m/s^2") return printf_string("%.4g mg", v / units::kMilliG);
  return {};
}

nlohmann::ordered_json location_json(const std::optional<SampleLocation>& loc) {
  if (!loc) return nullptr;
  nlohmann::ordered_json j;
  j["index"] = loc->index;
  j["line"] = loc->line ? nlohmann::ordered_json(*loc->line) : nlohmann::ordered_json(nullptr);
  return j;
}

}  // namespace

std::string format_sampling_report(const SamplingReport& report, std::string_view source_path) {
  const TimingReport& t = report.timing;
  std::string out;
  out += "file:       " + std::string(source_path) + "\n";
  out += printf_string("samples:    %" PRId64 "\n", report.samples);
  if (report.rows_dropped > 0 || report.non_finite_dropped > 0) {
    out += printf_string("dropped:    %" PRId64 " rows holding %" PRId64 " NaN/Inf values\n",
                         report.rows_dropped, report.non_finite_dropped);
  }
  if (!t.has_timestamps) {
    out += printf_string("rate:       %.6g Hz (given; no time stamps to check)\n", t.rate_hz);
    out += "duration:   " + seconds(t.duration_s) + "\n";
  } else {
    out += printf_string("rate:       %.6g Hz from the median interval ", t.rate_hz) +
           seconds(t.median_interval_s) + printf_string(" (mean rate %.6g Hz)\n", t.mean_rate_hz);
    out += "duration:   " + seconds(t.duration_s) + "\n";
    out += printf_string("gaps:       %" PRId64, t.gap_count);
    if (t.gap_count > 0) {
      out += " (longest " + seconds(t.longest_gap_s) +
             printf_string(", about %" PRId64 " samples missing)", t.missing_samples) +
             where(t.first_gap);
    }
    out += "\n";
    out += printf_string("order:      %" PRId64 " non-monotonic", t.non_monotonic_count) +
           where(t.first_non_monotonic) +
           printf_string(", %" PRId64 " duplicate", t.duplicate_count) + where(t.first_duplicate) +
           " time stamps\n";
    out += "jitter:     RMS " + seconds(t.jitter_rms_s) + ", max " + seconds(t.jitter_max_s) +
           " (interval - median, gaps excluded)\n";
  }
  for (const ChannelReport& c : report.channels) {
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

nlohmann::ordered_json sampling_report_to_json(const SamplingReport& report,
                                               std::string_view source_path) {
  const TimingReport& t = report.timing;
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
  for (const GapRecord& g : t.gaps) {
    gaps.push_back(
        {{"after", location_json(g.after)}, {"start_s", g.start_s}, {"length_s", g.length_s}});
  }
  j["gaps"] = std::move(gaps);
  j["non_finite_dropped"] = report.non_finite_dropped;
  j["rows_dropped"] = report.rows_dropped;
  nlohmann::ordered_json channels = nlohmann::ordered_json::array();
  for (const ChannelReport& c : report.channels) {
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
