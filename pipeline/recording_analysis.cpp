#include "pipeline/recording_analysis.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <optional>
#include <span>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/parallel_for.h"
#include "pipeline/data_quality.h"
#include "pipeline/datasheet_check.h"
#include "pipeline/line_findings.h"
#include "pipeline/low_pass_corner.h"
#include "pipeline/temperature_coefficient.h"

namespace imunoise::pipeline {

namespace {

/// analyze_recording; when RELEASE is given (it is RECORDING's time_s), the time stamps are
/// freed as soon as the gaps are planned: nothing after the plan reads them.
RecordingAnalysis analyze(const Recording& recording, const std::string& source,
                          const RecordingAnalysisOptions& options, const ChannelFeedback& feedback,
                          std::vector<double>* release) {
  const double tau0_s = recording.sample_period_s;
  // The readers guarantee a positive period; a Recording built by other code might not, and
  // τ0 = 0 would turn every τ and rate into 0 or Inf.
  if (!(tau0_s > 0.0) || !std::isfinite(tau0_s)) {
    throw InputError(source + ": no usable sample period (" + shortest_number_text(tau0_s) +
                     " s): give the rate or a time column that increases");
  }
  std::vector<std::pair<std::size_t, const Channel*>> channels;
  for (std::size_t c = 0; c < kImuChannelNames.size(); ++c) {
    if (const Channel* channel = recording.find_channel(kImuChannelNames[c])) {
      channels.emplace_back(c, channel);
    }
  }
  if (channels.empty()) {
    throw InputError(source + ": no gyro or accelerometer channels to analyse");
  }
  const GapPlan gap_plan =
      plan_gaps(recording, source, options.gaps, options.axis.bootstrap_replicates >= 2,
                options.gap_policy_setting);
  if (release != nullptr) std::vector<double>().swap(*release);
  // The samples each channel is analysed on: the recording, its gap-free pieces, or a copy
  // with the gaps filled (kept alive here for the spans).
  std::vector<std::vector<double>> filled(channels.size());
  std::vector<std::vector<std::span<const double>>> pieces(channels.size());
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const std::vector<double>& values = channels[i].second->values;
    if (gap_plan.policy == GapPolicy::interpolate && !gap_plan.gaps.empty()) {
      filled[i] = interpolate_gaps(values, gap_plan.gaps);
      pieces[i].emplace_back(filled[i]);
    } else if (!gap_plan.pieces.empty()) {
      for (const SampleRange& r : gap_plan.pieces) {
        pieces[i].push_back(std::span<const double>(values).subspan(r.begin, r.size()));
      }
    } else {
      pieces[i].emplace_back(values);
    }
  }

  // The data-quality stage before the fit. Outliers first (per channel and piece, in
  // parallel): a channel whose outliers carry a finding is analysed on its copy handled by
  // options.outliers; the warm-up scan then sees spike-free means.
  std::vector<std::vector<std::vector<double>>> cleaned(channels.size());
  std::vector<OutlierScan> outlier_scans(channels.size());
  std::vector<double> outlier_n_effect(channels.size(), 0.0);
  parallel_for(channels.size(), options.threads, [&](std::size_t i) {
    OutlierScan merged;
    double excess = 0.0, scale = 0.0;
    std::size_t samples = 0, offset = 0;
    double msd_before = 0.0, msd_after = 0.0;
    std::vector<std::vector<double>> handled;
    bool any = false;
    for (std::size_t j = 0; j < pieces[i].size(); ++j) {
      const std::span<const double> piece = pieces[i][j];
      const OutlierScan scan = find_outliers(piece);
      for (std::size_t k : scan.indices) merged.indices.push_back(offset + k);
      merged.largest = std::max(merged.largest, scan.largest);
      excess += scan.excess_variance_fraction * static_cast<double>(piece.size());
      scale += scan.residual_scale * static_cast<double>(piece.size());
      samples += piece.size();
      offset += piece.size();
      const double n = static_cast<double>(piece.size());
      msd_before += mean_square_difference(piece) * n;
      if (scan.significant) {
        // The effect on N is stated whatever the policy: measured against the dropped copy.
        std::vector<double> dropped =
            apply_outlier_policy(piece, scan, OutlierPolicy::drop,
                                 options.axis.seed * 7919ULL + 1000ULL * channels[i].first + j);
        msd_after += mean_square_difference(dropped) * n;
        if (options.outliers == OutlierPolicy::drop) {
          handled.push_back(std::move(dropped));
        } else {
          handled.push_back(apply_outlier_policy(piece, scan, options.outliers, 0));
        }
        any = true;
      } else {
        msd_after += mean_square_difference(piece) * n;
        handled.emplace_back();
      }
    }
    if (samples > 0) {
      merged.excess_variance_fraction = excess / static_cast<double>(samples);
      merged.residual_scale = scale / static_cast<double>(samples);
    }
    merged.significant = any;
    outlier_scans[i] = std::move(merged);
    if (msd_after > 0.0) outlier_n_effect[i] = std::sqrt(msd_before / msd_after) - 1.0;
    if (any && options.outliers != OutlierPolicy::keep) {
      cleaned[i] = std::move(handled);
      for (std::size_t j = 0; j < pieces[i].size(); ++j) {
        if (!cleaned[i][j].empty()) pieces[i][j] = cleaned[i][j];
      }
    }
  });

