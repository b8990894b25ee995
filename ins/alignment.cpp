/// @file
/// @brief Coarse alignment from a stationary window (see alignment.h, theory.md §7.3).
#include "ins/alignment.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>

#include "common/errors.h"
#include "common/units.h"
#include "ins/earth_model.h"

namespace imunoise::ins {
namespace {

using Eigen::AngleAxisd;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using units::kDeg;

/// Below this |f̄| the window cannot be levelled: 1 m/s² is a tenth of gravity, far outside any
/// stationary accelerometer's error, so it flags a wrong unit or a missing channel.
constexpr double kMinSpecificForce = 1.0;
/// Above this |L| the horizontal Earth rate (Ω_ie cos L) and the yaw of NED lose meaning.
constexpr double kMaxLatitude = 89.9 * kDeg;

/// VALUE with DIGITS significant digits, for the human-readable note and messages.
std::string rounded_text(double value, int digits) {
  char buffer[32];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, digits);
  return std::string(buffer, result.ptr);
}

void check_input(const AlignmentInput& in) {
  IMUNOISE_CHECK(std::isfinite(in.latitude_rad) && std::abs(in.latitude_rad) < kMaxLatitude,
                 InputError,
                 "coarse_alignment: latitude must be finite and |L| < 89.9 deg (got " +
                     rounded_text(in.latitude_rad / kDeg, 6) + " deg)");
  IMUNOISE_CHECK(std::isfinite(in.height_m), InputError, "coarse_alignment: height must be finite");
  IMUNOISE_CHECK(
      in.mean_f_ib_b_m_per_s2.allFinite() && in.mean_f_ib_b_m_per_s2.norm() >= kMinSpecificForce,
      InputError,
      "coarse_alignment: mean specific force must be finite with |f| >= 1 m/s^2 to "
      "level (got " +
          rounded_text(in.mean_f_ib_b_m_per_s2.norm(), 3) +
          " m/s^2); is the accelerometer in m/s^2 and the IMU at rest?");
  IMUNOISE_CHECK(in.mean_w_ib_b_rad_per_s.allFinite(), InputError,
                 "coarse_alignment: mean angular rate must be finite");
  IMUNOISE_CHECK(std::isfinite(in.gyro_bias_sigma_rad_per_s) && in.gyro_bias_sigma_rad_per_s >= 0.0,
                 InputError,
                 "coarse_alignment: gyro bias sigma must be finite and >= 0 (got " +
                     rounded_text(in.gyro_bias_sigma_rad_per_s, 6) + " rad/s)");
  IMUNOISE_CHECK(std::isfinite(in.max_gyrocompass_heading_sigma_rad) &&
                     in.max_gyrocompass_heading_sigma_rad >= 0.0,
                 InputError, "coarse_alignment: max gyrocompass heading sigma must be >= 0");
  IMUNOISE_CHECK(std::isfinite(in.given_heading_sigma_rad) && in.given_heading_sigma_rad >= 0.0,
                 InputError, "coarse_alignment: given heading sigma must be finite and >= 0");
  IMUNOISE_CHECK(!in.given_heading_rad || std::isfinite(*in.given_heading_rad), InputError,
                 "coarse_alignment: given heading must be finite");
}

}  // namespace

