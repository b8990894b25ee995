// Tests of the low-pass corner (pipeline/low_pass_corner.h) on spectra built from the closed
// form of a 2nd-order Butterworth (|H|² = 1/(1 + (f/f_c)⁴)) times a white floor, against the
// white model: the −3 dB point is f_c by construction.
#include "pipeline/low_pass_corner.h"

#include <gtest/gtest.h>

#include <cmath>

#include "analysis/psd_model.h"

namespace imunoise::pipeline {
namespace {

/// Log-binned spectrum from 0.01 Hz to Nyquist of tau0: the white model's S₁ times GAIN(f).
template <class Gain>
analysis::Spectrum spectrum(const NoiseCoefficients& c, double tau0, Gain gain) {
  analysis::Spectrum s;
  for (double f = 0.01; f <= 0.5 / tau0; f *= std::pow(10.0, 0.05)) {
    s.frequency_hz.push_back(f);
    s.density.push_back(analysis::model_psd_one_sided(c, f, tau0) * gain(f));
    s.dof.push_back(100.0);
  }
  return s;
}

TEST(LowPassCorner, ButterworthCornerIsFoundAtMinusThreeDecibels) {
  NoiseCoefficients c;
  c.white_noise = 1e-3;
  const double tau0 = 0.01;  // 100 Hz
  for (const double fc : {10.0, 25.0, 35.0}) {
    const auto s = spectrum(c, tau0, [fc](double f) { return 1.0 / (1.0 + std::pow(f / fc, 4)); });
    const LowPassCorner corner = find_low_pass_corner(s, c, tau0);
    ASSERT_TRUE(corner.found) << fc;
    // Bins are a twentieth of a decade apart (12 %); the log interpolation between the two
    // around the corner is within a few % for this smooth a gain.
    EXPECT_NEAR(corner.corner_hz / fc, 1.0, 0.03) << fc;
  }
}

TEST(LowPassCorner, FlatOrNearlyFlatSpectraHaveNone) {
  NoiseCoefficients c;
  c.white_noise = 1e-3;
  const double tau0 = 0.01;
  EXPECT_FALSE(find_low_pass_corner(spectrum(c, tau0, [](double) { return 1.0; }), c, tau0).found);
  // A 30 % droop near Nyquist (a mild filter) is not a corner: never below half.
  EXPECT_FALSE(
      find_low_pass_corner(
          spectrum(c, tau0, [](double f) { return 1.0 - 0.3 * std::pow(f / 50.0, 2); }), c, tau0)
          .found);
}

}  // namespace
}  // namespace imunoise::pipeline
