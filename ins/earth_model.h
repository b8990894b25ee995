/// @file
/// @brief WGS84 earth model in the local NED frame (theory.md §7.1, Groves 2013 ch. 2):
/// radii of curvature, Somigliana gravity with its height terms, Earth rate and transport
/// rate. Latitude L is geodetic [rad], height h is above the ellipsoid [m], SI throughout.
#pragma once

#include <Eigen/Dense>

namespace imunoise::ins {

/// @name WGS84 constants (theory.md §7.1)
/// γ_e and k are the "revised" WGS84 values theory.md §9 item 5 pins for regression tests
/// (not the older 9.7803267714 / 0.00193185138639, nor Groves's truncated k = 0.001931853).
/// @{
namespace wgs84 {
inline constexpr double kSemiMajorAxis = 6378137.0;         ///< a [m]
inline constexpr double kFlattening = 1.0 / 298.257223563;  ///< f [-]
inline constexpr double kEccentricitySquared =              ///< e² = f(2 − f) [-]
    kFlattening * (2.0 - kFlattening);                      //   = 6.69437999014e-3
inline constexpr double kSemiMinorAxis = kSemiMajorAxis * (1.0 - kFlattening);  ///< b [m]
inline constexpr double kEarthRate = 7.292115e-5;                               ///< Ω_ie [rad/s]
inline constexpr double kGravitationalConstant = 3.986004418e14;  ///< μ = GM [m³/s²]
inline constexpr double kEquatorialGravity = 9.7803253359;        ///< γ_e [m/s²]
inline constexpr double kSomiglianaK = 0.00193185265241;          ///< k [-]
}  // namespace wgs84
/// @}

/// @name Radii of curvature; |L| ≤ π/2
/// @{

/// Meridian radius R_N = a(1 − e²)/(1 − e² sin²L)^{3/2} [m].
/// @throws InputError when L is not finite or |L| > π/2 (likewise for every function below).
double meridian_radius(double latitude_rad);
/// Transverse (prime-vertical) radius R_E = a/√(1 − e² sin²L) [m].
double transverse_radius(double latitude_rad);
/// dR_N/dL = 3 R_N e² sinL cosL/(1 − e² sin²L) [m/rad] (differentiating the formula above).
double meridian_radius_d_latitude(double latitude_rad);
/// dR_E/dL = R_E e² sinL cosL/(1 − e² sin²L) [m/rad].
double transverse_radius_d_latitude(double latitude_rad);

/// @}

/// @name Gravity (plumb-bob: gravitation plus centrifugal), NED [m/s²]
/// @{

/// Somigliana surface gravity g₀(L) = γ_e(1 + k sin²L)/√(1 − e² sin²L); g₀(45°) = 9.80620.
double surface_gravity(double latitude_rad);

/// g^n = [g_N, 0, g_D] with g_D = g₀(L)[1 − (2/a)(1 + f(1 − 2sin²L) + Ω_ie²a²b/μ)h + 3h²/a²]
/// and g_N = −8.08e-9·h·sin 2L (theory.md §7.1, as Groves's Gravity_NED.m).
/// @throws InputError also when h is not finite.
Eigen::Vector3d gravity_ned(double latitude_rad, double height_m);

/// Partial derivatives of gravity_ned() (the exact derivatives of the formulas above).
struct GravityGradient {
  Eigen::Vector3d d_latitude;  ///< ∂g^n/∂L [m/s²/rad]
  Eigen::Vector3d d_height;    ///< ∂g^n/∂h [1/s²]; down: ≈ −2g/a (free air, −3.086e-6)
};
GravityGradient gravity_ned_gradient(double latitude_rad, double height_m);

/// @}

/// @name Frame rates, NED [rad/s] (theory.md §7.1)
/// @{

/// ω_ie^n = Ω_ie [cos L, 0, −sin L]: Earth rate resolved in NED.
Eigen::Vector3d earth_rate_ned(double latitude_rad);

/// ω_en^n = [v_E/(R_E+h), −v_N/(R_N+h), −v_E tan L/(R_E+h)]: rotation of NED w.r.t. the
/// Earth when moving at V_NED [m/s] over the ellipsoid.
/// @throws InputError when |L| ≥ π/2 (tan L), h or v not finite, or R_N + h ≤ 0.
Eigen::Vector3d transport_rate_ned(double latitude_rad, double height_m,
                                   const Eigen::Vector3d& v_ned_m_per_s);

/// @}

}  // namespace imunoise::ins
