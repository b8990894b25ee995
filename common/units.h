/// @file
/// @brief The one place where human units meet SI. Everything inside imunoise is SI
/// (rad, rad/s, m/s, m/s², s); multiply a value in the named unit by the factor to get SI.
/// Factors and their derivation: ../shared/docs/theory.md §1.3.
#pragma once

#include <numbers>

namespace imunoise::units {

inline constexpr double kPi = std::numbers::pi;

/// Standard gravity g₀ [m/s²] — the definition of the unit "g", never local gravity.
inline constexpr double kStandardGravity = 9.80665;

/// @name Angle and angular rate → rad, rad/s
/// @{
inline constexpr double kDeg = kPi / 180.0;             ///< deg → rad
inline constexpr double kDegPerS = kDeg;                ///< deg/s → rad/s
inline constexpr double kDegPerHour = kDeg / 3600.0;    ///< deg/h → rad/s (4.848137e-6)
inline constexpr double kDegPerSqrtHour = kDeg / 60.0;  ///< deg/√h → rad/√s (2.908882e-4)
inline constexpr double kDegPerHourPerSqrtHour =
    kDeg / (3600.0 * 60.0);  ///< deg/h/√h → rad/s^{3/2}
/// @}

/// @name Specific force → m/s²
/// @{
inline constexpr double kG = kStandardGravity;              ///< g → m/s²
inline constexpr double kMilliG = 1e-3 * kStandardGravity;  ///< mg → m/s²
inline constexpr double kMicroG = 1e-6 * kStandardGravity;  ///< µg → m/s²
/// @}

/// @name Time → s
/// @{
inline constexpr double kMillisecond = 1e-3;
inline constexpr double kMicrosecond = 1e-6;
inline constexpr double kNanosecond = 1e-9;
inline constexpr double kHour = 3600.0;
/// @}

}  // namespace imunoise::units
