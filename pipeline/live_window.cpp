#include "pipeline/live_window.h"

#include <cmath>
#include <utility>

#include "common/errors.h"
#include "common/sampling_gap.h"

namespace imunoise::pipeline {

namespace {

/// b − a [µs] in double: stamps come from the network and may be anything, so no int64
/// subtraction that could overflow.
double difference_us(std::int64_t a, std::int64_t b) {
  return static_cast<double>(b) - static_cast<double>(a);
}

bool all_finite(const ImuSample& s) {
  for (double v : s.values) {
    if (!std::isfinite(v)) return false;
  }
  return !s.temperature_degc || std::isfinite(*s.temperature_degc);
}

}  // namespace

LiveWindow::LiveWindow(const LiveWindowLimits& limits, ImuSampleFields fields)
    : window_us_(limits.window_s * 1e6),
      max_samples_(limits.max_samples),
      every_s_(limits.every_s),
      fields_(std::move(fields)) {
  IMUNOISE_EXPECT(std::isfinite(limits.window_s) && limits.window_s > 0.0,
                  "LiveWindow: window_s must be finite and > 0");
  IMUNOISE_EXPECT(limits.max_samples >= 1, "LiveWindow: max_samples must be >= 1");
  IMUNOISE_EXPECT(std::isfinite(limits.every_s) && limits.every_s > 0.0,
                  "LiveWindow: every_s must be finite and > 0");
}

void LiveWindow::add_undecodable() {
  ++counts_.received;
  ++counts_.undecodable;
}

void LiveWindow::add(const ImuSample& sample) {
  ++counts_.received;
  if (!all_finite(sample)) {
    ++counts_.non_finite;
    return;
  }
  if (!window_.empty()) {
    const ImuSample& last = window_.back();
    const bool out_of_order = sample.utime_us <= last.utime_us;
    const bool mode_change = sample.increments != last.increments;
    if (out_of_order || mode_change) {
      // A long run of rejections is not noise but a new stream (the sender restarted, its
      // clock was reset, it switched to increments): start the window again from here
      // rather than reject everything from now on. Every message is counted once: as
      // rejected, or (the one that restarts the window) as accepted.
      if (++consecutive_rejections_ < kRestartAfterRejections) {
        ++(out_of_order ? counts_.out_of_order : counts_.mode_changes);
        return;
      }
      window_.clear();
      ++counts_.restarts;
    } else if (nominal_period_us_ > 0 &&
               difference_us(last.utime_us, sample.utime_us) > kGapFactor * nominal_period_us_) {
      ++counts_.gaps;
    }
  }
  consecutive_rejections_ = 0;
  window_.push_back(sample);
  ++counts_.accepted;
  ++new_samples_;
  while (window_.size() > 1 &&
         difference_us(window_.front().utime_us, window_.back().utime_us) > window_us_) {
    window_.pop_front();
  }
  while (static_cast<std::int64_t>(window_.size()) > max_samples_) {
    window_.pop_front();
    ++counts_.trimmed_by_cap;
  }
}

void LiveWindow::set_nominal_period_s(double period_s) {
  nominal_period_us_ = static_cast<std::int64_t>(period_s * 1e6);
}

double LiveWindow::span_s() const {
  return window_.size() < 2
             ? 0.0
             : difference_us(window_.front().utime_us, window_.back().utime_us) * 1e-6;
}

std::int64_t LiveWindow::last_utime() const {
  return window_.empty() ? 0 : window_.back().utime_us;
}

bool LiveWindow::analysis_due() const {
  const double since_last_s = difference_us(analysed_until_us_, last_utime()) * 1e-6;
  return new_samples_ > 0 && span_s() >= every_s_ &&
         (since_last_s >= every_s_ || since_last_s < 0.0);
}

bool LiveWindow::has_unanalysed_data() const { return new_samples_ > 0 && span_s() > 0.0; }

ImuSampleColumns LiveWindow::snapshot() {
  ImuSampleColumns columns;
  columns.utime_us.reserve(window_.size());
  for (auto& v : columns.values) v.reserve(window_.size());
  if (!window_.empty()) {
    // Every sample of the window has the mode of its first (a switch is rejected or
    // restarts the window).
    columns.increments = window_.front().increments;
    columns.source_fields = columns.increments ? fields_.increment_fields : fields_.rate_fields;
    columns.source_units = columns.increments ? fields_.increment_units : fields_.rate_units;
    columns.temperature_field = fields_.temperature_field;
  }
  for (const ImuSample& s : window_) {
    columns.utime_us.push_back(s.utime_us);
    for (std::size_t c = 0; c < 6; ++c) columns.values[c].push_back(s.values[c]);
    append_sample_temperature(columns, s.temperature_degc);
  }
  new_samples_ = 0;
  analysed_until_us_ = last_utime();
  return columns;
}

}  // namespace imunoise::pipeline
