/// @file
/// @brief The drift curves of `imunoise drift` (theory.md §7.6–7.7), one type each: the drift
/// envelope on the output time grid (the model's 1σ prediction, the RMS of the recorded
/// segments, the Monte Carlo percentiles) and one recorded segment's navigation errors. What
/// pipeline/drift_run computes, io/drift_files writes and reads back (drift_envelope.csv,
/// drift_segments.csv), io/lcm_messages publishes and report/figures draws. Pure data, SI.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace imunoise::pipeline {

/// The drift envelope against time since the end of the alignment. Horizontal channel only:
/// the vertical channel is held (theory.md §7.2). Every non-empty vector is as long as time_s.
struct DriftSeries {
  std::vector<double> time_s;  ///< output grid [s]: step, 2·step, … navigation time
  /// @name The model's 1σ prediction (ins::DriftPrediction on time_s)
  /// @{
  std::vector<double> predicted_north_sigma_m, predicted_east_sigma_m;  ///< position [m]
  std::vector<double> predicted_drms_m;  ///< horizontal DRMS √(σ_N² + σ_E²) [m]
  std::vector<double> predicted_velocity_drms_m_per_s;  ///< √(σ_vN² + σ_vE²) [m/s]
  /// Small-angle roll, pitch and heading errors [rad]
  std::vector<double> predicted_roll_sigma_rad, predicted_pitch_sigma_rad,
      predicted_heading_sigma_rad;
  /// Total attitude 1σ √(σ_roll² + σ_pitch² + σ_heading²) [rad], computed from the three
  /// above in the unit they were given in (rad from the prediction, deg from
  /// drift_envelope.csv); not a column of the file.
  std::vector<double> predicted_attitude_sigma_rad;
  /// @}
  /// RMS over the recorded segments of the horizontal position error [m]; empty when there
  /// is no recorded drift.
  std::vector<double> recorded_rms_m;
  /// @name Monte Carlo of the model through the same protocol: percentiles and RMS of the
  /// horizontal radial error [m]; all empty when it did not run
  /// @{
  std::vector<double> mc_radial_p50_m, mc_radial_p68_m, mc_radial_p95_m, mc_radial_rms_m;
  /// @}
};

/// One recorded free-inertial segment: its navigation errors against time since the end of
/// its alignment (the truth is at rest at the start point). All vectors as long as time_s.
struct DriftSegment {
  double start_s = 0.0;        ///< start of its alignment window in the recording [s]
  std::vector<double> time_s;  ///< since the end of the alignment [s]
  std::vector<Eigen::Vector2d> position_error_ne_m;       ///< [north, east] position error [m]
  std::vector<double> velocity_error_horizontal_m_per_s;  ///< |horizontal velocity| [m/s]
  /// Attitude change since the end of the alignment, as the small rotation δψ resolved in NED
  /// [rad] (north, east, down): the truth is at rest, so any change is error.
  std::vector<Eigen::Vector3d> attitude_error_ned_rad;

  /// |position_error_ne_m| at each time [m].
  std::vector<double> horizontal_error_m() const {
    std::vector<double> out;
    out.reserve(position_error_ne_m.size());
    for (const Eigen::Vector2d& e : position_error_ne_m) out.push_back(e.norm());
    return out;
  }
};

}  // namespace imunoise::pipeline
