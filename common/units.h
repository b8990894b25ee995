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

/// @name Noise coefficients → SI (theory.md §1.3); 1 h = 3600 s, so √h = 60 √s
/// Densities are two-sided (theory.md §1.2): a value "per √Hz" is N with S_Ω = N², the
/// convention of Kalibr's σ_g, not a one-sided ASD (that would be √2·N).
/// @{
inline constexpr double kMicroradian = 1e-6;  ///< µrad → rad (angle quantization Q)
/// (deg/s)/√Hz → rad/√s: (π/180 rad/s)·√s = π/180 rad/√s (1.745329e-2)
inline constexpr double kDegPerSPerSqrtHz = kDeg;
/// deg/s/√s → rad/s^{3/2} (RRW K; how theory.md §8.1 reads the ITG-3200 "deg/s²")
inline constexpr double kDegPerSPerSqrtS = kDeg;
/// deg/h² → rad/s² (ramp R): (π/180)/3600² = 1.346705e-9
inline constexpr double kDegPerHourSquared = kDeg / (3600.0 * 3600.0);
/// (deg/s)/h → rad/s² (ramp R as a rate change per hour): (π/180)/3600 = 4.848137e-6
inline constexpr double kDegPerSPerHour = kDeg / 3600.0;
/// m/s/√h → m/s/√s (VRW N): 1/60
inline constexpr double kMPerSPerSqrtHour = 1.0 / 60.0;
/// µg/√Hz → (m/s²)/√Hz = m/s/√s (VRW N, two-sided density): 9.80665e-6
inline constexpr double kMicroGPerSqrtHz = kMicroG;
/// (m/s/h)/√h → m/s^{5/2} (accel RW K): 1/(3600·60) = 4.62963e-6
inline constexpr double kMPerSPerHourPerSqrtHour = 1.0 / (3600.0 * 60.0);
/// µg/√s → m/s^{5/2} (accel RW K): 9.80665e-6
inline constexpr double kMicroGPerSqrtS = kMicroG;
/// (m/s²)/h → m/s³ (accel ramp R): 1/3600
inline constexpr double kMPerS2PerHour = 1.0 / 3600.0;
/// @}

/// @name Time → s
/// @{
inline constexpr double kMillisecond = 1e-3;
inline constexpr double kMicrosecond = 1e-6;
inline constexpr double kNanosecond = 1e-9;
inline constexpr double kHour = 3600.0;
/// @}

}  // namespace imunoise::units
