/// @file
/// @brief The units datasheets quote the five IEEE-952 coefficients in (deg/√h, deg/h, µg/√Hz,
/// …), for display only: the models stay in SI (theory.md §1.3), and a value is converted at the
/// edge as SI value × factor.
#pragma once

#include <string_view>

#include "models/noise_model.h"

namespace imunoise::models {

/// A display unit of one term: SI value × factor = value in this unit.
struct DatasheetUnit {
  double factor = 1.0;
  std::string_view ascii;    ///< plain-ASCII name for terminals, e.g. "deg/sqrt(h)"
  std::string_view unicode;  ///< the name as printed on datasheets, e.g. "°/√h"
};

/// Gyro: Q µrad, N deg/√h, B deg/h, K deg/h/√h, R deg/h². Accelerometer: Q mm/s, N µg/√Hz,
/// B µg, K m/s/h/√h, R µg/h.
DatasheetUnit datasheet_unit(NoiseTerm term, SensorKind kind);

}  // namespace imunoise::models
