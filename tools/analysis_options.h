/// @file
/// @brief The analysis flags of `imunoise analyze`, shared with `imunoise live`, and the call of
/// pipeline::analyze_recording with them (progress bar and stage times fed from the channels).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pipeline/recording_analysis.h"

namespace CLI {
class App;
}

namespace imunoise::io {
class ProgressBar;
class StageTimes;
}  // namespace imunoise::io

namespace imunoise::tools {

/// The analysis flags (`--taus`, `--confidence`, `--bootstrap`, …) as given.
struct AnalysisSettings {
  std::string taus = "log:10";
  double confidence = 0.95;
  /// `--bootstrap N`: the reference bootstrap of simulated records (N ≥ 2) or least-squares
  /// intervals (0); unset: the interval draws below.
  std::optional<int> bootstrap;
  int interval_draws =
      200;  ///< `--interval-draws N`: OAVAR vectors drawn per axis (0: least squares)
  std::uint64_t seed = 1;
  unsigned threads = 0;
  bool gauss_markov = false;     ///< `--gauss-markov`: GM terms always tried in the selection
  bool no_gauss_markov = false;  ///< `--no-gauss-markov`: power-law terms and sinusoids only
  bool no_low_pass_check = false;
  double tau_min_s = 0.0;
  double min_edf = analysis::FitOptions{}.min_edf;  ///< `--min-edf`: fit only τ with EDF ≥ this
  double tau_max_s = 0.0;
  std::vector<double> sinusoid_hz;
  bool no_lines = false;  ///< `--no-lines`: no automatic spectral-line search
  /// `--estimator`: "wnnls" (default: the points weighted as independent) or "gls" (the
  /// selected structure re-estimated with the correlation across tau).
  std::string estimator = "wnnls";
  /// Time-stamp gaps: "refuse" (default), "split" or "interpolate" (pipeline::GapPolicy).
  std::string gaps = "refuse";
  /// Outliers of a channel whose outliers carry a finding: "keep", "clip" or "drop" (default).
  std::string outliers = "drop";
  /// `--trim-start DURATION`: the start to drop; unset = the automatic warm-up trim, "0" = none.
  std::optional<std::string> trim_start;
  bool temperature_compensate = false;  ///< `--temperature-compensate`
  /// `--spec FILE`: the sensor's datasheet spec (the format of `imunoise fleet --spec`); empty:
  /// none.
  std::string spec;
  /// `--fftw-wisdom FILE`; unset: $IMUNOISE_FFTW_WISDOM, if set and not empty; set to "": no
  /// wisdom whatever the environment says.
  std::optional<std::string> fftw_wisdom;
};

/// Adds the analysis flags to `cmd`; values land in `settings` (which must outlive the parse).
void add_analysis_options(CLI::App& cmd, AnalysisSettings& settings);

/// The gap policy of `--gaps`; InputError "--gaps: expected refuse, split or interpolate, got
/// '…'" for another value.
pipeline::GapPolicy gap_policy_option(const AnalysisSettings& settings);

/// What analyze_recording reports while it runs; every part is optional and none changes the
/// result.
struct AnalysisFeedback {
  /// Advanced per stage and bootstrap replicate of every channel ("k/6 channels"); the caller
  /// finishes it.
  io::ProgressBar* bar = nullptr;
  /// Wall seconds per stage (deviations, fit, PSD, bootstrap/intervals), summed over channels.
  io::StageTimes* channel_times = nullptr;
};

/// The pipeline's options of SETTINGS for a record of sample period TAU0_S, with the flags as
/// the names the pipeline's messages and notes give its settings (--gaps, --bootstrap N).
/// Throws InputError naming the flag for a value out of range (--confidence, --bootstrap,
/// --sinusoid-hz beyond Nyquist, --taus, --gaps, --outliers, --trim-start).
pipeline::RecordingAnalysisOptions recording_analysis_options(const AnalysisSettings& settings,
                                                              double tau0_s);

/// pipeline::analyze_recording with the options of SETTINGS, feeding FEEDBACK. A recording
/// with time-stamp gaps under `--gaps refuse` is refused with pipeline::gap_refusal_message.
pipeline::RecordingAnalysis analyze_recording(const pipeline::Recording& recording,
                                              const std::string& source,
                                              const AnalysisSettings& settings,
                                              const AnalysisFeedback& feedback = {});

/// analyze_recording through pipeline::analyze_recording_freeing_time_stamps (RECORDING.time_s
/// is freed once the gaps are planned).
pipeline::RecordingAnalysis analyze_recording_freeing_time_stamps(
    pipeline::Recording& recording, const std::string& source, const AnalysisSettings& settings,
    const AnalysisFeedback& feedback = {});

/// Imports the FFTW wisdom file of `--fftw-wisdom`, or else of $IMUNOISE_FFTW_WISDOM, into the
/// process so that the PSD plans come from it (analysis::WelchEstimator); call once, before the
/// analysis. `--fftw-wisdom ""` imports nothing, even with the variable set. Returns the file
/// imported ("" when none).
/// @throws InputError naming the file when it cannot be read or is not FFTW wisdom.
std::string import_fftw_wisdom_option(const AnalysisSettings& settings);

}  // namespace imunoise::tools
