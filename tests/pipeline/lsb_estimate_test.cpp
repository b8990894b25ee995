// Tests of the quantization step (estimate_lsb; pipeline/lsb_estimate.cpp) on constructed series
// whose step is known by construction, and against the plain search
// (sampling_reference_scans.h).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <random>
#include <vector>

#include "common/units.h"
#include "pipeline/sampling_checks.h"
#include "pipeline/sampling_reference_scans.h"

namespace imunoise::pipeline {
namespace {

using namespace sampling_test;  // the plain scans, the comparisons and the shared inputs

TEST(EstimateLsb, BinaryStep) { EXPECT_EQ(estimate_lsb(quantized_walk(5000, 0.0625)), 0.0625); }

TEST(EstimateLsb, ScaledAdcCodesInSi) {
  // 16-bit gyro at ±250 deg/s: 250/32768 deg/s per code, stored in rad/s.
  const double lsb = 250.0 / 32768.0 * units::kDegPerS;
  const auto q = estimate_lsb(quantized_walk(20000, lsb));
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(*q, lsb, lsb * 1e-9);
}

TEST(EstimateLsb, SmallestSeenStepIsTwoCodes) {
  // Steps of 2 and 3 codes only: the code grid is still 1 LSB (common divisor).
  std::vector<double> v{0.0};
  std::mt19937 rng(3);
  for (int i = 0; i < 1000; ++i) v.push_back(v.back() + ((rng() & 1) ? 2.0 : -3.0) * 0.01);
  const auto q = estimate_lsb(v);
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(*q, 0.01, 1e-9);
}

TEST(EstimateLsb, DecimalPrintingOfCodes) {
  // Codes printed with 6 decimals: each value carries up to 5e-7 of rounding.
  const double lsb = 0.00762939453125;
  std::vector<double> v = quantized_walk(5000, lsb);
  for (double& x : v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6f", x);
    x = std::strtod(text, nullptr);
  }
  const auto q = estimate_lsb(v);
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(*q, lsb, 1e-6);
}

TEST(EstimateLsb, PrintResolutionOfWideNoiseNearAnOffset) {
  // Accelerometer-like 9.8 ± 0.02 m/s² printed with 6 decimals: the file's own step is 1e-6,
  // though the smallest step between neighbours is usually several of them.
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(9.8, 0.02);
  std::vector<double> v(5000);
  for (double& x : v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6f", noise(rng));
    x = std::strtod(text, nullptr);
  }
  const auto q = estimate_lsb(v);
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(*q, 1e-6, 1e-12);
}

TEST(EstimateLsb, NoneForNineSignificantDigits) {
  // "%.9g" keeps relative, not absolute, resolution: no code grid.
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::vector<double> v(5000);
  for (double& x : v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", noise(rng));
    x = std::strtod(text, nullptr);
  }
  EXPECT_FALSE(estimate_lsb(v).has_value());
}

TEST(EstimateLsb, NoneForContinuousNoise) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::vector<double> v(10000);
  for (double& x : v) x = noise(rng);
  EXPECT_FALSE(estimate_lsb(v).has_value());
}

TEST(EstimateLsb, NoneWithTooFewSteps) {
  EXPECT_FALSE(estimate_lsb(std::vector<double>{1.0, 2.0, 3.0}).has_value());
}

// --- equality with the plain scans (sampling_reference_scans.h) ---------------------------------

TEST(SamplingReferenceEquality, EstimateLsbOnLongPrintedRecords) {
  // The exact offender scan behind the vector test: decimal printing puts every step a little
  // off the grid; "%.9g" keeps no absolute grid at all.
  std::mt19937_64 rng(77);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const char* format : {"%.6f", "%.5f", "%.9g", "%.4f"}) {
    std::vector<double> v(200000);
    for (double& x : v) {
      x = std::strtod(printed(9.8 + 0.02 * normal(rng), format).c_str(), nullptr);
    }
    SCOPED_TRACE(format);
    EXPECT_TRUE(same(estimate_lsb(v), plain::estimate_lsb(v)));
  }
}

TEST(SamplingReferenceEquality, EstimateLsbFindsTheFirstOffGridStepLate) {
  // Codes whose first off-grid step comes after the small steps were collected, so the full
  // scan (in analyze_channel: within its second pass) must find it: just outside the 10 %
  // tolerance, well outside, and just inside.
  for (double off : {0.105, 0.15, 0.25, 0.45, 0.095}) {
    for (std::size_t at : {60000, 60001, 60007, 99990}) {
      std::vector<double> v = quantized_walk(100003, 1e-3, static_cast<unsigned>(at));
      v[at] += off * 1e-3;
      v[at + 5] += 0.3 * 1e-3;
      SCOPED_TRACE(::testing::Message() << "off " << off << " at " << at);
      expect_channel_matches(v, std::nullopt, {});  // analyze_channel and estimate_lsb
    }
  }
}

}  // namespace
}  // namespace imunoise::pipeline
