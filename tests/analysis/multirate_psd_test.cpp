// Multi-rate log-frequency PSD (analysis/multirate_psd.h) against independent truths: the
// white level 2N² (theory.md §1.2), the exact expectation of a Hann-windowed Welch bin of a
// random walk and of a flicker process simulated exactly here (closed-form spectra smoothed by
// the window's spectral kernel, by quadrature), sinusoid line powers A²/2, the stated dof
// against the spread over 400 records, Parseval, pooling, and the one-level case against the
// classic estimate. Own generators (std::mt19937_64), fixed seeds; every tolerance derived in
// the comment next to it.
#include "analysis/multirate_psd.h"

#include <fftw3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <limits>
#include <mutex>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include "analysis/chi_square.h"
#include "analysis/halfband.h"
#include "analysis/psd.h"
#include "analysis/psd_model.h"
#include "common/errors.h"
#include "common/fftw_planner_lock.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Generators (exact simulations of the processes whose spectra are tested)

std::vector<double> white(std::size_t n, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x) v = normal(rng);
  return x;
}

/// x_k = x_{k−1} + σe_k: one-sided S₁(f) = 2σ²τ0/(2 sin πfτ0)² exactly (stationary
/// increments; Welch bins j ≥ 2 of a Hann window see only increments, see expected_raw).
std::vector<double> random_walk(std::size_t n, double sigma, std::uint64_t seed) {
  std::vector<double> x = white(n, sigma, seed);
  for (std::size_t k = 1; k < n; ++k) x[k] += x[k - 1];
  return x;
}

/// Flicker: increments y = (1 − z⁻¹)^{1/2} e (fractional noise d = −½, Hosking 1981) drawn
/// exactly by circulant embedding (Davies & Harte 1987, Biometrika 74, 95), then summed:
/// S₁,x(f) = 2σ²τ0/|2 sin πfτ0| ≈ σ²/(πf), i.e. B = σ (theory.md §5.3). Autocovariance of y:
/// γ(0) = σ²Γ(1 − 2d)/Γ(1 − d)² = 4σ²/π, γ(k) = γ(k − 1)(k − 1 + d)/(k − d).
std::vector<double> flicker(std::size_t n, double sigma, std::uint64_t seed) {
  const std::size_t m = n, size = 2 * m;
  std::vector<double> c(size);
  double g = 4.0 * sigma * sigma / kPi;
  for (std::size_t k = 0; k <= m; ++k) {
    if (k > 0) g *= (static_cast<double>(k) - 1.5) / (static_cast<double>(k) + 0.5);
    c[k] = g;
    if (k > 0 && k < m) c[size - k] = g;
  }
  std::vector<double> real(size);
  std::vector<std::complex<double>> spectrum(m + 1);
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_plan forward =
        fftw_plan_dft_r2c_1d(static_cast<int>(size), c.data(),
                             reinterpret_cast<fftw_complex*>(spectrum.data()), FFTW_ESTIMATE);
    fftw_execute(forward);
    fftw_destroy_plan(forward);
  }
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  const double s = static_cast<double>(size);
  for (std::size_t k = 0; k <= m; ++k) {
    const double lambda = spectrum[k].real();
    EXPECT_GE(lambda, -1e-12 * c[0]) << "circulant embedding not non-negative at " << k;
    const double v = std::max(0.0, lambda);
    if (k == 0 || k == m) {
      spectrum[k] = std::sqrt(v / s) * normal(rng);
    } else {
      const double a = std::sqrt(v / (2.0 * s));
      const double re = normal(rng), im = normal(rng);
      spectrum[k] = {a * re, a * im};
    }
  }
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_plan backward = fftw_plan_dft_c2r_1d(static_cast<int>(size),
                                              reinterpret_cast<fftw_complex*>(spectrum.data()),
                                              real.data(), FFTW_ESTIMATE);
    fftw_execute(backward);
    fftw_destroy_plan(backward);
  }
  std::vector<double> x(real.begin(), real.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t k = 1; k < n; ++k) x[k] += x[k - 1];
  return x;
}

// ---------------------------------------------------------------------------------------------
// Exact expectation of a Hann Welch bin

/// Gauss–Legendre nodes and weights on [0, 1] (Newton on P_n).
struct GaussRule {
  std::vector<double> x, w;
  explicit GaussRule(int n) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1.0);
        const double dz = p1 / dp;
        z -= dz;
        if (std::fabs(dz) < 1e-15) break;
      }
      x.push_back(0.5 * (1.0 - z));
      w.push_back(1.0 / ((1.0 - z * z) * dp * dp));
    }
  }
};

/// K(u) = |W(u)|²/(L·Σw²) of the periodic Hann window, u in bins: W = ½D(u) − ¼D(u − 1) −
/// ¼D(u + 1) with the Dirichlet kernel D(v) = e^{−iπv(L−1)/L} sin(πv)/sin(πv/L); Σw² = 3L/8.
/// ∫K over one period (L bins) is 1. u must not be an integer (the Gauss nodes never are).
double hann_kernel(double u, std::size_t length) {
  const double l = static_cast<double>(length);
  const auto dirichlet = [l](double v) {
    const double magnitude = std::sin(kPi * v) / std::sin(kPi * v / l);  // may be negative
    const double phase = -kPi * v * (l - 1.0) / l;
    return std::complex<double>(magnitude * std::cos(phase), magnitude * std::sin(phase));
  };
  const std::complex<double> w =
      0.5 * dirichlet(u) - 0.25 * dirichlet(u - 1.0) - 0.25 * dirichlet(u + 1.0);
  return std::norm(w) / (l * 3.0 * l / 8.0);
}

