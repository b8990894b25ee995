/// @file
/// @brief The one definition of what a time-stamp gap is and how many samples it lacks, shared by
/// the sampling report (io) and the gap policy (pipeline), so that both count the same and both
/// stay defined on absurd stamps.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

namespace imunoise {

/// An interval longer than kGapFactor × the median (nominal) interval is a time-stamp gap: the
/// one criterion of the sampling report, the gap policy, the live node and every text that
/// states it.
inline constexpr double kGapFactor = 1.5;

/// Samples an interval of INTERVAL_S lacks at the nominal period PERIOD_S: round(interval /
/// period) − 1, at least 0. Saturates at INT64_MAX: with absurd stamps the ratio can be beyond
/// the int64 range or infinite, where std::llround has no defined result.
inline std::int64_t missing_samples_in_gap(double interval_s, double period_s) {
  const double missing = std::round(interval_s / period_s) - 1.0;
  if (!(missing > 0.0)) return 0;
  if (missing >= 0x1p63) return std::numeric_limits<std::int64_t>::max();
  return static_cast<std::int64_t>(missing);
}

}  // namespace imunoise
