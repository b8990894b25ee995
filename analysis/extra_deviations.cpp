#include "analysis/extra_deviations.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "analysis/difference_sums.h"
#include "analysis/kernel_support.h"
#include "common/errors.h"

namespace imunoise::analysis {

namespace {

using detail::blocked_sum;
using detail::CompensatedSum;

/// Σ_{i<n} Σ_{j=1}^{h} (1/j)·[(x_i − x_{i+j}) + (x_{i+m} − x_{i+m−j})]², n = M − m, h = m/2.
///
/// Why not O(M): expanding the square leaves Σ_i x_{i+j}·x_{i+m−j}/j, a sum of lag-(m−2j)
/// products over windows that move with j — one autocorrelation lag per j, so prefix sums of
/// x and x² (or of k·x) do not collapse it; an exact fast form needs FFT correlations (or the
/// all-τ Lewis recursion), and the expanded form would also cancel badly on offset data. So
/// the loop order is j outside (weight applied once per j), i inside over contiguous data in
/// blocked compensated sums: O(n·h), each bracket formed as two differences.
double theo1_sum(const double* x, std::int64_t n, std::int64_t m) {
  const std::int64_t h = m / 2;
  CompensatedSum total;
  for (std::int64_t j = 1; j <= h; ++j) {
    const double* a = x;          // x_i
    const double* b = x + j;      // x_{i+j}
    const double* c = x + m;      // x_{i+m}
    const double* d = x + m - j;  // x_{i+m−j}
    const double s = blocked_sum(n, [&](std::int64_t i) {
      const double v = (a[i] - b[i]) + (c[i] - d[i]);
      return v * v;
    });
    total.add(s / static_cast<double>(j));
  }
  return total.value();
}

/// Σ_{i<n} S_i², S_i = Σ_{k=0}^{m−1} c_k·d_{i+k}, c_k = (m−1)/2 − k, d_l = x_l − x_{l+m}.
///
/// O(M) form: with W_i = Σ_{l=i}^{i+m−1} d_l (a sliding window sum) and c_{k−1} = c_k + 1,
///   W_{i+1} = W_i − d_i + d_{i+m},   S_{i+1} = S_i − c_0·d_i + c_m·d_{i+m} + W_{i+1},
/// c_0 = (m−1)/2, c_m = −(m+1)/2 — the prefix-sum identity of the brief (weights (m−1)/2 − k
/// ⇒ sums of d and k·d) written as differences, so no prefix array whose magnitude grows with
/// the record (and cancels digits) is ever formed. S integrates W's rounding error, so both
/// are recomputed exactly every K = max(m, 32) steps: O(m) per restart, O(M) overall, and
/// the drift stays ≲ √m·ε relative.
double parabolic_sum(const double* x, std::int64_t n, std::int64_t m) {
  const double c0 = 0.5 * static_cast<double>(m - 1);
  const double cm = -0.5 * static_cast<double>(m + 1);
  auto d = [&](std::int64_t l) { return x[l] - x[l + m]; };
  const std::int64_t restart = std::max<std::int64_t>(m, 32);
  CompensatedSum total;
  for (std::int64_t i0 = 0; i0 < n; i0 += restart) {
    const std::int64_t i1 = std::min(n, i0 + restart);
    double s = 0.0;
    double w = 0.0;
    for (std::int64_t k = 0; k < m; ++k) {
      const double dk = d(i0 + k);
      s += (c0 - static_cast<double>(k)) * dk;
      w += dk;
    }
    double block = s * s;
    for (std::int64_t i = i0; i + 1 < i1; ++i) {
      const double di = d(i);
      const double dim = d(i + m);
      w += dim - di;
      s += (cm * dim - c0 * di) + w;
      block += s * s;
    }
    total.add(block);
  }
  return total.value();
}

}  // namespace

VarianceEstimate theo1_variance(std::span<const double> phase, std::int64_t m, double tau0_s,
                                bool bias_corrected, int alpha) {
  const auto M = static_cast<std::int64_t>(phase.size());
  IMUNOISE_EXPECT(m >= 2 && m % 2 == 0,
                  "theo1: averaging factor must be even and >= 2, got " + std::to_string(m));
  IMUNOISE_CHECK(m <= M - 1, AnalysisError,
                 "theo1: averaging factor " + std::to_string(m) + " needs at least " +
                     std::to_string(m + 1) + " phase samples, got " + std::to_string(M));
  detail::check_sample_period(tau0_s);
  IMUNOISE_CHECK(alpha >= -2 && alpha <= 2, AnalysisError,
                 "theo1: noise exponent alpha must be in -2..2, got " + std::to_string(alpha));
  const std::int64_t n = M - m;
  const double tau = static_cast<double>(m) * tau0_s;
  VarianceEstimate out;
  out.n_terms = n * (m / 2);
  out.variance = theo1_sum(phase.data(), n, m) / (0.75 * static_cast<double>(n) * tau * tau);
  if (bias_corrected) {
    // SP 1065 Thêo1 bias table: AVAR/Theo1 = a + b/t^c, t = 0.75·m (see header).
    struct Coefficients {
      double a, b, c;
    };
    static constexpr Coefficients kTable[5] = {
        {2.70, -1.53, 0.85},  // α = −2, random-walk rate
        {1.87, -1.05, 0.79},  // α = −1, flicker rate
        {1.00, 0.00, 0.00},   // α =  0, white rate
        {0.14, 0.82, 0.30},   // α = +1, flicker angle
        {0.09, 0.74, 0.40},   // α = +2, white angle
    };
    const Coefficients& k = kTable[alpha + 2];
    const double t = 0.75 * static_cast<double>(m);
    out.variance *= k.a + k.b / std::pow(t, k.c);
  }
  return out;
}

double theo1_edf(int alpha, std::int64_t m, std::int64_t n_phase) {
  IMUNOISE_CHECK(alpha >= -2 && alpha <= 2, AnalysisError,
                 "theo1_edf: noise exponent alpha must be in -2..2, got " + std::to_string(alpha));
  IMUNOISE_CHECK(m >= 2 && m % 2 == 0 && m < n_phase, AnalysisError,
                 "theo1_edf: need even 2 <= m < N, got m = " + std::to_string(m) +
                     ", N = " + std::to_string(n_phase));
  const double N = static_cast<double>(n_phase);
  const double t = 0.75 * static_cast<double>(m);
  double edf = 0.0;
  switch (alpha) {
    case 2:
      edf = 0.86 * (N + 1.0) * (N - 4.0 * t / 3.0) / (N - t) * (t / (t + 1.14));
      break;
    case 1:
      edf = (4.798 * N * N - 6.374 * N * t + 12.387 * t) / (std::sqrt(t + 36.6) * (N - t)) *
            (t / (t + 0.3));
      break;
    case 0: {
      const double t15 = t * std::sqrt(t);
      edf = ((4.1 * N + 0.8) / t - (3.1 * N + 6.5) / N) * (t15 / (t15 + 5.2));
      break;
    }
    case -1: {
      const double t3 = t * t * t;
      edf = (2.0 * N * N - 1.3 * N * t - 3.5 * t) / (N * t) * (t3 / (t3 + 2.3));
      break;
    }
    default: {  // −2
      const double u = 4.4 * N - 1.0;
      edf = (4.4 * N - 2.0) / (2.9 * t) *
            ((u * u - 8.6 * t * u + 11.4 * t * t) / ((4.4 * N - 3.0) * (4.4 * N - 3.0)));
      break;
    }
  }
  IMUNOISE_CHECK(edf > 0.0 && std::isfinite(edf), AnalysisError,
                 "theo1_edf: the SP 1065 fit gives no positive EDF at m = " + std::to_string(m) +
                     ", N = " + std::to_string(n_phase) + ", alpha = " + std::to_string(alpha));
  return edf;
}

VarianceEstimate parabolic_variance(std::span<const double> phase, std::int64_t m, double tau0_s) {
  const auto M = static_cast<std::int64_t>(phase.size());
  IMUNOISE_EXPECT(m >= 1, "pdev: averaging factor must be >= 1, got " + std::to_string(m));
  detail::check_sample_period(tau0_s);
  IMUNOISE_CHECK(M - 2 * m >= 1, AnalysisError,
                 "pdev: too few samples at m = " + std::to_string(m) + ": " + std::to_string(M) +
                     " phase samples give no term (need >= " + std::to_string(2 * m + 1) + ")");
  if (m == 1) {  // PDEV at m = 1 is OADEV (SP 1065)
    return {detail::lag_one_overlapping_variance(phase, 2, tau0_s), M - 2};
  }
  const std::int64_t n = M - 2 * m;
  const double md = static_cast<double>(m);
  const double tau = md * tau0_s;
  VarianceEstimate out;
  out.n_terms = n;
  out.variance = 72.0 * parabolic_sum(phase.data(), n, m) /
                 (static_cast<double>(n) * md * md * md * md * tau * tau);
  return out;
}

VarianceEstimate sample_variance_of_averages(std::span<const double> phase, std::int64_t m,
                                             double tau0_s) {
  const auto M = static_cast<std::int64_t>(phase.size());
  IMUNOISE_EXPECT(m >= 1, "std dev: averaging factor must be >= 1, got " + std::to_string(m));
  detail::check_sample_period(tau0_s);
  const std::int64_t J = M >= 1 ? (M - 1) / m : 0;
  IMUNOISE_CHECK(J >= 2, AnalysisError,
                 "std dev: too few samples at m = " + std::to_string(m) + ": " + std::to_string(M) +
                     " phase samples give " + std::to_string(J) + " averages (need >= 2)");
  const double* x = phase.data();
  // Mean increment over the J blocks, in phase units; then the two-pass sum of squares.
  const double mean_increment = (x[J * m] - x[0]) / static_cast<double>(J);
  const double s = blocked_sum(J, [&](std::int64_t j) {
    const double u = (x[(j + 1) * m] - x[j * m]) - mean_increment;
    return u * u;
  });
  const double tau = static_cast<double>(m) * tau0_s;
  VarianceEstimate out;
  out.n_terms = J;
  out.variance = s / (static_cast<double>(J - 1) * tau * tau);
  return out;
}

}  // namespace imunoise::analysis
