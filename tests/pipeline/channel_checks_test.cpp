// Tests of the channel checks (analyze_channel; pipeline/channel_checks.cpp) on constructed
// series whose saturation runs and full-scale samples are known by construction, and against
// the plain scan (sampling_reference_scans.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <random>
#include <vector>

#include "pipeline/sampling_checks.h"
#include "pipeline/sampling_reference_scans.h"

namespace imunoise::pipeline {
namespace {

using namespace sampling_test;  // the plain scans, the comparisons and the shared inputs

TEST(AnalyzeChannel, SaturationRunsAtMinAndMax) {
  std::vector<double> v = quantized_walk(200, 1.0);
  // Clamp-like runs at the extremes: 6 at +1e4 and 5 at −1e4; a run of 4 does not count.
  std::fill(v.begin() + 20, v.begin() + 26, 1e4);
  std::fill(v.begin() + 100, v.begin() + 105, -1e4);
  std::fill(v.begin() + 150, v.begin() + 154, 1e4);
  const ChannelReport r = analyze_channel({"gyro_x", "rad/s", v, std::nullopt});
  EXPECT_EQ(r.max, 1e4);
  EXPECT_EQ(r.min, -1e4);
  EXPECT_EQ(r.saturation_runs, 2);
  EXPECT_EQ(r.saturated_samples, 11);
  EXPECT_EQ(r.longest_saturation_run, 6);
  EXPECT_EQ(r.first_saturation->index, 20);
  EXPECT_FALSE(r.constant);
}

TEST(AnalyzeChannel, FullScaleLimitCountsSamplesAtOrBeyond) {
  const std::vector<double> v{0.1, 34.9, -35.0, 35.2, 0.0, -1.0};
  const ChannelReport r = analyze_channel({"gyro_z", "rad/s", v, 35.0});
  EXPECT_EQ(r.beyond_full_scale, 2);
  EXPECT_EQ(r.first_beyond_full_scale->index, 2);
  EXPECT_EQ(r.full_scale, 35.0);
}

TEST(AnalyzeChannel, ConstantChannelIsNotSaturation) {
  const std::vector<double> v(50, 0.0);
  const ChannelReport r = analyze_channel({"accel_x", "m/s^2", v, std::nullopt});
  EXPECT_TRUE(r.constant);
  EXPECT_EQ(r.saturation_runs, 0);
  EXPECT_FALSE(r.lsb.has_value());
}

TEST(AnalyzeChannel, MeanAndStd) {
  const std::vector<double> v{1.0, 2.0, 3.0, 4.0};
  const ChannelReport r = analyze_channel({"x", "", v, std::nullopt});
  EXPECT_DOUBLE_EQ(r.mean, 2.5);
  EXPECT_DOUBLE_EQ(r.std_dev, std::sqrt(5.0 / 3.0));
}

/// Channel values of kind KIND (0 … kChannelKinds − 1), N samples.
constexpr int kChannelKinds = 17;
std::vector<double> channel_values(int kind, std::size_t n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> v(n);
  const double lsbs[] = {1e-3, 0.0078125, 1.0 / 3.0 * 1e-4};
  const double offsets[] = {0.0, 9.80665, -123.4};
  const double q = lsbs[static_cast<std::size_t>(kind) % 3];
  const double offset = offsets[static_cast<std::size_t>(kind / 3) % 3];
  switch (kind) {
    case 0:
    case 1:
    case 2:
    case 3:
    case 4:
    case 5:
    case 6:
    case 7:
    case 8: {
      // Codes q·k + offset, σ of 0.3 to 30 codes: from mostly equal neighbours to none.
      const double sigma = std::array{0.3, 3.0, 30.0}[rng() % 3];
      for (double& x : v) x = offset + q * std::nearbyint(sigma * normal(rng));
      break;
    }
    case 9:  // codes printed with 6 decimals
      for (double& x : v) {
        x = std::strtod(printed(9.8 + 0.0078125 * std::nearbyint(5 * normal(rng)), "%.6f").c_str(),
                        nullptr);
      }
      break;
    case 10:  // unquantised noise
      for (double& x : v) x = 1e-3 * normal(rng);
      break;
    case 11: {  // constant (also ±0)
      const double c = std::array{0.0, -0.0, 1.5, -2.25}[rng() % 4];
      std::fill(v.begin(), v.end(), c);
      break;
    }
    case 12:  // codes with a glitch off the grid now and then
      for (double& x : v) x = 1e-3 * std::nearbyint(4 * normal(rng));
      for (std::size_t i = 0; i < n; i += 1 + rng() % 5000) v[i] += 0.37e-3;
      break;
    case 13:  // a few values only, zeros of both signs among them
      for (double& x : v) x = std::array{0.0, -0.0, 1.0, -1.0, 0.5}[rng() % 5];
      break;
    case 14:  // zero is the minimum, +0 and −0 both present (which comes first is the min)
      for (double& x : v) x = std::array{0.0, -0.0, 0.25, 1.0}[rng() % 4];
      break;
    case 15:  // zero is the maximum
      for (double& x : v) x = std::array{-0.0, 0.0, -0.25, -1.0}[rng() % 4];
      break;
    case 16:  // codes near 1000 whose equal values differ by float rounding (below the floor)
      for (double& x : v) {
        x = 1000.0 + 1e-3 * std::nearbyint(3 * normal(rng));
        if (rng() % 4 == 0) x = std::nextafter(x, 2000.0);
      }
      break;
  }
  return v;
}

/// Clips V at both ends in runs of the given lengths, at the very start and end, across the
/// block edges of the scans (8 + 32·k) and at random places.
void add_saturation(std::vector<double>& v, std::mt19937_64& rng) {
  const std::size_t n = v.size();
  if (n == 0) return;
  double lo = *std::min_element(v.begin(), v.end());
  double hi = *std::max_element(v.begin(), v.end());
  if (rng() % 2) {  // clip beyond the data: new extremes
    hi += 1.0;
    lo -= 1.0;
  }
  const std::size_t lengths[] = {1, 2, 3, 4, 5, 6, 10, 17};
  const auto run = [&](std::size_t start, std::size_t len, double value) {
    for (std::size_t i = start; i < std::min(n, start + len); ++i) v[i] = value;
  };
  run(0, lengths[rng() % 8], rng() % 2 ? lo : hi);
  const std::size_t tail = lengths[rng() % 8];
  run(n - std::min(n, tail), tail, rng() % 2 ? lo : hi);
  for (int k = 0; k < 6; ++k) {
    const std::size_t len = lengths[rng() % 8];
    std::size_t start = rng() % n;
    if (k % 2 == 0) {  // across or up to a block edge
      const std::size_t edge = 8 + 32 * (rng() % (n / 32 + 1));
      start = edge - std::min(edge, static_cast<std::size_t>(rng() % (len + 1)));
    }
    if (start < n) run(start, len, rng() % 2 ? lo : hi);
  }
}

TEST(SamplingReferenceEquality, ChannelMatchesPlainScan) {
  std::mt19937_64 rng(2024);
  int cases = 0;
  for (std::size_t n : kSizes) {
    for (int kind = 0; kind < kChannelKinds; ++kind) {
      for (int variant = 0; variant < 4; ++variant) {
        std::vector<double> v = channel_values(kind, n, rng);
        if (variant >= 2) add_saturation(v, rng);
        std::optional<double> full_scale;
        if (variant % 2 == 1 && n > 0) {  // at, between and beyond some of the samples
          const double top = std::fabs(v[rng() % n]);
          full_scale = std::array{top, 0.5 * top, 1e300, 0.0}[rng() % 4];
        }
        SamplingOptions options;
        options.saturation_min_run = std::array<std::int64_t, 5>{5, 1, 2, 3, 0}[rng() % 5];
        if (rng() % 2) {
          options.line_of_sample = [](std::size_t i) { return static_cast<std::int64_t>(i) + 2; };
        }
        SCOPED_TRACE(::testing::Message() << "n " << n << ", kind " << kind << ", variant "
                                          << variant << ", min run " << options.saturation_min_run);
        expect_channel_matches(v, full_scale, options);
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, static_cast<int>(std::size(kSizes)) * kChannelKinds * 4);
}

TEST(SamplingReferenceEquality, SaturationRunAtEveryPositionAndLength) {
  // An 80-sample walk with one clipped run [start, start + len) at its maximum, for every start
  // and length: every alignment of a run to the blocks of the scan (edges at 8, 40 and 72).
  SamplingOptions options;
  options.saturation_min_run = 3;
  for (std::size_t len = 1; len <= 12; ++len) {
    for (std::size_t start = 0; start + len <= 80; ++start) {
      std::vector<double> v = quantized_walk(80, 1.0, static_cast<unsigned>(len));
      const double top = *std::max_element(v.begin(), v.end()) + 1.0;
      std::fill(v.begin() + static_cast<std::ptrdiff_t>(start),
                v.begin() + static_cast<std::ptrdiff_t>(start + len), top);
      SCOPED_TRACE(::testing::Message() << "run [" << start << ", " << start + len << ")");
      expect_channel_matches(v, top, options);
    }
  }
}

TEST(SamplingReferenceEquality, ZeroExtremeKeepsTheSignOfTheFirstZero) {
  // min = 0 (or max = 0) with +0 and −0 both present, the first of them anywhere: the
  // extreme is the first zero, as a left-to-right std::min / std::max fold finds it.
  for (std::size_t n : {9, 16, 40, 1000}) {
    for (std::size_t first = 0; first + 1 < n; first += 3) {
      for (double sign : {1.0, -1.0}) {
        std::vector<double> v(n, sign);  // all ±1, zeros later
        v[first] = std::copysign(0.0, -sign);
        v[first + 1 + (first * 7) % (n - first - 1)] = std::copysign(0.0, sign);
        SCOPED_TRACE(::testing::Message() << "n " << n << ", first zero " << first);
        expect_channel_matches(v, std::nullopt, {});
      }
    }
  }
}

}  // namespace
}  // namespace imunoise::pipeline
