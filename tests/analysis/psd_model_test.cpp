// The sampled model PSD of every term (analysis/psd_model.h, docs/conventions.md §4.1) against an
// independent truth: the Welch average of a record simulated here, by generators written in
// this file (std::mt19937_64, FFTW; not models/noise_simulator) that produce each rate sample
// as the exact average of the continuous process over its interval — an angle increment over
// τ0, what an IMU outputs. Tolerances come from the dof of each log-binned Welch value: under
// the model ν·Ŝ/S ~ χ²_ν, sd √(2/ν); every comparison allows 4.5 sd (two-sided 7e-6 per
// bin), plus a stated generator bias where the generator is not exact. Each test also checks
// that the continuous law of theory.md §5.3 lies outside that tolerance, so that it has the
// power to tell the forms apart. The failure diagnosis of cross_check_psd() (bands and likely
// causes) is checked on records with one known defect each.
#include "analysis/psd_model.h"

#include <fftw3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "analysis/psd.h"

namespace imunoise::analysis {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTau0 = 0.01;  // 100 Hz
constexpr std::size_t kSamples = std::size_t{1} << 20;
constexpr double kSd = 4.5;  // allowed standard deviations per compared bin

class Normal {
 public:
  explicit Normal(std::uint64_t seed) : rng_(seed) {}
  double operator()() { return dist_(rng_); }

 private:
  std::mt19937_64 rng_;
  std::normal_distribution<double> dist_;
};

/// White angle error of σ = Q on every angle sample, differenced (quantized angle counter).
std::vector<double> quantized_increments(double q, std::uint64_t seed, std::size_t n = kSamples) {
  Normal g(seed);
  std::vector<double> y(n);
  double previous = q * g();
  for (double& v : y) {
    const double angle = q * g();
    v = (angle - previous) / kTau0;
    previous = angle;
  }
  return y;
}

/// Averages over [kτ0, (k+1)τ0] of a continuous random walk of intensity K²: given the walk
/// w_k at the start, the increment Δ and the integral I = ∫(w − w_k) over the interval are
/// jointly Gaussian, Var Δ = K²τ0, Var I = K²τ0³/3, Cov = K²τ0²/2 (Brownian motion).
std::vector<double> averaged_random_walk(double k, std::uint64_t seed, std::size_t n = kSamples) {
  Normal g(seed);
  std::vector<double> y(n);
  double w = 0.0;
  for (double& v : y) {
    const double z1 = g(), z2 = g();
    const double increment = k * std::sqrt(kTau0) * z1;
    const double integral = k * std::pow(kTau0, 1.5) * (0.5 * z1 + z2 / (2.0 * std::sqrt(3.0)));
    v = w + integral / kTau0;
    w += increment;
  }
  return y;
}

/// The discrete walk of the battery generator (theory.md §1.4): point samples, step K√τ0.
std::vector<double> point_random_walk(double k, std::uint64_t seed) {
  Normal g(seed);
  std::vector<double> y(kSamples);
  double w = 0.0;
  for (double& v : y) {
    w += k * std::sqrt(kTau0) * g();
    v = w;
  }
  return y;
}

/// Averages of a stationary OU process (autocovariance σ²e^{−|t|/T}): x(t) = x₀e^{−t/T} +
/// q∫e^{−(t−s)/T}dW, q² = 2σ²/T. Over one interval the innovation e = x(τ0) − φx₀ and the
/// noise part J of ∫x are jointly Gaussian (u = τ0 − s): Var e = σ²(1 − φ²),
/// Cov = q²T∫e^{−u/T}(1 − e^{−u/T})du = σ²T(1 − φ)², Var J = 2σ²T[τ0 − 2T(1 − φ) + T(1 − φ²)/2].
std::vector<double> averaged_gauss_markov(double sigma, double t, std::uint64_t seed,
                                          std::size_t n = kSamples) {
  Normal g(seed);
  const double phi = std::exp(-kTau0 / t);
  const double var = sigma * sigma;
  const double vee = var * (1.0 - phi * phi);
  const double vej = var * t * (1.0 - phi) * (1.0 - phi);
  const double vjj = 2.0 * var * t * (kTau0 - 2.0 * t * (1.0 - phi) + 0.5 * t * (1.0 - phi * phi));
  const double a = std::sqrt(vee), b = vej / a, c = std::sqrt(vjj - b * b);
  std::vector<double> y(n);
  double x = sigma * g();
  for (double& v : y) {
    const double z1 = g(), z2 = g();
    v = (x * t * (1.0 - phi) + b * z1 + c * z2) / kTau0;
    x = phi * x + a * z1;
  }
  return y;
}

/// Averages of flicker noise S₁c = B²/(πf): FFT synthesis at M = 16 times the rate (bin j a
/// random-phase cosine of variance S₁c(f_j)·Δf = B²/(πj), DC and Nyquist 0), then means of M
/// samples. Its expected spectrum is Σ_{|x+k|<M/2} (B²τ0/(π|x + k|))·D_M(x + k), D_M(u) =
/// sin²(πu)/(M² sin²(πu/M)), not the exact fold of the τ0 boxcar: summed numerically, it is
/// +0.39 % of the model at 0.36 fs and +0.57 % at 0.49 fs (kFlickerBias covers both).
constexpr std::size_t kFlickerSamples = std::size_t{1} << 18;
constexpr double kFlickerBias = 0.006;
std::vector<double> averaged_flicker(double b, std::uint64_t seed) {
  const std::size_t m = 16, length = kFlickerSamples * m, bins = length / 2 + 1;
  auto* spectrum = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins));
  auto* series = static_cast<double*>(fftw_malloc(sizeof(double) * length));
  fftw_plan plan = fftw_plan_dft_c2r_1d(static_cast<int>(length), spectrum, series, FFTW_ESTIMATE);
  Normal g(seed);
  spectrum[0][0] = spectrum[0][1] = 0.0;
  for (std::size_t j = 1; j < length / 2; ++j) {
    // x_k = Y₀ + 2Σ Re(Y_j e^{2πijk/L}): Y_j = (c/2)(a − ib) gives c(a cos + b sin), var c².
    const double c = b / std::sqrt(kPi * static_cast<double>(j));
    spectrum[j][0] = 0.5 * c * g();
    spectrum[j][1] = -0.5 * c * g();
  }
  spectrum[length / 2][0] = spectrum[length / 2][1] = 0.0;
  fftw_execute(plan);
  std::vector<double> y(kFlickerSamples, 0.0);
  for (std::size_t k = 0; k < kFlickerSamples; ++k) {
    for (std::size_t i = 0; i < m; ++i) y[k] += series[k * m + i];
    y[k] /= static_cast<double>(m);
  }
  fftw_destroy_plan(plan);
  fftw_free(series);
  fftw_free(spectrum);
  return y;
}

