#include "analysis/spectral_lines.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "analysis/psd.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

using test::white_noise;
constexpr double kPi = std::numbers::pi;
constexpr double kRateHz = 100.0;
constexpr std::size_t kSamples = 1 << 16;  // 655 s at 100 Hz: Welch L = 2^13, K = 15
constexpr double kDurationS = kSamples / kRateHz;

/// White noise of σ (one-sided S₁ = 2σ²/f_s) plus, when RED, a random walk whose density
/// K²/(2π²f²) crosses the white floor at 0.5 Hz (bin 41 of 4096): a steep red continuum over
/// the low tenth of the band, where the running median must follow it.
std::vector<double> noise(std::uint64_t seed, bool red, double sigma = 1.0) {
  std::vector<double> x = white_noise(kSamples, sigma, seed);
  if (red) {
    // Random-walk steps of sd q per sample: S₁ ≈ 2q²f_s/(2πf)² at f ≪ f_s, equal to the white
    // 2σ²/f_s at f_c = 0.5 Hz when q = 2πσ·f_c/f_s.
    const double q = 2.0 * kPi * sigma * 0.5 / kRateHz;
    const std::vector<double> steps = white_noise(kSamples, q, seed ^ 0x9e3779b97f4a7c15ULL);
    double walk = 0.0;
    for (std::size_t i = 0; i < kSamples; ++i) {
      walk += steps[i];
      x[i] += walk;
    }
  }
  return x;
}

/// Amplitude of a line whose power A²/2 is SNR times the continuum power in a T/16 bin
/// (the battery's definition): A = √(2·SNR·S₁·16/T).
double amplitude_for_snr(double snr, double continuum) {
  return std::sqrt(2.0 * snr * continuum * 16.0 / kDurationS);
}

LineDetection detect(const std::vector<double>& x, double probability) {
  LineSearchOptions options;
  options.false_alarm_probability = probability;
  return detect_spectral_lines(welch_psd(x, kRateHz), options);
}

// The stated rate is an upper bound (Bonferroni over the M searched bins, with the scatter of
// the median continuum integrated in): records of pure noise must show at least one line in
// at most P of them. 300 records at P = 0.2: the count is binomial with mean ≤ 60 and sd ≤ 6.9;
// failing above 60 + 3·6.9 = 81 has a chance of ~0.1 % when the rate holds. Below, a rate far
// under P would mean a needlessly high threshold: the exceedances of nearby bins are nearly
// independent (power correlation 1/4 between Hann neighbours), so the rate is at least half
// of P (mean ≥ 30; the floor 30 − 3·5 = 15).
void expect_false_alarm_rate(bool red, std::uint64_t seed0) {
  constexpr int kRecords = 300;
  int with_line = 0;
  for (int r = 0; r < kRecords; ++r) {
    with_line += !detect(noise(seed0 + static_cast<std::uint64_t>(r), red), 0.2).candidates.empty();
  }
  std::printf("false alarms (%s, P = 0.2): %d of %d records\n", red ? "red" : "white", with_line,
              kRecords);
  EXPECT_LE(with_line, 81) << (red ? "red" : "white");
  EXPECT_GE(with_line, 15) << (red ? "red" : "white");
}

TEST(SpectralLines, FalseAlarmRateOnWhiteNoiseIsAtMostTheStatedRate) {
  expect_false_alarm_rate(false, 1000);
}

TEST(SpectralLines, FalseAlarmRateOnRedNoiseIsAtMostTheStatedRate) {
  expect_false_alarm_rate(true, 5000);
}

// At the default P_FA = 1 %, 300 white records: mean ≤ 3, fail above 3 + 3·√3 ≈ 8.
TEST(SpectralLines, DefaultFalseAlarmRateIsOnePercent) {
  int with_line = 0;
  for (int r = 0; r < 300; ++r) {
    with_line +=
        !detect(noise(20000 + static_cast<std::uint64_t>(r), true), 0.01).candidates.empty();
  }
  std::printf("false alarms (red, P = 0.01): %d of 300 records\n", with_line);
  EXPECT_LE(with_line, 8);
}

// An SNR-10 line (the battery's weakest) half-way between two Welch bins (the worst
// scalloping of Hann, −1.42 dB): its peak bin sits at ≈ 0.48·SNR·16/T·(T/8)·… ≈ 9.6× the
// continuum against a threshold of ≈ 3.2 (ν ≈ 28, M ≈ 4000 bins at P = 1 %); the noise of the
// peak bin (sd ≈ 2.8 at that level) leaves a miss below 1 % per record. 50 records: ≥ 48.
TEST(SpectralLines, FindsAnSnrTenLineBetweenBins) {
  const double bin_hz = kRateHz / 8192.0;
  const double f = 123.5 * bin_hz;
  const double a = amplitude_for_snr(10.0, 2.0 / kRateHz);
  int found = 0;
  for (int r = 0; r < 50; ++r) {
    std::vector<double> x = noise(40000 + static_cast<std::uint64_t>(r), false);
    for (std::size_t i = 0; i < kSamples; ++i)
      x[i] += a * std::sin(2.0 * kPi * f * i / kRateHz + 0.3 * r);
    const LineDetection d = detect(x, 0.01);
    found += d.candidates.size() == 1 && std::abs(d.candidates[0].frequency_hz - f) < bin_hz;
  }
  EXPECT_GE(found, 48);
}

