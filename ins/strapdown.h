/// @file
/// @brief Strapdown NED mechanization from IMU increments (theory.md §7.2; Groves 2013 ch. 5,
/// Titterton & Weston 2004 ch. 11, Savage's velocity split), used to mechanize simulated or
/// recorded stationary data and measure the horizontal drift of theory.md §7.7.
///
/// Conventions: q_bn rotates body (FRD) vectors into NED (x^n = q_bn x^b, Hamilton); the
/// increments are the integrals of ω_ib^b and f_ib^b over one sample interval; SI throughout.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace imunoise::ins {

/// Geodetic position, NED velocity and attitude of the body.
struct NavState {
  double latitude_rad = 0.0;                                 ///< L, geodetic [rad]
  double longitude_rad = 0.0;                                ///< λ [rad]
  double height_m = 0.0;                                     ///< h above the ellipsoid [m]
  Eigen::Vector3d v_ned_m_per_s = Eigen::Vector3d::Zero();   ///< v_eb^n [m/s]
  Eigen::Quaterniond q_bn = Eigen::Quaterniond::Identity();  ///< body (FRD) → NED
};

/// One IMU sample as increments over its interval (what most IMUs output internally).
struct ImuIncrement {
  Eigen::Vector3d dtheta_b_rad = Eigen::Vector3d::Zero();  ///< Δθ = ∫ω_ib^b dt [rad]
  Eigen::Vector3d dv_b_m_per_s = Eigen::Vector3d::Zero();  ///< Δv = ∫f_ib^b dt [m/s]
  double dt_s = 0.0;                                       ///< interval length [s] > 0
};

struct MechanizationOptions {
  /// Keep h at its initial value and v_D = 0 after every step: the stationary-analysis
  /// convention of theory.md §7.2 (the free vertical channel diverges, e-folding ≈ 570 s).
  bool height_hold = true;
  /// Add the two-sample corrections that use the previous increment: coning
  /// (1/12)Δθ_{k−1}×Δθ_k and sculling (1/12)(Δθ_{k−1}×Δv_k + Δv_{k−1}×Δθ_k). Both vanish
  /// at rest; the rotation compensation ½Δθ×Δv + (1/6)Δθ×(Δθ×Δv) is always applied.
  bool coning_sculling = true;
};

/// NED strapdown navigator, one update per IMU sample; update() does not allocate.
///
/// Each update, with ω_ie^n, ω_en^n, g^n evaluated at the state before the step, runs the
/// explicit order velocity → position → attitude (theory.md §7.2):
/// - velocity: Δv^n = C̄(Δv + ½Δθ×Δv + (1/6)Δθ×(Δθ×Δv) [+ sculling])
///   + (g^n − (2ω_ie^n + ω_en^n)×v^n)Δt, with C̄ = q(−½ω_in^nΔt) ⊗ q_bn: the body at the start
///   of the interval seen from the mid-interval n-frame. The Δθ terms carry the body's rotation
///   during the interval (Groves's C̄ of §7.2 to second order in |Δθ|; the
///   n-frame/body split follows Savage 1998, JGCD 21(2), equation number unchecked). At rest the
///   n-frame and body rotations cancel to first order; the remainder is ~1e-14 m/s² at 100 Hz;
/// - position: trapezoid of the old and new velocity, L̇ = v_N/(R_N+h),
///   λ̇ = v_E/((R_E+h)cos L) with cos of the mid-interval latitude, ḣ = −v_D, summed with
///   Kahan compensation so that sub-ulp steps of a slow drift are not lost;
/// - attitude: q_bn ← q(−ω_in^nΔt) ⊗ q_bn ⊗ q(α), α = Δθ_k [+ (1/12)Δθ_{k−1}×Δθ_k],
///   renormalized.
class StrapdownNavigator {
 public:
  /// @param[in] initial  starting state; q_bn is normalized here
  /// @throws InputError when a field is not finite, |L| ≥ π/2 or q_bn has zero norm.
  StrapdownNavigator(const NavState& initial, const MechanizationOptions& options);

  /// Advances the state by one IMU sample.
  /// @throws InputError when an increment is not finite, ContractViolation when dt ≤ 0 or not
  ///   finite; the state is then unchanged.
  void update(const ImuIncrement& increment);

  const NavState& state() const { return state_; }

 private:
  NavState state_;
  MechanizationOptions options_;
  double initial_height_m_;
  Eigen::Vector3d previous_dtheta_b_rad_ = Eigen::Vector3d::Zero();  ///< zero before sample 1
  Eigen::Vector3d previous_dv_b_m_per_s_ = Eigen::Vector3d::Zero();
  /// Low-order parts of L, λ, h lost to rounding (compensated summation, see strapdown.cpp).
  double latitude_carry_ = 0.0, longitude_carry_ = 0.0, height_carry_ = 0.0;
};

/// Rectangular increments from constant rates over one interval: Δθ = ω·dt, Δv = f·dt.
ImuIncrement increment_from_rates(const Eigen::Vector3d& w_ib_b_rad_per_s,
                                  const Eigen::Vector3d& f_ib_b_m_per_s2, double dt_s);

/// Horizontal position of NAV relative to (L₀, λ₀) [m] as [north, east], using the local radii
/// at NAV: δr_N = (R_N+h)(L − L₀), δr_E = (R_E+h)cos L (λ − λ₀) (theory.md §7.6).
Eigen::Vector2d horizontal_offset_m(const NavState& nav, double latitude0_rad,
                                    double longitude0_rad);

}  // namespace imunoise::ins
