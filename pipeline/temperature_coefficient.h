/// @file
/// @brief The bias-vs-temperature coefficient of a channel from a temperature column recorded
/// with it, and its removal. Pure computation.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace imunoise::pipeline {

/// Least squares of a channel's block means on the temperature's block means.
struct TemperatureCoefficient {
  bool fitted = false;            ///< false: too few samples or a constant temperature
  double coefficient = 0.0;       ///< d(bias)/dT [channel unit / °C]
  double correlation = 0.0;       ///< correlation of the block means (−1 … 1)
  double temperature_low = 0.0;   ///< lowest block-mean temperature [°C]
  double temperature_high = 0.0;  ///< highest block-mean temperature [°C]
};

/// Blocks the channel and the temperature are averaged over before the regression: the white
/// noise of a sample carries no temperature information and the block means make the
/// regression a question about the slow part, where a thermal bias lives.
inline constexpr std::size_t kTemperatureBlocks = 256;

/// The coefficient of X [unit] on TEMPERATURE_DEGC (same length; ContractViolation otherwise).
/// Needs at least kTemperatureBlocks samples and a temperature that varies.
TemperatureCoefficient temperature_coefficient(std::span<const double> x,
                                               std::span<const double> temperature_degc);

/// X − coefficient·(T − mean T), sample by sample: the bias the temperature explains removed.
std::vector<double> remove_temperature_bias(std::span<const double> x,
                                            std::span<const double> temperature_degc,
                                            double coefficient);

}  // namespace imunoise::pipeline
