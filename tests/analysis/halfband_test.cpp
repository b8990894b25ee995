// The half-band decimation filter of the multi-rate PSD (analysis/halfband.h): its stated
// passband ripple and stopband attenuation from its frequency response on a dense grid, the
// half-band symmetry, and the polyphase decimation against the direct convolution.
#include "analysis/halfband.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

/// H(f) = Σ h_i e^{−2πif(i − c)} (f in cycles per input sample; real, the filter being
/// symmetric about c).
double response(double f) {
  const auto h = halfband_coefficients();
  const double c = static_cast<double>(h.size() / 2);
  double sum = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    sum += h[i] * std::cos(2.0 * std::numbers::pi * f * (static_cast<double>(i) - c));
  }
  return sum;
}

TEST(Halfband, CoefficientsAreSymmetricHalfBandWithUnitDcGain) {
  const auto h = halfband_coefficients();
  ASSERT_EQ(h.size(), kHalfbandTaps);
  const std::size_t c = h.size() / 2;
  EXPECT_EQ(h[c], 0.5);
  double sum = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    EXPECT_EQ(h[i], h[h.size() - 1 - i]) << i;
    const std::size_t offset = i > c ? i - c : c - i;
    if (offset != 0 && offset % 2 == 0) {
      EXPECT_EQ(h[i], 0.0) << i;
    }
    if (offset % 2 == 1) {
      EXPECT_NE(h[i], 0.0) << i;
    }
    sum += h[i];
  }
  EXPECT_NEAR(sum, 1.0, 1e-15);
}

TEST(Halfband, PassbandRippleAndStopbandAttenuationAsStated) {
  // Grid of 20 001 points over each band (the response varies on a scale of 1/N ≈ 0.026 of
  // the input rate, so a step of 6e-6 resolves every ripple). Stated: |H − 1| ≤ 1.3e-7 on
  // [0, 1/8], |H| ≤ 1.3e-7 (137.7 dB) on [3/8, 1/2].
  double pass = 0.0, stop = 0.0;
  for (int q = 0; q <= 20000; ++q) {
    const double f = 0.125 * q / 20000.0;
    pass = std::max(pass, std::fabs(response(f) - 1.0));
    stop = std::max(stop, std::fabs(response(0.5 - f)));
    // Half-band: H(f) + H(1/2 − f) = 2h_c = 1 (the odd-offset cosines change sign).
    EXPECT_NEAR(response(f) + response(0.5 - f), 1.0, 1e-14) << f;
  }
  EXPECT_LE(pass, 1.3e-7);
  EXPECT_LE(stop, 1.3e-7);
  EXPECT_GE(-20.0 * std::log10(stop), 137.0);
  EXPECT_LE(20.0 * std::log10(1.0 + pass), 1.2e-6);  // dB of amplitude ripple per stage
  // A cascade of 12 stages: a frequency f in the band of the deepest level passes stage s at
  // f·2^s of that stage's rate, inside its passband. The power gain stays within 1.3e-5 dB.
  double worst_db = 0.0;
  for (int q = 0; q <= 2000; ++q) {
    const double f = 0.125 * q / 2000.0;  // of the last stage's input rate
    double gain = 1.0;
    for (int s = 0; s < 12; ++s) gain *= std::pow(response(f / std::pow(2.0, s)), 2);
    worst_db = std::max(worst_db, std::fabs(10.0 * std::log10(gain)));
  }
  EXPECT_LE(worst_db, 1.3e-5);
}

TEST(Halfband, DecimationIsTheDirectConvolutionKeptEverySecondSample) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const auto h = halfband_coefficients();
  // Sizes around the kernel's 512-output blocks.
  for (const std::size_t inputs : {39u, 40u, 41u, 1061u, 1062u, 1063u, 5000u}) {
    std::vector<double> x(inputs);
    for (double& v : x) v = normal(rng);
    const std::size_t outputs = halfband_outputs(inputs);
    ASSERT_EQ(outputs, (inputs - kHalfbandTaps) / 2 + 1);
    std::vector<double> y(outputs);
    halfband_decimate(x, y);
    for (std::size_t k = 0; k < outputs; ++k) {
      double direct = 0.0;
      for (std::size_t i = 0; i < h.size(); ++i) direct += h[i] * x[2 * k + i];
      EXPECT_NEAR(y[k], direct, 1e-14) << inputs << " inputs, output " << k;
    }
  }
  EXPECT_EQ(halfband_outputs(38), 0u);
  std::vector<double> x(50, 1.0), y(6);
  halfband_decimate(x, y);  // DC passes with gain 1
  for (double v : y) EXPECT_NEAR(v, 1.0, 1e-15);
  std::vector<double> too_many(7);
  test::expect_throw_containing<ContractViolation>([&] { halfband_decimate(x, too_many); },
                                                   "7 outputs need 51 inputs (got 50)");
}

}  // namespace
}  // namespace imunoise::analysis