/// E[Ŝ_j] of raw bin j ≥ 2 of a Hann Welch spectrum of spacing DF and length L for a process
/// with one-sided spectrum S1 (any level: the level's process has S1 in its passband):
/// (c_j/2)·∫₀^{L/2} S1(uΔf)[K(u − j) + K(u + j)] du, c_j = 1 at Nyquist, else 2. Valid for
/// processes with stationary increments too: for j ≥ 2 the Hann window's DFT vanishes at DC
/// (Σw_n e^{−2πijn/L} = 0), so the segment mean cancels and only increments enter (Yaglom).
/// The kernel falls below 1e-10 beyond ±48 bins: the integral stops there (and at 0).
double expected_raw(const std::function<double(double)>& s1, std::size_t j, double df,
                    std::size_t length) {
  static const GaussRule rule(16);
  const double jd = static_cast<double>(j);
  const double half = static_cast<double>(length / 2);
  const double lo = std::max(0.0, jd - 48.0), hi = std::min(half, jd + 48.0);
  double sum = 0.0;
  for (double a = lo; a < hi; a += 1.0) {
    const double b = std::min(hi, a + 1.0);
    for (std::size_t q = 0; q < rule.x.size(); ++q) {
      const double u = a + (b - a) * rule.x[q];
      sum += (b - a) * rule.w[q] * s1(u * df) *
             (hann_kernel(u - jd, length) + hann_kernel(u + jd, length));
    }
  }
  return (j == length / 2 ? 0.5 : 1.0) * sum;
}

/// Binned point I ends at the Nyquist raw bin L/2 (counted as half a bin in its mean).
bool holds_nyquist(const Spectrum& s, std::size_t i) {
  return s.first_raw_bin[i] + s.raw_bins[i] - 1 == s.segment_length / 2;
}

/// The expectation of binned point I: Σ expected_raw over its raw bins / (n, or n − ½ with
/// the Nyquist bin).
double expected_bin(const Spectrum& s, std::size_t i, const std::function<double(double)>& s1) {
  double sum = 0.0;
  for (std::size_t j = 0; j < s.raw_bins[i]; ++j) {
    sum += expected_raw(s1, s.first_raw_bin[i] + j, s.bin_resolution_hz[i], s.segment_length);
  }
  return sum / (static_cast<double>(s.raw_bins[i]) - (holds_nyquist(s, i) ? 0.5 : 0.0));
}

/// Level of binned point I: its spacing is f_s/(2^d·L).
int level_of(const Spectrum& s, std::size_t i) {
  return static_cast<int>(std::lround(std::log2(
      s.sample_rate_hz / (static_cast<double>(s.segment_length) * s.bin_resolution_hz[i]))));
}

/// Two-sided χ² acceptance interval of a ratio Ŝ/S with NU dof, tail probability P.
std::pair<double, double> chi2_interval(double nu, double p) {
  return {chi_square_quantile(0.5 * p, nu) / nu, chi_square_upper_quantile(0.5 * p, nu) / nu};
}

// ---------------------------------------------------------------------------------------------
// Plan, levels and the classic case

