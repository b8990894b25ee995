/// @file
/// @brief The analysis of `imunoise analyze`, shared with `imunoise live`: its flags, and one
/// Recording → NoiseModel run over the six channels in parallel. The same flags and the same
/// recording give the same model whichever command runs it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "models/noise_model.h"
#include "pipeline/axis_analysis.h"
#include "pipeline/recording.h"

namespace CLI {
class App;
}

namespace imunoise::tools {

/// The analysis flags (`--taus`, `--confidence`, `--bootstrap`, …) as given.
struct AnalysisSettings {
  std::string taus = "log:10";
  double confidence = 0.95;
  int bootstrap = 50;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  bool gauss_markov = false;
  bool no_low_pass_check = false;
  double tau_min_s = 0.0;
  double tau_max_s = 0.0;
  std::vector<double> sinusoid_hz;
  /// Time-stamp gaps: "refuse" (default), "split" or "interpolate" (pipeline::GapPolicy).
  std::string gaps = "refuse";
  /// `--fftw-wisdom FILE`; unset: $IMUNOISE_FFTW_WISDOM, if set and not empty; set to "": no
  /// wisdom whatever the environment says.
  std::optional<std::string> fftw_wisdom;
};

/// Adds the analysis flags to `cmd`; values land in `settings` (which must outlive the parse).
void add_analysis_options(CLI::App& cmd, AnalysisSettings& settings);

/// The result of one analysis.
struct AnalysisResult {
  models::NoiseModel model;
  std::vector<pipeline::AxisAnalysis> axes;  ///< in model.axes order
  double tau0_s = 0.0;
};

class ProgressBar;
class StageTimes;

/// What analyze_recording reports while it runs; every part is optional and none changes the
/// result.
struct AnalysisFeedback {
  /// Advanced per stage and bootstrap replicate of every channel ("k/6 channels"); the caller
  /// finishes it.
  ProgressBar* bar = nullptr;
  /// Wall seconds per stage (deviations, fit, PSD, bootstrap/intervals), summed over channels.
  StageTimes* channel_times = nullptr;
};

/// Analyses every gyro/accel channel of `recording` (threads across channels). `source` names
/// the data in the model (model.source; sensor_name is its file name). Time-stamp gaps follow
/// settings.gaps: refused (InputError naming the file, the gaps and the two flags), split
/// into gap-free pieces whose curves and PSD are pooled, or filled by linear interpolation
/// (gaps longer than pipeline::max_interpolated_gap refused) — either way said in
/// model.data_quality. Throws InputError for bad settings (naming the flag) or a recording
/// without IMU channels, AnalysisError when the data cannot give a fit.
AnalysisResult analyze_recording(const pipeline::Recording& recording, const std::string& source,
                                 const AnalysisSettings& settings,
                                 const AnalysisFeedback& feedback = {});

/// analyze_recording for a caller that needs no time stamps afterwards: RECORDING.time_s is
/// freed (left empty) as soon as the gaps are planned, which lowers the peak memory by one
/// column (0.7 GB for 24 h at 1 kHz). Everything else in RECORDING is unchanged.
AnalysisResult analyze_recording_freeing_time_stamps(pipeline::Recording& recording,
                                                     const std::string& source,
                                                     const AnalysisSettings& settings,
                                                     const AnalysisFeedback& feedback = {});

/// Imports the FFTW wisdom file of `--fftw-wisdom`, or else of $IMUNOISE_FFTW_WISDOM, into the
/// process so that the PSD plans come from it (analysis::WelchEstimator); call once, before the
/// analysis. `--fftw-wisdom ""` imports nothing, even with the variable set. Returns the file
/// imported ("" when none).
/// @throws InputError naming the file when it cannot be read or is not FFTW wisdom.
std::string import_fftw_wisdom_option(const AnalysisSettings& settings);

/// For `-v`: "PSD FFT plan (L = N): from FFTW wisdom" or "…: FFTW_ESTIMATE (no wisdom for this
/// length)", for the segment length RESULT's PSD used. Plans once more to find out (no
/// measurement, but buffers of ~4×8·L bytes for a moment): call only when it is printed.
std::string psd_plan_text(const AnalysisResult& result);

/// Data-quality findings of a sampling report, one line each (empty = nothing to say).
std::vector<std::string> quality_findings(const pipeline::SamplingReport& report);

/// The one-line refusal of a recording with time-stamp gaps under `--gaps refuse`: SOURCE
/// (with the line of the first gap when known), the number of gaps, where the first is, the
/// longest, the samples missing, and the two flags that go on. Empty when there is no gap.
std::string gap_refusal_message(const std::string& source, const pipeline::TimingReport& timing);

}  // namespace imunoise::tools