  // A temperature column (read as the extra channel "temperature", °C) on a record without
  // gaps: each channel's bias-vs-temperature coefficient, and its removal when asked (before
  // the warm-up scan, which then sees what the temperature does not explain).
  std::vector<TemperatureCoefficient> temperature(channels.size());
  std::vector<std::vector<double>> compensated(channels.size());
  const Channel* temperature_channel = recording.find_channel("temperature");
  const bool temperature_usable =
      temperature_channel != nullptr && !temperature_channel->kind && gap_plan.gaps.empty() &&
      std::all_of(pieces.begin(), pieces.end(), [&](const auto& p) {
        return p.size() == 1 && p.front().size() == temperature_channel->values.size();
      });
  if (temperature_usable) {
    for (std::size_t i = 0; i < channels.size(); ++i) {
      temperature[i] = temperature_coefficient(pieces[i].front(), temperature_channel->values);
      if (options.temperature_compensate && temperature[i].fitted) {
        compensated[i] = remove_temperature_bias(pieces[i].front(), temperature_channel->values,
                                                 temperature[i].coefficient);
        pieces[i].front() = compensated[i];
      }
    }
  }

  // The warm-up scan on the first piece of every channel (the start of the record), then the
  // trim: the automatic one unless options.trim_start_s says otherwise.
  StartTransient start_transient;
  {
    std::vector<std::span<const double>> starts;
    std::vector<std::string> names;
    bool same_length = true;
    for (std::size_t i = 0; i < channels.size(); ++i) {
      starts.push_back(pieces[i].front());
      names.push_back(channels[i].second->name);
      same_length = same_length && starts.back().size() == starts.front().size();
    }
    if (same_length) start_transient = detect_start_transient(starts, names, tau0_s);
  }
  const double trim_s = options.trim_start_s
                            ? *options.trim_start_s
                            : (start_transient.detected ? start_transient.trim_s : 0.0);
  std::size_t trimmed = 0;
  if (trim_s > 0.0) {
    const auto trim_samples = static_cast<std::size_t>(std::llround(trim_s / tau0_s));
    const std::size_t total = static_cast<std::size_t>(gap_plan.samples);
    if (trim_samples + 16 > total) {
      throw InputError(source + ": " + options.trim_setting + " " + shortest_number_text(trim_s) +
                       " s leaves fewer than 16 samples of the " +
                       shortest_number_text(static_cast<double>(total) * tau0_s) + " s record");
    }
    // Pieces in time order lose their first TRIM_SAMPLES samples (with gaps split, analysed
    // samples are counted, not the time across the gaps).
    for (auto& channel_pieces : pieces) {
      std::size_t left = trim_samples;
      std::vector<std::span<const double>> kept;
      for (const std::span<const double> piece : channel_pieces) {
        if (left >= piece.size()) {
          left -= piece.size();
          continue;
        }
        kept.push_back(piece.subspan(left));
        left = 0;
      }
      channel_pieces = std::move(kept);
    }
    trimmed = trim_samples;
  }

  // Channels in parallel: each worker takes the next channel (the bootstrap of an axis runs in
  // its thread, so the total never exceeds options.threads). Each axis's result depends only on
  // its data and index (seeded per axis), not on the thread that ran it. Every channel runs to
  // its end and keeps its own error, so the error reported is the first in channel order
  // whatever the timing.
  std::vector<std::optional<AxisAnalysis>> results(channels.size());
  std::vector<std::exception_ptr> errors(channels.size());
  parallel_for(channels.size(), options.threads, [&](std::size_t i) {
    const auto [index, channel] = channels[i];
    try {
      AxisAnalysisOptions channel_options = options.axis;
      channel_options.progress = feedback.progress ? feedback.progress(i) : ProgressCallback{};
      results[i] = analyze_axis_pieces(channel->name, kImuChannelKinds[index], pieces[i], tau0_s,
                                       static_cast<int>(index), channel_options);
    } catch (...) {
      errors[i] = std::current_exception();
    }
    if (feedback.channel_finished) feedback.channel_finished();
  });
  for (std::size_t i = 0; i < channels.size(); ++i) {
    if (!errors[i]) continue;
    // The axis analysis names the channel; the user also needs the file.
    try {
      std::rethrow_exception(errors[i]);
    } catch (const AnalysisError& e) {
      throw AnalysisError(source + ": " + e.what());
    } catch (const InputError& e) {
      throw InputError(source + ": " + e.what());
    }
  }