Spectrum welch_bins(const std::vector<double>& y) {
  WelchOptions options;
  options.segment_length = 4096;
  return log_bin(welch_psd(y, 1.0 / kTau0, options), 10);
}

/// Mean of LAW over the raw frequencies of log bin I (as cross_check_psd() compares).
template <typename Law>
double bin_mean(const Spectrum& s, std::size_t i, Law law) {
  double sum = 0.0;
  for (std::size_t j = 0; j < s.raw_bins[i]; ++j)
    sum += law(static_cast<double>(s.first_raw_bin[i] + j) * s.resolution_hz);
  return sum / static_cast<double>(s.raw_bins[i]);
}

/// The log bin holding frequency F.
std::size_t bin_at(const Spectrum& s, double f) {
  for (std::size_t i = 0; i < s.frequency_hz.size(); ++i) {
    const double lo = static_cast<double>(s.first_raw_bin[i]) * s.resolution_hz;
    const double hi = static_cast<double>(s.first_raw_bin[i] + s.raw_bins[i] - 1) * s.resolution_hz;
    if (f >= lo - 0.5 * s.resolution_hz && f <= hi + 0.5 * s.resolution_hz) return i;
  }
  ADD_FAILURE() << "no bin at " << f << " Hz";
  return 0;
}

/// Measured/model at the bin holding F is 1 within kSd sd (+ BIAS), and the continuous law's
/// ratio is not.
template <typename Continuous>
void expect_sampled_law_at(const Spectrum& s, const NoiseCoefficients& model, double f,
                           Continuous continuous, double bias = 0.0) {
  const std::size_t i = bin_at(s, f);
  const double tolerance = kSd * std::sqrt(2.0 / s.dof[i]) + bias;
  const double sampled =
      bin_mean(s, i, [&](double fj) { return model_psd_one_sided(model, fj, kTau0); });
  EXPECT_NEAR(s.density[i] / sampled, 1.0, tolerance)
      << "at " << s.frequency_hz[i] << " Hz (" << f * kTau0 << " fs), dof " << s.dof[i];
  const double cont = bin_mean(s, i, continuous);
  EXPECT_GT(std::fabs(s.density[i] / cont - 1.0), tolerance)
      << "the continuous law is not rejected at " << f << " Hz: the test has no power there";
}

