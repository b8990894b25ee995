// Welch PSD, log binning, model PSD, cross-check and slope read-off (theory.md §1.2, §4.1, §5).
// Every expectation is checked against an independent truth (a closed form or the simulated
// coefficients), with a tolerance derived in the comment next to it. Fixed seeds throughout.
#include "analysis/psd.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include "analysis/psd_model.h"
#include "common/errors.h"
#include "models/noise_simulator.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

constexpr double kPi = std::numbers::pi;

/// n white samples of standard deviation sigma.
std::vector<double> white_samples(std::size_t n, double sigma, std::uint64_t seed) {
  models::StandardNormal draw{std::mt19937_64(seed)};
  std::vector<double> x(n);
  for (double& v : x) v = sigma * draw();
  return x;
}

/// n samples of one simulated channel.
std::vector<double> simulate(const models::ChannelNoiseModel& model, double rate_hz, std::size_t n,
                             std::uint64_t seed) {
  models::SimulationOptions options;
  options.sample_rate_hz = rate_hz;
  options.seed = seed;
  options.flicker_band.tau_min_s = 0.0;                                     // one sample period
  options.flicker_band.tau_max_s = 2.0 * static_cast<double>(n) / rate_hz;  // beyond the record
  models::ChannelSimulator simulator(model, options, 0);
  std::vector<double> x(n);
  simulator.next_block(x);
  return x;
}

double mean_of(const std::vector<double>& v, std::size_t first, std::size_t last) {
  double sum = 0.0;
  for (std::size_t i = first; i <= last; ++i) sum += v[i];
  return sum / static_cast<double>(last - first + 1);
}

// ---------------------------------------------------------------------------------------------
// Welch level, Parseval, lines

TEST(Welch, WhiteNoiseLevelIsTwoNSquared) {
  // theory.md §1.2: white rate noise of ARW N, sampled as σ_d = N/√Δt, has one-sided S₁ = 2N².
  const double rate_hz = 200.0;
  const double arw = 0.01;  // N [rad/√s]
  const std::size_t n = std::size_t{1} << 20;
  const auto x = white_samples(n, arw * std::sqrt(rate_hz), 101);
  WelchOptions options;
  options.segment_length = 4096;
  const Spectrum s = welch_psd(x, rate_hz, options);
  ASSERT_EQ(s.frequency_hz.size(), 2049u);
  EXPECT_EQ(s.segments, 511u);  // (2^20 − 4096)/2048 + 1
  // Tolerance: by Parseval the mean of S₁ over all bins is a weighted mean Σ a_n x_n² of the
  // squared samples, with 50 %-overlap Hann weights ∝ w_n² + w_{n+L/2}² = ½ + ½cos²; so its
  // relative variance is (2/n)·⟨a²⟩/⟨a⟩² = (2/n)·(19/32)/(9/16) = (2/n)(19/18) → sd 0.0014.
  // The constant detrend takes 1/6 of bin 1 (its Hann leakage from DC): 8e-5 over 2047 bins.
  // 4 sd = 0.0057.
  const double ratio = mean_of(s.density, 1, 2047) / (2.0 * arw * arw);
  EXPECT_NEAR(ratio, 1.0, 4.0 * std::sqrt(2.0 * 19.0 / 18.0 / static_cast<double>(n)));
}

TEST(Welch, ParsevalIntegratedPowerMatchesSampleVariance) {
  const double rate_hz = 200.0;
  const std::size_t n = std::size_t{1} << 20;
  const auto x = white_samples(n, 0.3, 102);
  WelchOptions options;
  options.segment_length = 4096;
  const Spectrum s = welch_psd(x, rate_hz, options);
  // Both numbers are means of the same x_n²: integrated_power weights them by the summed
  // squared windows (Parseval per segment), sample_variance uniformly. The difference
  // Σ(a_n − 1/n)x_n² has relative sd √(2·(1/18)/n) = 3e-4 (Hann ripple, see above); the per-
  // segment mean removal biases it by −1/L = −2e-4 and the half-covered first and last L/2
  // samples by ~L/(2n) = 0.2 %. 1 % is > 3× the sum.
  EXPECT_NEAR(s.integrated_power / s.sample_variance, 1.0, 0.01);
  EXPECT_NEAR(s.sample_variance, 0.09, 0.09 * 5.0 * std::sqrt(2.0 / static_cast<double>(n)));
}

TEST(Welch, SinusoidLinePowerIsHalfAmplitudeSquared) {
  // A sinusoid A·sin(2πf₀t) carries power A²/2 (theory.md §5.3); the Σw² normalisation makes
  // the density integrate to it whatever the window. f₀ lies between bins on purpose.
  const double rate_hz = 200.0;
  const double amplitude = 0.3;
  const double f0 = 12.3456;
  const std::size_t n = std::size_t{1} << 18;
  auto x = white_samples(n, 1e-3 * std::sqrt(rate_hz), 103);
  for (std::size_t k = 0; k < n; ++k) {
    x[k] += amplitude * std::sin(2.0 * kPi * f0 * static_cast<double>(k) / rate_hz + 0.4);
  }
  for (const Window window : {Window::hann, Window::blackman_harris, Window::hamming}) {
    WelchOptions options;
    options.segment_length = 4096;
    options.window = window;
    const Spectrum s = welch_psd(x, rate_hz, options);
    const auto peak = static_cast<std::size_t>(
        std::max_element(s.density.begin(), s.density.end()) - s.density.begin());
    EXPECT_NEAR(s.frequency_hz[peak], f0, s.resolution_hz);
    // Sum ±8 bins around the peak. Without noise this reproduces A²/2 to 1e-6 for all three
    // windows (scratch run): the sidelobes beyond 8 bins hold < 1e-6, and the cos(4πf₀t)
    // part of sin² averages out. The noise adds 17·2N²·Δf = 1.7e-6 (4e-5 of the line) and
    // a line × noise cross term of zero mean and relative sd ≈ √2·√(P_noise,lobe/P_line)/
    // √K_eff ≈ √2·√(4·2N²Δf/0.045)/√120 ≈ 4e-4. Tolerance 0.5 %, > 10 sd.
    double line_power = 0.0;
    for (std::size_t j = peak - 8; j <= peak + 8; ++j) line_power += s.density[j] * s.resolution_hz;
    EXPECT_NEAR(line_power / (0.5 * amplitude * amplitude), 1.0, 5e-3)
        << "window " << static_cast<int>(window);
  }
}