  RecordingAnalysis result;
  result.tau0_s = tau0_s;
  models::NoiseModel& model = result.model;
  model.source = source;
  model.sensor_name = std::filesystem::path(source).filename().string();
  model.sample_rate_hz = 1.0 / tau0_s;
  model.samples = gap_plan.samples - static_cast<std::int64_t>(trimmed);
  model.duration_s = static_cast<double>(model.samples) * tau0_s;
  model.confidence = options.axis.confidence;
  model.data_quality = quality_findings(recording.report);
  if (!gap_plan.note.empty()) model.data_quality.push_back(gap_plan.note);
  for (std::size_t i = 0; i < channels.size(); ++i) {
    std::size_t samples = 0;
    for (const auto& piece : pieces[i]) samples += piece.size();
    const std::string line = outlier_finding(channels[i].second->name, channels[i].second->unit(),
                                             samples + trimmed, outlier_scans[i], options.outliers,
                                             outlier_n_effect[i], options.outlier_setting);
    if (!line.empty()) model.data_quality.push_back(line);
  }
  if (temperature_usable && temperature.front().fitted) {
    std::string line =
        "temperature column: " + significant_number_text(temperature.front().temperature_low, 4) +
        " to " + significant_number_text(temperature.front().temperature_high, 4) +
        " degC (256 block means); bias vs temperature coefficient (least squares "
        "of the block means):";
    for (std::size_t i = 0; i < channels.size(); ++i) {
      line += std::string(i == 0 ? " " : ", ") + channels[i].second->name + " " +
              significant_number_text(temperature[i].coefficient, 3) + " " +
              std::string(channels[i].second->unit()) +
              "/degC (r = " + significant_number_text(temperature[i].correlation, 2) + ")";
    }
    line += "; cause: the bias follows the sensor's temperature; remedy: ";
    line += options.temperature_compensate
                ? "removed (" + options.temperature_setting +
                      ": each channel minus its coefficient x (T - mean T) before the fit)"
                : "not removed (" + options.temperature_setting +
                      " subtracts coefficient x (T - mean T) from each channel before the fit)";
    model.data_quality.push_back(line);
  }
  {
    std::vector<std::string> units;
    for (const auto& c : channels) units.emplace_back(c.second->unit());
    StartTrim trim;
    trim.trim_s = static_cast<double>(trimmed) * tau0_s;
    trim.automatic = !options.trim_start_s.has_value();
    trim.setting = options.trim_setting;
    const std::string line = start_transient_finding(start_transient, trim, units);
    if (!line.empty()) model.data_quality.push_back(line);
  }
  result.start_transient = std::move(start_transient);
  result.trimmed_s = static_cast<double>(trimmed) * tau0_s;
  for (auto& r : results) {
    for (std::string& line : spectral_line_findings(r->model, model.confidence))
      model.data_quality.push_back(std::move(line));
    model.axes.push_back(r->model);
    result.axes.push_back(std::move(*r));
  }
  {
    // The low-pass corner of each channel (found by analyze_axis from its PSD and model).
    std::string listed;
    double lowest_tau_min = 0.0;
    for (const AxisAnalysis& a : result.axes) {
      const LowPassCorner& corner = a.low_pass;
      if (!corner.found) continue;
      listed += std::string(listed.empty() ? "" : ", ") + a.model.name + " " +
                significant_number_text(corner.corner_hz, 3) + " Hz (" +
                significant_number_text(corner.corner_hz * tau0_s, 2) + " fs)";
      lowest_tau_min =
          lowest_tau_min == 0.0 ? a.fit.tau_min_s : std::min(lowest_tau_min, a.fit.tau_min_s);
    }
    if (!listed.empty()) {
      model.data_quality.push_back(
          "low-pass roll-off: the PSD falls below half the fitted white floor towards Nyquist, "
          "-3 dB corner at " +
          listed +
          "; cause: the sensor's digital low-pass or anti-alias filter, which bends the AVAR "
          "below the white-noise slope at short tau; remedy: the fit starts at tau >= " +
          significant_number_text(lowest_tau_min, 3) +
          " s, where that deficit (decaying like 1/tau) is below 0.2 % of N^2/tau (" +
          options.low_pass_setting + " keeps the short tau)");
    }
  }
  if (options.spec) {
    for (std::string& line : datasheet_findings(model, *options.spec))
      model.data_quality.push_back(std::move(line));
  }
  return result;
}

}  // namespace

RecordingAnalysis analyze_recording(const Recording& recording, const std::string& source,
                                    const RecordingAnalysisOptions& options,
                                    const ChannelFeedback& feedback) {
  return analyze(recording, source, options, feedback, nullptr);
}

RecordingAnalysis analyze_recording_freeing_time_stamps(Recording& recording,
                                                        const std::string& source,
                                                        const RecordingAnalysisOptions& options,
                                                        const ChannelFeedback& feedback) {
  return analyze(recording, source, options, feedback, &recording.time_s);
}

std::string psd_plan_text(const RecordingAnalysis& result) {
  if (result.axes.empty() || result.axes.front().psd.segment_length < 2) return "no PSD";
  const analysis::Spectrum& psd = result.axes.front().psd;
  std::string text = "PSD FFT plan (L = " + std::to_string(psd.segment_length) + "): ";
  text.append(psd.fft_plan_from_wisdom ? "from FFTW wisdom"
                                       : "FFTW_ESTIMATE (no wisdom for this length)");
  return text;
}

}  // namespace imunoise::pipeline
