/// @file
/// @brief The summary `imunoise analyze` prints on the terminal: the recording's facts, the
/// verdict (report/verdict.h: per sensor the term × axis matrix in datasheet units with
/// intervals, what was identified, every finding — data quality, failed PSD cross-checks, fit
/// notes — with its cause and remedy, and which export suits which filter), then the details:
/// per sensor and term the fitted coefficient of each axis with its interval and the IEEE-952
/// read-off, and the simulator's true value when given. Pure: a model in, text out.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "common/noise_coefficients.h"
#include "models/noise_model.h"

namespace imunoise::report {

/// The summary of MODEL. TRUTH, when given, holds the true coefficients of gyro_x … accel_z
/// (pipeline::kImuChannelNames order): each axis of that name shows its true value and whether
/// it lies inside the interval. MODEL_PATH is how the verdict's commands name model.yaml. Every
/// line ends with '\n'.
std::string summary_text(const models::NoiseModel& model,
                         const std::optional<std::array<NoiseCoefficients, 6>>& truth,
                         std::string_view model_path = "model.yaml");

}  // namespace imunoise::report