TEST(SampledModelPsd, QuantizationMatchesDifferencedWhiteAngleAt036And049Fs) {
  const double q = 2e-6;
  const Spectrum s = welch_bins(quantized_increments(q, 401));
  NoiseCoefficients model;
  model.quantization = q;
  const auto continuous = [&](double f) {
    const double w = 2.0 * kPi * f;
    return 2.0 * w * w * kTau0 * q * q;
  };
  for (const double x : {0.36, 0.49}) expect_sampled_law_at(s, model, x / kTau0, continuous);
}

TEST(SampledModelPsd, RandomWalkOfAveragesMatchesNearNyquistAndNearDc) {
  const double k = 1e-3;
  const std::vector<double> y = averaged_random_walk(k, 402);
  const Spectrum s = welch_bins(y);
  NoiseCoefficients model;
  model.random_walk = k;
  const auto continuous = [&](double f) { return k * k / (2.0 * kPi * kPi * f * f); };
  for (const double x : {0.36, 0.49}) expect_sampled_law_at(s, model, x / kTau0, continuous);
  // Near DC the Hann window's leakage biases an f⁻² Welch estimate (+14 % at bin 3), so the
  // low bins are checked on the first difference, whose spectrum 4 sin²(πfτ0)·S₁ is smooth
  // (the pre-whitening of theory.md §5.1): every bin below 1 Hz, bins 3 and up.
  std::vector<double> d(y.size() - 1);
  for (std::size_t i = 0; i + 1 < y.size(); ++i) d[i] = y[i + 1] - y[i];
  const Spectrum sd = welch_bins(d);
  std::size_t checked = 0;
  for (std::size_t i = 0; i < sd.frequency_hz.size() && sd.frequency_hz[i] < 1.0; ++i) {
    if (sd.first_raw_bin[i] < 3) continue;
    const double expected = bin_mean(sd, i, [&](double f) {
      const double sn = std::sin(kPi * f * kTau0);
      return 4.0 * sn * sn * model_psd_one_sided(model, f, kTau0);
    });
    EXPECT_NEAR(sd.density[i] / expected, 1.0, kSd * std::sqrt(2.0 / sd.dof[i]))
        << sd.frequency_hz[i] << " Hz";
    ++checked;
  }
  EXPECT_GE(checked, 5u);
}

TEST(SampledModelPsd, PointSampledWalkIsTheAveragedOnePlusWhiteOfKSquaredTauSquaredOverSix) {
  // The battery generator's walk: K²τ0²/(2 sin²) = the averaged form + a white 2N², N² =
  // K²τ0²/6 — the N its AVAR (2m² + 1)K²τ0/(6m) = K²τ/3 + (K²τ0²/6)/τ makes the fit add.
  const double k = 1e-3;
  const Spectrum s = welch_bins(point_random_walk(k, 403));
  NoiseCoefficients model;
  model.random_walk = k;
  model.white_noise = k * kTau0 / std::sqrt(6.0);
  const auto averaged_only = [&](double f) {
    NoiseCoefficients walk;
    walk.random_walk = k;
    return model_psd_one_sided(walk, f, kTau0);
  };
  for (const double x : {0.36, 0.49}) expect_sampled_law_at(s, model, x / kTau0, averaged_only);
}