TEST(MultiratePsd, PlanKeepsTheClassicResolutionWithShortSegments) {
  // 24 h at 1 kHz: L₀ = 2^23 → L = 4096 at 12 levels (D = 11); 8 h at 400 Hz (11.52 M): 2^20
  // → D = 8; 10 000 samples: L₀ = 1024 ≤ 4096, one level.
  EXPECT_EQ(multirate_plan(86'400'000).segment_length, 4096u);
  EXPECT_EQ(multirate_plan(86'400'000).deepest_level, 11u);
  EXPECT_EQ(multirate_plan(11'520'000).deepest_level, 8u);
  EXPECT_EQ(multirate_plan(10'000).segment_length, 1024u);
  EXPECT_EQ(multirate_plan(10'000).deepest_level, 0u);
  MultirateOptions o;
  o.level_segment_length = 1024;
  o.welch.segment_length = 1 << 15;
  EXPECT_EQ(multirate_plan(100, o).deepest_level, 5u);  // given L₀: the record size is not used

  const auto x = white(std::size_t{1} << 20, 1.0, 1);
  const Spectrum m = multirate_psd(x, 100.0);
  const Spectrum c = log_bin(welch_psd(x, 100.0), 10);
  EXPECT_EQ(m.resolution_hz, c.resolution_hz);  // f_s/L₀, L₀ = 2^17
  EXPECT_EQ(m.segment_length, 4096u);
  EXPECT_EQ(m.sample_rate_hz, 100.0);
  // The bins of the deepest level are the classic bins: same raw grid, same frequencies.
  std::size_t deepest_bins = 0;
  for (std::size_t i = 0; i < m.frequency_hz.size() && level_of(m, i) == 5; ++i) {
    EXPECT_EQ(m.frequency_hz[i], c.frequency_hz[i]);
    EXPECT_EQ(m.first_raw_bin[i], c.first_raw_bin[i]);
    EXPECT_EQ(m.raw_bins[i], c.raw_bins[i]);
    ++deepest_bins;
  }
  EXPECT_GE(deepest_bins, 25u);  // 2^17/4 raw bins: from 7.6e-4 Hz to ~0.8 Hz, 3 decades
  // Deepest level: n_D = 32 731 samples (5 decimations, each (n − 39)/2 + 1), K = 14.
  std::size_t n_d = x.size();
  for (int d = 0; d < 5; ++d) n_d = halfband_outputs(n_d);
  EXPECT_EQ(m.segments, (n_d - 4096) / 2048 + 1);
  EXPECT_EQ(m.segments, 14u);
}

TEST(MultiratePsd, EachBinComesFromTheDeepestLevelWhoseBandHoldsItAll) {
  // Stated rule: level d ≥ 1 is usable for raw bins j ≤ L/4 − 2 (main lobe inside the
  // passband f_d/4); a bin is taken from the deepest level holding it whole, which is the one
  // with the most raw bins in it.
  const auto x = white(std::size_t{1} << 21, 1.0, 2);
  const double rate = 200.0;
  const Spectrum s = multirate_psd(x, rate);
  const std::size_t l = s.segment_length;
  ASSERT_EQ(s.bin_resolution_hz.size(), s.frequency_hz.size());
  int previous_level = std::numeric_limits<int>::max();
  std::vector<int> bins_per_level(7, 0);
  for (std::size_t i = 0; i < s.frequency_hz.size(); ++i) {
    const int d = level_of(s, i);
    ASSERT_GE(d, 0);
    ASSERT_LE(d, 6);  // L₀ = 2^18 = 4096·2^6
    EXPECT_LE(d, previous_level) << "levels must not deepen with frequency";
    previous_level = d;
    ++bins_per_level[static_cast<std::size_t>(d)];
    if (i > 0) {
      EXPECT_GT(s.frequency_hz[i], s.frequency_hz[i - 1]);
    }
    const std::size_t last = s.first_raw_bin[i] + s.raw_bins[i] - 1;
    if (d > 0) {
      EXPECT_LE(last, l / 4 - 2) << "bin " << i << " leaves the usable band of level " << d;
      // Whole bin: the next raw bin after it already falls in the next log bin.
      const double next = static_cast<double>(last + 1) * s.bin_resolution_hz[i];
      EXPECT_GT(std::floor(10.0 * std::log10(next) + 1e-9),
                std::floor(10.0 * std::log10(s.frequency_hz[i]) + 1e-9));
    }
    if (d < 6) {
      // Above the deepest level's band: ≥ 0.1·L·(10^{0.1} − 1) ≈ 106 raw bins per bin, but for
      // the top bin, which Nyquist may cut (here 100 Hz = 10^2 opens a bin of its own, as in
      // log_bin()).
      if (last < l / 2) {
        EXPECT_GE(s.raw_bins[i], 100u) << "bin at " << s.frequency_hz[i] << " Hz";
      }
      // It does not fit the next deeper level: that level's raw bin L/4 − 1 (the first beyond
      // its usable band, at half the spacing) lies in this bin or below it.
      const double beyond = static_cast<double>(l / 4 - 1) * 0.5 * s.bin_resolution_hz[i];
      EXPECT_LE(std::floor(10.0 * std::log10(beyond) + 1e-9),
                std::floor(10.0 * std::log10(s.frequency_hz[i]) + 1e-9));
    }
  }
  for (int d = 0; d <= 6; ++d) EXPECT_GE(bins_per_level[static_cast<std::size_t>(d)], 2) << d;
}

TEST(MultiratePsd, OneLevelIsTheClassicLogBinnedWelchBitForBit) {
  // L₀ = 2048 ≤ 4096: one level, the same segment kernel and binning arithmetic.
  const auto x = white(30000, 0.7, 3);
  const Spectrum c = log_bin(welch_psd(x, 50.0), 10);
  const Spectrum m = multirate_psd(x, 50.0);
  EXPECT_EQ(m.frequency_hz, c.frequency_hz);
  ASSERT_EQ(m.density.size(), c.density.size());
  for (std::size_t i = 0; i + 1 < m.density.size(); ++i) EXPECT_EQ(m.density[i], c.density[i]);
  // The top bin ends at Nyquist (raw bin L/2, c = 1): Σ S₁/(n − ½) instead of Σ S₁/n.
  const double n_top = static_cast<double>(m.raw_bins.back());
  EXPECT_EQ(m.first_raw_bin.back() + m.raw_bins.back() - 1, 1024u);
  EXPECT_NEAR(m.density.back(), c.density.back() * n_top / (n_top - 0.5), 1e-15 * m.density.back());
  EXPECT_EQ(m.dof, c.dof);
  EXPECT_EQ(m.first_raw_bin, c.first_raw_bin);
  EXPECT_EQ(m.raw_bins, c.raw_bins);
  EXPECT_EQ(m.integrated_power, c.integrated_power);
  EXPECT_EQ(m.segments, c.segments);
  EXPECT_EQ(m.resolution_hz, c.resolution_hz);
  // sample_variance: one blocked pass instead of two passes; equal to rounding.
  EXPECT_NEAR(m.sample_variance, c.sample_variance, 1e-13 * c.sample_variance);
  // Pooled: pooled_welch_psd's numbers bit for bit.
  const std::span<const double> all(x);
  const std::span<const double> pieces[] = {all.subspan(0, 17000), all.subspan(17000, 12000),
                                            all.subspan(29000, 1000)};
  std::size_t used_c = 0, used_m = 0;
  const Spectrum pc = log_bin(pooled_welch_psd(pieces, 50.0, {}, &used_c), 10);
  const Spectrum pm = pooled_multirate_psd(pieces, 50.0, {}, &used_m);
  EXPECT_EQ(used_m, used_c);
  EXPECT_EQ(used_m, 2u);
  for (std::size_t i = 0; i + 1 < pm.density.size(); ++i) EXPECT_EQ(pm.density[i], pc.density[i]);
  EXPECT_EQ(pm.dof, pc.dof);
  EXPECT_EQ(pm.integrated_power, pc.integrated_power);
}

// ---------------------------------------------------------------------------------------------
// Levels of known spectra

TEST(MultiratePsd, WhiteNoiseIsFlatAtTwoNSquaredWithinItsDofInEveryBin) {
  // theory.md §1.2: ARW N sampled as σ = N/√τ0 sits at S₁ = 2N². Exceptions stated by the
  // estimator's maths: raw bin 1 of the deepest level loses 1/6 to the segment mean (Hann:
  // Σ|w − W₁/L|² = Σw² − |W₁|²/L = 3L/8 − L/16, i.e. 5/6); the Nyquist raw bin (c = 1, half
  // the level) counts as half a bin in its mean, so the top bin is at the level. Every bin
  // within its two-sided 1 − 1e-4 χ² interval: ~60 bins, a false alarm in < 1 % of seeds.
  const double rate = 200.0, arw = 0.01;
  const auto x = white(std::size_t{1} << 22, arw * std::sqrt(rate), 4);
  const Spectrum s = multirate_psd(x, rate);
  ASSERT_GE(level_of(s, 0), 7);
  double weighted = 0.0, dof_sum = 0.0;
  for (std::size_t i = 0; i < s.density.size(); ++i) {
    double factor = 0.0;
    for (std::size_t j = s.first_raw_bin[i]; j < s.first_raw_bin[i] + s.raw_bins[i]; ++j) {
      factor += j == 1 ? 5.0 / 6.0 : (j == s.segment_length / 2 ? 0.5 : 1.0);
    }
    factor /= static_cast<double>(s.raw_bins[i]) - (holds_nyquist(s, i) ? 0.5 : 0.0);
    const double ratio = s.density[i] / (2.0 * arw * arw * factor);
    const auto [lo, hi] = chi2_interval(s.dof[i], 1e-4);
    EXPECT_GE(ratio, lo) << "bin " << s.frequency_hz[i] << " Hz, level " << level_of(s, i)
                         << ", dof " << s.dof[i];
    EXPECT_LE(ratio, hi) << "bin " << s.frequency_hz[i] << " Hz, level " << level_of(s, i)
                         << ", dof " << s.dof[i];
    weighted += s.dof[i] * ratio;
    dof_sum += s.dof[i];
  }
  // The dof-weighted mean ratio: sd ≈ √(2/Σν) (the bins cover disjoint bands) = 0.14 %; 4 sd.
  EXPECT_NEAR(weighted / dof_sum, 1.0, 4.0 * std::sqrt(2.0 / dof_sum));
}

/// Records of the red processes: R records of 2^18 samples at 100 Hz, L = 256 (L₀ = 2^15:
/// 8 levels, the deepest at 0.78 Hz, K = 14), so the comparison reaches the lowest bins with
/// R·ν ≥ 1000 dof per bin (R = 40: ±4.5 % sd).
void expect_follows_expected_value(const std::function<std::vector<double>(std::uint64_t)>& make,
                                   const std::function<double(double)>& s1, int records,
                                   const char* name) {
  const int kRecords = records;
  MultirateOptions options;
  options.level_segment_length = 256;
  std::vector<double> sum;
  Spectrum s;
  for (int r = 0; r < kRecords; ++r) {
    s = multirate_psd(make(static_cast<std::uint64_t>(100 + r)), 100.0, options);
    sum.resize(s.density.size(), 0.0);
    for (std::size_t i = 0; i < s.density.size(); ++i) sum[i] += s.density[i];
  }
  ASSERT_EQ(level_of(s, 0), 7);
  // The closed form itself, smoothed by the Hann kernel (the exact Welch expectation), per bin;
  // the mean over R independent records of Ŝ/E has R·ν dof. Two-sided 1e-5 interval per bin
  // (~50 bins: a false alarm in 0.05 % of seed sets).
  std::size_t compared = 0, deepest = 0;
  double worst_smoothing = 0.0;  // |E/S(f) − 1| above raw bin 10
  for (std::size_t i = 0; i < s.density.size(); ++i) {
    if (s.first_raw_bin[i] < 2) continue;  // bin 1: the segment mean removal reshapes it
    const double expected = expected_bin(s, i, s1);
    const double ratio = sum[i] / kRecords / expected;
    const auto [lo, hi] = chi2_interval(kRecords * s.dof[i], 1e-5);
    EXPECT_GE(ratio, lo) << name << " bin " << s.frequency_hz[i] << " Hz, level " << level_of(s, i)
                         << ", raw bins from " << s.first_raw_bin[i];
    EXPECT_LE(ratio, hi) << name << " bin " << s.frequency_hz[i] << " Hz, level " << level_of(s, i)
                         << ", raw bins from " << s.first_raw_bin[i];
    ++compared;
    if (level_of(s, i) == 7) ++deepest;
    if (s.first_raw_bin[i] >= 10) {
      double plain = 0.0;
      for (std::size_t j = 0; j < s.raw_bins[i]; ++j) {
        plain += s1(static_cast<double>(s.first_raw_bin[i] + j) * s.bin_resolution_hz[i]);
      }
      plain /= static_cast<double>(s.raw_bins[i]);
      if (s.first_raw_bin[i] + s.raw_bins[i] - 1 < s.segment_length / 2) {
        worst_smoothing = std::max(worst_smoothing, std::fabs(expected / plain - 1.0));
      }
    }
  }
  EXPECT_GE(compared, 38u) << name;
  EXPECT_GE(deepest, 13u) << name;  // down to raw bin 2 of the deepest level
  // From raw bin 10 up the window's main lobe moves the expectation by < 1.1 % (≈ 1/j² for
  // f⁻², 1/(3j²) for f⁻¹): there the estimate follows the closed form itself.
  EXPECT_LT(worst_smoothing, 0.011) << name;
}

TEST(MultiratePsd, RandomWalkFollowsItsClosedFormDownToTheLowestBins) {
  const double sigma = 1e-3, tau0 = 0.01;
  expect_follows_expected_value(
      [&](std::uint64_t seed) { return random_walk(std::size_t{1} << 18, sigma, seed); },
      [&](double f) {
        const double s = 2.0 * std::sin(kPi * f * tau0);
        return 2.0 * sigma * sigma * tau0 / (s * s);
      },
      64, "random walk");
}

TEST(MultiratePsd, FlickerFollowsItsClosedFormDownToTheLowestBins) {
  const double sigma = 1e-3, tau0 = 0.01;
  expect_follows_expected_value(
      [&](std::uint64_t seed) { return flicker(std::size_t{1} << 18, sigma, seed); },
      [&](double f) { return 2.0 * sigma * sigma * tau0 / (2.0 * std::sin(kPi * f * tau0)); }, 40,
      "flicker");
}

TEST(MultiratePsd, ExpectationHelperIntegratesAFlatSpectrumToItsLevel) {
  // The quadrature of the test itself: ∫K = 1 except the kernel beyond ±48 bins (< 1e-9).
  for (const std::size_t j : {2u, 3u, 40u, 100u}) {
    EXPECT_NEAR(expected_raw([](double) { return 1.0; }, j, 0.1, 256), 1.0, 1e-9) << j;
  }
  EXPECT_NEAR(expected_raw([](double) { return 1.0; }, 128, 0.1, 256), 0.5, 1e-9);
}

TEST(MultiratePsd, SinusoidPowerIsHalfAmplitudeSquaredAtShallowAndDeepLevels) {
  // A·sin(2πf₀t) carries A²/2 (theory.md §5.3). 2^20 samples at 100 Hz, L₀ = 2^17: 6 levels.
  // Lines at 34.3 Hz (level 0), 2.23 Hz (level 3) and 0.29 Hz (level 5, the deepest), each
  // away from log-bin edges and level boundaries. Power = Σ S₁·(raw bins)·Δf over the bins
  // within ±8 raw bins of the line, minus the white floor 2N² over the same bandwidth.
  const double rate = 100.0, arw = 1e-3, amplitude = 0.2;
  const std::size_t n = std::size_t{1} << 20;
  const double lines[] = {34.3, 2.23, 0.29};
  const int levels[] = {0, 3, 5};
  for (int k = 0; k < 3; ++k) {
    auto x = white(n, arw * std::sqrt(rate), 20 + static_cast<std::uint64_t>(k));
    for (std::size_t t = 0; t < n; ++t) {
      x[t] += amplitude * std::sin(2.0 * kPi * lines[k] * static_cast<double>(t) / rate + 0.3);
    }
    const Spectrum s = multirate_psd(x, rate);
    double power = 0.0, floor = 0.0;
    int line_level = -1;
    for (std::size_t i = 0; i < s.density.size(); ++i) {
      const double df = s.bin_resolution_hz[i];
      const double lo = static_cast<double>(s.first_raw_bin[i]) * df;
      const double hi = static_cast<double>(s.first_raw_bin[i] + s.raw_bins[i] - 1) * df;
      if (hi < lines[k] - 8.0 * df || lo > lines[k] + 8.0 * df) continue;
      const double width = static_cast<double>(s.raw_bins[i]) * df;
      power += s.density[i] * width;
      floor += 2.0 * arw * arw * width;
      if (lines[k] >= lo && lines[k] <= hi) line_level = level_of(s, i);
    }
    EXPECT_EQ(line_level, levels[k]) << lines[k] << " Hz";
    // The floor (≤ 2N²·0.26·f₀ = 1.8e-5 at 34.3 Hz, 9e-4 of the line) is known to its relative
    // sd √(2/ν) < 1 %, i.e. < 1e-5 of the line; the line × noise cross term has relative sd
    // ≈ √(2·4·2N²Δf/(A²/2))/√K_eff < 1e-4. Sidelobes beyond ±8 bins hold < 1e-6 of a Hann
    // line. 0.2 % is > 10 sd.
    EXPECT_NEAR((power - floor) / (0.5 * amplitude * amplitude), 1.0, 2e-3) << lines[k] << " Hz";
  }
}

// ---------------------------------------------------------------------------------------------
// Degrees of freedom and Parseval

TEST(MultiratePsd, StatedDofMatchesTheSpreadOverFourHundredRecords) {
  // 400 white records of 2^16 samples, L = 256 (L₀ = 2^13, 6 levels, shallow bins of ~7 raw
  // bins: the regime where the correlation of neighbouring Hann bins matters most). For each
  // bin, Var(Ŝ)/E(Ŝ)² must be 2/ν. The sample variance of R values of a χ²_ν/ν variable has
  // relative sd √(2/(R − 1) + κ/R), κ = 12/ν its excess kurtosis: ≤ 8 % here; each bin within
  // 4.4 sd (~40 bins: 0.04 % false alarms), and the mean ratio over the bins within 4 sd of
  // its own sd (bins of disjoint bands are independent).
  constexpr int kRecords = 400;
  MultirateOptions options;
  options.level_segment_length = 256;
  std::vector<std::vector<double>> density;  // [record][bin]
  Spectrum s;
  for (int r = 0; r < kRecords; ++r) {
    s = multirate_psd(white(std::size_t{1} << 16, 1.0, 5000 + static_cast<std::uint64_t>(r)), 1.0,
                      options);
    density.push_back(s.density);
  }
  ASSERT_EQ(level_of(s, 0), 5);
  const std::size_t n_bins = s.density.size();
  std::vector<double> sum(n_bins, 0.0), sum2(n_bins, 0.0);
  for (const auto& d : density) {
    for (std::size_t i = 0; i < n_bins; ++i) {
      sum[i] += d[i];
      sum2[i] += d[i] * d[i];
    }
  }
  // Coverage of the stated 90 % interval, with the level from the mean over all records (known
  // to ±√(2/(Rν)) ≤ 2.5 %, which moves the coverage of a 90 % interval by ≤ 1 point).
  std::vector<int> inside(n_bins, 0);
  for (const auto& d : density) {
    for (std::size_t i = 0; i < n_bins; ++i) {
      const auto [lo, hi] = chi2_interval(s.dof[i], 0.10);
      const double ratio = d[i] / (sum[i] / kRecords);
      inside[i] += ratio >= lo && ratio <= hi ? 1 : 0;
    }
  }
  double ratio_sum = 0.0, ratio_var = 0.0;
  int bins = 0, trials = 0, covered = 0;
  std::vector<int> levels_seen(6, 0);
  for (std::size_t i = 0; i < n_bins; ++i) {
    if (s.first_raw_bin[i] < 2) continue;  // bin 1: the segment mean removal reshapes it
    const double mean = sum[i] / kRecords;
    const double var = (sum2[i] - kRecords * mean * mean) / (kRecords - 1);
    const double ratio = var / (mean * mean) * s.dof[i] / 2.0;
    const double sd = std::sqrt(2.0 / (kRecords - 1) + 12.0 / s.dof[i] / kRecords);
    EXPECT_NEAR(ratio, 1.0, 4.4 * sd)
        << "bin " << s.frequency_hz[i] << " Hz, level " << level_of(s, i) << ", " << s.raw_bins[i]
        << " raw bins, dof " << s.dof[i];
    ratio_sum += ratio;
    ratio_var += sd * sd;
    ++bins;
    ++levels_seen[static_cast<std::size_t>(level_of(s, i))];
    trials += kRecords;
    covered += inside[i];
  }
  for (int d = 0; d < 6; ++d) EXPECT_GE(levels_seen[static_cast<std::size_t>(d)], 2) << d;
  EXPECT_NEAR(ratio_sum / bins, 1.0, 4.0 * std::sqrt(ratio_var) / bins);
  // Coverage of the stated 90 % χ² interval, pooled: binomial sd √(0.09/trials) = 0.24 %
  // (bins nearly independent); the χ² shape itself is an approximation for the bins of a
  // few raw bins, so allow 1.5 points (> 6 sd).
  EXPECT_NEAR(static_cast<double>(covered) / trials, 0.90, 0.015);
}

TEST(MultiratePsd, ParsevalIntegratedPowerMatchesSampleVariance) {
  // Σ S₁·Δf over the raw bins behind the bins (plus the deepest DC bin) against the mean
  // square. As for Welch (psd_test): Hann-weighted vs uniform mean of x² (sd 3e-4 at 2^20),
  // the segment means (−1/L per level, 2e-4), and here the tiling between levels, exact to one
  // raw bin per boundary: Σ_d Δf_d/(f_s/2) ≈ 4/L = 1e-3. 1 % is > 3× the sum.
  const auto x = white(std::size_t{1} << 20, 0.3, 6);
  const Spectrum s = multirate_psd(x, 200.0);
  EXPECT_NEAR(s.integrated_power / s.sample_variance, 1.0, 0.01);
  EXPECT_NEAR(s.sample_variance, 0.09, 0.09 * 5.0 * std::sqrt(2.0 / static_cast<double>(x.size())));
  // The bins alone: Σ density·(raw bins)·Δf is the same sum without the DC bin (the Nyquist
  // raw bin counting as half a bin).
  double bins = 0.0;
  for (std::size_t i = 0; i < s.density.size(); ++i) {
    const double width = static_cast<double>(s.raw_bins[i]) - (holds_nyquist(s, i) ? 0.5 : 0.0);
    bins += s.density[i] * width * s.bin_resolution_hz[i];
  }
  EXPECT_NEAR(bins / s.integrated_power, 1.0, 1e-4);
  // Linear detrend: the sample variance about the least-squares line, one blocked pass.
  std::vector<double> ramp = x;
  for (std::size_t k = 0; k < ramp.size(); ++k) ramp[k] += 5.0 + 1e-4 * static_cast<double>(k);
  MultirateOptions linear;
  linear.welch.detrend = Detrend::linear;
  const Spectrum r = multirate_psd(ramp, 200.0, linear);
  EXPECT_NEAR(r.sample_variance / s.sample_variance, 1.0, 1e-3);  // the line, not the noise, goes
  EXPECT_NEAR(r.integrated_power / r.sample_variance, 1.0, 0.01);
}

// ---------------------------------------------------------------------------------------------
// Pieces, determinism, errors

/// Segment count of a piece of N samples at level D (L = 4096, step 2048).
std::size_t segments_at(std::size_t n, int d) {
  for (int k = 0; k < d; ++k) n = halfband_outputs(n);
  return n < 4096 ? 0 : (n - 4096) / 2048 + 1;
}

TEST(MultiratePsd, PooledPiecesAverageTheirSegmentsLevelByLevel) {
  const auto x = white(std::size_t{1} << 21, 1.0, 7);
  const std::span<const double> all(x);
  // One piece: exactly multirate_psd.
  const std::span<const double> one[] = {all};
  const Spectrum single = multirate_psd(x, 10.0);
  const Spectrum pooled_one = pooled_multirate_psd(one, 10.0);
  EXPECT_EQ(single.density, pooled_one.density);
  EXPECT_EQ(single.dof, pooled_one.dof);
  // Three pieces: the longest (2^20) fixes L₀ = 2^17 (D = 5); the second (100 000 samples,
  // 3090 at level 5) has segments down to level 4 only, the third (3000) is shorter than
  // L = 4096 and is left out.
  const std::span<const double> a = all.subspan(0, std::size_t{1} << 20);
  const std::span<const double> b = all.subspan(std::size_t{1} << 20, 100000);
  const std::span<const double> c = all.subspan((std::size_t{1} << 20) + 100000, 3000);
  const std::span<const double> pieces[] = {a, b, c};
  std::size_t used = 0;
  const Spectrum p = pooled_multirate_psd(pieces, 10.0, {}, &used);
  EXPECT_EQ(used, 2u);
  EXPECT_EQ(p.resolution_hz, multirate_psd(a, 10.0).resolution_hz);
  EXPECT_EQ(p.segments, segments_at(a.size(), 5) + segments_at(b.size(), 5));
  EXPECT_EQ(segments_at(b.size(), 5), 0u);
  // Each level: the K-weighted mean of the pieces' spectra with the same plan. The pieces'
  // own spectra at L₀ = 2^17 (the second throws at the deepest level: it is too short).
  MultirateOptions fixed;
  fixed.welch.segment_length = std::size_t{1} << 17;
  const Spectrum sa = multirate_psd(a, 10.0, fixed);
  test::expect_throw_containing<ContractViolation>([&] { (void)multirate_psd(b, 10.0, fixed); },
                                                   "shorter than one segment of 4096 samples at "
                                                   "level 5");
  MultirateOptions shallow = fixed;
  shallow.welch.segment_length = std::size_t{1} << 16;  // b's own plan: levels 0 … 4
  const Spectrum sb = multirate_psd(b, 10.0, shallow);
  ASSERT_EQ(sa.density.size(), p.density.size());
  std::size_t checked = 0;
  for (std::size_t i = 0; i < p.density.size(); ++i) {
    const int d = level_of(p, i);
    if (d == 5) {
      EXPECT_EQ(p.density[i], sa.density[i]);  // only the long piece reaches it
      continue;
    }
    // Same bin in b's spectrum (same level spacing, same raw bins).
    const auto it = std::find(sb.first_raw_bin.begin(), sb.first_raw_bin.end(), p.first_raw_bin[i]);
    const std::size_t k = static_cast<std::size_t>(it - sb.first_raw_bin.begin());
    if (it == sb.first_raw_bin.end() || sb.bin_resolution_hz[k] != p.bin_resolution_hz[i]) continue;
    const double ka = static_cast<double>(segments_at(a.size(), d));
    const double kb = static_cast<double>(segments_at(b.size(), d));
    EXPECT_NEAR(p.density[i], (ka * sa.density[i] + kb * sb.density[k]) / (ka + kb),
                1e-12 * p.density[i]);
    EXPECT_GT(p.dof[i], sa.dof[i]);
    ++checked;
  }
  EXPECT_GE(checked, 10u);
  // Sample variance: the sample-weighted mean over the pieces used.
  EXPECT_NEAR(p.sample_variance,
              (static_cast<double>(a.size()) * sa.sample_variance +
               static_cast<double>(b.size()) * sb.sample_variance) /
                  static_cast<double>(a.size() + b.size()),
              1e-14);
  // No piece long enough for one segment: a clear error.
  const std::span<const double> short_pieces[] = {c};
  test::expect_throw_containing<ContractViolation>(
      [&] { (void)pooled_multirate_psd(short_pieces, 10.0, fixed); }, "no piece is as long");
}

TEST(MultiratePsd, DeterministicAndIndependentOfConcurrentCalls) {
  const auto x = white(std::size_t{1} << 19, 1.0, 8);
  const Spectrum serial = multirate_psd(x, 100.0);
  std::vector<Spectrum> parallel(3);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < parallel.size(); ++t) {
    threads.emplace_back([&, t] { parallel[t] = multirate_psd(x, 100.0); });
  }
  for (std::thread& thread : threads) thread.join();
  for (const Spectrum& p : parallel) {
    EXPECT_EQ(p.density, serial.density);
    EXPECT_EQ(p.dof, serial.dof);
  }
}

TEST(MultiratePsd, CrossCheckAndReadoffReadTheLevelsRight) {
  // White + random walk: the truth passes the cross-check (which averages the model over each
  // bin's raw frequencies at that bin's spacing), N × 1.5 fails; the read-off finds N and K.
  const double rate = 100.0, arw = 2e-3, k = 1e-4;
  const std::size_t n = std::size_t{1} << 21;
  auto x = white(n, arw * std::sqrt(rate), 9);
  const auto walk = random_walk(n, k / std::sqrt(rate), 10);  // K² = σ²/τ0
  for (std::size_t t = 0; t < n; ++t) x[t] += walk[t];
  const Spectrum s = multirate_psd(x, rate);
  NoiseCoefficients truth;
  truth.white_noise = arw;
  truth.random_walk = k;
  const PsdCrossCheck good = cross_check_psd(s, truth, 1.0 / rate);
  EXPECT_TRUE(good.pass) << good.bins_outside << " of " << good.bins_compared;
  EXPECT_GE(good.bins_compared, 40u);
  EXPECT_GE(good.f_min_hz, 3.0 * s.resolution_hz);
  NoiseCoefficients wrong = truth;
  wrong.white_noise = 1.5 * arw;
  EXPECT_FALSE(cross_check_psd(s, wrong, 1.0 / rate).pass);
  // Read-offs (tolerances as psd_test's: a read-off, not an estimator): N of white noise, K of
  // a pure random walk (linear detrend, as psd_test), Q of white angle noise.
  const PsdReadoff rn = psd_readoff(multirate_psd(white(n, arw * std::sqrt(rate), 12), rate));
  ASSERT_TRUE(rn.terms[NoiseTerm::white_noise].found);
  EXPECT_NEAR(rn.terms[NoiseTerm::white_noise].value / arw, 1.0, 0.02);
  MultirateOptions linear;
  linear.welch.detrend = Detrend::linear;
  const PsdReadoff rk = psd_readoff(multirate_psd(walk, rate, linear));
  ASSERT_TRUE(rk.terms[NoiseTerm::random_walk].found);
  EXPECT_NEAR(rk.terms[NoiseTerm::random_walk].value / k, 1.0, 0.10);
  // Q uses τ0 = 1/sample_rate_hz (resolution_hz·segment_length is f_s/2^D here): white angle
  // noise of σ_θ = Q gives rate (θ_k − θ_{k−1})/τ0, S₁ = 2(2 sin πfτ0)²Q²/τ0 ≈ 2(2πf)²τ0Q².
  const double q = 1e-5;
  const auto theta = white(n + 1, q, 11);
  std::vector<double> rate_q(n);
  for (std::size_t t = 0; t < n; ++t) rate_q[t] = (theta[t + 1] - theta[t]) * rate;
  const PsdReadoff rq = psd_readoff(multirate_psd(rate_q, rate));
  ASSERT_TRUE(rq.terms[NoiseTerm::quantization].found);
  // The +2 region reaches up to where sin πfτ0 bends below πfτ0 (−10 % at 0.1·f_s): 15 %.
  EXPECT_NEAR(rq.terms[NoiseTerm::quantization].value / q, 1.0, 0.15);
}

TEST(MultiratePsd, RejectsBadInputWithAClearMessage) {
  using test::expect_throw_containing;
  MultirateOptions bad;
  bad.level_segment_length = 1000;
  expect_throw_containing<ContractViolation>(
      [&] { (void)multirate_plan(1 << 20, bad); },
      "level_segment_length must be a power of two >= 256 (got 1000)");
  bad.level_segment_length = 128;
  expect_throw_containing<ContractViolation>([&] { (void)multirate_plan(1 << 20, bad); },
                                             "power of two >= 256 (got 128)");
  MultirateOptions odd;
  odd.welch.segment_length = 3 * 4096;
  expect_throw_containing<ContractViolation>([&] { (void)multirate_plan(1 << 20, odd); },
                                             "L0 = 12288 must be level_segment_length (4096)");
  expect_throw_containing<ContractViolation>(
      [] { (void)multirate_psd(std::vector<double>(10), 1.0); }, "too short");
  std::vector<double> x = white(std::size_t{1} << 17, 1.0, 12);
  x[70000] = std::numeric_limits<double>::quiet_NaN();
  expect_throw_containing<ContractViolation>([&] { (void)multirate_psd(x, 1.0); },
                                             "sample 70000 is not finite");
  x[70000] = 0.0;
  expect_throw_containing<ContractViolation>([&] { (void)multirate_psd(x, 0.0); },
                                             "sample rate must be finite and > 0");
  MultirateOptions long_l0;
  long_l0.welch.segment_length = std::size_t{1} << 18;
  expect_throw_containing<ContractViolation>([&] { (void)multirate_psd(x, 1.0, long_l0); },
                                             "shorter than one segment");
}

}  // namespace
}  // namespace imunoise::analysis
