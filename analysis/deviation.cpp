#include "analysis/deviation.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "analysis/confidence.h"
#include "analysis/difference_sums.h"
#include "analysis/edf.h"
#include "analysis/extra_deviations.h"
#include "analysis/kernel_support.h"
#include "analysis/noise_id.h"
#include "analysis/tau_grid.h"
#include "analysis/total_family.h"
#include "common/errors.h"
#include "common/huge_pages.h"
#include "common/parallel_for.h"

namespace imunoise::analysis {

namespace {

using detail::blocked_sum;
using detail::CompensatedSum;

// Second difference x_{k+2m} − 2x_{k+m} + x_k (Allan) and third difference (Hadamard).
inline double second_difference(const double* x, std::int64_t k, std::int64_t m) {
  return x[k + 2 * m] - 2.0 * x[k + m] + x[k];
}
inline double third_difference(const double* x, std::int64_t k, std::int64_t m) {
  return x[k + 3 * m] - 3.0 * x[k + 2 * m] + 3.0 * x[k + m] - x[k];
}

/// The difference order of the overlapping statistics whose sums come from
/// detail::overlapping_difference_sums (2: OADEV, 3: OHDEV), else 0.
int overlapping_order(DeviationType type) {
  return type == DeviationType::oadev ? 2 : type == DeviationType::ohdev ? 3 : 0;
}

/// theory.md §2: OAVAR = S/(2τ²n), OHVAR = S/(6τ²n), from the sum S of n squared differences.

/// Σ_j (Σ_{k=j}^{j+m−1} d_k)², j = 0..n−1, d = second difference at stride m (MVAR, SP 1065).
/// The inner sum w_j is a sliding window: w_{j+1} = w_j + third_difference(j), O(1) per j —
/// the prefix-sum form of theory.md §2 without forming a prefix array whose magnitude would
/// grow like M^{3/2} and cost digits. Four lanes start at exact window sums in four quarters
/// of the range, which breaks the add-latency chain and bounds rounding drift to M/4 steps.
double modified_sum(const double* x, std::int64_t n, std::int64_t m) {
  constexpr int kLanes = 4;
  auto window_at = [&](std::int64_t j) {
    double w = 0.0;
    for (std::int64_t k = j; k < j + m; ++k) w += second_difference(x, k, m);
    return w;
  };
  const std::int64_t lane_length = n / kLanes;
  CompensatedSum total;
  double w[kLanes];
  std::int64_t start[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    start[l] = l * lane_length;
    w[l] = lane_length > 0 ? window_at(start[l]) : 0.0;
  }
  // Each lane visits windows start..start+lane_length−1; it advances only between them, so
  // no third difference past the last valid window (j ≤ n−2) is ever formed.
  constexpr std::int64_t kBlock = 2048;
  const std::int64_t advances = std::max<std::int64_t>(lane_length - 1, 0);
  for (std::int64_t i0 = 0; i0 < advances; i0 += kBlock) {
    const std::int64_t i1 = std::min(advances, i0 + kBlock);
    double acc[kLanes] = {0.0, 0.0, 0.0, 0.0};
    for (std::int64_t i = i0; i < i1; ++i) {
      for (int l = 0; l < kLanes; ++l) {
        acc[l] += w[l] * w[l];
        w[l] += third_difference(x, start[l] + i, m);
      }
    }
    for (int l = 0; l < kLanes; ++l) total.add(acc[l]);
  }
  if (lane_length > 0) {
    for (int l = 0; l < kLanes; ++l) total.add(w[l] * w[l]);
  }
  // Tail [kLanes·lane_length, n): continue from the last lane's final window.
  const std::int64_t tail_start = kLanes * lane_length;
  double tail_w = 0.0;
  if (tail_start < n) {
    tail_w =
        lane_length > 0 ? w[kLanes - 1] + third_difference(x, tail_start - 1, m) : window_at(0);
  }
  double tail = 0.0;
  for (std::int64_t j = tail_start; j < n; ++j) {
    tail += tail_w * tail_w;
    if (j + 1 < n) tail_w += third_difference(x, j, m);
  }
  total.add(tail);
  return total.value();
}

/// Σ_{i=1}^{M−2} (x*_{i−m} − 2x*_i + x*_{i+m})² over the doubly reflected extension
/// x*_{−j} = 2x_0 − x_j, x*_{M−1+j} = 2x_{M−1} − x_{M−1−j} (SP 1065 eq. 25, 0-based).
double total_sum(const double* x, std::int64_t M, std::int64_t m) {
  auto ext = [&](std::int64_t i) {
    if (i < 0) return 2.0 * x[0] - x[-i];
    if (i > M - 1) return 2.0 * x[M - 1] - x[2 * (M - 1) - i];
    return x[i];
  };
  auto edge_term = [&](std::int64_t i) {
    const double d = ext(i - m) - 2.0 * ext(i) + ext(i + m);
    return d * d;
  };
  // Interior where no reflection is needed: m ≤ i ≤ M−1−m.
  const std::int64_t lo = std::max<std::int64_t>(1, m);
  const std::int64_t hi = std::min<std::int64_t>(M - 2, M - 1 - m);
  CompensatedSum total;
  double edges = 0.0;
  for (std::int64_t i = 1; i < std::min(lo, M - 1); ++i) edges += edge_term(i);
  if (hi >= lo) {
    total.add(blocked_sum(hi - lo + 1, [&](std::int64_t k) {
      const std::int64_t i = lo + k;
      const double d = x[i - m] - 2.0 * x[i] + x[i + m];
      return d * d;
    }));
  }
  for (std::int64_t i = std::max(lo, hi + 1); i <= M - 2; ++i) edges += edge_term(i);
  total.add(edges);
  return total.value();
}

}  // namespace

namespace {

/// The number of terms of TYPE's estimator at factor M on N_PHASE phase samples; a
/// ContractViolation when m < 1 (the tau grids give m >= 1), an AnalysisError when there is no
/// term (the checks of every single-τ entry point).
std::int64_t checked_term_count(DeviationType type, std::int64_t n_phase, std::int64_t m) {
  IMUNOISE_EXPECT(m >= 1, "averaging factor must be >= 1, got " + std::to_string(m));
  const std::int64_t n = estimator_term_count(type, n_phase, m);
  IMUNOISE_CHECK(n >= 1, AnalysisError,
                 "too few samples for " + std::string(to_string(type)) +
                     " at m = " + std::to_string(m) + ": " + std::to_string(n_phase) +
                     " phase samples give no term");
  return n;
}

}  // namespace

std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s) {
  std::vector<double> phase;
  reserve_huge_pages(phase, rate.size() + 1);
  CompensatedSum mean_sum;
  for (double y : rate) mean_sum.add(y);
  const double mean = rate.empty() ? 0.0 : mean_sum.value() / static_cast<double>(rate.size());
  CompensatedSum running;
  phase.push_back(0.0);
  for (std::size_t k = 0; k < rate.size(); ++k) {
    running.add(tau0_s * (rate[k] - mean));
    phase.push_back(running.value());
  }
  return phase;
}