TEST(SampledModelPsd, GaussMarkovOfAveragesMatchesNearDcAndNearNyquist) {
  // T_c = 2τ0 (r = 0.5): the sampled form is 0.71 of the Lorentzian at 0.36 fs and 0.79 at
  // 0.49 fs; near DC both are the plateau 4σ²T_c (flat: no leakage bias).
  const double sigma = 0.02, t = 2.0 * kTau0;
  const Spectrum s = welch_bins(averaged_gauss_markov(sigma, t, 404));
  NoiseCoefficients model;
  model.gauss_markov.push_back({sigma, t});
  const auto lorentzian = [&](double f) {
    const double w = 2.0 * kPi * f * t;
    return 4.0 * sigma * sigma * t / (1.0 + w * w);
  };
  for (const double x : {0.36, 0.49}) expect_sampled_law_at(s, model, x / kTau0, lorentzian);
  for (const double f : {0.1, 0.3}) {
    const std::size_t i = bin_at(s, f);
    const double sampled =
        bin_mean(s, i, [&](double fj) { return model_psd_one_sided(model, fj, kTau0); });
    EXPECT_NEAR(s.density[i] / sampled, 1.0, kSd * std::sqrt(2.0 / s.dof[i])) << f << " Hz";
  }
  // A slower GM (T_c = 50τ0, corner 0.32 Hz) across the whole band: every log bin from
  // raw bin 3 up within tolerance (a Lorentzian's curvature under the Hann main lobe is
  // below 0.3 % at bin 3 of this resolution).
  const double t_slow = 50.0 * kTau0;
  const Spectrum slow = welch_bins(averaged_gauss_markov(sigma, t_slow, 405));
  NoiseCoefficients slow_model;
  slow_model.gauss_markov.push_back({sigma, t_slow});
  for (std::size_t i = 0; i < slow.frequency_hz.size(); ++i) {
    if (slow.first_raw_bin[i] < 3) continue;
    const double sampled =
        bin_mean(slow, i, [&](double fj) { return model_psd_one_sided(slow_model, fj, kTau0); });
    EXPECT_NEAR(slow.density[i] / sampled, 1.0, kSd * std::sqrt(2.0 / slow.dof[i]) + 0.003)
        << slow.frequency_hz[i] << " Hz";
  }
}

TEST(SampledModelPsd, FlickerOfAveragesMatchesAt036And049Fs) {
  const double b = 1e-3;
  const Spectrum s = welch_bins(averaged_flicker(b, 406));
  NoiseCoefficients model;
  model.bias_instability = b;
  const auto continuous = [&](double f) { return b * b / (kPi * f); };
  for (const double x : {0.36, 0.49})
    expect_sampled_law_at(s, model, x / kTau0, continuous, kFlickerBias);
}

TEST(SampledModelPsd, DeterministicRampHasNoDensityAndWhitePlusRampPassesTheCheck) {
  // A rate ramp R·t. After each segment's mean removal the Hann-windowed remainder has a DFT
  // falling as k⁻³ (power k⁻⁶; computed for L = 4096: 0.20 of the f⁻³ law 2R²/(2πf)³ at raw
  // bin 3, the lowest compared, 0.036 at bin 5, 0.004 at bin 10). With R = 5e-4 that law is
  // 2.6× the white level at bin 3: the white-only density passes the check, and the excess at
  // bin 3 (0.20 × 2.6 = 0.5) is well below what the f⁻³ law predicts.
  const double n = 1e-3, r = 5e-4;
  Normal g(407);
  std::vector<double> y(kSamples);
  for (std::size_t i = 0; i < kSamples; ++i)
    y[i] = n / std::sqrt(kTau0) * g() + r * static_cast<double>(i) * kTau0;
  NoiseCoefficients model;
  model.white_noise = n;
  model.ramp = r;
  EXPECT_EQ(model_psd_terms(model, 0.01, kTau0).terms[NoiseTerm::ramp], 0.0);
  const Spectrum s = welch_bins(y);
  const PsdCrossCheck check = cross_check_psd(s, model, kTau0);
  EXPECT_TRUE(check.pass) << check.bins_outside << " of " << check.bins_compared;
  const std::size_t i = bin_at(s, check.f_min_hz);
  ASSERT_EQ(s.first_raw_bin[i], 3u);
  const double w = 2.0 * kPi * s.frequency_hz[i];
  const double f3_law = 2.0 * r * r / (w * w * w) / (2.0 * n * n);
  EXPECT_GT(f3_law, 2.0);
  EXPECT_LT(s.density[i] / (2.0 * n * n) - 1.0, 0.3 * f3_law);
}

