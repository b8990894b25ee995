/// @file
/// @brief WGS84 earth model (see earth_model.h, theory.md §7.1).
#include "ins/earth_model.h"

#include <cmath>
#include <numbers>
#include <string>

#include "common/errors.h"

namespace imunoise::ins {
namespace {

using namespace wgs84;

void check_latitude(double latitude_rad, const char* where) {
  IMUNOISE_CHECK(std::isfinite(latitude_rad) && std::abs(latitude_rad) <= std::numbers::pi / 2.0,
                 InputError,
                 std::string(where) + ": latitude must be finite and within ±pi/2 rad (got " +
                     std::to_string(latitude_rad) + ")");
}

void check_height(double height_m, const char* where) {
  IMUNOISE_CHECK(
      std::isfinite(height_m), InputError,
      std::string(where) + ": height must be finite (got " + std::to_string(height_m) + ")");
}

/// 1 − e² sin²L, the denominator every radius and g₀ share.
double one_minus_e2_sin2(double latitude_rad) {
  const double s = std::sin(latitude_rad);
  return 1.0 - kEccentricitySquared * s * s;
}

}  // namespace

double meridian_radius(double latitude_rad) {
  check_latitude(latitude_rad, "meridian_radius");
  const double d = one_minus_e2_sin2(latitude_rad);
  return kSemiMajorAxis * (1.0 - kEccentricitySquared) / (d * std::sqrt(d));
}

double transverse_radius(double latitude_rad) {
  check_latitude(latitude_rad, "transverse_radius");
  return kSemiMajorAxis / std::sqrt(one_minus_e2_sin2(latitude_rad));
}

double meridian_radius_d_latitude(double latitude_rad) {
  check_latitude(latitude_rad, "meridian_radius_d_latitude");
  const double sc = std::sin(latitude_rad) * std::cos(latitude_rad);
  return 3.0 * meridian_radius(latitude_rad) * kEccentricitySquared * sc /
         one_minus_e2_sin2(latitude_rad);
}

double transverse_radius_d_latitude(double latitude_rad) {
  check_latitude(latitude_rad, "transverse_radius_d_latitude");
  const double sc = std::sin(latitude_rad) * std::cos(latitude_rad);
  return transverse_radius(latitude_rad) * kEccentricitySquared * sc /
         one_minus_e2_sin2(latitude_rad);
}

double surface_gravity(double latitude_rad) {
  check_latitude(latitude_rad, "surface_gravity");
  const double s = std::sin(latitude_rad);
  return kEquatorialGravity * (1.0 + kSomiglianaK * s * s) /
         std::sqrt(one_minus_e2_sin2(latitude_rad));
}

namespace {

/// m = Ω_ie²a²b/μ, the centrifugal-to-gravitational ratio in the free-air term (§7.1).
constexpr double kCentrifugalRatio = kEarthRate * kEarthRate * kSemiMajorAxis * kSemiMajorAxis *
                                     kSemiMinorAxis / kGravitationalConstant;

/// Height factor of g_D: 1 − (2/a)(1 + f(1 − 2sin²L) + m)h + 3h²/a².
double height_factor(double sin2_lat, double height_m) {
  return 1.0 -
         (2.0 / kSemiMajorAxis) * (1.0 + kFlattening * (1.0 - 2.0 * sin2_lat) + kCentrifugalRatio) *
             height_m +
         3.0 * height_m * height_m / (kSemiMajorAxis * kSemiMajorAxis);
}

/// North gravity coefficient of Groves's Gravity_NED.m: g_N = −8.08e-9·h·sin 2L [1/s²].
constexpr double kNorthGravityPerMetre = -8.08e-9;

}  // namespace

Eigen::Vector3d gravity_ned(double latitude_rad, double height_m) {
  check_latitude(latitude_rad, "gravity_ned");
  check_height(height_m, "gravity_ned");
  const double s = std::sin(latitude_rad);
  return {kNorthGravityPerMetre * height_m * std::sin(2.0 * latitude_rad), 0.0,
          surface_gravity(latitude_rad) * height_factor(s * s, height_m)};
}

GravityGradient gravity_ned_gradient(double latitude_rad, double height_m) {
  check_latitude(latitude_rad, "gravity_ned_gradient");
  check_height(height_m, "gravity_ned_gradient");
  const double s = std::sin(latitude_rad), c = std::cos(latitude_rad);
  const double d = one_minus_e2_sin2(latitude_rad);
  const double g0 = surface_gravity(latitude_rad);
  // dg₀/dL = γ_e sinL cosL [2k(1 − e²sin²L) + e²(1 + k sin²L)]/(1 − e² sin²L)^{3/2}
  const double dg0_dlat =
      kEquatorialGravity * s * c *
      (2.0 * kSomiglianaK * d + kEccentricitySquared * (1.0 + kSomiglianaK * s * s)) /
      (d * std::sqrt(d));
  // ∂(height factor)/∂L: only f(1 − 2sin²L) depends on L → (2/a)·f·4 sinL cosL·h.
  const double dfactor_dlat = 8.0 * kFlattening * s * c * height_m / kSemiMajorAxis;
  const double dfactor_dh =
      -(2.0 / kSemiMajorAxis) * (1.0 + kFlattening * (1.0 - 2.0 * s * s) + kCentrifugalRatio) +
      6.0 * height_m / (kSemiMajorAxis * kSemiMajorAxis);
  GravityGradient gradient;
  gradient.d_latitude = {2.0 * kNorthGravityPerMetre * height_m * std::cos(2.0 * latitude_rad), 0.0,
                         dg0_dlat * height_factor(s * s, height_m) + g0 * dfactor_dlat};
  gradient.d_height = {kNorthGravityPerMetre * std::sin(2.0 * latitude_rad), 0.0, g0 * dfactor_dh};
  return gradient;
}

Eigen::Vector3d earth_rate_ned(double latitude_rad) {
  check_latitude(latitude_rad, "earth_rate_ned");
  return {kEarthRate * std::cos(latitude_rad), 0.0, -kEarthRate * std::sin(latitude_rad)};
}

Eigen::Vector3d transport_rate_ned(double latitude_rad, double height_m,
                                   const Eigen::Vector3d& v_ned_m_per_s) {
  IMUNOISE_CHECK(std::isfinite(latitude_rad) && std::abs(latitude_rad) < std::numbers::pi / 2.0,
                 InputError,
                 "transport_rate_ned: latitude must be finite and strictly within ±pi/2 rad, "
                 "where longitude is defined (got " +
                     std::to_string(latitude_rad) + ")");
  check_height(height_m, "transport_rate_ned");
  IMUNOISE_CHECK(v_ned_m_per_s.allFinite(), InputError,
                 "transport_rate_ned: velocity must be finite");
  const double rn_h = meridian_radius(latitude_rad) + height_m;
  const double re_h = transverse_radius(latitude_rad) + height_m;
  IMUNOISE_CHECK(rn_h > 0.0, InputError,
                 "transport_rate_ned: height must be above the centre of curvature (got " +
                     std::to_string(height_m) + " m)");
  return {v_ned_m_per_s.y() / re_h, -v_ned_m_per_s.x() / rn_h,
          -v_ned_m_per_s.y() * std::tan(latitude_rad) / re_h};
}

}  // namespace imunoise::ins
