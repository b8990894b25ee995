// Tests of the bias-vs-temperature coefficient (pipeline/temperature_coefficient.h): a channel
// built as c·T(t) + white noise with a known c, T a warm-up curve, as the battery's
// temperature class writes it.
#include "pipeline/temperature_coefficient.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "common/errors.h"

namespace imunoise::pipeline {
namespace {

TEST(TemperatureCoefficient, RecoversAKnownCoefficientAndRemovesIt) {
  // n = 262144 samples of unit white noise; 256 blocks of 1024: block-mean noise σ/32. T rises
  // 25 → 33 °C with τ = n/8: its block means spread ≈ 2.5 °C RMS, so the slope's SE is about
  // (1/32)/(2.5·√256) = 8e-4 per °C against c = 0.05: 2 % at 1 SE; 6 % is 3 SE.
  const std::size_t n = 262144;
  const double c = 0.05;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::vector<double> t(n), x(n);
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = 25.0 + 8.0 * (1.0 - std::exp(-static_cast<double>(i) / (n / 8.0)));
    x[i] = c * t[i] + normal(rng);
  }
  const TemperatureCoefficient r = temperature_coefficient(x, t);
  ASSERT_TRUE(r.fitted);
  EXPECT_NEAR(r.coefficient / c, 1.0, 0.06);
  EXPECT_GT(r.correlation, 0.9);
  EXPECT_NEAR(r.temperature_high, 33.0, 0.01);
  const std::vector<double> y = remove_temperature_bias(x, t, r.coefficient);
  const TemperatureCoefficient after = temperature_coefficient(y, t);
  EXPECT_NEAR(after.coefficient, 0.0, 1e-12);
}

TEST(TemperatureCoefficient, ConstantTemperatureOrShortRecordGivesNone) {
  std::vector<double> x(1000, 1.0), t(1000, 25.0);
  EXPECT_FALSE(temperature_coefficient(x, t).fitted);
  std::vector<double> short_x(100, 1.0), short_t(100, 25.0);
  EXPECT_FALSE(temperature_coefficient(short_x, short_t).fitted);
  EXPECT_THROW(temperature_coefficient(x, short_t), ContractViolation);
}

}  // namespace
}  // namespace imunoise::pipeline
