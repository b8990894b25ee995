#include "pipeline/data_quality.h"

#include <algorithm>
#include <cmath>

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

namespace imunoise::pipeline {

std::string start_transient_finding(const StartTransient& scan, const StartTrim& trim,
                                    std::span<const std::string> units) {
  if (!scan.detected) {
    if (trim.trim_s > 0.0) {
      return "start trimmed by " + trim.setting + ": the first " +
             significant_number_text(trim.trim_s) + " s dropped (no warm-up detected; statistic " +
             significant_number_text(scan.statistic, 3) + " below its threshold " +
             significant_number_text(scan.threshold, 3) + ")";
    }
    return "";
  }
  std::string text =
      "warm-up (thermal start-up transient) detected: adjacent " +
      significant_number_text(scan.segment_s, 3) +
      " s means at the start differ by sum z^2 = " + significant_number_text(scan.statistic, 3) +
      " over " + std::to_string(scan.channels.size()) + " channel(s) (threshold " +
      significant_number_text(scan.threshold, 3) +
      ", 0.5 % false alarms on stationary noise); A*exp(-t/tau) with tau = " +
      significant_number_text(scan.time_constant_s, 3) + " s, A =";
  for (std::size_t i = 0; i < scan.channels.size(); ++i) {
    const StartTransientChannel& c = scan.channels[i];
    text += std::string(i == 0 ? " " : ", ") + c.name + " " +
            significant_number_text(c.amplitude, 3) + " " + (i < units.size() ? units[i] : "") +
            " (" + significant_number_text(std::abs(c.amplitude) / c.adev_at_tau, 2) +
            " x its ADEV at tau)";
  }
  text +=
      "; cause: the sensor had not reached thermal equilibrium when the recording began, "
      "and the drift goes into K and a ramp if fitted; remedy: ";
  if (trim.automatic) {
    text += trim.trim_s > 0.0
                ? "the first " + significant_number_text(trim.trim_s) +
                      " s were dropped (automatic trim: the transient left is at most each "
                      "channel's ADEV at tau" +
                      (scan.trim_capped ? ", capped at half the record" : "") + "); " +
                      trim.setting + " DURATION to choose, " + trim.setting + " 0 to keep all"
                : "nothing dropped (the transient is already below the ADEV at tau); " +
                      trim.setting + " DURATION to drop the start";
  } else if (trim.trim_s > 0.0) {
    text += "the first " + significant_number_text(trim.trim_s) + " s were dropped (" +
            trim.setting + "; the automatic trim would drop " +
            significant_number_text(scan.trim_s) + " s)";
  } else {
    text += "nothing dropped (" + trim.setting + " 0); the automatic trim would drop " +
            significant_number_text(scan.trim_s) + " s";
  }
  return text;
}

std::string outlier_finding(const std::string& name, std::string_view unit, std::size_t samples,
                            const OutlierScan& scan, OutlierPolicy policy, double n_effect,
                            std::string_view setting) {
  if (!scan.significant) return "";
  const double share = 100.0 * static_cast<double>(scan.indices.size()) /
                       static_cast<double>(std::max<std::size_t>(1, samples));
  std::string text =
      name + ": " + std::to_string(scan.indices.size()) + " outliers (" +
      significant_number_text(share, 2) + " % of the samples) beyond " +
      significant_number_text(kOutlierThreshold, 2) + " robust scales (" +
      significant_number_text(scan.residual_scale, 3) + " " + std::string(unit) +
      ", MAD of the residual to the mean of the 8 nearest good neighbours), the largest " +
      significant_number_text(scan.largest, 3) + " scales; they carry " +
      significant_number_text(100.0 * scan.excess_variance_fraction, 2) +
      " % of the residual variance: N " + (n_effect >= 0.0 ? "+" : "") +
      significant_number_text(100.0 * n_effect, 3) +
      " % with them kept (first-difference RMS); cause: spikes from the sensor or its link "
      "(bit errors, interference), not noise of the model; remedy: ";
  const std::string flag(setting);
  switch (policy) {
    case OutlierPolicy::drop:
      text += "dropped (" + flag +
              " drop: each replaced by the mean of the good samples within +-" +
              std::to_string(kOutlierLevelHalfWindow) +
              " plus white noise of the robust sample sigma, so the sampling stays regular); " +
              flag + " keep|clip to change";
      break;
    case OutlierPolicy::clip:
      text += "clipped to the threshold around the neighbours' median (" + flag +
              " clip; N stays biased by what is left); " + flag + " drop replaces them";
      break;
    case OutlierPolicy::keep:
      text += "kept (" + flag + " keep): N above is biased; " + flag + " drop removes them";
      break;
  }
  return text;
}

}  // namespace imunoise::pipeline
