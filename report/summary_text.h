/// @file
/// @brief The summary `imunoise analyze` prints on the terminal: per sensor and term the fitted
/// coefficient of each axis in datasheet units with its interval and the IEEE-952 read-off, the
/// simulator's true value when given, then the failed PSD cross-checks and the data-quality
/// findings. Pure: a model in, text out.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "common/noise_coefficients.h"
#include "models/noise_model.h"

namespace imunoise::report {

/// The summary of MODEL. TRUTH, when given, holds the true coefficients of gyro_x … accel_z
/// (pipeline::kImuChannelNames order): each axis of that name shows its true value and whether
/// it lies inside the interval. Every line ends with '\n'.
std::string summary_text(const models::NoiseModel& model,
                         const std::optional<std::array<NoiseCoefficients, 6>>& truth);

}  // namespace imunoise::report
