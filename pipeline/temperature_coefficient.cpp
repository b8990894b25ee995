#include "pipeline/temperature_coefficient.h"

#include <algorithm>
#include <cmath>

#include "common/errors.h"

namespace imunoise::pipeline {

namespace {

std::vector<double> block_means(std::span<const double> x, std::size_t b) {
  std::vector<double> out(x.size() / b);
  for (std::size_t i = 0; i < out.size(); ++i) {
    double s = 0.0;
    for (std::size_t k = 0; k < b; ++k) s += x[i * b + k];
    out[i] = s / static_cast<double>(b);
  }
  return out;
}

}  // namespace

TemperatureCoefficient temperature_coefficient(std::span<const double> x,
                                               std::span<const double> temperature_degc) {
  IMUNOISE_EXPECT(x.size() == temperature_degc.size(),
                  "temperature_coefficient: channel and temperature of different lengths");
  TemperatureCoefficient out;
  if (x.size() < kTemperatureBlocks) return out;
  const std::size_t b = x.size() / kTemperatureBlocks;
  const std::vector<double> y = block_means(x, b);
  const std::vector<double> t = block_means(temperature_degc, b);
  const double n = static_cast<double>(y.size());
  double my = 0.0, mt = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    my += y[i];
    mt += t[i];
  }
  my /= n;
  mt /= n;
  double stt = 0.0, sty = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    stt += (t[i] - mt) * (t[i] - mt);
    sty += (t[i] - mt) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(stt > 0.0) || !std::isfinite(stt)) return out;
  out.fitted = true;
  out.coefficient = sty / stt;
  out.correlation = syy > 0.0 ? sty / std::sqrt(stt * syy) : 0.0;
  const auto [low, high] = std::minmax_element(t.begin(), t.end());
  out.temperature_low = *low;
  out.temperature_high = *high;
  return out;
}

std::vector<double> remove_temperature_bias(std::span<const double> x,
                                            std::span<const double> temperature_degc,
                                            double coefficient) {
  IMUNOISE_EXPECT(x.size() == temperature_degc.size(),
                  "remove_temperature_bias: channel and temperature of different lengths");
  double mean = 0.0;
  for (double v : temperature_degc) mean += v;
  mean /= static_cast<double>(std::max<std::size_t>(1, temperature_degc.size()));
  std::vector<double> out(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    out[i] = x[i] - coefficient * (temperature_degc[i] - mean);
  }
  return out;
}

}  // namespace imunoise::pipeline