void phase_from_rate_in_place(std::vector<double>& samples, double tau0_s) {
  const std::size_t n = samples.size();
  // The same operations in the same order as phase_from_rate; rate sample k is read before
  // phase sample k + 1 overwrites it.
  CompensatedSum mean_sum;
  for (double y : samples) mean_sum.add(y);
  const double mean = n == 0 ? 0.0 : mean_sum.value() / static_cast<double>(n);
  samples.push_back(0.0);
  CompensatedSum running;
  double rate = samples[0];
  for (std::size_t k = 0; k < n; ++k) {
    const double next_rate = samples[k + 1];
    running.add(tau0_s * (rate - mean));
    samples[k + 1] = running.value();
    rate = next_rate;
  }
  samples[0] = 0.0;
}

std::vector<VarianceEstimate> overlapping_variances(DeviationType type,
                                                    std::span<const double> phase,
                                                    std::span<const std::int64_t> m_values,
                                                    double tau0_s) {
  const int order = overlapping_order(type);
  IMUNOISE_EXPECT(order != 0, "overlapping_variances: " + std::string(to_string(type)) +
                                  " is not an overlapping Allan or Hadamard variance");
  detail::check_sample_period(tau0_s);
  const auto M = static_cast<std::int64_t>(phase.size());
  std::vector<VarianceEstimate> out(m_values.size());
  for (std::size_t i = 0; i < m_values.size(); ++i) {
    out[i].n_terms = checked_term_count(type, M, m_values[i]);
  }
  std::vector<double> sums(m_values.size());
  detail::overlapping_difference_sums(phase, order, m_values, sums);
  for (std::size_t i = 0; i < m_values.size(); ++i) {
    out[i].variance =
        detail::overlapping_variance_of_sum(order, sums[i], out[i].n_terms, m_values[i], tau0_s);
  }
  return out;
}

