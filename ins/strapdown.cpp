/// @file
/// @brief Strapdown NED mechanization (see strapdown.h, theory.md §7.2).
#include "ins/strapdown.h"

#include <cmath>
#include <numbers>
#include <string>

#include "common/errors.h"
#include "ins/earth_model.h"

namespace imunoise::ins {
namespace {

using Eigen::Quaterniond;
using Eigen::Vector3d;

/// q(r) = [cos(|r|/2), sin(|r|/2) r/|r|] (theory.md §7.2). Below |r| = 1e-4 the Taylor series
/// to |r|⁴ avoids 0/0; its first omitted terms are ~|r|⁶/46080 < 1e-28.
Quaterniond rotation_vector_quaternion(const Vector3d& r) {
  const double angle2 = r.squaredNorm();
  double cos_half = 0.0, sin_half_over_angle = 0.0;
  if (angle2 < 1e-8) {
    cos_half = 1.0 - angle2 / 8.0 + angle2 * angle2 / 384.0;
    sin_half_over_angle = 0.5 - angle2 / 48.0 + angle2 * angle2 / 3840.0;
  } else {
    const double angle = std::sqrt(angle2);
    cos_half = std::cos(0.5 * angle);
    sin_half_over_angle = std::sin(0.5 * angle) / angle;
  }
  const Vector3d v = sin_half_over_angle * r;
  return Quaterniond(cos_half, v.x(), v.y(), v.z());
}

/// SUM += INCREMENT with Kahan compensation, CARRY holding the low-order part lost so far. At
/// rest the per-sample position steps are tiny against L itself: 1e-8 m/s at 100 Hz moves L by
/// 1.6e-17 rad, below half an ulp of 0.785 (5.6e-17), so plain summation would drop it every
/// sample and stall a slow drift.
void kahan_add(double& sum, double& carry, double increment) {
  const double corrected = increment - carry;
  const double next = sum + corrected;
  carry = (next - sum) - corrected;
  sum = next;
}

}  // namespace

StrapdownNavigator::StrapdownNavigator(const NavState& initial, const MechanizationOptions& options)
    : state_(initial), options_(options), initial_height_m_(initial.height_m) {
  IMUNOISE_CHECK(std::isfinite(initial.latitude_rad) &&
                     std::abs(initial.latitude_rad) < std::numbers::pi / 2.0,
                 InputError,
                 "StrapdownNavigator: latitude must be finite and strictly within ±pi/2 rad (got " +
                     std::to_string(initial.latitude_rad) + ")");
  IMUNOISE_CHECK(std::isfinite(initial.longitude_rad) && std::isfinite(initial.height_m) &&
                     initial.v_ned_m_per_s.allFinite() && initial.q_bn.coeffs().allFinite(),
                 InputError, "StrapdownNavigator: initial state must be finite");
  IMUNOISE_CHECK(initial.q_bn.norm() > 0.0, InputError,
                 "StrapdownNavigator: initial attitude quaternion has zero norm");
  state_.q_bn.normalize();
  if (options_.height_hold) state_.v_ned_m_per_s.z() = 0.0;
}

void StrapdownNavigator::update(const ImuIncrement& increment) {
  const double dt = increment.dt_s;
  // Δt is the recording's sample period, which the drift analysis checked (make_grid).
  IMUNOISE_EXPECT(
      std::isfinite(dt) && dt > 0.0,
      "StrapdownNavigator::update: dt must be finite and > 0 (got " + std::to_string(dt) + " s)");
  IMUNOISE_CHECK(increment.dtheta_b_rad.allFinite() && increment.dv_b_m_per_s.allFinite(),
                 InputError, "StrapdownNavigator::update: increment must be finite");
  const Vector3d& dtheta = increment.dtheta_b_rad;
  const Vector3d& dv = increment.dv_b_m_per_s;

  // Earth terms at the state before the step (theory.md §7.1); one set serves all three stages.
  const double lat = state_.latitude_rad, h = state_.height_m;
  const Vector3d v_old = state_.v_ned_m_per_s;
  const Vector3d w_ie = earth_rate_ned(lat);
  const Vector3d w_en = transport_rate_ned(lat, h, v_old);
  const Vector3d w_in = w_ie + w_en;
  const double rn_h = meridian_radius(lat) + h;
  const double re_h = transverse_radius(lat) + h;

  // 1. Velocity. The body increment resolved in b(k−1), ∫(I + [θ×] + ½[θ×]²)f dt: Δv, the
  // rotation compensation ½Δθ×Δv and its second-order term (1/6)Δθ×(Δθ×Δv) (Groves's C̄ of
  // theory.md §7.2 to second order in |Δθ|), and optionally the two-sample sculling term for
  // linearly varying rates (Titterton & Weston 2004 ch. 11). The second-order term matters as
  // much as sculling: for an IMU rocking in gravity it rectifies to −2× the sculling term.
  Vector3d dv_body = dv + 0.5 * dtheta.cross(dv) + dtheta.cross(dtheta.cross(dv)) / 6.0;
  if (options_.coning_sculling) {
    dv_body += (previous_dtheta_b_rad_.cross(dv) + previous_dv_b_m_per_s_.cross(dtheta)) / 12.0;
  }
  // C̄ = C_{b(k−1)}^{n(k−½)}: the n-frame half of the mid-interval rotation (the body's share is
  // in the Δθ terms above); at rest the two cancel, which keeps a perfect stationary IMU still.
  const Quaterniond q_mid = rotation_vector_quaternion(-0.5 * dt * w_in) * state_.q_bn;
  const Vector3d dv_specific_force_n = q_mid * dv_body;
  const Vector3d dv_gravity_coriolis_n =
      (gravity_ned(lat, h) - (2.0 * w_ie + w_en).cross(v_old)) * dt;
  Vector3d v_new = v_old + dv_specific_force_n + dv_gravity_coriolis_n;
  if (options_.height_hold) v_new.z() = 0.0;

  // 2. Position: trapezoid of the old and new velocity (theory.md §7.2).
  const Vector3d v_mean = 0.5 * (v_old + v_new);
  const double dlat = v_mean.x() / rn_h * dt;
  const double dlon = v_mean.y() / (re_h * std::cos(lat + 0.5 * dlat)) * dt;
  kahan_add(state_.latitude_rad, latitude_carry_, dlat);
  kahan_add(state_.longitude_rad, longitude_carry_, dlon);
  if (options_.height_hold) {
    state_.height_m = initial_height_m_;
  } else {
    kahan_add(state_.height_m, height_carry_, -v_mean.z() * dt);
  }
  state_.v_ned_m_per_s = v_new;

  // 3. Attitude: q_bn ← q(−ω_in^nΔt) ⊗ q_bn ⊗ q(α), α with the optional coning term.
  Vector3d alpha = dtheta;
  if (options_.coning_sculling) alpha += previous_dtheta_b_rad_.cross(dtheta) / 12.0;
  state_.q_bn =
      rotation_vector_quaternion(-dt * w_in) * state_.q_bn * rotation_vector_quaternion(alpha);
  state_.q_bn.normalize();

  previous_dtheta_b_rad_ = dtheta;
  previous_dv_b_m_per_s_ = dv;
}

ImuIncrement increment_from_rates(const Eigen::Vector3d& w_ib_b_rad_per_s,
                                  const Eigen::Vector3d& f_ib_b_m_per_s2, double dt_s) {
  return {w_ib_b_rad_per_s * dt_s, f_ib_b_m_per_s2 * dt_s, dt_s};
}

Eigen::Vector2d horizontal_offset_m(const NavState& nav, double latitude0_rad,
                                    double longitude0_rad) {
  const double lat = nav.latitude_rad, h = nav.height_m;
  // Longitude difference wrapped to [−π, π] so a track across ±180° stays short.
  const double dlon = std::remainder(nav.longitude_rad - longitude0_rad, 2.0 * std::numbers::pi);
  return {(meridian_radius(lat) + h) * (lat - latitude0_rad),
          (transverse_radius(lat) + h) * std::cos(lat) * dlon};
}

}  // namespace imunoise::ins
