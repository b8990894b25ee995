/// @file
/// @brief What the noise model means in metres, checked against the recording itself
/// (theory.md §7.6–7.7): split a stationary recording into independent segments, align and
/// free-run each through the strapdown navigator, and compare the actual horizontal drift
/// with the covariance prediction of the fitted model (NEES with its χ² band, 2-D coverage,
/// RMS ratio); plus a Monte Carlo envelope from simulating the model through the same
/// alignment + mechanization. Pure computation: spans in, values out.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/progress_callback.h"
#include "common/units.h"
#include "ins/alignment.h"
#include "ins/drift_prediction.h"
#include "ins/error_state_model.h"
#include "models/noise_simulator.h"
#include "pipeline/drift_series.h"

namespace imunoise::pipeline {

/// Six equally long channels of a stationary recording in SI, body FRD: gyro x, y, z
/// [rad/s], accel x, y, z [m/s²], sampled every sample_period_s.
struct ImuSeries {
  std::array<std::span<const double>, 6> channels;
  double sample_period_s = 0.0;
  std::size_t size() const { return channels[0].size(); }
};

struct DriftOptions {
  double latitude_rad = 45.0 * units::kDeg;  ///< where the recording was made
  double longitude_rad = 0.0;
  double height_m = 0.0;
  /// Heading [rad] from outside; without it each segment gyrocompasses, which needs a gyro
  /// good enough (ins::coarse_alignment decides and says why).
  std::optional<double> heading_rad;
  /// How an alignment that cannot gyrocompass names the way to give the heading
  /// (ins::AlignmentInput::heading_setting); the CLI passes its flag, "--heading DEG".
  std::string heading_setting = "heading_rad";
  double heading_sigma_rad = 0.0;  ///< 1σ of the given heading [rad]
  double align_s = 60.0;           ///< alignment window T_a [s]
  double navigation_s = 600.0;     ///< free-inertial time after it [s]
  double warmup_s = 0.0;           ///< skipped at the start of the recording [s]
  double output_step_s = 1.0;      ///< time grid of the per-segment series [s]
  /// Times at which the consistency statistics are computed [s], each ≤ navigation_s and a
  /// whole number of output steps.
  std::vector<double> report_times_s{60.0, 300.0, 600.0};
  /// Optional progress: analyze_drift reports ("segments", segments done, segments),
  /// monte_carlo_drift ("Monte Carlo", runs done, runs). Does not change the result.
  ProgressCallback progress;
};

/// Why the drift analysis refused its input, so that a caller (the CLI) can say how to get
/// past it (a flag of its own): the pure layer only says what is wrong.
enum class DriftRefusal {
  missing_channel,   ///< the recording lacks one of the six IMU channels
  time_gaps,         ///< the recording has time gaps (pipeline/drift_run.h, unless forced)
  not_stationary,    ///< check_stationary() failed (pipeline/drift_run.h, unless forced)
  too_few_segments,  ///< fewer than 2 segments of alignment + navigation fit
};

/// An InputError of the drift analysis with its DriftRefusal.
class DriftRefused : public InputError {
 public:
  DriftRefused(DriftRefusal reason, const std::string& message)
      : InputError(message), reason_(reason) {}
  DriftRefusal reason() const noexcept { return reason_; }