std::vector<double> detrended_phase(std::span<const double> phase) {
  std::vector<double> out(phase.begin(), phase.end());
  const std::size_t M = phase.size();
  if (M < 2) {
    std::fill(out.begin(), out.end(), 0.0);
    return out;
  }
  const double x0 = phase[0];
  const double slope = (phase[M - 1] - x0) / static_cast<double>(M - 1);
  for (std::size_t k = 0; k < M; ++k) out[k] = (phase[k] - x0) - slope * static_cast<double>(k);
  return out;
}

VarianceEstimate allan_family_variance(DeviationType type, std::span<const double> phase,
                                       std::int64_t m, double tau0_s) {
  const auto M = static_cast<std::int64_t>(phase.size());
  IMUNOISE_EXPECT(m >= 1, "averaging factor must be >= 1, got " + std::to_string(m));
  detail::check_sample_period(tau0_s);
  const std::int64_t n = checked_term_count(type, M, m);
  const double* x = phase.data();
  const double tau = static_cast<double>(m) * tau0_s;
  const double nn = static_cast<double>(n);
  VarianceEstimate out;
  out.n_terms = n;
  switch (type) {
    case DeviationType::adev: {  // SP 1065 eq. 7 on phase, stride m
      const double s = blocked_sum(n, [&](std::int64_t j) {
        const double d = second_difference(x, j * m, m);
        return d * d;
      });
      out.variance = s / (2.0 * tau * tau * nn);
      break;
    }
    case DeviationType::oadev: {  // theory.md §2 overlapping AVAR
      double s = 0.0;
      detail::overlapping_difference_sums(phase, 2, std::span(&m, 1), std::span(&s, 1));
      out.variance = detail::overlapping_variance_of_sum(2, s, n, m, tau0_s);
      break;
    }
    case DeviationType::mdev:
    case DeviationType::tdev: {  // theory.md §2 modified AVAR; TVAR = τ²/3 · MVAR
      const double s = modified_sum(x, n, m);
      const double mvar =
          s / (2.0 * static_cast<double>(m) * static_cast<double>(m) * tau * tau * nn);
      out.variance = type == DeviationType::mdev ? mvar : tau * tau / 3.0 * mvar;
      break;
    }
    case DeviationType::hdev: {  // non-overlapping Hadamard, stride m
      const double s = blocked_sum(n, [&](std::int64_t j) {
        const double d = third_difference(x, j * m, m);
        return d * d;
      });
      out.variance = s / (6.0 * tau * tau * nn);
      break;
    }
    case DeviationType::ohdev: {  // theory.md §2 overlapping Hadamard
      double s = 0.0;
      detail::overlapping_difference_sums(phase, 3, std::span(&m, 1), std::span(&s, 1));
      out.variance = detail::overlapping_variance_of_sum(3, s, n, m, tau0_s);
      break;
    }
    case DeviationType::totdev: {  // theory.md §2 total variance (SP 1065 eq. 25)
      out.variance = total_sum(x, M, m) / (2.0 * tau * tau * nn);
      break;
    }
    case DeviationType::mtotdev:
    case DeviationType::ttotdev:
    case DeviationType::htotdev:
      return total_family_variance(*total_family_type(type), phase, m, tau0_s);
    case DeviationType::theo1:
      return theo1_variance(phase, m, tau0_s);
  }
  return out;
}