TEST(Welch, LinearDetrendRemovesAnExactRamp) {
  const std::size_t n = 1 << 16;
  std::vector<double> ramp(n);
  for (std::size_t k = 0; k < n; ++k) ramp[k] = 3.0 + 0.01 * static_cast<double>(k);
  WelchOptions options;
  options.segment_length = 1024;
  options.detrend = Detrend::linear;
  const Spectrum s = welch_psd(ramp, 100.0, options);
  // Each segment is an exact line, so what remains is rounding: residuals ~1e-13 of values
  // ~600 give powers ~1e-26, against the ramp's own variance (0.01·n)²/12 ≈ 3.6e4.
  const double ramp_variance = std::pow(0.01 * static_cast<double>(n), 2) / 12.0;
  EXPECT_LT(s.integrated_power, 1e-24 * ramp_variance);
  EXPECT_LT(*std::max_element(s.density.begin(), s.density.end()), 1e-24 * ramp_variance);
  EXPECT_LT(s.sample_variance, 1e-24 * ramp_variance);
  // Contrast: removing only the mean leaves the segment ramp (variance (0.01·1024)²/12
  // ≈ 8.7, Hann-weighted), so the same input is far from zero.
  options.detrend = Detrend::constant;
  EXPECT_GT(welch_psd(ramp, 100.0, options).integrated_power, 1.0);
}

TEST(Welch, AutomaticSegmentLengthCoversTheRecordFromTheStart) {
  // n = 100000: n/8 = 12500 → L = 8192, step 4096, K = ⌊(100000 − 8192)/4096⌋ + 1 = 23;
  // the last 100000 − (22·4096 + 8192) = 1696 samples are left out.
  const auto x = white_samples(100000, 1.0, 109);
  const Spectrum s = welch_psd(x, 50.0);
  EXPECT_EQ(s.segment_length, 8192u);
  EXPECT_EQ(s.segments, 23u);
  EXPECT_DOUBLE_EQ(s.resolution_hz, 50.0 / 8192.0);
  ASSERT_EQ(s.frequency_hz.size(), 4097u);
  EXPECT_DOUBLE_EQ(s.frequency_hz.back(), 25.0);
  // Dropping the tail: the same estimate from the first 98304 samples only.
  const std::vector<double> head(x.begin(), x.begin() + 22 * 4096 + 8192);
  const Spectrum h = welch_psd(head, 50.0, {8192, 0.5, Window::hann, Detrend::constant});
  for (std::size_t j = 0; j < s.density.size(); ++j) EXPECT_EQ(s.density[j], h.density[j]);
  // Short records: at least 16 samples per segment.
  EXPECT_EQ(welch_psd(std::vector<double>(20, 1.0), 1.0).segment_length, 16u);
}

