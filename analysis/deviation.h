/// @file
/// @brief Allan-family deviations (ADEV, OADEV, MDEV, TDEV, HDEV, OHDEV, TOTDEV) from phase
/// (integrated) data, O(M) per averaging factor, with EDF-based confidence intervals.
/// Estimator definitions: ../shared/docs/theory.md §2 (NIST SP 1065 eqs. as cited there).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "analysis/deviation_type.h"
#include "analysis/variance_estimate.h"

namespace imunoise::analysis {

/// @name Input preparation
/// @{
/// Phase from rate samples y (e.g. rad/s): x_0 = 0, x_k = τ0·Σ_{i<k}(y_i − ȳ), with the mean
/// removed first and a compensated running sum (theory.md §2 "Numerics"). Size n+1.
std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s);

/// phase_from_rate without a second array: SAMPLES holds the n rate samples on entry and the
/// n+1 phase samples on return, bit for bit those of phase_from_rate (for loops that turn one
/// simulated record after another into phase, e.g. the bootstrap).
void phase_from_rate_in_place(std::vector<double>& samples, double tau0_s);

/// Phase data with its mean slope removed: x_k − x_0 − k·(x_{M−1} − x_0)/(M−1). Every
/// statistic here is invariant to that trend; removing it keeps digits on large biases.
std::vector<double> detrended_phase(std::span<const double> phase);
/// @}

/// One statistic at averaging factor m (τ = m·τ0) from M phase samples. Throws
/// imunoise::AnalysisError when the record is too short for a single term, ContractViolation
/// when m < 1 or τ0 ≤ 0.
/// For TDEV the value is the time variance (phase unit²).
VarianceEstimate allan_family_variance(DeviationType type, std::span<const double> phase,
                                       std::int64_t m, double tau0_s);

/// OAVAR (TYPE oadev) or OHVAR (ohdev) at every factor of M_VALUES, the small factors sharing
/// cache-resident passes and the large ones a pass per group (analysis/difference_sums.h),
/// on the calling thread; each value equals allan_family_variance at that factor bit for bit.
/// Throws AnalysisError for a factor without a term, ContractViolation for another TYPE.
std::vector<VarianceEstimate> overlapping_variances(DeviationType type,
                                                    std::span<const double> phase,
                                                    std::span<const std::int64_t> m_values,
                                                    double tau0_s);

/// One point of a deviation curve.
struct DeviationPoint {
  std::int64_t m = 0;        ///< averaging factor
  double tau_s = 0.0;        ///< τ = m·τ0 [s] (Thêo1: 0.75·m·τ0) (Thêo1: 0.75·m·τ0)
  double value = 0.0;        ///< the deviation (not the variance), input unit (TDEV: phase unit)
  std::int64_t n_terms = 0;  ///< number of terms in the estimator sum
  int alpha = 0;             ///< power-law exponent of S_y(f) used for the EDF
  double edf = 0.0;          ///< equivalent degrees of freedom
  double ci_low = 0.0;       ///< lower confidence bound of the deviation
  double ci_high = 0.0;      ///< upper confidence bound of the deviation
};

/// Options of compute_deviation().
struct DeviationOptions {
  DeviationType type = DeviationType::oadev;
  double confidence = 0.683;  ///< two-sided confidence level of [ci_low, ci_high], in (0, 1)
  std::optional<int> alpha;   ///< force the noise type (else identified per τ, §3.4)
  unsigned threads = 0;       ///< worker threads across τ (0 = all cores)
  /// MTOTDEV, TTOTDEV, HTOTDEV, Thêo1: apply the SP 1065 bias removal for the per-τ alpha
  /// (Stable32's "bias correction"); ignored by the other statistics.
  bool bias_corrected = false;
};

/// A deviation curve with confidence intervals.
struct DeviationCurve {
  DeviationType type = DeviationType::oadev;
  double tau0_s = 0.0;
  std::int64_t n_phase = 0;  ///< M, number of phase samples (pooled curves: Σ M_k)
  double confidence = 0.683;
  std::vector<DeviationPoint> points;
  /// Pooled curves (compute_pooled_deviation) only: M_k of each independent piece; empty for
  /// a curve of one record. curve_edf() sums the EDF over these.
  std::vector<std::int64_t> piece_n_phase;
};

