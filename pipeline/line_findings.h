/// @file
/// @brief The data-quality findings of the spectral lines of an analysed axis, one line each,
/// as model.yaml's data_quality list and the summary print them ("gyro_x: spectral line at
/// 0.57 Hz (amplitude …)", with its cause and remedy).
#pragma once

#include <string>
#include <vector>

#include "models/noise_model.h"

namespace imunoise::pipeline {

/// One finding per sinusoid of AXIS (frequency, amplitude and its interval at CONFIDENCE).
std::vector<std::string> spectral_line_findings(const models::AxisModel& axis, double confidence);

}  // namespace imunoise::pipeline