TEST(Welch, EstimatorsInParallelThreadsMatchSerialResults) {
  // Plans are made and destroyed under one mutex; fftw_execute is re-entrant on distinct
  // plans. Four threads, each with its own estimator (two share L), must reproduce the
  // serial results.
  const auto x = white_samples(1 << 16, 1.0, 110);
  const std::vector<std::size_t> lengths = {256, 1024, 1024, 4096};
  std::vector<Spectrum> serial, parallel(lengths.size());
  for (const std::size_t l : lengths) {
    serial.push_back(welch_psd(x, 1.0, {l, 0.5, Window::hann, Detrend::constant}));
  }
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < lengths.size(); ++t) {
    threads.emplace_back([&, t] {
      WelchEstimator estimator(lengths[t], {lengths[t], 0.5, Window::hann, Detrend::constant});
      for (int repeat = 0; repeat < 3; ++repeat) parallel[t] = estimator.estimate(x, 1.0);
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (std::size_t t = 0; t < lengths.size(); ++t) {
    ASSERT_EQ(parallel[t].density.size(), serial[t].density.size());
    for (std::size_t j = 0; j < serial[t].density.size(); ++j) {
      EXPECT_NEAR(parallel[t].density[j], serial[t].density[j], 1e-12 * serial[t].density[j]);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Degrees of freedom

TEST(WelchDof, HannHalfOverlapCorrelationIsOneThirtySixth) {
  // Periodic Hann w_n = ½ − ½cos θ_n, θ_n = 2πn/L: w_n·w_{n+L/2} = ¼ sin²θ_n, summed over
  // n < L/2 gives L/16; Σw² = 3L/8; so ρ(L/2) = ((L/16)/(3L/8))² = (1/6)² = 1/36 for any
  // L ≥ 4 (exact, the sums of cos over whole periods vanish).
  for (const std::size_t length : {16u, 1000u, 4096u}) {
    const auto w = window_coefficients(Window::hann, length);
    EXPECT_NEAR(window_overlap_correlation(w, length / 2), 1.0 / 36.0, 1e-14) << length;
    EXPECT_NEAR(window_overlap_correlation(w, 0), 1.0, 1e-14);
    EXPECT_EQ(window_overlap_correlation(w, length), 0.0);
  }
  // Welch: K_eff = K/(1 + 2(1 − 1/K)/36) when only the half-shift overlaps.
  const auto w = window_coefficients(Window::hann, 1024);
  EXPECT_NEAR(effective_segments(w, 100, 512), 100.0 / (1.0 + 2.0 * 0.99 / 36.0), 1e-10);
  EXPECT_NEAR(effective_segments(w, 1, 512), 1.0, 1e-15);
  // Rectangular, no overlap: independent segments.
  const auto rect = window_coefficients(Window::rectangular, 64);
  EXPECT_NEAR(effective_segments(rect, 10, 64), 10.0, 1e-15);
}

TEST(WelchDof, RawBinDofIsTwiceTheEffectiveSegmentCount) {
  // The estimator's per-bin dof (computed from the window's lag spectra, see psd.cpp) must
  // reduce to Welch's 2·K_eff away from DC/Nyquist and K_eff at both ends.
  const auto x = white_samples(50000, 1.0, 104);
  for (const Window window : {Window::hann, Window::blackman_harris}) {
    for (const double overlap : {0.5, 0.75}) {
      WelchOptions options;
      options.segment_length = 512;
      options.window = window;
      options.overlap = overlap;
      const Spectrum s = welch_psd(x, 10.0, options);
      const auto w = window_coefficients(window, 512);
      const std::size_t step = 512 - static_cast<std::size_t>(overlap * 512);
      const double k_eff = effective_segments(w, s.segments, step);
      EXPECT_NEAR(s.dof[128], 2.0 * k_eff, 1e-9 * k_eff);
      EXPECT_NEAR(s.dof[0], k_eff, 1e-9 * k_eff);
      EXPECT_NEAR(s.dof[256], k_eff, 1e-9 * k_eff);
    }
  }
}

TEST(WelchDof, EmpiricalVarianceOfWhiteNoiseBinsMatchesTwoOverDof) {
  // For white noise every interior bin estimates the same level; Var(S₁)/E(S₁)² = 2/ν.
  // Pooling over M interior bins, the sample variance of S₁/mean has relative sd
  // √((2/M)(1 + 2Σr_k²)) with r_k the correlation of bins k apart (Hann: r₁² = (4/9)² ...
  // ≈ 0.2) → √(2.4/M). Two cases: 50 % overlap (K_eff/K = 0.947) and 75 % overlap, where
  // neighbouring segments are strongly correlated (K_eff/K ≈ 0.52) — a dof that ignored
  // the overlap would be off by 92 % there.
  const std::size_t n = std::size_t{1} << 20;
  const auto x = white_samples(n, 1.0, 105);
  for (const double overlap : {0.5, 0.75}) {
    WelchOptions options;
    options.segment_length = 16384;
    options.overlap = overlap;
    const Spectrum s = welch_psd(x, 1.0, options);
    const std::size_t first = 3, last = 8189;  // away from DC and Nyquist
    const double m = mean_of(s.density, first, last);
    double var = 0.0;
    for (std::size_t j = first; j <= last; ++j) var += std::pow(s.density[j] / m - 1.0, 2);
    var /= static_cast<double>(last - first);
    const double ratio = var * s.dof[4096] / 2.0;
    const double sd = std::sqrt(2.4 / static_cast<double>(last - first + 1));
    EXPECT_NEAR(ratio, 1.0, 4.0 * sd) << "overlap " << overlap << ", dof " << s.dof[4096];
  }
}

TEST(WelchDof, LogBinnedDofMatchesMonteCarlo) {
  // 400 independent white records; for each log bin the variance across records of S₁/2N²
  // must equal 2/ν. With R records the relative sd of an empirical variance is √(2/(R−1))
  // = 7.1 %: each bin within 4 sd (28 %); the mean over the 9 bins of ≥ 8 raw bins has sd
  // 7.1 %/3 = 2.4 %, so within 10 %. Summing raw dofs instead would claim 1.7–2.1× the
  // dof of these bins (neighbouring Hann bins share 4/9 of their power variance), far
  // outside. (Scratch run with 8000 records: mean ratio 0.9975 ± 0.0035 over 20 bins; also
  // 0.9965 for Blackman–Harris at 75 % overlap, 0.994 for rectangular without overlap.)
  constexpr int kRecords = 400;
  const std::size_t n = 8192;
  WelchOptions options;
  options.segment_length = 512;
  WelchEstimator estimator(512, options);
  std::vector<double> sum, sum2;
  Spectrum binned;
  for (int r = 0; r < kRecords; ++r) {
    const auto x = white_samples(n, 1.0, 2000 + static_cast<std::uint64_t>(r));
    binned = log_bin(estimator.estimate(x, 1.0), 10);
    sum.resize(binned.density.size(), 0.0);
    sum2.resize(binned.density.size(), 0.0);
    for (std::size_t i = 0; i < binned.density.size(); ++i) {
      const double v = binned.density[i] / 2.0;  // S₁/(2σ²τ0) with σ = 1, τ0 = 1
      sum[i] += v;
      sum2[i] += v * v;
    }
  }
  double wide_ratio_sum = 0.0;
  int wide_bins = 0;
  for (std::size_t i = 0; i < binned.density.size(); ++i) {
    const double mean = sum[i] / kRecords;
    const double var = (sum2[i] - kRecords * mean * mean) / (kRecords - 1);
    const double ratio = var / (mean * mean) * binned.dof[i] / 2.0;
    if (binned.first_raw_bin[i] < 3) continue;  // bins 1, 2: mean removal reshapes them
    EXPECT_NEAR(ratio, 1.0, 0.28) << "bin at " << binned.frequency_hz[i] << " Hz, "
                                  << binned.raw_bins[i] << " raw bins, dof " << binned.dof[i];
    if (binned.raw_bins[i] >= 8) {
      wide_ratio_sum += ratio;
      ++wide_bins;
    }
  }
  ASSERT_GE(wide_bins, 8);
  EXPECT_NEAR(wide_ratio_sum / wide_bins, 1.0, 0.10);
}

// ---------------------------------------------------------------------------------------------
// Log binning

TEST(PsdLogBin, ConstantDensityStaysConstantAndDofSums) {
  // A hand-made raw spectrum with independent bins (no power_covariance): 0 … 10.24 Hz.
  Spectrum raw;
  raw.resolution_hz = 0.01;
  raw.segment_length = 2048;
  raw.segments = 1;
  for (std::size_t j = 0; j <= 1024; ++j) {
    raw.frequency_hz.push_back(0.01 * static_cast<double>(j));
    raw.density.push_back(3.0);
    raw.dof.push_back(2.0);
  }
  for (const int per_decade : {10, 20}) {
    const Spectrum b = log_bin(raw, per_decade);
    std::size_t total = 0;
    int in_unit_decade = 0;
    for (std::size_t i = 0; i < b.density.size(); ++i) {
      EXPECT_NEAR(b.density[i], 3.0, 1e-12);
      EXPECT_EQ(b.dof[i], 2.0 * static_cast<double>(b.raw_bins[i]));
      // All raw frequencies of a bin inside one edge interval [10^{k/b}, 10^{(k+1)/b}).
      const double lo = raw.frequency_hz[b.first_raw_bin[i]];
      const double hi = raw.frequency_hz[b.first_raw_bin[i] + b.raw_bins[i] - 1];
      EXPECT_EQ(std::floor(per_decade * std::log10(lo) + 1e-9),
                std::floor(per_decade * std::log10(hi) + 1e-9));
      EXPECT_GE(b.frequency_hz[i], lo * (1.0 - 1e-12));
      EXPECT_LE(b.frequency_hz[i], hi * (1.0 + 1e-12));
      if (b.frequency_hz[i] >= 1.0 && b.frequency_hz[i] < 10.0) ++in_unit_decade;
      total += b.raw_bins[i];
    }
    EXPECT_EQ(total, 1024u);                // every raw bin but DC, once
    EXPECT_EQ(in_unit_decade, per_decade);  // raw spacing 0.01 Hz fills every bin of 1–10 Hz
  }
  // Geometric centre of a bin holding many raw bins, by its definition.
  const Spectrum b = log_bin(raw, 10);
  const std::size_t i = 20;
  double log_sum = 0.0;
  for (std::size_t j = 0; j < b.raw_bins[i]; ++j) {
    log_sum += std::log(raw.frequency_hz[b.first_raw_bin[i] + j]);
  }
  EXPECT_NEAR(b.frequency_hz[i], std::exp(log_sum / static_cast<double>(b.raw_bins[i])), 1e-12);
}

TEST(PsdLogBin, WelchBinsOfOneRawBinKeepTheirDof) {
  const auto x = white_samples(1 << 14, 1.0, 106);
  WelchOptions options;
  options.segment_length = 1024;
  const Spectrum raw = welch_psd(x, 1.0, options);
  const Spectrum b = log_bin(raw, 10);
  for (std::size_t i = 0; i < b.density.size(); ++i) {
    if (b.raw_bins[i] != 1) continue;
    EXPECT_NEAR(b.dof[i], raw.dof[b.first_raw_bin[i]], 1e-9 * b.dof[i]);
    EXPECT_EQ(b.density[i], raw.density[b.first_raw_bin[i]]);
  }
  // Wider bins: fewer dof than the naive sum, never fewer than one raw bin's.
  for (std::size_t i = 0; i < b.density.size(); ++i) {
    double naive = 0.0;
    for (std::size_t j = 0; j < b.raw_bins[i]; ++j) naive += raw.dof[b.first_raw_bin[i] + j];
    EXPECT_LE(b.dof[i], naive * (1.0 + 1e-12));
    EXPECT_GE(b.dof[i], raw.dof[b.first_raw_bin[i]] * (1.0 - 1e-12));
  }
}

// ---------------------------------------------------------------------------------------------
// Model PSD

/// σ²(τ = mτ0) of a τ0-sampled record from its one-sided PSD on [0, f_s/2]:
/// 2∫₀^{1/2τ0} S₁(f)·sin⁴(πfmτ0)/(m² sin²(πfτ0)) df (the discrete form of theory.md §5.4's
/// kernel: the second difference of m-sums of the samples), by Simpson on 4e5 steps; the
/// integrand is finite at f → 0 for every term (K: K²m²τ0²/2), evaluated just above 0.
double sampled_avar_from_psd(const NoiseCoefficients& model, int m, double tau0) {
  const int steps = 400000;
  const double f_max = 0.5 / tau0, h = f_max / steps;
  double sum = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const double f = i == 0 ? 1e-6 * h : i * h;
    const double kernel =
        std::pow(std::sin(kPi * f * m * tau0), 4) / (m * m * std::pow(std::sin(kPi * f * tau0), 2));
    const double weight = (i == 0 || i == steps) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * model_psd_one_sided(model, f, tau0) * kernel;
  }
  return 2.0 * sum * h / 3.0;
}

TEST(PsdModel, SampledFormsIntegrateToTheContinuousAvarClosedForms) {
  // The sampled S₁ of each term (psd_model.h) with the AVAR kernel of τ0-spaced samples
  // gives theory.md §4.1's AVAR column exactly at every τ = mτ0 — the model the fit uses —
  // because τ0-averages averaged again over m samples are the continuous m·τ0 averages. An
  // independent check of every factor in the sampled forms (the continuous laws would give
  // +9 % for K and −4 % for N-like terms at m = 1). Simpson's error here is below 1e-8; the
  // flicker integrand has a 1/f·f² = f kink at 0, worth ~1e-7.
  const double tau0 = 0.01;
  for (const int m : {1, 3, 250}) {
    const double tau = m * tau0;
    NoiseCoefficients white;
    white.white_noise = 0.02;
    EXPECT_NEAR(sampled_avar_from_psd(white, m, tau0) / (0.02 * 0.02 / tau), 1.0, 1e-7) << m;
    NoiseCoefficients flicker;
    flicker.bias_instability = 0.003;
    EXPECT_NEAR(sampled_avar_from_psd(flicker, m, tau0) / (2.0 * std::log(2.0) / kPi * 9e-6), 1.0,
                1e-6)
        << m;
    NoiseCoefficients walk;
    walk.random_walk = 0.001;
    EXPECT_NEAR(sampled_avar_from_psd(walk, m, tau0) / (1e-6 * tau / 3.0), 1.0, 1e-7) << m;
    for (const double t : {0.02, 1.7}) {
      NoiseCoefficients gm;
      gm.gauss_markov.push_back({0.05, t});
      const double gm_avar =
          0.0025 * t / (tau * tau) *
          (2.0 * tau - t * (3.0 - 4.0 * std::exp(-tau / t) + std::exp(-2.0 * tau / t)));
      EXPECT_NEAR(sampled_avar_from_psd(gm, m, tau0) / gm_avar, 1.0, 1e-7) << m << " " << t;
    }
  }
}

TEST(PsdModel, QuantizationIntegratesToThreeQSquaredOverTauSquared) {
  // The sampled Q law S₁ = 8 sin²(πfτ0)Q²/τ0 with the AVAR kernel of τ0-spaced samples,
  // σ²(m) = 2∫₀^{f_s/2} S₁ sin⁴(πfmτ0)/(m² sin²(πfτ0)) df
  //       = (16Q²/(τ0m²))·∫₀^{1/2τ0} sin⁴(πfmτ0) df = (16Q²/(τ0m²))(3/8)/(2τ0) = 3Q²/τ² exactly,
  // the AVAR of white angle noise of σ = Q (theory.md §4.1).
  const double tau0 = 0.01, q = 1e-4;
  NoiseCoefficients model;
  model.quantization = q;
  for (const int m : {1, 4, 7}) {
    const double tau = m * tau0;
    const int steps = 20000;
    const double f_max = 0.5 / tau0;
    const double h = f_max / steps;
    double sum = 0.0;
    for (int i = 1; i <= steps; ++i) {  // S₁(0) = 0: start at the first step
      const double f = i * h;
      const double weight = i == steps ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      const double kernel = std::pow(std::sin(kPi * f * m * tau0), 4) /
                            (m * m * std::pow(std::sin(kPi * f * tau0), 2));
      sum += weight * model_psd_one_sided(model, f, tau0) * kernel;
    }
    EXPECT_NEAR(2.0 * sum * h / 3.0 / (3.0 * q * q / (tau * tau)), 1.0, 1e-9) << m;
  }
  EXPECT_EQ(model_psd_one_sided(model, 0.5 / tau0 * 1.001, tau0), 0.0);
  // Where fτ0 ≪ 1 it is theory.md's continuous 2(2πf)²τ0Q²; at Nyquist 4/π² of it.
  const double f_low = 0.01 / tau0, w_low = 2.0 * kPi * f_low;
  EXPECT_NEAR(model_psd_one_sided(model, f_low, tau0) / (2.0 * w_low * w_low * tau0 * q * q), 1.0,
              1e-3);
  const double w_nyq = kPi / tau0;
  EXPECT_NEAR(model_psd_one_sided(model, 0.5 / tau0, tau0) / (2.0 * w_nyq * w_nyq * tau0 * q * q),
              4.0 / (kPi * kPi), 1e-12);
}

TEST(PsdModel, TermsMatchTheTheoryTableWhereFTau0IsSmallAndSumToTheTotal) {
  // At x = fτ0 = 0.03 the sampled forms are theory.md §5.3's continuous rows to within
  // (πx)² ≈ 1 % (K: −(πx)²/3·…, measured −0.3 %; B −0.3 %; GM −0.3 %); Q and N exactly their
  // sampled forms; R has no density (a deterministic ramp). Exactness is checked by the AVAR
  // integral above and against simulated records in psd_model_test.cpp.
  NoiseCoefficients model;
  model.quantization = 1e-4;
  model.white_noise = 2e-3;
  model.bias_instability = 5e-4;
  model.random_walk = 3e-5;
  model.ramp = 1e-7;
  model.gauss_markov.push_back({1e-3, 10.0});
  model.sinusoids.push_back({1.0, 3.0, 0.0});  // a line: no density
  const double f = 3.0, tau0 = 0.01, x = f * tau0;
  const PsdTerms t = model_psd_terms(model, f, tau0);
  const double w = 2.0 * kPi * f, small = kPi * kPi * x * x;
  EXPECT_DOUBLE_EQ(t.terms[NoiseTerm::quantization],
                   8.0 * std::pow(std::sin(kPi * f * tau0), 2) * 1e-8 / tau0);
  EXPECT_DOUBLE_EQ(t.terms[NoiseTerm::white_noise], 2.0 * 4e-6);
  EXPECT_NEAR(t.terms[NoiseTerm::bias_instability] / (25e-8 / (kPi * f)), 1.0, small);
  EXPECT_NEAR(t.terms[NoiseTerm::random_walk] / (9e-10 / (2.0 * kPi * kPi * f * f)), 1.0, small);
  EXPECT_EQ(t.terms[NoiseTerm::ramp], 0.0);
  ASSERT_EQ(t.gauss_markov.size(), 1u);
  EXPECT_NEAR(t.gauss_markov[0] / (4.0 * 1e-6 * 10.0 / (1.0 + 100.0 * w * w)), 1.0, small);
  EXPECT_DOUBLE_EQ(model_psd_one_sided(model, f, tau0), t.total());
  // No density above Nyquist.
  EXPECT_EQ(model_psd_one_sided(model, 0.51 / tau0, tau0), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Read-off from simulated records

TEST(PsdReadoff, WhiteNoiseGivesN) {
  // Region: the flat spectrum from where the 5-point slopes of the low-dof bins settle
  // within ±0.3 up to Nyquist (here 35 of 46 bins, 0.018–45 Hz). Its dof-weighted mean of
  // S₁/2 has relative sd ≈ √(2/ν_total), ν_total ≈ n/1.06 ≈ 1e6 → 0.14 % in N², 0.07 % in
  // N; 20 seeds gave 0.998–1.0014. 2 % is generous on purpose (it is a read-off).
  const double rate_hz = 100.0, arw = 3e-3;
  models::ChannelNoiseModel model;
  model.white_noise = arw;
  const auto x = simulate(model, rate_hz, std::size_t{1} << 20, 11);
  const PsdReadoff r = psd_readoff(log_bin(welch_psd(x, rate_hz), 10));
  ASSERT_TRUE(r.terms[NoiseTerm::white_noise].found);
  EXPECT_NEAR(r.terms[NoiseTerm::white_noise].value / arw, 1.0, 0.02);
  EXPECT_GE(r.terms[NoiseTerm::white_noise].bins, 20u);
  EXPECT_GT(r.terms[NoiseTerm::white_noise].f_high_hz, 40.0);
  EXPECT_FALSE(r.gm_plateau.found);
}

TEST(PsdReadoff, RandomWalkGivesK) {
  // Pure rate random walk, K²/(2π²f²). Leakage: the danger for a red spectrum is power
  // from below the lowest bins (each segment's residual drift) leaking upwards through the
  // window's sidelobes. Hann sidelobes fall as f⁻⁶ in power, much faster than the f⁻²
  // signal, so only the main lobe (±2 bins) matters and Hann is enough; a linear detrend
  // removes most of the drift before windowing. (Scratch study, 20 seeds: Hann or
  // Blackman–Harris, constant or linear detrend, all gave K within 0.992–0.998: the
  // dof-weighted region is dominated by its upper, leakage-free bins.) Blackman–Harris
  // would matter for spectra of f⁻⁴ and steeper, or with > ~60 dB of dynamic range.
  // Remaining biases: the window main lobe at the lowest bins (+14 % at bin 3, little
  // weight) and the sample averaging near f_s/8 (−5 %, the top of the region). 10 %.
  const double rate_hz = 100.0, k = 2e-4;
  models::ChannelNoiseModel model;
  model.random_walk = k;
  const auto x = simulate(model, rate_hz, std::size_t{1} << 20, 12);
  WelchOptions options;
  options.detrend = Detrend::linear;
  const PsdReadoff r = psd_readoff(log_bin(welch_psd(x, rate_hz, options), 10));
  ASSERT_TRUE(r.terms[NoiseTerm::random_walk].found);
  EXPECT_NEAR(r.terms[NoiseTerm::random_walk].value / k, 1.0, 0.10);
  EXPECT_GE(r.terms[NoiseTerm::random_walk].bins, 10u);
}

TEST(PsdReadoff, FlickerGivesB) {
  // Bias instability simulated as one Gauss–Markov per decade over a band wider than the
  // record: S₁ = B²/(πf) with a ripple of period one decade, ±5.5 % (Poisson summation of
  // Lorentzians spaced ln 10 apart: 2·sech(π²/ln 10)), which averages out over a region of
  // several decades. 20 seeds gave 0.987–0.993; 10 %.
  const double rate_hz = 100.0, b = 1e-3;
  models::ChannelNoiseModel model;
  model.bias_instability = b;
  const auto x = simulate(model, rate_hz, std::size_t{1} << 20, 13);
  const PsdReadoff r = psd_readoff(log_bin(welch_psd(x, rate_hz), 10));
  ASSERT_TRUE(r.terms[NoiseTerm::bias_instability].found);
  EXPECT_NEAR(r.terms[NoiseTerm::bias_instability].value / b, 1.0, 0.10);
  EXPECT_GE(r.terms[NoiseTerm::bias_instability].bins, 10u);
}

TEST(PsdReadoff, GaussMarkovPlateauAndCorner) {
  // S₁ = 4σ²T_c/(1 + (2πfT_c)²): plateau 4σ²T_c, half-power at f_c = 1/(2πT_c) (§5.3).
  // T_c = 0.2 s puts f_c = 0.8 Hz two decades above the lowest bin, so the plateau is seen
  // over bins of ~100 dof; the roll-off has ~1e4 dof per bin, but the simulator's point-
  // sampled AR(1) differs from the Lorentzian by a few % near f_s/8.
  const double rate_hz = 100.0, sigma = 0.01, tc = 0.2;
  models::ChannelNoiseModel model;
  model.gauss_markov.push_back({sigma, tc});
  const auto x = simulate(model, rate_hz, std::size_t{1} << 20, 14);
  const PsdReadoff r = psd_readoff(log_bin(welch_psd(x, rate_hz), 10));
  ASSERT_TRUE(r.gm_plateau.found);
  ASSERT_TRUE(r.gm_corner_hz.found);
  // Scratch study over 20 seeds: plateau 0.95–1.06, corner 0.93–1.09 of the truth (the
  // plateau bins have ν ≈ 50–600, i.e. ±6–20 % each). 10 %.
  EXPECT_NEAR(r.gm_plateau.value / (4.0 * sigma * sigma * tc), 1.0, 0.10);
  EXPECT_NEAR(r.gm_corner_hz.value * 2.0 * kPi * tc, 1.0, 0.10);
  EXPECT_FALSE(r.terms[NoiseTerm::white_noise].found);
}

// ---------------------------------------------------------------------------------------------
// Cross-check

TEST(PsdCrossCheck, WhitePlusRandomWalkPassesWithTruthAndFailsWithWrongN) {
  // RW dominates below 2N² = K²/(2π²f²) ⇔ f = 0.008 Hz (~1 decade of bins), white above.
  // Scratch study over 40 seeds: the true model had 0–2 of 43 bins outside (never failed);
  // N × 1.5 had ≥ 34 of 43 outside.
  const double rate_hz = 100.0, arw = 2e-3, k = 1e-4;
  models::ChannelNoiseModel sim;
  sim.white_noise = arw;
  sim.random_walk = k;
  const auto x = simulate(sim, rate_hz, std::size_t{1} << 20, 15);
  const Spectrum binned = log_bin(welch_psd(x, rate_hz), 10);
  NoiseCoefficients truth;
  truth.white_noise = arw;
  truth.random_walk = k;
  const PsdCrossCheck good = cross_check_psd(binned, truth, 1.0 / rate_hz);
  EXPECT_TRUE(good.pass) << good.bins_outside << " of " << good.bins_compared;
  EXPECT_GE(good.bins_compared, 30u);
  // Default band: up to 0.8 of Nyquist, i.e. the last bin centre within one bin (10^0.1)
  // below 40 Hz.
  EXPECT_LE(good.f_max_hz, 40.0);
  EXPECT_GT(good.f_max_hz, 40.0 / std::pow(10.0, 0.1));
  EXPECT_GE(good.f_min_hz, 3.0 * binned.resolution_hz);
  // N 1.5× too large: the white part 2.25× too high, far outside the intervals of the
  // high-frequency bins (dof in the thousands, ±a few %).
  NoiseCoefficients wrong = truth;
  wrong.white_noise = 1.5 * arw;
  const PsdCrossCheck bad = cross_check_psd(binned, wrong, 1.0 / rate_hz);
  EXPECT_FALSE(bad.pass);
  EXPECT_GT(bad.bins_outside, bad.bins_compared / 2);
  // The worst bin sits at log10(2.25) = 0.35 plus that bin's own noise (measured 0.40).
  EXPECT_NEAR(bad.worst_log10_ratio, std::log10(2.25), 0.1);
}

TEST(PsdCrossCheck, SkipsBinsHoldingAModelSinusoid) {
  const double rate_hz = 100.0, arw = 2e-3;
  auto x = white_samples(std::size_t{1} << 18, arw * std::sqrt(rate_hz), 107);
  for (std::size_t n = 0; n < x.size(); ++n) {
    x[n] += 0.05 * std::sin(2.0 * kPi * 7.3 * static_cast<double>(n) / rate_hz);
  }
  const Spectrum binned = log_bin(welch_psd(x, rate_hz), 10);
  NoiseCoefficients model;
  model.white_noise = arw;
  // Without the line in the model, the bin holding 7.3 Hz is ~2 decades above the white
  // level (line power A²/2 = 1.25e-3 spread over a ~1.8 Hz bin, against 2N² = 8e-6).
  const PsdCrossCheck without = cross_check_psd(binned, model, 1.0 / rate_hz);
  EXPECT_GE(without.bins_outside, 1u);
  EXPECT_GT(without.worst_log10_ratio, 1.0);
  model.sinusoids.push_back({0.05, 7.3, 0.0});
  const PsdCrossCheck with = cross_check_psd(binned, model, 1.0 / rate_hz);
  EXPECT_TRUE(with.pass) << with.bins_outside << " of " << with.bins_compared;
  EXPECT_LT(with.bins_compared, without.bins_compared);
  EXPECT_LT(with.bins_outside, without.bins_outside);
  EXPECT_LT(with.worst_log10_ratio, 0.25 * without.worst_log10_ratio);
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST(Welch, RejectsBadInputWithAClearMessage) {
  using test::expect_throw_containing;
  const std::vector<double> shortx(10, 1.0);
  WelchOptions options;
  options.segment_length = 16;
  expect_throw_containing<ContractViolation>(
      [&] { welch_psd(shortx, 1.0, options); },
      "record of 10 samples is shorter than one segment of 16");
  expect_throw_containing<ContractViolation>([&] { welch_psd(shortx, 1.0); }, "too short");
  std::vector<double> with_nan(64, 0.0);
  with_nan[5] = std::numeric_limits<double>::quiet_NaN();
  expect_throw_containing<ContractViolation>([&] { welch_psd(with_nan, 1.0, options); },
                                             "sample 5 is not finite");
  options.overlap = 1.0;
  expect_throw_containing<ContractViolation>(
      [&] { welch_psd(std::vector<double>(64, 0.0), 1.0, options); },
      "overlap must be in [0, 1) (got 1)");
  options.overlap = 0.5;
  expect_throw_containing<ContractViolation>(
      [&] { welch_psd(std::vector<double>(64, 0.0), 0.0, options); },
      "sample rate must be finite and > 0");
  expect_throw_containing<ContractViolation>([&] { WelchEstimator(1, options); },
                                             "segment_length must be >= 2 and fit an int (got 1)");
  expect_throw_containing<ContractViolation>([&] { log_bin(Spectrum{}, 0); },
                                             "bins_per_decade must be >= 1 (got 0)");
  expect_throw_containing<ContractViolation>(
      [&] { log_bin(log_bin(welch_psd(std::vector<double>(64, 1.0), 1.0, options)), 10); },
      "already binned");
}

TEST(PsdModel, RejectsBadArgumentsWithAClearMessage) {
  using test::expect_throw_containing;
  NoiseCoefficients model;
  model.white_noise = 1e-3;
  expect_throw_containing<ContractViolation>([&] { model_psd_one_sided(model, 0.0, 0.01); },
                                             "frequency must be finite and > 0 (got 0 Hz)");
  expect_throw_containing<ContractViolation>([&] { model_psd_one_sided(model, 1.0, -1.0); },
                                             "tau0 must be finite and > 0");
  model.random_walk = -1.0;
  expect_throw_containing<ContractViolation>([&] { model_psd_terms(model, 1.0, 0.01); },
                                             "random_walk K must be finite and >= 0 (got -1)");
  model.random_walk = 0.0;
  // A band that holds no bin.
  const auto x = white_samples(4096, 1.0, 108);
  const Spectrum binned = log_bin(welch_psd(x, 100.0), 10);
  expect_throw_containing<AnalysisError>([&] { cross_check_psd(binned, model, 0.01, 1e-9); },
                                         "no spectrum bin between");
  expect_throw_containing<ContractViolation>([&] { psd_readoff(Spectrum{}); }, "spectrum is empty");
}

}  // namespace
}  // namespace imunoise::analysis

namespace imunoise::analysis {
namespace {

TEST(PsdModel, QuantizedAngleIncrementsPassTheCrossCheckUpToNyquist) {
  // Angle increments of a white angle error σ = Q (theory.md §4.1: Q = Δ/√12 of a quantizer),
  // simulated here exactly (std::mt19937_64), 2^20 samples at 400 Hz: the measured log-binned
  // PSD follows the sampled law in every bin up to Nyquist — the continuous (2πf)²τ0Q² would
  // sit 2.5x above the top bins (4/π² = 0.405 at Nyquist).
  const double tau0 = 1.0 / 400.0, q = 2e-6;
  std::mt19937_64 rng(20);
  std::normal_distribution<double> normal;
  std::vector<double> rate(1u << 20);
  double previous = q * normal(rng);
  for (double& r : rate) {
    const double angle = q * normal(rng);
    r = (angle - previous) / tau0;
    previous = angle;
  }
  const Spectrum binned = log_bin(welch_psd(rate, 1.0 / tau0), 10);
  NoiseCoefficients model;
  model.quantization = q;
  const PsdCrossCheck check = cross_check_psd(binned, model, tau0, 0.5 / tau0);
  EXPECT_TRUE(check.pass) << check.bins_outside << " of " << check.bins_compared;
  EXPECT_GT(check.f_max_hz, 0.45 / tau0);
  // The bins above f_s/4 (hundreds of dof each) within 5 standard deviations √(2/ν) of the
  // sampled law, and the top one clearly below the continuous law.
  for (std::size_t i = 0; i < binned.frequency_hz.size(); ++i) {
    const double f = binned.frequency_hz[i];
    if (f < 0.25 / tau0) continue;
    const double ratio = binned.density[i] / model_psd_one_sided(model, f, tau0);
    EXPECT_NEAR(ratio, 1.0, 5.0 * std::sqrt(2.0 / binned.dof[i])) << f << " Hz";
  }
  const double f_top = binned.frequency_hz.back(), w_top = 2.0 * kPi * f_top;
  EXPECT_LT(binned.density.back() / (2.0 * w_top * w_top * tau0 * q * q), 0.8);
}

}  // namespace
}  // namespace imunoise::analysis