TEST(SampledModelPsd, CompleteModelOfEveryTermPassesUpToNyquist) {
  // Q + N + B + K + GM, each generated as above, summed: the complete model passes over the
  // whole band up to 0.49 fs. B leads in the lowest bins (K adds 20 % there), the GM
  // (T_c = 3τ0) from 0.3 to 10 Hz, Q above 20 Hz, N adds 15–50 % in between.
  const std::size_t n_samples = kFlickerSamples;
  const double q = 4e-6, n = 5e-5, b = 1e-4, k = 3e-5, sigma = 5e-4, t = 3.0 * kTau0;
  std::vector<double> y = quantized_increments(q, 411, n_samples);
  const std::vector<double> parts[] = {averaged_flicker(b, 412),
                                       averaged_random_walk(k, 413, n_samples),
                                       averaged_gauss_markov(sigma, t, 414, n_samples)};
  Normal g(415);
  for (std::size_t i = 0; i < n_samples; ++i) {
    y[i] += n / std::sqrt(kTau0) * g();
    for (const std::vector<double>& p : parts) y[i] += p[i];
  }
  NoiseCoefficients model;
  model.quantization = q;
  model.white_noise = n;
  model.bias_instability = b;
  model.random_walk = k;
  model.gauss_markov.push_back({sigma, t});
  const Spectrum s = welch_bins(y);
  const PsdCrossCheck check = cross_check_psd(s, model, kTau0, 0.49 / kTau0);
  EXPECT_TRUE(check.pass) << check.bins_outside << " of " << check.bins_compared;
  EXPECT_TRUE(check.misfits.empty());
  EXPECT_GT(check.f_max_hz, 0.4 / kTau0);
}

// ---------------------------------------------------------------------------------------------
// Diagnosis of a failed check

/// White noise N with one defect added, checked against the white-only model.
PsdCrossCheck white_with(const std::vector<double>& defect, std::uint64_t seed,
                         bool low_pass = false) {
  const double n = 1e-3;
  Normal g(seed);
  std::vector<double> y(kSamples);
  for (std::size_t i = 0; i < kSamples; ++i)
    y[i] = n / std::sqrt(kTau0) * g() + (defect.empty() ? 0.0 : defect[i]);
  if (low_pass) {
    // 2nd-order Butterworth at fs/8 by the bilinear transform (K = tan(π/8)).
    const double kk = std::tan(kPi / 8.0), norm = 1.0 / (1.0 + std::sqrt(2.0) * kk + kk * kk);
    const double b0 = kk * kk * norm, a1 = 2.0 * (kk * kk - 1.0) * norm,
                 a2 = (1.0 - std::sqrt(2.0) * kk + kk * kk) * norm;
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    for (double& v : y) {
      const double out = b0 * (v + 2.0 * x1 + x2) - a1 * y1 - a2 * y2;
      x2 = x1;
      x1 = v;
      y2 = y1;
      y1 = out;
      v = out;
    }
  }
  NoiseCoefficients model;
  model.white_noise = n;
  return cross_check_psd(welch_bins(y), model, kTau0, 0.4 / kTau0);
}

bool has_cause(const PsdCrossCheck& c, PsdMisfitCause cause, double f_in_band = -1.0) {
  for (const PsdMisfitBand& band : c.misfits) {
    if (band.cause != cause) continue;
    if (f_in_band < 0.0 || (f_in_band >= band.f_low_hz / 1.3 && f_in_band <= band.f_high_hz * 1.3))
      return true;
  }
  return false;
}

