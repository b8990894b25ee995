/// @file
/// @brief Tests of ins/earth_model.h against the WGS84 figures of theory.md §7.1, the
/// closed-form radii at the equator and pole, the free-air gradient, finite differences of
/// the model itself, and the frame rates composed from their geometric definition.
#include "ins/earth_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "common/errors.h"
#include "common/units.h"
#include "test_support.h"

namespace imunoise::ins {
namespace {

using units::kDeg;
using namespace wgs84;

TEST(EarthModel, Wgs84DerivedConstantsMatchTheory71) {
  EXPECT_NEAR(kEccentricitySquared, 6.69437999014e-3, 1e-14);  // printed in §7.1
  EXPECT_NEAR(kSemiMinorAxis, 6356752.3142, 1e-4);             // WGS84 b
}

TEST(EarthModel, SurfaceGravityAt45DegIs9_80620) {
  EXPECT_NEAR(surface_gravity(45.0 * kDeg), 9.80620, 5e-6);  // §7.1 (V), 5 decimals
  EXPECT_DOUBLE_EQ(gravity_ned(45.0 * kDeg, 0.0).z(), surface_gravity(45.0 * kDeg));
}

TEST(EarthModel, RadiiAtEquatorAndPoleMatchClosedForms) {
  const double a = kSemiMajorAxis, e2 = kEccentricitySquared;
  EXPECT_NEAR(meridian_radius(0.0), a * (1.0 - e2), 1e-6);
  EXPECT_NEAR(transverse_radius(0.0), a, 1e-6);
  const double polar = a / std::sqrt(1.0 - e2);  // both radii equal a²/b at the pole
  EXPECT_NEAR(meridian_radius(std::numbers::pi / 2.0), polar, 1e-6);
  EXPECT_NEAR(transverse_radius(-std::numbers::pi / 2.0), polar, 1e-6);
  EXPECT_NEAR(polar, a * a / kSemiMinorAxis, 1e-6);
}

TEST(EarthModel, GravityAtPoleAndEquatorMatchesSomigliana) {
  const Eigen::Vector3d equator = gravity_ned(0.0, 0.0);
  const Eigen::Vector3d pole = gravity_ned(std::numbers::pi / 2.0, 0.0);
  EXPECT_NEAR(equator.z(), kEquatorialGravity, 1e-12);
  EXPECT_NEAR(pole.z(),
              kEquatorialGravity * (1.0 + kSomiglianaK) / std::sqrt(1.0 - kEccentricitySquared),
              1e-12);
  EXPECT_NEAR(pole.z(), 9.8321849378, 1e-9);  // WGS84 normal gravity at the pole (NIMA TR8350.2)
  EXPECT_EQ(equator.x(), 0.0);
  EXPECT_EQ(equator.y(), 0.0);
  EXPECT_EQ(pole.y(), 0.0);
}

TEST(EarthModel, HeightTermsGiveTheFreeAirGradient) {
  // Free-air gradient ≈ 0.3086 mGal/m = 3.086e-6 s⁻² (geodesy textbooks); the −8.08e-9·h·sin2L
  // north term is §7.1's own.
  const double lat = 45.0 * kDeg, h = 1000.0;
  const Eigen::Vector3d g0 = gravity_ned(lat, 0.0), g = gravity_ned(lat, h);
  EXPECT_NEAR((g0.z() - g.z()) / h, 3.086e-6, 0.005e-6);
  EXPECT_NEAR(g.x(), -8.08e-9 * h, 1e-15);
  EXPECT_EQ(g.y(), 0.0);
}

TEST(EarthModel, DerivativesMatchFiniteDifferences) {
  for (const double lat_deg : {-70.0, -10.0, 0.0, 33.0, 45.0, 80.0}) {
    const double lat = lat_deg * kDeg;
    for (const double h : {0.0, 2500.0, -300.0}) {
      const double dl = 1e-5, dh = 1.0;
      const GravityGradient grad = gravity_ned_gradient(lat, h);
      const Eigen::Vector3d fd_lat =
          (gravity_ned(lat + dl, h) - gravity_ned(lat - dl, h)) / (2.0 * dl);
      const Eigen::Vector3d fd_h =
          (gravity_ned(lat, h + dh) - gravity_ned(lat, h - dh)) / (2.0 * dh);
      EXPECT_LT((grad.d_latitude - fd_lat).norm(), 1e-9) << lat_deg << " deg, " << h << " m";
      EXPECT_LT((grad.d_height - fd_h).norm(), 1e-13) << lat_deg << " deg, " << h << " m";
    }
    const double dl = 1e-5;
    EXPECT_NEAR(meridian_radius_d_latitude(lat),
                (meridian_radius(lat + dl) - meridian_radius(lat - dl)) / (2.0 * dl), 1e-3);
    EXPECT_NEAR(transverse_radius_d_latitude(lat),
                (transverse_radius(lat + dl) - transverse_radius(lat - dl)) / (2.0 * dl), 1e-3);
  }
}

TEST(EarthModel, EarthRateIsThePolarAxisInNed) {
  const double lat = 30.0 * kDeg;
  const Eigen::Vector3d w = earth_rate_ned(lat);
  EXPECT_NEAR(w.norm(), kEarthRate, 1e-20);
  EXPECT_NEAR(w.x(), kEarthRate * std::sqrt(3.0) / 2.0, 1e-18);  // cos 30°
  EXPECT_EQ(w.y(), 0.0);
  EXPECT_NEAR(w.z(), -kEarthRate * 0.5, 1e-18);  // up component of the north-pointing axis
}

TEST(EarthModel, TransportRateIsLatitudeAndLongitudeRateRotations) {
  // Independent composition: NED turns at λ̇ about the polar axis (in NED: [cosL, 0, −sinL])
  // and at L̇ about −east, with L̇ = v_N/(R_N+h), λ̇ = v_E/((R_E+h)cosL) (theory.md §7.2).
  const double lat = -37.0 * kDeg, h = 850.0;
  const Eigen::Vector3d v(41.0, -17.0, 3.0);
  const double lat_rate = v.x() / (meridian_radius(lat) + h);
  const double lon_rate = v.y() / ((transverse_radius(lat) + h) * std::cos(lat));
  const Eigen::Vector3d expected = lon_rate * Eigen::Vector3d(std::cos(lat), 0.0, -std::sin(lat)) +
                                   lat_rate * Eigen::Vector3d(0.0, -1.0, 0.0);
  EXPECT_LT((transport_rate_ned(lat, h, v) - expected).norm(), 1e-20);
  EXPECT_EQ(transport_rate_ned(lat, h, Eigen::Vector3d::Zero()).norm(), 0.0);
}

TEST(EarthModel, RejectsLatitudeOutOfRange) {
  test::expect_throw_containing<InputError>([] { meridian_radius(2.0); },
                                            "meridian_radius: latitude");
  test::expect_throw_containing<InputError>(
      [] { gravity_ned(std::numeric_limits<double>::quiet_NaN(), 0.0); }, "gravity_ned: latitude");
  test::expect_throw_containing<InputError>(
      [] { gravity_ned(0.1, std::numeric_limits<double>::infinity()); }, "gravity_ned: height");
  test::expect_throw_containing<InputError>(
      [] { transport_rate_ned(std::numbers::pi / 2.0, 0.0, Eigen::Vector3d::Zero()); },
      "strictly within");
  test::expect_throw_containing<InputError>(
      [] { transport_rate_ned(0.1, -7e6, Eigen::Vector3d::Zero()); }, "centre of curvature");
  test::expect_throw_containing<InputError>(
      [] {
        transport_rate_ned(0.1, 0.0,
                           Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0));
      },
      "velocity must be finite");
}

}  // namespace
}  // namespace imunoise::ins
