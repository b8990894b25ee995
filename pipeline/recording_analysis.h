/// @file
/// @brief The analysis of a whole recording, `imunoise analyze`'s and `imunoise live`'s: the
/// gap plan, every gyro/accelerometer channel through analyze_axis_pieces in parallel
/// (common/parallel_for), the data-quality findings and the NoiseModel. The same options and
/// the same recording give the same model whichever caller runs it.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "common/progress_callback.h"
#include "models/noise_model.h"
#include "pipeline/axis_analysis.h"
#include "pipeline/gap_policy.h"
#include "pipeline/recording.h"

namespace imunoise::pipeline {

/// Settings of one analysis of a recording.
struct RecordingAnalysisOptions {
  /// Settings of every axis (their `progress` and `threads` are set per channel here).
  AxisAnalysisOptions axis;
  /// How messages and the data-quality note name the gap policy (plan_gaps); the CLI: "--gaps".
  std::string gap_policy_setting{kGapPolicySetting};
  GapPolicy gaps = GapPolicy::refuse;  ///< what to do with time-stamp gaps
  unsigned threads = 0;                ///< worker threads across channels (0 = all cores)
};

/// The result of one analysis.
struct RecordingAnalysis {
  models::NoiseModel model;
  std::vector<AxisAnalysis> axes;  ///< in model.axes order
  double tau0_s = 0.0;
};

/// What analyze_recording reports while it runs; every part is optional and none changes the
/// result. Both are called from the worker threads.
struct ChannelFeedback {
  /// The progress callback of the I-th analysed channel (stages and bootstrap replicates, as
  /// AxisAnalysisOptions::progress); an empty function or callback means nobody listens.
  std::function<ProgressCallback(std::size_t channel)> progress;
  /// Called once per channel when its analysis has ended (successfully or not).
  std::function<void()> channel_finished;
};

/// Analyses every gyro/accel channel of RECORDING (one worker per channel, up to
/// options.threads; each channel's result depends only on its data and index). SOURCE names
/// the data in the model (model.source; sensor_name is its file name) and in messages.
/// Time-stamp gaps follow options.gaps (plan_gaps): refused, split into gap-free pieces whose
/// curves and PSD are pooled, or filled by linear interpolation — either way said in
/// model.data_quality. Throws InputError for a recording without IMU channels or without a
/// usable sample period, AnalysisError when the data cannot give a fit (prefixed with SOURCE;
/// the first failing channel in channel order).
RecordingAnalysis analyze_recording(const Recording& recording, const std::string& source,
                                    const RecordingAnalysisOptions& options,
                                    const ChannelFeedback& feedback = {});

/// analyze_recording for a caller that needs no time stamps afterwards: RECORDING.time_s is
/// freed (left empty) as soon as the gaps are planned, which lowers the peak memory by one
/// column (0.7 GB for 24 h at 1 kHz). Everything else in RECORDING is unchanged.
RecordingAnalysis analyze_recording_freeing_time_stamps(Recording& recording,
                                                        const std::string& source,
                                                        const RecordingAnalysisOptions& options,
                                                        const ChannelFeedback& feedback = {});

/// "PSD FFT plan (L = N): from FFTW wisdom" or "…: FFTW_ESTIMATE (no wisdom for this length)",
/// for the segment length RESULT's PSD used ("no PSD" without one).
std::string psd_plan_text(const RecordingAnalysis& result);

}  // namespace imunoise::pipeline