namespace {

/// The variance of one curve point: the plain estimator, or for MTOTDEV, TTOTDEV, HTOTDEV and
/// Thêo1 with options.bias_corrected, the SP 1065 bias-corrected one for noise type ALPHA.
VarianceEstimate point_variance(const DeviationOptions& options, std::span<const double> phase,
                                std::int64_t m, double tau0_s, int alpha) {
  if (options.bias_corrected) {
    if (const auto family = total_family_type(options.type)) {
      return total_family_variance(*family, phase, m, tau0_s, true, alpha);
    }
    if (options.type == DeviationType::theo1) {
      return theo1_variance(phase, m, tau0_s, true, alpha);
    }
  }
  return allan_family_variance(options.type, phase, m, tau0_s);
}

/// The OAVAR sums at OAVAR_FACTORS and the OHVAR sums at OHVAR_FACTORS of one record (each
/// factor with a term), split over THREADS. A factor in both lists (M − 3m ≥ 1) is evaluated
/// for both orders in one pass (detail::allan_hadamard_difference_sums), the others for one
/// order. Within each kind the small factors are dealt round-robin into one shared pass per
/// thread, and the large ones, ascending, are cut into runs of consecutive factors, at most a
/// group each (one pass over memory per run) and at least as many runs as threads. Every sum
/// is bit for bit the single-factor one (fixed blocks, difference_sums.h), so neither the
/// dealing nor the thread count shows in the results.
struct OverlappingSums {
  std::vector<double> oavar;
  std::vector<double> ohvar;
};

OverlappingSums overlapping_sums(std::span<const double> phase,
                                 std::span<const std::int64_t> oavar_factors,
                                 std::span<const std::int64_t> ohvar_factors, unsigned threads) {
  OverlappingSums out{std::vector<double>(oavar_factors.size()),
                      std::vector<double>(ohvar_factors.size())};
  // A job is one factor: its index in each list (kNone where it is not asked for).
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  struct Job {
    std::int64_t m;
    std::size_t oavar;
    std::size_t ohvar;
  };
  // The kernel each kind of job goes to, the order whose span decides which factors share a
  // cache-resident pass, and how many large factors share a pass.
  enum Kind : std::size_t { kOavarOnly, kOhvarOnly, kBoth, kKinds };
  constexpr int kSpanOrder[kKinds] = {2, 3, 3};
  constexpr std::size_t kGroup[kKinds] = {detail::kLargePassFactors, detail::kLargePassFactors,
                                          detail::kLargeJointPassFactors};
  const std::vector<std::size_t> by2 = detail::ascending_order(oavar_factors);
  const std::vector<std::size_t> by3 = detail::ascending_order(ohvar_factors);
  const auto M = static_cast<std::int64_t>(phase.size());
  std::vector<Job> jobs[kKinds];  // each ascending in m
  std::size_t a = 0;
  std::size_t b = 0;
  while (a < by2.size() || b < by3.size()) {
    const std::int64_t m2 = a < by2.size() ? oavar_factors[by2[a]] : INT64_MAX;
    const std::int64_t m3 = b < by3.size() ? ohvar_factors[by3[b]] : INT64_MAX;
    if (m2 == m3 && M - 3 * m2 >= 1) {
      jobs[kBoth].push_back({m2, by2[a++], by3[b++]});
    } else if (m2 <= m3) {
      jobs[kOavarOnly].push_back({m2, by2[a++], kNone});
    } else {
      jobs[kOhvarOnly].push_back({m3, kNone, by3[b++]});
    }
  }
  struct Item {
    Kind kind;
    std::vector<Job> jobs;
  };
  std::vector<Item> items;
  for (std::size_t k = 0; k < kKinds; ++k) {
    const auto kind = static_cast<Kind>(k);
    std::vector<Job> large;
    std::vector<Item> small(threads, Item{kind, {}});
    std::size_t dealt = 0;
    for (const Job& job : jobs[kind]) {
      if (kSpanOrder[kind] * job.m <= detail::kSharedPassSpan) {
        small[dealt++ % threads].jobs.push_back(job);
      } else {
        large.push_back(job);
      }
    }
    for (Item& item : small) items.push_back(std::move(item));
    const std::size_t runs = std::max((large.size() + kGroup[kind] - 1) / kGroup[kind],
                                      std::min<std::size_t>(threads, large.size()));
    for (std::size_t r = 0; r < runs; ++r) {
      items.push_back(Item{
          kind, std::vector<Job>(
                    large.begin() + static_cast<std::ptrdiff_t>(r * large.size() / runs),
                    large.begin() + static_cast<std::ptrdiff_t>((r + 1) * large.size() / runs))});
    }
  }
  std::erase_if(items, [](const Item& item) { return item.jobs.empty(); });
  parallel_for(items.size(), threads, [&](std::size_t t) {
    const Item& item = items[t];
    std::vector<std::int64_t> m_values;
    for (const Job& job : item.jobs) m_values.push_back(job.m);
    std::vector<double> sums2(m_values.size());
    std::vector<double> sums3(m_values.size());
    switch (item.kind) {
      case kBoth:
        detail::allan_hadamard_difference_sums(phase, m_values, sums2, sums3);
        break;
      case kOavarOnly:
        detail::overlapping_difference_sums(phase, 2, m_values, sums2);
        break;
      default:
        detail::overlapping_difference_sums(phase, 3, m_values, sums3);
        break;
    }
    for (std::size_t k = 0; k < item.jobs.size(); ++k) {
      if (item.jobs[k].oavar != kNone) out.oavar[item.jobs[k].oavar] = sums2[k];
      if (item.jobs[k].ohvar != kNone) out.ohvar[item.jobs[k].ohvar] = sums3[k];
    }
  });
  return out;
}

/// Worker threads for the curves of one record of N_PHASE samples at COUNT factors.
unsigned curve_threads(unsigned requested, std::size_t count, std::int64_t n_phase) {
  if (n_phase < 50000) return 1;  // thread start-up would dominate
  return std::max(1u, std::min<unsigned>(resolve_threads(requested),
                                         static_cast<unsigned>(std::max<std::size_t>(count, 1))));
}

/// Throws AnalysisError unless every factor of AVERAGING_FACTORS is usable for TYPE on N_PHASE
/// samples (WHERE: how the record is described in the message), ContractViolation unless the
/// confidence is in (0, 1).
void check_curve_request(DeviationType type, std::int64_t n_phase,
                         std::span<const std::int64_t> averaging_factors, double confidence,
                         const std::string& where) {
  IMUNOISE_EXPECT(confidence > 0.0 && confidence < 1.0,
                  "confidence must be in (0, 1), got " + std::to_string(confidence));
  const std::int64_t max_m = max_averaging_factor(type, n_phase);
  for (std::int64_t m : averaging_factors) {
    IMUNOISE_CHECK(m >= 1 && m <= max_m, AnalysisError,
                   "too few samples for the requested tau: m = " + std::to_string(m) + " (" +
                       std::string(to_string(type)) + " allows m <= " + std::to_string(max_m) +
                       where + std::to_string(n_phase) + " phase samples)");
  }
}

/// The curve of one record once the request is checked: SUMS holds the difference sum of
/// every factor for OADEV/OHDEV (overlapping_sums), and is empty for the other statistics.
DeviationCurve single_record_curve(std::span<const double> phase, double tau0_s,
                                   std::span<const std::int64_t> averaging_factors,
                                   const DeviationOptions& options, std::span<const double> sums,
                                   unsigned threads) {
  DeviationCurve curve;
  curve.type = options.type;
  curve.tau0_s = tau0_s;
  curve.n_phase = static_cast<std::int64_t>(phase.size());
  curve.confidence = options.confidence;
  curve.points.resize(averaging_factors.size());
  const int order = overlapping_order(options.type);
  auto compute_point = [&](std::size_t i) {
    const std::int64_t m = averaging_factors[i];
    DeviationPoint& p = curve.points[i];
    p.m = m;
    p.tau_s = tau_of(options.type, m, tau0_s);
    // The noise type comes first because the bias-corrected total family and Thêo1 need it,
    // and those estimators cost O(M·m): each is evaluated once. A constant signal gives no
    // identification and falls back to white FM (alpha 0), the neutral choice for its EDF.
    p.alpha = options.alpha ? *options.alpha : noise_alpha_for(options.type, phase, m);
    VarianceEstimate v;
    if (order != 0) {
      v.n_terms = estimator_term_count(options.type, curve.n_phase, m);
      v.variance = detail::overlapping_variance_of_sum(order, sums[i], v.n_terms, m, tau0_s);
    } else {
      v = point_variance(options, phase, m, tau0_s, p.alpha);
    }
    p.value = std::sqrt(std::max(v.variance, 0.0));
    p.n_terms = v.n_terms;
    p.edf = edf_for(options.type, p.alpha, m, curve.n_phase);
    const DeviationInterval ci = deviation_interval(p.value, p.edf, options.confidence);
    p.ci_low = ci.low;
    p.ci_high = ci.high;
  };
  // Every τ of the non-overlapping statistics costs an O(M) pass, so the points are split
  // over threads; each is written by exactly one work item and computed the same way whoever
  // runs it, so results do not depend on the thread count.
  parallel_for(averaging_factors.size(), threads, compute_point);
  return curve;
}

}  // namespace