/// Computes TYPE at every averaging factor of AVERAGING_FACTORS (each must satisfy
/// 1 ≤ m ≤ max_averaging_factor(type, M)), with EDF (Greenhall–Riley, TOTDEV per SP 1065)
/// and chi-square intervals.
DeviationCurve compute_deviation(std::span<const double> phase, double tau0_s,
                                 std::span<const std::int64_t> averaging_factors,
                                 const DeviationOptions& options);

/// The statistics compute_pooled_deviation() can pool: those whose estimate is the mean of
/// squared differences, each inside one piece (ADEV, OADEV, MDEV, TDEV, HDEV, OHDEV).
bool is_poolable(DeviationType type);

/// TYPE over independent pieces of one record (the gap-free pieces of a recording with
/// time-stamp gaps), each piece's PHASES from its own rate samples. At every averaging
/// factor m, every piece with at least one term contributes:
///   σ²(m) = Σ_k n_k·σ²_k(m) / Σ_k n_k,
/// n_k its number of terms — exactly the estimator of theory.md §2 over all differences that
/// do not straddle a gap. The pieces are independent, so EDF = Σ_k EDF_k (each Greenhall–
/// Riley at the piece's M_k) and the interval follows from it as for one record (§3.1).
/// The noise type α per τ is options.alpha, else identified on the longest piece (§3.4).
/// Each m must satisfy 1 ≤ m ≤ max_averaging_factor(type, longest M_k). One piece gives
/// exactly compute_deviation(). Throws ContractViolation for a type that cannot be pooled or
/// no pieces, AnalysisError for an m out of range.
DeviationCurve compute_pooled_deviation(std::span<const std::span<const double>> phases,
                                        double tau0_s,
                                        std::span<const std::int64_t> averaging_factors,
                                        const DeviationOptions& options);

/// OADEV and OHDEV of the same record or pieces (the pair `analyze` reports).
struct AllanHadamardCurves {
  DeviationCurve oadev;
  DeviationCurve ohdev;
};

/// OADEV at OADEV_FACTORS and OHDEV at OHDEV_FACTORS of PHASES (one record, or pieces pooled
/// as compute_pooled_deviation does), each curve bit for bit the one compute_pooled_deviation
/// gives for its type with OPTIONS (whose type is ignored). A factor in both lists is read
/// from memory once for both statistics (x_k … x_{k+3m}: 4 streams instead of 3 + 4), which
/// took 0.72× the time of the two curves one after the other on 11.52 M samples, 0.63–0.69× on
/// 86.4 M (bench/RESULTS.md).
AllanHadamardCurves compute_pooled_allan_hadamard(std::span<const std::span<const double>> phases,
                                                  double tau0_s,
                                                  std::span<const std::int64_t> oadev_factors,
                                                  std::span<const std::int64_t> ohdev_factors,
                                                  const DeviationOptions& options);

/// The EDF imunoise attaches to each statistic (the models of analysis/edf.h,
/// total_family.h and extra_deviations.h): adev → GR03 (d=2, non-overlapping,
/// unmodified); oadev → d=2 overlapping; mdev and tdev → d=2 overlapping modified;
/// hdev → d=3 non-overlapping; ohdev → d=3 overlapping; totdev → edf_totdev(); mtotdev, ttotdev,
/// htotdev → total_family_edf(); theo1 → theo1_edf().
double edf_for(DeviationType type, int alpha, std::int64_t m, std::int64_t n_phase);

/// EDF of a point of CURVE at averaging factor M for noise type ALPHA: edf_for() at the
/// curve's n_phase, or for a pooled curve the sum over its pieces that hold a term at M.
double curve_edf(const DeviationCurve& curve, int alpha, std::int64_t m);

}  // namespace imunoise::analysis