Alignment coarse_alignment(const AlignmentInput& input) {
  check_input(input);
  const double lat = input.latitude_rad;
  const Vector3d& f = input.mean_f_ib_b_m_per_s2;

  // Heading source (theory.md §7.3): the gyrocompass resolves the horizontal Earth rate, so its
  // heading σ is the bias σ over Ω_ie cos L; a given heading always wins.
  const double earth_rate_horizontal = wgs84::kEarthRate * std::cos(lat);
  const double gyrocompass_sigma = input.gyro_bias_sigma_rad_per_s / earth_rate_horizontal;
  const bool gyrocompass_possible = gyrocompass_sigma <= input.max_gyrocompass_heading_sigma_rad;
  const std::string why = "gyro bias " + rounded_text(input.gyro_bias_sigma_rad_per_s, 2) +
                          " rad/s vs Earth rate horizontal " +
                          rounded_text(earth_rate_horizontal, 2) + " rad/s";
  IMUNOISE_CHECK(gyrocompass_possible || input.given_heading_rad, InputError,
                 "coarse_alignment: gyrocompassing is not possible (predicted heading sigma " +
                     rounded_text(gyrocompass_sigma / kDeg, 2) + " deg > " +
                     rounded_text(input.max_gyrocompass_heading_sigma_rad / kDeg, 2) +
                     " deg: " + why + "); give the heading with " + input.heading_setting);

  // Levelling in the plumb-line frame p, in which the mean specific force is [0, 0, −|f̄|].
  const double roll_p = std::atan2(-f.y(), -f.z());
  const double pitch_p = std::atan2(f.x(), std::hypot(f.y(), f.z()));
  const Matrix3d C_level_b =
      (AngleAxisd(pitch_p, Vector3d::UnitY()) * AngleAxisd(roll_p, Vector3d::UnitX()))
          .toRotationMatrix();

  // C_bn = R_y(β) R_z(ψ_p) C_level_b, ψ_p the yaw in the plumb frame. The tilt about east
  // β = asin(g_N/|f̄|) makes the north part of Ĉ f̄ exactly −g_N, so with the height hold (which
  // removes only the down residual |f̄| − |g|) the navigator sees no horizontal force at rest.
  // Using the direction of g^n instead, atan2(g_N, g_D), would leave (|g| − |f̄|) sin β north:
  // 2.5e-9 m/s², 0.4 mm in 10 min, for a 3 mg accelerometer bias at h = 100 m.
  const double g_north = gravity_ned(lat, input.height_m).x();
  const AngleAxisd plumb_to_ned(std::asin(std::clamp(g_north / f.norm(), -1.0, 1.0)),
                                Vector3d::UnitY());
  const auto attitude = [&](double yaw_p) -> Matrix3d {
    return plumb_to_ned * AngleAxisd(yaw_p, Vector3d::UnitZ()) * C_level_b;
  };
  const auto yaw_of = [](const Matrix3d& C_bn) { return std::atan2(C_bn(1, 0), C_bn(0, 0)); };

  Alignment out;
  Matrix3d C_bn;
  if (input.given_heading_rad) {
    // Solve yaw(C_bn(ψ_p)) = given: ψ_p differs from it by O(β tan θ) (4e-9 rad at h = 100 m,
    // θ = 3°), and each fixed-point step shrinks the residual by another factor O(β).
    const double given = *input.given_heading_rad;
    double yaw_p = given;
    for (int iteration = 0; iteration < 3; ++iteration) {
      yaw_p += std::remainder(given - yaw_of(attitude(yaw_p)), 2.0 * std::numbers::pi);
    }
    C_bn = attitude(yaw_p);
    out.heading_source = Alignment::HeadingSource::given;
    out.heading_sigma_rad = input.given_heading_sigma_rad;
    out.heading_note =
        "given heading " + rounded_text(given / kDeg, 6) +
        " deg: gyrocompass heading sigma would be " + rounded_text(gyrocompass_sigma / kDeg, 2) +
        " deg (" + why + ")" +
        (gyrocompass_possible
             ? ", within the limit, but a given heading wins"
             : ", above the " + rounded_text(input.max_gyrocompass_heading_sigma_rad / kDeg, 2) +
                   " deg limit");
  } else {
    // Gyrocompass: the level-frame Earth rate is R_z(−ψ_p)·R_y(−β)ω_ie^n, whose horizontal part
    // lies along plumb-frame north because that frame is tilted about east only.
    const Vector3d w_level = C_level_b * input.mean_w_ib_b_rad_per_s;
    C_bn = attitude(std::atan2(-w_level.y(), w_level.x()));
    out.heading_source = Alignment::HeadingSource::gyrocompass;
    out.heading_sigma_rad = gyrocompass_sigma;
    out.heading_note = "gyrocompass: predicted heading sigma " +
                       rounded_text(gyrocompass_sigma / kDeg, 2) + " deg (" + why + ")";
  }

  out.q_bn = Eigen::Quaterniond(C_bn).normalized();
  out.roll_rad = std::atan2(C_bn(2, 1), C_bn(2, 2));
  out.pitch_rad = -std::asin(std::clamp(C_bn(2, 0), -1.0, 1.0));
  out.yaw_rad = yaw_of(C_bn);
  // Bias removal with the same attitude the navigator starts from (theory.md §7.3).
  out.gyro_bias_estimate_rad_per_s =
      input.mean_w_ib_b_rad_per_s - C_bn.transpose() * earth_rate_ned(lat);
  return out;
}

}  // namespace imunoise::ins