DeviationCurve compute_deviation(std::span<const double> phase, double tau0_s,
                                 std::span<const std::int64_t> averaging_factors,
                                 const DeviationOptions& options) {
  const auto n_phase = static_cast<std::int64_t>(phase.size());
  check_curve_request(options.type, n_phase, averaging_factors, options.confidence, " on ");
  detail::check_sample_period(tau0_s);
  const unsigned threads = curve_threads(options.threads, averaging_factors.size(), n_phase);
  // OADEV and OHDEV, the statistics of `analyze`: their difference sums come first, the
  // small factors sharing cache-resident passes (analysis/difference_sums.h).
  OverlappingSums sums;
  const int order = overlapping_order(options.type);
  if (order == 2) sums = overlapping_sums(phase, averaging_factors, {}, threads);
  if (order == 3) sums = overlapping_sums(phase, {}, averaging_factors, threads);
  return single_record_curve(phase, tau0_s, averaging_factors, options,
                             order == 2 ? sums.oavar : sums.ohvar, threads);
}

bool is_poolable(DeviationType type) {
  switch (type) {
    case DeviationType::adev:
    case DeviationType::oadev:
    case DeviationType::mdev:
    case DeviationType::tdev:
    case DeviationType::hdev:
    case DeviationType::ohdev:
      return true;
    default:
      return false;
  }
}