TEST(PsdMisfit, ASingleTopBinJustBelowTheModelIsNotALowPass) {
  // A hand-made white spectrum equal to the model except three bins: two isolated mid-band
  // excesses (so that the check fails) and the top bin low by RATIO. 10⁵ dof per bin: the 99 %
  // interval is ±0.8 %, so ×0.985 is outside, and alone it is not a roll-off.
  NoiseCoefficients model;
  model.white_noise = 1e-3;
  const auto check_with_top = [&](double ratio) {
    Spectrum s;
    for (double f = 0.01; f <= 0.4 / kTau0; f *= std::pow(10.0, 0.1)) {
      s.frequency_hz.push_back(f);
      s.density.push_back(model_psd_one_sided(model, f, kTau0));
      s.dof.push_back(1e5);
    }
    s.resolution_hz = 0.001;
    const std::size_t n = s.density.size();
    s.density[n / 3] *= 1.05;
    s.density[2 * n / 3] *= 1.05;
    s.density[n - 1] *= ratio;
    return cross_check_psd(s, model, kTau0, 0.4 / kTau0);
  };
  const PsdCrossCheck slight = check_with_top(0.985);
  ASSERT_FALSE(slight.pass);
  ASSERT_EQ(slight.misfits.size(), 3u);
  EXPECT_EQ(slight.misfits.back().cause, PsdMisfitCause::isolated);
  const PsdCrossCheck deep = check_with_top(0.8);
  ASSERT_EQ(deep.misfits.size(), 3u);
  EXPECT_EQ(deep.misfits.back().cause, PsdMisfitCause::low_pass);
}

TEST(PsdMisfit, NamesALineALowPassAMissingWalkAndAWrongLevel) {
  // Three sinusoids (one or two would stay within the allowance of 2 bins), each of power
  // 100× the white level in its bin: a narrow excess at each.
  std::vector<double> line(kSamples);
  for (std::size_t i = 0; i < kSamples; ++i) {
    const double t = static_cast<double>(i) * kTau0;
    line[i] = 0.05 * (std::sin(2.0 * kPi * 2.1 * t) + std::sin(2.0 * kPi * 7.3 * t) +
                      std::sin(2.0 * kPi * 23.0 * t));
  }
  const PsdCrossCheck with_line = white_with(line, 421);
  ASSERT_FALSE(with_line.pass);
  for (const double f : {2.1, 7.3, 23.0})
    EXPECT_TRUE(has_cause(with_line, PsdMisfitCause::spectral_line, f)) << f << " Hz";
  for (const PsdMisfitBand& band : with_line.misfits) EXPECT_TRUE(band.above);

  // A low-pass at fs/8: the top of the band below the model.
  const PsdCrossCheck filtered = white_with({}, 422, true);
  ASSERT_FALSE(filtered.pass);
  ASSERT_FALSE(filtered.misfits.empty());
  EXPECT_EQ(filtered.misfits.back().cause, PsdMisfitCause::low_pass);
  EXPECT_FALSE(filtered.misfits.back().above);
  EXPECT_NEAR(filtered.misfits.back().f_high_hz, filtered.f_max_hz, 1e-9);
  EXPECT_LT(filtered.misfits.back().extreme_ratio, 0.5);

  // A random walk the model lacks (K = 1e-3: above the white level below 0.16 Hz): excess at
  // the bottom of the band.
  const PsdCrossCheck walk = white_with(averaged_random_walk(1e-3, 423), 423);
  ASSERT_FALSE(walk.pass);
  ASSERT_FALSE(walk.misfits.empty());
  EXPECT_EQ(walk.misfits.front().cause, PsdMisfitCause::low_frequency_excess);
  EXPECT_TRUE(walk.misfits.front().above);
  EXPECT_NEAR(walk.misfits.front().f_low_hz, walk.f_min_hz, 1e-12);

  // Angle quantization the model lacks: excess at the top (unmodelled high-frequency noise).
  const PsdCrossCheck quantized = white_with(quantized_increments(3e-5, 424), 425);
  ASSERT_FALSE(quantized.pass);
  ASSERT_FALSE(quantized.misfits.empty());
  EXPECT_EQ(quantized.misfits.back().cause, PsdMisfitCause::high_frequency_excess);

  // White noise 1.3× the model's N everywhere: the level.
  std::vector<double> more(kSamples);
  Normal g(426);
  for (double& v : more) v = std::sqrt(1.3 * 1.3 - 1.0) * 1e-3 / std::sqrt(kTau0) * g();
  const PsdCrossCheck level = white_with(more, 427);
  ASSERT_FALSE(level.pass);
  ASSERT_EQ(level.misfits.size(), 1u);
  EXPECT_EQ(level.misfits[0].cause, PsdMisfitCause::level);
  EXPECT_NEAR(level.misfits[0].extreme_ratio, 1.69, 0.15);

  // A passing check has no bands.
  EXPECT_TRUE(white_with({}, 428).misfits.empty());
}

}  // namespace
}  // namespace imunoise::analysis
