#include "pipeline/recording_analysis.h"

#include <cmath>
#include <exception>
#include <filesystem>
#include <optional>
#include <span>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/parallel_for.h"
#include "pipeline/data_quality.h"

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
  model.samples = gap_plan.samples;
  model.duration_s = static_cast<double>(model.samples) * tau0_s;
  model.confidence = options.axis.confidence;
  model.data_quality = quality_findings(recording.report);
  if (!gap_plan.note.empty()) model.data_quality.push_back(gap_plan.note);
  for (auto& r : results) {
    model.axes.push_back(r->model);
    result.axes.push_back(std::move(*r));
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