double edf_for(DeviationType type, int alpha, std::int64_t m, std::int64_t n_phase) {
  switch (type) {
    case DeviationType::adev:
      return edf_greenhall(alpha, 2, m, n_phase, false, false);
    case DeviationType::oadev:
      return edf_greenhall(alpha, 2, m, n_phase, true, false);
    case DeviationType::mdev:
    case DeviationType::tdev:
      return edf_greenhall(alpha, 2, m, n_phase, true, true);
    case DeviationType::hdev:
      return edf_greenhall(alpha, 3, m, n_phase, false, false);
    case DeviationType::ohdev:
      return edf_greenhall(alpha, 3, m, n_phase, true, false);
    case DeviationType::totdev:
      return edf_totdev(alpha, m, n_phase);
    case DeviationType::mtotdev:
    case DeviationType::ttotdev:
    case DeviationType::htotdev:
      return total_family_edf(*total_family_type(type), alpha, m, n_phase);
    case DeviationType::theo1:
      return theo1_edf(alpha, m, n_phase);
  }
  throw ContractViolation("edf_for: unknown deviation type");
}

double curve_edf(const DeviationCurve& curve, int alpha, std::int64_t m) {
  if (curve.piece_n_phase.empty()) return edf_for(curve.type, alpha, m, curve.n_phase);
  // Independent pieces: the χ² variables add, and so do their dof (theory.md §3.1).
  double edf = 0.0;
  for (std::int64_t n_k : curve.piece_n_phase) {
    if (estimator_term_count(curve.type, n_k, m) >= 1) edf += edf_for(curve.type, alpha, m, n_k);
  }
  return edf;
}

