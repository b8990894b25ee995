/// @file
/// @brief The fitted model against the sensor's datasheet (the spec of `imunoise fleet --spec`,
/// given to `analyze --spec`): what the data alone cannot show. An output decimated without
/// averaging leaves no trace in its own samples — white noise kept every d-th sample is white
/// noise of √d·N, a random walk stays a random walk (docs/validation.md, "Decimation without
/// averaging") — but its white noise then stands √d above the density the datasheet states for
/// the sensor's internal rate (the Kalibr wiki's warning, theory.md §1.4).
#pragma once

#include <numbers>
#include <string>
#include <vector>

#include "models/noise_model.h"
#include "pipeline/fleet.h"

namespace imunoise::pipeline {

/// The white-noise ratio to the datasheet above which an axis gets the decimation finding:
/// √2, the smallest decimation without averaging (by 2). An axis within its datasheet's
/// tolerance (typical values, unit-to-unit spread of 10–30 %) stays well below it.
inline constexpr double kDecimationWhiteNoiseRatio = std::numbers::sqrt2;

/// The findings of MODEL against SPEC, one line each (data_quality): the axes whose white noise
/// N, by the lower end of its interval, is at least kDecimationWhiteNoiseRatio × the spec's N
/// for that sensor, with the ratio, the implied decimation factor (ratio²), the cause and the
/// remedy. Axes of a sensor the spec has no N for, and axes whose N is not identified, are not
/// judged. Empty when no axis qualifies.
std::vector<std::string> datasheet_findings(const models::NoiseModel& model, const FleetSpec& spec);

}  // namespace imunoise::pipeline