 private:
  DriftRefusal reason_;
};

/// Result of the stationarity check (a moving IMU cannot be judged by a noise model).
struct MotionCheck {
  bool stationary = true;
  std::string reason;  ///< the first test that failed, with numbers; empty when stationary
  double max_gyro_std_ratio = 0.0;   ///< largest 1-s window std / model per-sample σ, gyro
  double max_accel_std_ratio = 0.0;  ///< the same for the accelerometer
  double max_force_deviation_m_per_s2 = 0.0;  ///< largest | |f̄_window| − median |f̄| |
  double max_tilt_change_rad = 0.0;     ///< largest angle between a window's f̄ and the median f̄
  double max_rotation_rad_per_s = 0.0;  ///< largest |ω̄_window − median ω̄|
};

/// Stationarity from 1-s windows: the sample std of every channel at most 3× the model's
/// per-sample σ (N/√Δt, plus the variance of the GM/B stand-in and 2Q²/Δt² of quantization), the
/// specific-force magnitude within 0.5 m/s² of its median, its direction within 2° of the median
/// direction, and the window-mean rate within 0.5 deg/s (plus 10 window σ) of its median. A
/// recording that moves fails at least one of them; a MEMS at rest passes them all with margin.
MotionCheck check_stationary(const ImuSeries& series, const ins::InsSensorNoise& noise);

/// Consistency of actual and predicted drift at one time (theory.md §7.7).
struct DriftConsistency {
  double time_s = 0.0;
  double predicted_north_sigma_m = 0.0, predicted_east_sigma_m = 0.0, predicted_drms_m = 0.0;
  double actual_rms_m = 0.0;  ///< √(mean over segments of |e|²)
  /// Mean NEES ε̄ = mean eᵀP⁻¹e with P = diag(σ_N², σ_E²); M·ε̄ ~ χ²_{2M} for a consistent model
  double mean_nees = 0.0, nees_band_low = 0.0, nees_band_high = 0.0;  ///< 95 % band of ε̄
  bool nees_inside = false;
  /// The band each report time's ε̄ must hold so that a consistent model is inside at all K
  /// report times together with probability ≥ 95 %: each χ²_{2M} band at 0.95^{1/K} (Šidák).
  /// Conservative: the times share their segments, so their ε̄ are positively correlated.
  double nees_joint_band_low = 0.0, nees_joint_band_high = 0.0;
  bool nees_inside_joint_band = false;
  /// Fraction of segments inside the 1σ, 2σ, 3σ ellipses; expected 1 − e^{−k²/2} =
  /// 0.393, 0.865, 0.989 for Gaussian 2-D errors.
  std::array<double, 3> coverage{};
  /// The coverage expected of Gaussian 2-D errors, 1 − e^{−k²/2} to four digits.
  std::array<double, 3> expected_coverage{0.3935, 0.8647, 0.9889};
  /// RMS actual / predicted DRMS, and the 95 % interval of the true ratio from χ²_{2M}
  double rms_ratio = 0.0, rms_ratio_ci_low = 0.0, rms_ratio_ci_high = 0.0;
  /// The Monte Carlo radial RMS and 95th percentile at time_s [m]: set by run_drift()
  /// (pipeline/drift_run.h) when it ran the Monte Carlo, absent otherwise.
  std::optional<double> monte_carlo_radial_rms_m, monte_carlo_radial_p95_m;
};

struct DriftAnalysis {
  std::vector<double> time_s;  ///< output grid: output_step_s, 2·output_step_s, … navigation_s
  ins::DriftPrediction prediction;     ///< on time_s, for the alignment protocol of the segments
                                       ///< (with its variance budget)
  std::vector<DriftSegment> segments;  ///< each on time_s
  std::vector<ins::Alignment> alignments;     ///< of each segment, in the order of segments
  std::vector<DriftConsistency> consistency;  ///< at report_times_s
  std::string heading_note;                   ///< how the first segment got its heading
};

/// Splits SERIES into ⌊(duration − warmup)/(align + navigation)⌋ back-to-back segments; per
/// segment: coarse alignment over the first align_s (levelling, gyrocompass or the given
/// heading, gyro-bias estimate removed — theory.md §7.3), then navigation_s of free-inertial
/// NED mechanization with height hold from the aligned attitude, recording the horizontal
/// position and velocity error (truth: at rest at the start point). The prediction is
/// ins::predict_stationary_drift of NOISE with the same alignment protocol.
/// @throws InputError with a clear message when the options are inconsistent, DriftRefused
///   (too_few_segments) when the recording holds fewer than 2 segments; AnalysisError passes
///   through from the alignment.
DriftAnalysis analyze_drift(const ImuSeries& series, const ins::InsSensorNoise& noise,
                            const DriftOptions& options);

/// Percentiles of the horizontal radial error over Monte Carlo runs, on the output grid.
struct MonteCarloEnvelope {
  std::vector<double> time_s;
  std::vector<double> radial_p50_m, radial_p68_m, radial_p95_m;
  std::vector<double> radial_rms_m;  ///< comparable with the predicted DRMS
  int runs = 0;
};

/// Simulates SIMULATION (the fitted model as simulator terms, flicker B included) for RUNS
/// independent segments at the recording's rate, adds the true stationary signal (gravity and
/// Earth rate at the location, level, the given heading or 0), and runs each through the
/// same alignment + mechanization as analyze_drift(). NOISE sets the alignment's gyrocompass
/// decision as it does there.
MonteCarloEnvelope monte_carlo_drift(const models::ImuNoiseModel& simulation,
                                     const models::FlickerBand& flicker_band,
                                     const ins::InsSensorNoise& noise, double sample_period_s,
                                     const DriftOptions& options, int runs, std::uint64_t seed);

}  // namespace imunoise::pipeline