namespace {

/// Checks a pooled request of OPTIONS.type at AVERAGING_FACTORS over several PHASES (pieces)
/// and returns the index of the longest piece, which bounds the factors.
std::size_t check_pooled_request(std::span<const std::span<const double>> phases, double tau0_s,
                                 std::span<const std::int64_t> averaging_factors,
                                 const DeviationOptions& options) {
  IMUNOISE_EXPECT(is_poolable(options.type),
                  std::string(to_string(options.type)) +
                      " cannot be pooled over pieces (ADEV, OADEV, MDEV, TDEV, HDEV, OHDEV can)");
  IMUNOISE_EXPECT(options.confidence > 0.0 && options.confidence < 1.0,
                  "confidence must be in (0, 1), got " + std::to_string(options.confidence));
  detail::check_sample_period(tau0_s);
  std::size_t longest = 0;
  for (std::size_t k = 0; k < phases.size(); ++k) {
    if (phases[k].size() > phases[longest].size()) longest = k;
  }
  check_curve_request(options.type, static_cast<std::int64_t>(phases[longest].size()),
                      averaging_factors, options.confidence, " on the longest piece of ");
  return longest;
}

/// Every piece's OAVAR sums at OAVAR_FACTORS and OHVAR sums at OHVAR_FACTORS, indexed
/// [piece][factor] (0 where the piece holds no term), by overlapping_sums per piece.
struct PieceSums {
  std::vector<std::vector<double>> oavar;
  std::vector<std::vector<double>> ohvar;
};

PieceSums pooled_overlapping_sums(std::span<const std::span<const double>> phases,
                                  std::span<const std::int64_t> oavar_factors,
                                  std::span<const std::int64_t> ohvar_factors,
                                  unsigned requested_threads) {
  PieceSums out;
  for (const std::span<const double>& phase : phases) {
    const auto n_k = static_cast<std::int64_t>(phase.size());
    // The factors this piece holds a term at, and where they stand in the request.
    const auto usable = [n_k](DeviationType type, std::span<const std::int64_t> factors,
                              std::vector<std::size_t>& index, std::vector<std::int64_t>& m) {
      for (std::size_t i = 0; i < factors.size(); ++i) {
        if (estimator_term_count(type, n_k, factors[i]) < 1) continue;
        index.push_back(i);
        m.push_back(factors[i]);
      }
    };
    std::vector<std::size_t> index2;
    std::vector<std::size_t> index3;
    std::vector<std::int64_t> usable2;
    std::vector<std::int64_t> usable3;
    usable(DeviationType::oadev, oavar_factors, index2, usable2);
    usable(DeviationType::ohdev, ohvar_factors, index3, usable3);
    const unsigned threads = curve_threads(requested_threads, usable2.size() + usable3.size(), n_k);
    const OverlappingSums sums = overlapping_sums(phase, usable2, usable3, threads);
    out.oavar.emplace_back(oavar_factors.size(), 0.0);
    out.ohvar.emplace_back(ohvar_factors.size(), 0.0);
    for (std::size_t j = 0; j < index2.size(); ++j) out.oavar.back()[index2[j]] = sums.oavar[j];
    for (std::size_t j = 0; j < index3.size(); ++j) out.ohvar.back()[index3[j]] = sums.ohvar[j];
  }
  return out;
}

/// The pooled curve once the request is checked (LONGEST from check_pooled_request).
/// PIECE_SUMS: for OADEV/OHDEV the sums [piece][factor] (pooled_overlapping_sums), else empty.
DeviationCurve pooled_curve(std::span<const std::span<const double>> phases, double tau0_s,
                            std::span<const std::int64_t> averaging_factors,
                            const DeviationOptions& options, std::size_t longest,
                            const std::vector<std::vector<double>>& piece_sums) {
  DeviationCurve curve;
  curve.type = options.type;
  curve.tau0_s = tau0_s;
  curve.confidence = options.confidence;
  for (const std::span<const double>& phase : phases) {
    curve.piece_n_phase.push_back(static_cast<std::int64_t>(phase.size()));
    curve.n_phase += static_cast<std::int64_t>(phase.size());
  }
  const int order = overlapping_order(options.type);
  curve.points.reserve(averaging_factors.size());
  for (std::size_t i = 0; i < averaging_factors.size(); ++i) {
    const std::int64_t m = averaging_factors[i];
    DeviationPoint p;
    p.m = m;
    p.tau_s = tau_of(options.type, m, tau0_s);
    p.alpha = options.alpha ? *options.alpha : noise_alpha_for(options.type, phases[longest], m);
    // Σ n_k σ²_k = Σ (squared differences)/norm: the pooled mean over all terms. Compensated,
    // as the per-piece kernels are (theory.md §2 "Numerics"). σ²_k = S_k/(c·τ²·n_k) exactly
    // as allan_family_variance gives it.
    detail::CompensatedSum weighted;
    std::int64_t terms = 0;
    for (std::size_t k = 0; k < phases.size(); ++k) {
      const auto n_k = static_cast<std::int64_t>(phases[k].size());
      if (estimator_term_count(options.type, n_k, m) < 1) continue;
      VarianceEstimate v;
      if (order != 0) {
        v.n_terms = estimator_term_count(options.type, n_k, m);
        v.variance =
            detail::overlapping_variance_of_sum(order, piece_sums[k][i], v.n_terms, m, tau0_s);
      } else {
        v = allan_family_variance(options.type, phases[k], m, tau0_s);
      }
      weighted.add(static_cast<double>(v.n_terms) * v.variance);
      terms += v.n_terms;
    }
    p.n_terms = terms;
    p.value = std::sqrt(std::max(weighted.value() / static_cast<double>(terms), 0.0));
    p.edf = curve_edf(curve, p.alpha, m);
    const DeviationInterval ci = deviation_interval(p.value, p.edf, options.confidence);
    p.ci_low = ci.low;
    p.ci_high = ci.high;
    curve.points.push_back(p);
  }
  return curve;
}

}  // namespace

