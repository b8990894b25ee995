/// @file
/// @brief The whole drift job of `imunoise drift` (theory.md §7.6–7.7) in one call: from a
/// recording and a fitted noise model to everything drift_envelope.csv, drift_segments.csv and
/// drift_summary.json hold (io/drift_files.h writes them). Checks that the recording can be
/// judged (six channels, no time gaps, at rest — the last two unless forced), runs
/// analyze_drift() and, when asked, monte_carlo_drift() (pipeline/drift_analysis.h). Pure
/// computation: no files, no printing, no CLI flags in its messages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/progress_callback.h"
#include "models/bias_instability_gm.h"
#include "models/noise_model.h"
#include "pipeline/drift_analysis.h"
#include "pipeline/drift_series.h"
#include "pipeline/recording.h"
#include "pipeline/recording_analysis.h"

namespace imunoise::pipeline {

/// Where the recording was made, as the user gave it (recorded so in drift_summary.json).
struct DriftLocation {
  double latitude_deg = 45.0;  ///< geodetic latitude [deg]
  double longitude_deg = 0.0;  ///< [deg]
  double height_m = 0.0;       ///< above the ellipsoid [m]
  bool given = false;          ///< false: the default above was assumed
};

/// What run_drift() does; times in s, angles in rad except the location (as given).
struct DriftRunOptions {
  DriftLocation location;
  /// Heading of the IMU's x axis from north [rad]; without it each segment gyrocompasses.
  std::optional<double> heading_rad;
  /// The name of the heading setting in messages (DriftOptions::heading_setting).
  std::string heading_setting = "heading_rad";
  double heading_sigma_rad = 0.0;  ///< 1σ of the given heading [rad]
  double align_s = 60.0;           ///< alignment window per segment [s]
  double navigation_s = 600.0;     ///< free-inertial time per segment [s]
  double warmup_s = 0.0;           ///< skipped at the start of the recording [s]
  double output_step_s = 1.0;      ///< time step of the series [s]
  /// Times of the consistency statistics [s], each ≤ navigation_s (DriftOptions::report_times_s).
  std::vector<double> report_times_s{60.0, 300.0, 600.0};
  /// Which single GM stands for B in the prediction where an axis has no multi_gm terms
  /// (theory.md §4.4); with multi_gm, B is carried as those terms.
  models::GmConvention gm_convention = models::GmConvention::peak_match;
  int monte_carlo_runs = 100;  ///< 0: no Monte Carlo; else ≥ 2
  std::uint64_t seed = 1;      ///< of the Monte Carlo
  bool force = false;          ///< run on a recording with time gaps or one that moves
  std::string model_path;      ///< the model.yaml the model came from (named in the summary)
  /// Split-sample validation: fit a model on the first half of the recording
  /// (analyze_recording() with holdout_analysis, as `imunoise analyze` does by default), then
  /// predict and judge the segments of the second half with it (DriftSummary::holdout).
  bool holdout_half = false;
  RecordingAnalysisOptions holdout_analysis;  ///< the fit of the first half (defaults)
};

/// How the segments were run (the "protocol" of drift_summary.json).
struct DriftProtocol {
  double align_s = 0.0, navigation_s = 0.0, warmup_s = 0.0;  ///< [s]
  std::size_t segments = 0;
  std::string vertical_channel;        ///< how the vertical channel is treated
  std::string gyro_bias;               ///< how the gyro bias is treated
  std::string heading;                 ///< how the first segment got its heading
  std::string bias_instability_as_gm;  ///< models::name_of(GmConvention) (single-GM fallback)
  /// Which error states carry B, the GM terms and R in the covariance, e.g. "multi_gm: B as
  /// the model's Gauss-Markov terms, ..."; names the axes that fell back to one GM.
  std::string bias_states{};
};

/// The Monte Carlo that ran.
struct DriftMonteCarlo {
  int runs = 0;
  std::uint64_t seed = 0;
};

/// The split-sample check: a model fitted on one part of the recording judged on another.
struct DriftHoldout {
  std::string fitted_on;     ///< e.g. "first half: samples 0 … 719999 (0 … 14400 s)"
  std::string judged_on;     ///< e.g. "second half: samples 720000 … (14400 … 28800 s)"
  std::size_t segments = 0;  ///< segments of the judged part
  std::vector<DriftConsistency> consistency;  ///< at the report times, without Monte Carlo
};

/// What drift_summary.json holds: the inputs, the protocol, the stationarity check and the
/// consistency of the recorded with the predicted drift at the report times.
struct DriftSummary {
  std::string recording;  ///< path of the recording
  std::string model;      ///< path of the model.yaml
  DriftLocation location;
  DriftProtocol protocol;
  MotionCheck motion;
  bool forced = false;  ///< not stationary, run anyway
  std::vector<DriftConsistency> consistency;
  std::optional<DriftMonteCarlo> monte_carlo;  ///< absent when it did not run
  std::optional<DriftHoldout> holdout;         ///< with DriftRunOptions::holdout_half
};

/// The drift budget (drift_budget.csv): the predicted horizontal variance σ_N² + σ_E² of
/// the same-file prediction split by source (ins::DriftBudgetTerm; independent sources, each
/// propagated alone, so a row sums to the predicted variance) at each report time and, for
/// the stacked plot of the report, at about 10 times per decade of the output grid
/// (log-spaced, from the first output step to the end of the navigation), sorted.
struct DriftBudget {
  std::vector<double> time_s;                    ///< [s], increasing
  std::vector<ins::DriftBudgetRow> variance_m2;  ///< per time, in DriftBudgetTerm order [m²]
  std::vector<double> predicted_variance_m2;     ///< σ_N² + σ_E² at each time [m²]
  std::vector<bool> report_time;                 ///< per time: it is a report time
};

/// Everything `imunoise drift` writes.
struct DriftResult {
  DriftSummary summary;
  DriftSeries series;                  ///< the envelope (with the Monte Carlo when it ran)
  std::vector<DriftSegment> segments;  ///< the recorded segments, each on series.time_s
  DriftBudget budget;                  ///< of the prediction at the report times
};

/// The drift job: the six channels of RECORDING (gyro_x … accel_z, DriftRefused
/// missing_channel otherwise), refused when it has time gaps (time_gaps) or moves
/// (check_stationary(); not_stationary) unless options.force; the ins::InsSensorNoise of MODEL
/// by options.gm_convention; analyze_drift() at the location and with the protocol of OPTIONS;
/// with options.monte_carlo_runs > 0, monte_carlo_drift() of MODEL's simulator terms (flicker
/// B over τ up to max(10⁴ s, 10 × segment)). PROGRESS (optional) gets the stages of
/// analyze_drift() ("segments") and monte_carlo_drift() ("Monte Carlo"), in that order.
/// With options.holdout_half, also the split-sample check (DriftSummary::holdout; the fit of
/// the first half reports progress as analyze_recording does, stage names of axis analysis).
/// @throws DriftRefused as above (messages start with recording.source_path), InputError from
///   the model, the options and analyze_drift() (also when a half holds fewer than 2
///   segments), AnalysisError from the alignment or the fit of the first half.
DriftResult run_drift(const Recording& recording, const models::NoiseModel& model,
                      const DriftRunOptions& options, const ProgressCallback& progress = {});

}  // namespace imunoise::pipeline
