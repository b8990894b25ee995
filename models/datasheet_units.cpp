/// @file
/// @brief Datasheet display units of the IEEE-952 terms (see datasheet_units.h).
#include "models/datasheet_units.h"

#include <cmath>

#include "common/units.h"

namespace imunoise::models {

DatasheetUnit datasheet_unit(NoiseTerm term, SensorKind kind) {
  if (kind == SensorKind::gyro) {
    switch (term) {
      case NoiseTerm::quantization:
        return {1.0 / units::kMicroradian, "urad", "µrad"};
      case NoiseTerm::white_noise:
        return {1.0 / units::kDegPerSqrtHour, "deg/sqrt(h)", "°/√h"};
      case NoiseTerm::bias_instability:
        return {1.0 / units::kDegPerHour, "deg/h", "°/h"};
      case NoiseTerm::random_walk:
        return {1.0 / units::kDegPerHourPerSqrtHour, "deg/h/sqrt(h)", "°/h/√h"};
      case NoiseTerm::ramp:
        return {1.0 / units::kDegPerHourSquared, "deg/h^2", "°/h²"};
    }
  }
  switch (term) {
    case NoiseTerm::quantization:
      return {1e3, "mm/s", "mm/s"};
    case NoiseTerm::white_noise:
      return {1.0 / units::kMicroGPerSqrtHz, "ug/sqrt(Hz)", "µg/√Hz"};
    case NoiseTerm::bias_instability:
      return {1.0 / units::kMicroG, "ug", "µg"};
    case NoiseTerm::random_walk:
      return {1.0 / units::kMPerSPerHourPerSqrtHour, "m/s/h/sqrt(h)", "m/s/h/√h"};
    case NoiseTerm::ramp:
      return {units::kHour / units::kMicroG, "ug/h", "µg/h"};
  }
  return {};
}

}  // namespace imunoise::models