DeviationCurve compute_pooled_deviation(std::span<const std::span<const double>> phases,
                                        double tau0_s,
                                        std::span<const std::int64_t> averaging_factors,
                                        const DeviationOptions& options) {
  IMUNOISE_EXPECT(!phases.empty(), "pooled deviation: no pieces");
  if (phases.size() == 1) {
    return compute_deviation(phases.front(), tau0_s, averaging_factors, options);
  }
  const std::size_t longest = check_pooled_request(phases, tau0_s, averaging_factors, options);
  // OADEV/OHDEV: each piece's difference sums at all its factors in shared passes.
  const int order = overlapping_order(options.type);
  PieceSums sums;
  if (order == 2) sums = pooled_overlapping_sums(phases, averaging_factors, {}, options.threads);
  if (order == 3) sums = pooled_overlapping_sums(phases, {}, averaging_factors, options.threads);
  return pooled_curve(phases, tau0_s, averaging_factors, options, longest,
                      order == 2 ? sums.oavar : sums.ohvar);
}

AllanHadamardCurves compute_pooled_allan_hadamard(std::span<const std::span<const double>> phases,
                                                  double tau0_s,
                                                  std::span<const std::int64_t> oadev_factors,
                                                  std::span<const std::int64_t> ohdev_factors,
                                                  const DeviationOptions& options) {
  IMUNOISE_EXPECT(!phases.empty(), "pooled deviation: no pieces");
  DeviationOptions oadev = options;
  oadev.type = DeviationType::oadev;
  DeviationOptions ohdev = options;
  ohdev.type = DeviationType::ohdev;
  AllanHadamardCurves out;
  if (phases.size() == 1) {
    const std::span<const double> phase = phases.front();
    const auto n_phase = static_cast<std::int64_t>(phase.size());
    check_curve_request(DeviationType::oadev, n_phase, oadev_factors, options.confidence, " on ");
    check_curve_request(DeviationType::ohdev, n_phase, ohdev_factors, options.confidence, " on ");
    detail::check_sample_period(tau0_s);
    const unsigned threads =
        curve_threads(options.threads, oadev_factors.size() + ohdev_factors.size(), n_phase);
    const OverlappingSums sums = overlapping_sums(phase, oadev_factors, ohdev_factors, threads);
    out.oadev = single_record_curve(phase, tau0_s, oadev_factors, oadev, sums.oavar, threads);
    out.ohdev = single_record_curve(phase, tau0_s, ohdev_factors, ohdev, sums.ohvar, threads);
    return out;
  }
  const std::size_t longest = check_pooled_request(phases, tau0_s, oadev_factors, oadev);
  check_pooled_request(phases, tau0_s, ohdev_factors, ohdev);
  const PieceSums sums =
      pooled_overlapping_sums(phases, oadev_factors, ohdev_factors, options.threads);
  out.oadev = pooled_curve(phases, tau0_s, oadev_factors, oadev, longest, sums.oavar);
  out.ohdev = pooled_curve(phases, tau0_s, ohdev_factors, ohdev, longest, sums.ohvar);
  return out;
}

}  // namespace imunoise::analysis
