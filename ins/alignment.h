/// @file
/// @brief Coarse alignment from a stationary window (theory.md §7.3; Groves 2013 §5.6):
/// levelling from the mean specific force, heading by gyrocompassing or from the user, and
/// the gyro-bias estimate that makes the navigator self-consistent at rest.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "common/units.h"

namespace imunoise::ins {

struct AlignmentInput {
  Eigen::Vector3d mean_f_ib_b_m_per_s2 = Eigen::Vector3d::Zero();   ///< window mean of f_ib^b
  Eigen::Vector3d mean_w_ib_b_rad_per_s = Eigen::Vector3d::Zero();  ///< window mean of ω_ib^b
  double latitude_rad = 0.0;                                        ///< L, geodetic [rad]
  double height_m = 0.0;                                            ///< h above the ellipsoid [m]
  /// Heading (yaw) from outside [rad]; when set it is used even if gyrocompassing is possible.
  std::optional<double> given_heading_rad;
  /// 1σ of the given heading [rad], reported as heading_sigma_rad when the given heading is used.
  double given_heading_sigma_rad = 0.0;
  /// 1σ of the gyro-bias uncertainty over the window [rad/s] (from the noise model); it sets
  /// the gyrocompass heading σ = σ_b/(Ω_ie cos L).
  double gyro_bias_sigma_rad_per_s = 0.0;
  /// Gyrocompassing is possible when its predicted heading σ is at most this [rad].
  double max_gyrocompass_heading_sigma_rad = 5.0 * units::kDeg;
  /// How the refusal to gyrocompass names the way to give the heading ("give the heading with
  /// …"); the CLI passes its flag, "--heading DEG".
  std::string heading_setting = "given_heading_rad";
};

struct Alignment {
  /// @name Euler angles of q_bn (ZYX: C_bn = R_z(yaw) R_y(pitch) R_x(roll)) [rad]
  /// @{
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rad = 0.0;
  /// @}
  Eigen::Quaterniond q_bn = Eigen::Quaterniond::Identity();  ///< body (FRD) → NED
  enum class HeadingSource { gyrocompass, given };
  HeadingSource heading_source = HeadingSource::gyrocompass;
  std::string heading_note;  ///< which heading source was used and why, for the report
  /// Predicted 1σ of the heading [rad]: σ_b/(Ω_ie cos L) for the gyrocompass, the input's
  /// given_heading_sigma_rad for a given heading.
  double heading_sigma_rad = 0.0;
  /// b̂_g = ω̄^b − Ĉ_n^b ω_ie^n with the attitude above (theory.md §7.3) [rad/s]: subtracting it
  /// makes the navigator stationary at rest whatever the heading error.
  Eigen::Vector3d gyro_bias_estimate_rad_per_s = Eigen::Vector3d::Zero();
};

/// Coarse alignment (theory.md §7.3). Levelling: θ = atan2(f_x, √(f_y² + f_z²)),
/// φ = atan2(−f_y, −f_z) (FRD); gyrocompass: ω̄^b rotated by φ, θ into the level frame gives
/// ψ = atan2(−ω_y^L, ω_x^L). Both are done in a plumb-line frame, NED tilted about east by
/// β = asin(g_N/|f̄|) (g_N = −8.08e-9·h·sin 2L of gravity_ned(), §7.1; β ≈ −8e-8 rad at h = 100 m,
/// L = 45°), so that the horizontal part of Ĉ_bn f̄ + g^n is exactly zero and the navigator with
/// height hold sees no horizontal force at rest. A given heading becomes the yaw of q_bn exactly.
/// Errors: tilt ≈ b_a/g, gyrocompass heading ≈ −b_g,E/(Ω_ie cos L).
/// @throws InputError when f̄ is not finite or |f̄| < 1 m/s², ω̄ or h is not finite, L is not
/// finite or |L| ≥ 89.9°, a σ is negative or not finite, the given heading is not finite, or
/// gyrocompassing is not possible and no heading is given (the message names
/// input.heading_setting).
Alignment coarse_alignment(const AlignmentInput& input);

}  // namespace imunoise::ins
