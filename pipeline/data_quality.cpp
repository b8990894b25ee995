#include "pipeline/data_quality.h"

#include "common/number_text.h"

namespace imunoise::pipeline {

std::vector<std::string> quality_findings(const SamplingReport& report) {
  std::vector<std::string> out;
  const TimingReport& t = report.timing;
  if (t.gap_count > 0) {
    out.push_back(std::to_string(t.gap_count) + " time-stamp gap(s), longest " +
                  significant_number_text(t.longest_gap_s) + " s, about " +
                  std::to_string(t.missing_samples) + " samples missing");
  }
  if (t.non_monotonic_count > 0) {
    out.push_back(std::to_string(t.non_monotonic_count) + " non-monotonic time stamp(s)");
  }
  if (t.duplicate_count > 0) {
    out.push_back(std::to_string(t.duplicate_count) + " duplicate time stamp(s)");
  }
  if (t.period_from_mean) {
    out.push_back("time stamps quantized or alternating: median interval " +
                  significant_number_text(t.median_interval_s, 6) + " s, mean regular interval " +
                  significant_number_text(t.mean_interval_s, 6) + " s (" +
                  significant_number_text(
                      100.0 * (t.mean_interval_s - t.median_interval_s) / t.median_interval_s, 3) +
                  " %); the analysis uses the mean as the sample period");
  }
  if (t.has_timestamps && t.median_interval_s > 0.0 &&
      t.jitter_rms_s > 0.01 * t.median_interval_s) {
    out.push_back("time-stamp jitter " + significant_number_text(t.jitter_rms_s) + " s RMS (" +
                  significant_number_text(100.0 * t.jitter_rms_s / t.median_interval_s, 3) +
                  " % of the interval)");
  }
  if (report.rows_dropped > 0) {
    out.push_back(std::to_string(report.rows_dropped) + " row(s) with NaN/Inf dropped");
  }
  for (const ChannelReport& c : report.channels) {
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

}  // namespace imunoise::pipeline
