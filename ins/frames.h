/// @file
/// @brief The frames and rotation conventions of ins/ (docs/conventions.md "Frames", theory.md
/// §7.1–7.4), written once, and the small rotation helpers every ins module shares.
///
/// - Navigation frame n: local NED (north, east, down); body frame b: FRD (forward, right,
///   down). Earth frame e, inertial frame i.
/// - `C_bn` (matrix) and `q_bn` (Hamilton quaternion, Eigen's) map body vectors into NED:
///   x^n = C_bn·x^b (Groves C_b^n; gtsam `nRb`, KF-GINS `cbn`; style.md's `R_nb`). The inverse
///   is `C_nb = C_bnᵀ`.
/// - Vector names give the motion and the frame resolved in: `w_ib_b` is the rate of b with
///   respect to i resolved in b, `v_eb_n`, `f_ib_b` the specific force, `g_n` gravity.
/// - Euler angles are ZYX: C_bn = R_z(yaw)·R_y(pitch)·R_x(roll).
/// - Gravity is the plumb-bob value, positive down: g^n = [g_N, 0, g_D] with g_D ≈ +9.81 m/s²;
///   at rest f_ib^b = C_nb·(−g^n), so a level accelerometer's z axis reads ≈ −9.81 m/s².
/// - Errors are estimate − truth; the attitude error is the phi angle δψ with
///   Ĉ_bn = (I + [δψ×])·C_bn (theory.md §7.4).
#pragma once

#include <Eigen/Core>

namespace imunoise::ins {

/// [a×], the matrix of the cross product: skew(a)·b = a × b.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

}  // namespace imunoise::ins
