/// @file
/// @brief Tests of ins/strapdown.h: a perfect stationary IMU stays put (theory.md §7.2), a
/// constant accelerometer or gyro bias reproduces the Schuler closed forms of theory.md §7.5
/// and the 84.4 min period of §7.4, the coning term removes the drift of a turntable's
/// rectangular rate sum, and the horizontal offset agrees with an ECEF computation.
#include "ins/strapdown.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/units.h"
#include "ins/earth_model.h"
#include "test_support.h"

namespace imunoise::ins {
namespace {

using Eigen::AngleAxisd;
using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using units::kDeg;

constexpr double kDt = 0.01;  // 100 Hz sample interval [s]

/// C_bn = R_z(yaw) R_y(pitch) R_x(roll), composed from axis rotations (not from the code under
/// test).
Matrix3d attitude_from_euler(double roll_rad, double pitch_rad, double yaw_rad) {
  return (AngleAxisd(yaw_rad, Vector3d::UnitZ()) * AngleAxisd(pitch_rad, Vector3d::UnitY()) *
          AngleAxisd(roll_rad, Vector3d::UnitX()))
      .toRotationMatrix();
}

NavState state_at_rest(double latitude_rad, double height_m, const Matrix3d& C_bn) {
  NavState state;
  state.latitude_rad = latitude_rad;
  state.longitude_rad = 0.3;
  state.height_m = height_m;
  state.q_bn = Quaterniond(C_bn);
  return state;
}

/// The increment of an IMU at rest at (L, h) with attitude C_bn: f^b = C_nb(−g^n) and
/// ω^b = C_nb ω_ie^n (exact integrals, the rates being constant), plus sensor biases.
ImuIncrement stationary_increment(double latitude_rad, double height_m, const Matrix3d& C_bn,
                                  const Vector3d& accel_bias_b, const Vector3d& gyro_bias_b) {
  const Vector3d f_b = C_bn.transpose() * -gravity_ned(latitude_rad, height_m) + accel_bias_b;
  const Vector3d w_b = C_bn.transpose() * earth_rate_ned(latitude_rad) + gyro_bias_b;
  return increment_from_rates(w_b, f_b, kDt);
}

MechanizationOptions options_with(bool coning_sculling) {
  MechanizationOptions options;
  options.coning_sculling = coning_sculling;
  return options;
}

/// Schuler angular frequency ω_s = √(g/R), R = √(R_N R_E), g = |g^n| at (L, 0) (theory.md §7.4).
double schuler_frequency(double latitude_rad) {
  const double radius = std::sqrt(meridian_radius(latitude_rad) * transverse_radius(latitude_rad));
  return std::sqrt(gravity_ned(latitude_rad, 0.0).norm() / radius);
}

TEST(StrapdownNavigator, PerfectStationaryImuStaysPutForAnHour) {
  // L = 45°, h = 100 m (so g_N ≠ 0 is exercised), heading 30°, 1 h at 100 Hz.
  const double lat = 45.0 * kDeg, h = 100.0;
  const Matrix3d C_bn = attitude_from_euler(0.0, 0.0, 30.0 * kDeg);
  const ImuIncrement increment =
      stationary_increment(lat, h, C_bn, Vector3d::Zero(), Vector3d::Zero());
  for (const bool coning_sculling : {true, false}) {
    SCOPED_TRACE(coning_sculling ? "with coning/sculling" : "without coning/sculling");
    const NavState initial = state_at_rest(lat, h, C_bn);
    StrapdownNavigator navigator(initial, options_with(coning_sculling));
    for (int k = 0; k < 360000; ++k) navigator.update(increment);
    const NavState& nav = navigator.state();
    const double drift_m =
        horizontal_offset_m(nav, initial.latitude_rad, initial.longitude_rad).norm();
    const double attitude_rad = nav.q_bn.angularDistance(initial.q_bn);
    RecordProperty(coning_sculling ? "drift_m_coning" : "drift_m_plain",
                   shortest_number_text(drift_m));
    RecordProperty(coning_sculling ? "attitude_rad_coning" : "attitude_rad_plain",
                   shortest_number_text(attitude_rad));
    EXPECT_LT(drift_m, 1e-3);
    EXPECT_LT(attitude_rad, 1e-9);
    EXPECT_LT(nav.v_ned_m_per_s.norm(), 1e-6);
    EXPECT_EQ(nav.height_m, h);  // height hold
  }
}

// The bias tests run at latitude 0: there the vertical Earth rate Ω_ie sin L vanishes, and with
// it the Foucault rotation of the error between the north and east channels (theory.md §7.4);
// at 45° it would turn the north error by Ω_ie sin L·t = 7.5° at half a Schuler period (0.9 %
// of its size, the rest leaking east). What remains differs from the single-channel closed form
// by known amounts: the north channel turns on R_N, not √(R_N R_E) (period −0.17 %), and for a
// gyro bias the tilt not matched by position error turns into heading through Ω_ie
// (δψ̇_D = −Ω_ie(δψ_E − δL)), which feeds back as Ω_ie δψ_D.

TEST(StrapdownNavigator, NorthAccelBiasFollowsSchulerClosedForm) {
  const double b = 1e-3;  // accelerometer bias on the north-pointing x axis [m/s²] (≈ 100 µg)
  const Matrix3d C_bn = Matrix3d::Identity();  // heading 0, level
  const ImuIncrement increment =
      stationary_increment(0.0, 0.0, C_bn, Vector3d(b, 0.0, 0.0), Vector3d::Zero());
  const NavState initial = state_at_rest(0.0, 0.0, C_bn);
  StrapdownNavigator navigator(initial, options_with(true));

  const double ws = schuler_frequency(0.0);
  const int half_period_steps = static_cast<int>(std::lround(std::numbers::pi / ws / kDt));
  double previous_v_north = 0.0, zero_crossing_s = std::numeric_limits<double>::quiet_NaN();
  // Run past both the model's half period and the measured zero crossing (which comes first).
  for (int k = 1;
       k <= half_period_steps || (std::isnan(zero_crossing_s) && k <= 2 * half_period_steps); ++k) {
    navigator.update(increment);
    const double t = k * kDt;
    const NavState& nav = navigator.state();
    const Eigen::Vector2d offset =
        horizontal_offset_m(nav, initial.latitude_rad, initial.longitude_rad);
    if (k == 6000) {  // 60 s ≪ 84 min: b t²/2
      const double expected = b * t * t / 2.0;
      RecordProperty("north_60s_rel", shortest_number_text(offset.x() / expected - 1.0));
      EXPECT_NEAR(offset.x(), expected, 0.01 * expected);
    }
    if (k == half_period_steps) {  // (b/ω_s²)(1 − cos ω_s t), ≈ 2b/ω_s² = 1.3 km
      const double expected = b / (ws * ws) * (1.0 - std::cos(ws * t));
      RecordProperty("north_half_period_rel", shortest_number_text(offset.x() / expected - 1.0));
      EXPECT_NEAR(offset.x(), expected, 0.01 * expected);
      // East stays ~0: what leaks is the Foucault term of the error's own latitude (1.3 km north
      // is L = 2e-4 rad, Ω_ie sin L·t ≈ 4e-5 rad by now).
      EXPECT_LT(std::abs(offset.y()), 1e-4 * expected);
    }
    // δv_N = (b/ω_s) sin ω_s t: its first zero after t = 0 is half a Schuler period.
    const double v_north = nav.v_ned_m_per_s.x();
    if (std::isnan(zero_crossing_s) && previous_v_north > 0.0 && v_north <= 0.0) {
      zero_crossing_s = t - kDt * v_north / (v_north - previous_v_north);
    }
    previous_v_north = v_north;
  }
  ASSERT_FALSE(std::isnan(zero_crossing_s)) << "no zero crossing of the velocity error";
  const double expected_period_s = 2.0 * std::numbers::pi / ws;  // 2π√(R/g)
  EXPECT_NEAR(expected_period_s / 60.0, 84.4, 0.05);             // theory.md §7.4 (V)
  const double period_s = 2.0 * zero_crossing_s;
  RecordProperty("schuler_period_min", shortest_number_text(period_s / 60.0));
  RecordProperty("schuler_period_rel", shortest_number_text(period_s / expected_period_s - 1.0));
  EXPECT_NEAR(period_s, expected_period_s, 0.005 * expected_period_s);
}

TEST(StrapdownNavigator, NorthAccelBiasIsDeflectedEastByCoriolisAt45Deg) {
  // Away from the equator the velocity error δv_N ≈ b t feels the Coriolis term
  // −2ω_ie^n × δv: δv̇_E = 2Ω_ie sin L·δv_N, so δr_E ≈ Ω_ie sin L·b t³/3 (to the right of the
  // error's motion in the northern hemisphere). The tilt terms stay in step with the position
  // error (δψ_E = δL) and add only O(ω_s² t²/20) ≈ 3e-4 relative at 60 s.
  const double lat = 45.0 * kDeg, b = 1e-3;  // north accelerometer bias [m/s²]
  const Matrix3d C_bn = Matrix3d::Identity();
  const ImuIncrement increment =
      stationary_increment(lat, 0.0, C_bn, Vector3d(b, 0.0, 0.0), Vector3d::Zero());
  const NavState initial = state_at_rest(lat, 0.0, C_bn);
  StrapdownNavigator navigator(initial, options_with(true));
  for (int k = 0; k < 6000; ++k) navigator.update(increment);
  const double t = 60.0;
  const Eigen::Vector2d offset =
      horizontal_offset_m(navigator.state(), initial.latitude_rad, initial.longitude_rad);
  const double expected_east = wgs84::kEarthRate * std::sin(lat) * b * t * t * t / 3.0;  // 3.7 mm
  RecordProperty("east_60s_rel", shortest_number_text(offset.y() / expected_east - 1.0));
  EXPECT_NEAR(offset.y(), expected_east, 0.01 * expected_east);
  EXPECT_NEAR(offset.x(), b * t * t / 2.0, 0.01 * b * t * t / 2.0);
}

TEST(StrapdownNavigator, EastGyroBiasFollowsSchulerClosedForm) {
  // Sign convention (ins/error_state_model.h): errors are computed − true. A gyro reading ε too
  // high on the east-pointing y axis turns the computed attitude about east by +εt, so the
  // computed specific force gains a north component −g·εt and the north position error is
  // −R ε (t − sin(ω_s t)/ω_s), ≈ −g ε t³/6 for t ≪ 84 min (theory.md §7.5).
  const double eps = 0.1 * units::kDegPerHour;  // gyro bias [rad/s]
  const Matrix3d C_bn = Matrix3d::Identity();
  const ImuIncrement increment =
      stationary_increment(0.0, 0.0, C_bn, Vector3d::Zero(), Vector3d(0.0, eps, 0.0));
  const NavState initial = state_at_rest(0.0, 0.0, C_bn);
  StrapdownNavigator navigator(initial, options_with(true));

  const double ws = schuler_frequency(0.0);
  const double radius = std::sqrt(meridian_radius(0.0) * transverse_radius(0.0));
  const double g = gravity_ned(0.0, 0.0).norm();
  const int half_period_steps = static_cast<int>(std::lround(std::numbers::pi / ws / kDt));
  for (int k = 1; k <= half_period_steps; ++k) {
    navigator.update(increment);
    if (k != 6000 && k != half_period_steps) continue;
    const double t = k * kDt;
    const Eigen::Vector2d offset =
        horizontal_offset_m(navigator.state(), initial.latitude_rad, initial.longitude_rad);
    const double expected =
        k == 6000 ? -g * eps * t * t * t / 6.0 : -radius * eps * (t - std::sin(ws * t) / ws);
    RecordProperty(k == 6000 ? "north_60s_rel" : "north_half_period_rel",
                   shortest_number_text(offset.x() / expected - 1.0));
    EXPECT_NEAR(offset.x(), expected, 0.01 * std::abs(expected)) << "t = " << t << " s";
  }
}

TEST(StrapdownNavigator, ConingTermRemovesTurntableAttitudeDrift) {
  // A turntable at rest at 45° spinning at r about the local vertical: C_bn(t) = R_z(ψ₀ + r t),
  // ω_ib^b = R_z(−ψ)ω_ie^n + r e_z. The horizontal Earth rate rotates in the body, a weak
  // coning motion: the rectangular sum of Δθ drifts by ≈ (1/12)Ω_ie cos L r²Δt² per second
  // (1e-7 rad in 60 s at r = 2 rad/s), which the (1/12)Δθ_{k−1}×Δθ_k term removes.
  const double lat = 45.0 * kDeg, r = 2.0, yaw0 = 30.0 * kDeg;
  const double earth_horizontal = wgs84::kEarthRate * std::cos(lat);
  const double earth_down = -wgs84::kEarthRate * std::sin(lat);
  const int steps = 6000;
  const auto final_attitude_error = [&](bool coning_sculling) {
    StrapdownNavigator navigator(state_at_rest(lat, 0.0, attitude_from_euler(0.0, 0.0, yaw0)),
                                 options_with(coning_sculling));
    ImuIncrement increment;
    increment.dt_s = kDt;
    // h = 0: g^n is vertical, so f^b = [0, 0, −g_D] is unchanged by the spin.
    increment.dv_b_m_per_s = Vector3d(0.0, 0.0, -gravity_ned(lat, 0.0).z() * kDt);
    for (int k = 1; k <= steps; ++k) {
      const double yaw_before = yaw0 + r * (k - 1) * kDt, yaw_after = yaw0 + r * k * kDt;
      // ∫R_z(−ψ)[Ω_N, 0, Ω_D] dt + r Δt e_z, exactly, with ψ̇ = r.
      increment.dtheta_b_rad =
          Vector3d(earth_horizontal * (std::sin(yaw_after) - std::sin(yaw_before)) / r,
                   earth_horizontal * (std::cos(yaw_after) - std::cos(yaw_before)) / r,
                   (earth_down + r) * kDt);
      navigator.update(increment);
    }
    const Quaterniond truth(attitude_from_euler(0.0, 0.0, yaw0 + r * steps * kDt));
    return navigator.state().q_bn.angularDistance(truth);
  };
  const double with_coning = final_attitude_error(true);
  const double without_coning = final_attitude_error(false);
  const double predicted = earth_horizontal * r * r * kDt * kDt / 12.0 * steps * kDt;
  RecordProperty("error_with_coning_rad", shortest_number_text(with_coning));
  RecordProperty("error_without_coning_rad", shortest_number_text(without_coning));
  RecordProperty("without_coning_vs_prediction", shortest_number_text(without_coning / predicted));
  EXPECT_NEAR(without_coning, predicted, 0.1 * predicted);
  // What the two-sample term leaves is the next order, ∝ r³Δt³ (about north-east, 1 % here).
  EXPECT_LT(with_coning, 0.03 * predicted);
}

TEST(StrapdownNavigator, ScullingTermRemovesRockingImuVelocityError) {
  // An IMU rocking about its x axis at a fixed point, θ(t) = θ₀ sin(Ωt), C_bn(t) = C₀ R_x(θ):
  // ω_ib^b = θ̇ e_x + C_nb ω_ie^n, f^b = C_nb(−g^n), true velocity 0. Over one interval the exact
  // ∫θ×f dt exceeds ½Δθ×Δv by (Δt³/12)(ω×ḟ − ω̇×f) (expanding ω and f to first order in time);
  // with ḟ = −ω×f the first term is |ω|² f_⊥, averaging θ₀²Ω²/2 · f_⊥, while ω̇×f resolved in
  // n is ∝ sin Ωt and averages out. So without the sculling term the velocity error grows as
  // (Δt²/24) θ₀²Ω² g_⊥^n t, g_⊥^n the part of g^n normal to the rocking axis C₀e_x.
  const double lat = 45.0 * kDeg, amplitude = 0.1, rate = 2.0 * std::numbers::pi * 2.0;  // 2 Hz
  const Matrix3d C0 = attitude_from_euler(0.0, 10.0 * kDeg, 30.0 * kDeg);
  const Vector3d g_n = gravity_ned(lat, 0.0), w_ie = earth_rate_ned(lat);
  const auto C_bn = [&](double t) -> Matrix3d {
    return C0 * AngleAxisd(amplitude * std::sin(rate * t), Vector3d::UnitX());
  };
  // Increment = exact integral of the analytic rates by composite Simpson, 32 panels per sample
  // (relative error ~(Ω·Δt/32)⁴/180 ≈ 1e-13, far below what is checked).
  const auto exact_increment = [&](double t0) {
    ImuIncrement increment;
    increment.dt_s = kDt;
    constexpr int kPanels = 32;
    const double step = kDt / kPanels;
    for (int i = 0; i <= kPanels; ++i) {
      const double t = t0 + i * step;
      const double weight = (i == 0 || i == kPanels) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      const Matrix3d C_nb = C_bn(t).transpose();
      const Vector3d w_b = amplitude * rate * std::cos(rate * t) * Vector3d::UnitX() + C_nb * w_ie;
      increment.dtheta_b_rad += weight * step / 3.0 * w_b;
      increment.dv_b_m_per_s += weight * step / 3.0 * (C_nb * -g_n);
    }
    return increment;
  };
  const int steps = 1000;  // 10 s
  MechanizationOptions options;
  options.height_hold = false;  // the rectified error is mostly vertical; 10 s ≪ 570 s e-folding
  const auto velocity_error = [&](bool coning_sculling) {
    options.coning_sculling = coning_sculling;
    NavState initial = state_at_rest(lat, 0.0, C_bn(0.0));
    StrapdownNavigator navigator(initial, options);
    for (int k = 0; k < steps; ++k) navigator.update(exact_increment(k * kDt));
    return Vector3d(navigator.state().v_ned_m_per_s);
  };
  const Vector3d axis_n = C0 * Vector3d::UnitX();
  const Vector3d g_normal = g_n - g_n.dot(axis_n) * axis_n;
  const Vector3d predicted =
      kDt * kDt / 24.0 * amplitude * amplitude * rate * rate * (steps * kDt) * g_normal;
  const Vector3d without = velocity_error(false), with = velocity_error(true);
  RecordProperty("without_vs_prediction_rel",
                 shortest_number_text((without - predicted).norm() / predicted.norm()));
  RecordProperty("with_vs_prediction", shortest_number_text(with.norm() / predicted.norm()));
  EXPECT_LT((without - predicted).norm(), 0.02 * predicted.norm());  // ≈ 6e-4 m/s
  // What the two-sample term leaves is the next order, ∝ (ΩΔt)² relative (0.8 % here).
  EXPECT_LT(with.norm(), 0.03 * predicted.norm());
}

TEST(StrapdownNavigator, SlowDriftIsNotLostToRounding) {
  // A perfect IMU at rest with an initial north velocity of 10 nm/s: each 100 Hz step moves L by
  // 1.6e-17 rad, a third of an ulp of L = 45°. The position must still follow the Schuler
  // closed form v₀ sin(ω_s t)/ω_s (≈ v₀ t, 0.3 % less at 100 s) instead of staying at 0.
  const double lat = 45.0 * kDeg, v0 = 1e-8;
  const Matrix3d C_bn = Matrix3d::Identity();
  NavState initial = state_at_rest(lat, 0.0, C_bn);
  initial.v_ned_m_per_s.x() = v0;
  StrapdownNavigator navigator(initial, options_with(true));
  const ImuIncrement increment =
      stationary_increment(lat, 0.0, C_bn, Vector3d::Zero(), Vector3d::Zero());
  for (int k = 0; k < 10000; ++k) navigator.update(increment);
  const double t = 100.0, ws = std::sqrt(gravity_ned(lat, 0.0).z() / meridian_radius(lat));
  const double expected = v0 * std::sin(ws * t) / ws;
  const Eigen::Vector2d offset =
      horizontal_offset_m(navigator.state(), initial.latitude_rad, initial.longitude_rad);
  RecordProperty("north_rel", shortest_number_text(offset.x() / expected - 1.0));
  EXPECT_NEAR(offset.x(), expected, 0.01 * expected);
}

TEST(HorizontalOffset, MatchesEcefDifferenceProjectedOnLocalAxes) {
  // Independent truth: both points to ECEF (x = (R_E+h)cosL cosλ, y = (R_E+h)cosL sinλ,
  // z = (R_E(1−e²)+h)sinL) and the difference projected on the local north and east axes.
  const auto ecef = [](double lat, double lon, double h) {
    const double re = transverse_radius(lat);
    return Vector3d((re + h) * std::cos(lat) * std::cos(lon),
                    (re + h) * std::cos(lat) * std::sin(lon),
                    (re * (1.0 - wgs84::kEccentricitySquared) + h) * std::sin(lat));
  };
  const double lat0 = 45.0 * kDeg, h = 100.0;
  for (const double lon0 : {0.3, std::numbers::pi - 1e-6}) {  // the second crosses ±180°
    SCOPED_TRACE(lon0);
    NavState nav;
    nav.latitude_rad = lat0 + 1.5e-5;                                           // ≈ 96 m north
    nav.longitude_rad = std::remainder(lon0 + 2.0e-5, 2.0 * std::numbers::pi);  // ≈ 90 m east
    nav.height_m = h;
    const Vector3d d = ecef(nav.latitude_rad, nav.longitude_rad, h) - ecef(lat0, lon0, h);
    const double sl = std::sin(nav.latitude_rad), cl = std::cos(nav.latitude_rad);
    const double so = std::sin(nav.longitude_rad), co = std::cos(nav.longitude_rad);
    const Vector3d north(-sl * co, -sl * so, cl), east(-so, co, 0.0);
    const Eigen::Vector2d offset = horizontal_offset_m(nav, lat0, lon0);
    // Chord vs arc and the radii taken at one end differ by O(d²/R) ≈ 1.5e-3 m here.
    EXPECT_NEAR(offset.x(), d.dot(north), 3e-3);
    EXPECT_NEAR(offset.y(), d.dot(east), 3e-3);
    EXPECT_GT(offset.x(), 90.0);
    EXPECT_GT(offset.y(), 80.0);
  }
}

TEST(StrapdownNavigator, RejectsBadInputAndKeepsState) {
  NavState bad;
  bad.latitude_rad = std::numeric_limits<double>::quiet_NaN();
  test::expect_throw_containing<InputError>(
      [&] { StrapdownNavigator navigator(bad, MechanizationOptions{}); }, "latitude");
  StrapdownNavigator navigator(NavState{}, MechanizationOptions{});
  ImuIncrement increment;  // dt = 0
  test::expect_throw_containing<ContractViolation>([&] { navigator.update(increment); }, "dt");
  increment.dt_s = kDt;
  increment.dv_b_m_per_s.x() = std::numeric_limits<double>::infinity();
  test::expect_throw_containing<InputError>([&] { navigator.update(increment); }, "finite");
  EXPECT_EQ(navigator.state().v_ned_m_per_s, Vector3d::Zero());
  EXPECT_EQ(navigator.state().latitude_rad, 0.0);
}

}  // namespace
}  // namespace imunoise::ins
