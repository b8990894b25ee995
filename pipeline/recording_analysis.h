/// @file
/// @brief The analysis of a whole recording, `imunoise analyze`'s and `imunoise live`'s: the
/// gap plan, every gyro/accelerometer channel through analyze_axis_pieces in parallel
/// (common/parallel_for), the data-quality findings and the NoiseModel. The same options and
/// the same recording give the same model whichever caller runs it.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/progress_callback.h"
#include "models/noise_model.h"
#include "pipeline/axis_analysis.h"
#include "pipeline/fleet.h"
#include "pipeline/gap_policy.h"
#include "pipeline/outliers.h"
#include "pipeline/recording.h"
#include "pipeline/start_transient.h"

namespace imunoise::pipeline {

/// Settings of one analysis of a recording.
struct RecordingAnalysisOptions {
  /// Settings of every axis (their `progress` and `threads` are set per channel here).
  AxisAnalysisOptions axis;
  /// How messages and the data-quality note name the gap policy (plan_gaps); the CLI: "--gaps".
  std::string gap_policy_setting{kGapPolicySetting};
  GapPolicy gaps = GapPolicy::refuse;  ///< what to do with time-stamp gaps
  /// What to do with the outliers of a channel whose outliers carry a finding
  /// (pipeline/outliers.h); channels without the finding are analysed as recorded.
  OutlierPolicy outliers = OutlierPolicy::drop;
  std::string outlier_setting{"outliers"};  ///< how the finding names the setting ("--outliers")
  /// Start of the record to drop [s]: unset = the automatic trim of the warm-up scan
  /// (pipeline/start_transient.h; 0 when none is detected), 0 = keep everything.
  std::optional<double> trim_start_s;
  std::string trim_setting{"trim_start"};  ///< how the finding names it ("--trim-start")
  /// With a "temperature" column [°C] (and no gaps): subtract each channel's
  /// bias-vs-temperature coefficient × (T − mean T) before the analysis
  /// (pipeline/temperature_coefficient.h). The coefficient is reported either way.
  bool temperature_compensate = false;
  std::string temperature_setting{"temperature_compensate"};  ///< its name in the finding
  /// How the low-pass finding names the switch that keeps the short τ ("--no-low-pass-check").
  std::string low_pass_setting{"no_low_pass_check"};
  /// The sensor's datasheet (the spec of `imunoise fleet --spec`): the fitted white noise is
  /// held to its density, which shows an output decimated without averaging
  /// (pipeline/datasheet_check.h). Unset: no such check (the data alone cannot show it).
  std::optional<FleetSpec> spec;
  unsigned threads = 0;  ///< worker threads across channels (0 = all cores)
};

/// The result of one analysis.
struct RecordingAnalysis {
  models::NoiseModel model;
  std::vector<AxisAnalysis> axes;  ///< in model.axes order
  double tau0_s = 0.0;
  StartTransient start_transient;  ///< the warm-up scan (scanned false: record too short)
  double trimmed_s = 0.0;          ///< start dropped before the analysis [s]
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
/// model.data_quality. Before the fit, the data-quality stage: per channel the outliers
/// (find_outliers; handled by options.outliers when they carry a finding), then the warm-up
/// scan of the start of the record (detect_start_transient) and the trim of its start
/// (options.trim_start_s), and with a temperature column each channel's
/// bias-vs-temperature coefficient (options.temperature_compensate removes it) — each finding with
/// its cause and remedy in model.data_quality, the trim in model.samples and duration_s. Throws
/// InputError for a recording without IMU channels or without a usable sample period, AnalysisError
/// when the data cannot give a fit (prefixed with SOURCE; the first failing channel in channel
/// order).
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
