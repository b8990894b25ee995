#include "analysis/total_family.h"

#include <cmath>
#include <string>
#include <vector>

#include "analysis/deviation_type.h"
#include "analysis/difference_sums.h"
#include "analysis/edf.h"
#include "analysis/kernel_support.h"
#include "common/errors.h"

namespace imunoise::analysis {

namespace {

using detail::CompensatedSum;

/// Mean over one run of 3m samples w_0 … w_{3m−1} (phase for MTOT, frequency for HTOT) of the
/// 6m squared second differences of m-point averages of its 9m-point reflected extension
/// (SP 1065 eq. 27 inner sum; Howe & Vernotte 1999). PREFIX is scratch of 9m + 1 values.
///
/// Trend: h = ⌊3m/2⌋ points at each end are averaged and the slope is the difference of the
/// two means over the distance ⌈3m/2⌉ between their centres. The trend-free run
/// v_i = w_i − (mean₁ + slope·(i − (h−1)/2)) is near zero, which keeps the prefix sums
/// small; it is extended as e = (v reversed, v, v reversed) and the m-point sums are prefix
/// differences, accumulated in long double.
double reflected_run_mean_square(const double* w, std::int64_t m, long double* prefix) {
  const std::int64_t len = 3 * m;
  const std::int64_t h = len / 2;
  double head = 0.0;
  double tail = 0.0;
  for (std::int64_t i = 0; i < h; ++i) {
    head += w[i];
    tail += w[len - h + i];
  }
  const double mean1 = head / static_cast<double>(h);
  const double mean2 = tail / static_cast<double>(h);
  const double slope = (mean2 - mean1) / static_cast<double>(len - h);
  const double centre1 = 0.5 * static_cast<double>(h - 1);
  auto v = [&](std::int64_t i) {
    return w[i] - mean1 - slope * (static_cast<double>(i) - centre1);
  };
  // Prefix sums of the extension e_j, j = 0 … 9m−1.
  prefix[0] = 0.0L;
  std::int64_t j = 0;
  for (std::int64_t i = len - 1; i >= 0; --i, ++j) prefix[j + 1] = prefix[j] + v(i);
  for (std::int64_t i = 0; i < len; ++i, ++j) prefix[j + 1] = prefix[j] + v(i);
  for (std::int64_t i = len - 1; i >= 0; --i, ++j) prefix[j + 1] = prefix[j] + v(i);

  const long double inv_m = 1.0L / static_cast<long double>(m);
  long double acc = 0.0L;
  for (std::int64_t k = 0; k < 6 * m; ++k) {
    const long double d = (prefix[k + m] - prefix[k]) - 2.0L * (prefix[k + 2 * m] - prefix[k + m]) +
                          (prefix[k + 3 * m] - prefix[k + 2 * m]);
    const long double avg = d * inv_m;
    acc += avg * avg;
  }
  return static_cast<double>(acc / static_cast<long double>(6 * m));
}

/// Σ over all runs of length 3m in SAMPLES of reflected_run_mean_square (O(len·m)).
double sum_over_runs(std::span<const double> samples, std::int64_t m) {
  const std::int64_t runs = static_cast<std::int64_t>(samples.size()) - 3 * m + 1;
  std::vector<long double> prefix(static_cast<std::size_t>(9 * m + 1));
  CompensatedSum total;
  for (std::int64_t n = 0; n < runs; ++n) {
    total.add(reflected_run_mean_square(samples.data() + n, m, prefix.data()));
  }
  return total.value();
}

/// Riley CI2.pdf p. 6: Mod σ²_tot / Mod σ²_y for alpha 2 … −2.
double mtot_bias_ratio(int alpha) {
  switch (alpha) {
    case 2:
      return 0.94;
    case 1:
      return 0.83;
    case 0:
      return 0.73;
    case -1:
      return 0.70;
    case -2:
      return 0.69;
    default:
      break;
  }
  throw AnalysisError(
      "total_family_variance: MTOT/TTOT bias correction needs alpha in -2..2, got " +
      std::to_string(alpha));
}

/// Howe et al. PTTI 2000 Table 4: Htot/Hvar = 1 + a for alpha 0 … −4; PM noise: 1.
double htot_bias_ratio(int alpha) {
  switch (alpha) {
    case 2:
    case 1:
      return 1.0;
    case 0:
      return 1.0 - 0.005;
    case -1:
      return 1.0 - 0.149;
    case -2:
      return 1.0 - 0.229;
    case -3:
      return 1.0 - 0.283;
    case -4:
      return 1.0 - 0.321;
    default:
      break;
  }
  throw AnalysisError("total_family_variance: HTOT bias correction needs alpha in -4..2, got " +
                      std::to_string(alpha));
}

const char* name_of(TotalFamilyType type) {
  switch (type) {
    case TotalFamilyType::mtotdev:
      return "mtotdev";
    case TotalFamilyType::ttotdev:
      return "ttotdev";
    case TotalFamilyType::htotdev:
      return "htotdev";
  }
  return "?";
}

}  // namespace

std::int64_t total_family_term_count(TotalFamilyType type, std::int64_t n_phase, std::int64_t m) {
  return type == TotalFamilyType::htotdev ? n_phase - 3 * m : n_phase - 3 * m + 1;
}

std::int64_t total_family_max_m(TotalFamilyType type, std::int64_t n_phase) {
  const std::int64_t n = type == TotalFamilyType::htotdev ? n_phase - 1 : n_phase;
  return n >= 3 ? n / 3 : 0;
}

VarianceEstimate total_family_variance(TotalFamilyType type, std::span<const double> phase,
                                       std::int64_t m, double tau0_s, bool bias_corrected,
                                       int alpha) {
  const std::string where = std::string("total_family_variance(") + name_of(type) + "): ";
  IMUNOISE_EXPECT(m >= 1, where + "averaging factor must be >= 1, got " + std::to_string(m));
  detail::check_sample_period(tau0_s, where);
  const auto n_phase = static_cast<std::int64_t>(phase.size());
  const std::int64_t terms = total_family_term_count(type, n_phase, m);
  IMUNOISE_CHECK(terms >= 1 && m <= total_family_max_m(type, n_phase), AnalysisError,
                 where + "record too short: " + std::to_string(n_phase) +
                     " phase samples for m = " + std::to_string(m) + " (need >= " +
                     std::to_string(type == TotalFamilyType::htotdev ? 3 * m + 1 : 3 * m) + ")");
  const double tau = static_cast<double>(m) * tau0_s;
  VarianceEstimate out;
  out.n_terms = terms;

  if (type == TotalFamilyType::htotdev) {
    if (m == 1) {
      // SP 1065 §5.2.14 / Stable32: the overlapping Hadamard variance at m = 1, unbiased.
      out.variance = detail::lag_one_overlapping_variance(phase, 3, tau0_s);
      return out;
    }
    // Frequency values; the 1/τ0 scale is applied once at the end.
    std::vector<double> freq(static_cast<std::size_t>(n_phase - 1));
    for (std::size_t i = 0; i + 1 < phase.size(); ++i) freq[i] = phase[i + 1] - phase[i];
    const double sum = sum_over_runs(freq, m);
    out.variance = sum / (6.0 * static_cast<double>(terms) * tau0_s * tau0_s);
    if (bias_corrected) out.variance /= htot_bias_ratio(alpha);
    return out;
  }

  // MTOT (SP 1065 eq. 27): 1/(2τ²(M−3m+1)) Σ_n (run mean square).
  const double sum = sum_over_runs(phase, m);
  out.variance = sum / (2.0 * tau * tau * static_cast<double>(terms));
  if (bias_corrected) out.variance /= mtot_bias_ratio(alpha);
  if (type == TotalFamilyType::ttotdev) out.variance *= tau * tau / 3.0;  // SP 1065 eq. 28
  return out;
}

double total_family_edf(TotalFamilyType type, int alpha, std::int64_t m, std::int64_t n_phase) {
  const std::string where = std::string("total_family_edf(") + name_of(type) + "): ";
  IMUNOISE_CHECK(m >= 1 && m <= total_family_max_m(type, n_phase), AnalysisError,
                 where + "averaging factor " + std::to_string(m) + " outside 1.." +
                     std::to_string(total_family_max_m(type, n_phase)));
  if (type == TotalFamilyType::htotdev) {
    IMUNOISE_CHECK(alpha >= -4 && alpha <= 2, AnalysisError,
                   where + "alpha must be in -4..2, got " + std::to_string(alpha));
    return edf_greenhall(alpha, 3, m, n_phase, true, false);
  }
  double b = 0.0;
  double c = 0.0;
  switch (alpha) {
    case 2:
      b = 1.90, c = 2.10;
      break;
    case 1:
      b = 1.20, c = 1.40;
      break;
    case 0:
      b = 1.10, c = 1.20;
      break;
    case -1:
      b = 0.85, c = 0.50;
      break;
    case -2:
      b = 0.75, c = 0.31;
      break;
    default:
      throw AnalysisError(where + "alpha must be in -2..2, got " + std::to_string(alpha));
  }
  return b * static_cast<double>(n_phase) / static_cast<double>(m) - c;
}

std::optional<TotalFamilyType> total_family_type(DeviationType type) {
  switch (type) {
    case DeviationType::mtotdev:
      return TotalFamilyType::mtotdev;
    case DeviationType::ttotdev:
      return TotalFamilyType::ttotdev;
    case DeviationType::htotdev:
      return TotalFamilyType::htotdev;
    default:
      return std::nullopt;
  }
}

}  // namespace imunoise::analysis