// Amplitude interval: A ± 1.96·√(C/T) (header's derivation) must cover the truth in 95 % of
// records, on white and on red continuum (the line at 0.2 Hz, where the random walk is 6× the
// white floor). 200 records each: count binomial(200, 0.95), sd 3.1; fail outside
// [190 − 3·3.1, 190 + 3·3.1] = [181, 199]. The estimate of C comes from the detection's
// running median, as in the pipeline.
void expect_amplitude_coverage(bool red, double f_hz, std::uint64_t seed0) {
  constexpr int kRecords = 200;
  int covered = 0, found = 0;
  const double continuum = red ? 2.0 / kRateHz * (1.0 + std::pow(0.5 / f_hz, 2)) : 2.0 / kRateHz;
  const double a = amplitude_for_snr(30.0, continuum);
  for (int r = 0; r < kRecords; ++r) {
    std::vector<double> x = noise(seed0 + static_cast<std::uint64_t>(r), red);
    const double phase = 0.7 * r;
    for (std::size_t i = 0; i < kSamples; ++i)
      x[i] += a * std::sin(2.0 * kPi * f_hz * i / kRateHz + phase);
    const Spectrum raw = welch_psd(x, kRateHz);
    const LineDetection d = detect_spectral_lines(raw);
    // The candidate at the line (a false alarm elsewhere, 1 % of records, does not matter).
    const auto at_line = std::find_if(d.candidates.begin(), d.candidates.end(), [&](const auto& c) {
      return std::abs(c.frequency_hz - f_hz) < 2.0 * raw.resolution_hz;
    });
    if (at_line == d.candidates.end()) continue;
    ++found;
    const std::span<const double> pieces[] = {x};
    const double freq[] = {at_line->frequency_hz};
    const double cont[] = {at_line->continuum_density};
    const LineFit fit = fit_spectral_lines(pieces, kRateHz, freq, cont, raw.resolution_hz, 0.95);
    const FittedLine& line = fit.lines.at(0);
    covered += line.amplitude_ci_low <= a && a <= line.amplitude_ci_high;
    EXPECT_NEAR(line.value.frequency_hz, f_hz, 0.5 / kDurationS);
  }
  EXPECT_EQ(found, kRecords);
  std::printf("amplitude coverage (%s): %d of %d\n", red ? "red" : "white", covered, found);
  EXPECT_GE(covered, 181) << (red ? "red" : "white");
  EXPECT_LE(covered, 199) << (red ? "red" : "white");
}

TEST(SpectralLines, AmplitudeIntervalCoversOnWhiteNoise) {
  expect_amplitude_coverage(false, 7.31, 60000);
}

TEST(SpectralLines, AmplitudeIntervalCoversOnRedNoise) {
  expect_amplitude_coverage(true, 0.2, 70000);
}

// Frequency, amplitude and phase of a strong line are those simulated; removing it leaves
// the noise (the residual's mean square is the noise's within rounding of the fit, 4 of
// n parameters: relative (A²/2 fitted away) ≪ 1e-3).
TEST(SpectralLines, FitsAndRemovesALine) {
  std::vector<double> x = noise(7, false, 0.01);
  const std::vector<double> clean = x;
  const double f = 3.217, a = 0.05, phase = 1.1;
  for (std::size_t i = 0; i < kSamples; ++i)
    x[i] += a * std::sin(2.0 * kPi * f * i / kRateHz + phase);
  const Spectrum raw = welch_psd(x, kRateHz);
  const LineDetection d = detect_spectral_lines(raw);
  ASSERT_EQ(d.candidates.size(), 1u);
  const std::span<const double> pieces[] = {x};
  const double freq[] = {d.candidates[0].frequency_hz};
  const double cont[] = {d.candidates[0].continuum_density};
  const LineFit fit = fit_spectral_lines(pieces, kRateHz, freq, cont, raw.resolution_hz, 0.95);
  // σ_A = √(2σ²/f_s/T) = 0.01·√(2/65536) = 5.5e-5; σ_f ≈ √6·σ/(π·A·T·√(n/2))-ish ≪ 1e-5 Hz.
  EXPECT_NEAR(fit.lines[0].value.frequency_hz, f, 1e-5);
  EXPECT_NEAR(fit.lines[0].value.amplitude, a, 4 * 5.5e-5);
  EXPECT_NEAR(std::remainder(fit.lines[0].value.phase_rad - phase, 2 * kPi), 0.0, 0.01);
  const std::vector<double> residual = remove_spectral_lines(x, 0, fit, kRateHz);
  double line_left = 0.0, noise_power = 0.0;
  for (std::size_t i = 0; i < kSamples; ++i) {
    line_left += (residual[i] - clean[i]) * (residual[i] - clean[i]);
    noise_power += clean[i] * clean[i];
  }
  EXPECT_LT(line_left / noise_power, 1e-3);
}

TEST(SpectralLines, RefusesABinnedSpectrum) {
  const Spectrum binned = log_bin(welch_psd(noise(1, false), kRateHz));
  EXPECT_THROW(detect_spectral_lines(binned), ContractViolation);
}

}  // namespace
}  // namespace imunoise::analysis
