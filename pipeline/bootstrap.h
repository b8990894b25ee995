/// @file
/// @brief Parametric bootstrap of the noise fit (theory.md §4.3 "Parameter uncertainties"):
/// simulate the fitted model at the recording's length and rate, re-run the same OAVAR and the
/// same fixed-structure fit on each replicate, and turn the spread into 95 % intervals
/// (bias-corrected normal intervals on the log scale, see bootstrap.cpp). It
/// accounts for the correlation between τ points that (ΦᵀWΦ)⁻¹ ignores (theory.md §3.5).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "analysis/noise_fit.h"
#include "analysis/variance_covariance.h"
#include "common/noise_coefficients.h"
#include "common/progress_callback.h"

namespace imunoise::pipeline {

/// Where a replicate's variances come from.
enum class ReplicateSource {
  /// Simulate the fitted model at the record's length and rate (models::ChannelSimulator) and
  /// compute its OAVAR: the reference, at a cost proportional to the record per replicate.
  simulated_record,
  /// Draw the vector of OAVAR estimates from its distribution under the fitted model
  /// (analysis/variance_covariance.h): the model's correlation across τ through a Gaussian
  /// copula, each margin σ²·χ²_ν/ν with the model's EDF ν. Cost independent of the record.
  variance_distribution,
};

/// Settings of one bootstrap.
struct BootstrapOptions {
  ReplicateSource source = ReplicateSource::simulated_record;
  int replicates = 50;       ///< number of replicates
  std::uint64_t seed = 1;    ///< master seed; replicate r uses (seed, r)
  double confidence = 0.95;  ///< two-sided level of the intervals
  unsigned threads = 1;      ///< worker threads across replicates
  /// The correlation of the estimates at the fit's used points (row-major, n_used²): each
  /// replicate is refitted by generalized least squares with it (analysis::refit_fixed_terms);
  /// empty: the independent-point fit.
  std::vector<double> used_correlation;
  /// With ReplicateSource::variance_draw: the joint moments of the estimates at the fit's used
  /// points under FIT's model (analysis::overlapping_variance_covariance), when the caller has
  /// them (it outlives the call); null: computed here.
  const analysis::VarianceCovariance* moments = nullptr;
  /// Optional: ("bootstrap", replicates finished, replicates) after each replicate, from the
  /// worker threads. Does not change the result.
  ProgressCallback progress;
};

/// Interval of one scalar parameter.
using Interval = analysis::CoefficientInterval;

/// Bootstrap intervals of every fitted parameter.
struct BootstrapResult {
  int replicates = 0;
  PerTerm<Interval> terms;
  std::vector<Interval> gauss_markov_sigma;  ///< per fitted GM term (same order as the fit)
  std::vector<Interval> gauss_markov_tau_c;  ///< [s]
  /// Replicate values per term (for diagnostics and tests), replicates × 5.
  std::vector<PerTerm<double>> term_samples;
};

/// Bootstraps FIT (made by analysis::fit_noise_model on POINTS, whose τ are m·τ0 with the
/// averaging factors M_LIST) for a record of N_SAMPLES rate samples at τ0 = TAU0_S.
///
/// Each replicate gets OAVAR values at the M_LIST of FIT.used from options.source (simulated:
/// FIT's coefficients with models::ChannelSimulator, flicker band [τ0, record length]), reuses
/// the EDF of POINTS (the weights are model-based, theory.md §4.3), and refits with
/// analysis::refit_fixed_terms. The interval
/// of an identified term is the bias-corrected normal interval of ln θ (a scale parameter's
/// error is multiplicative) with Student's t for the replicate count, or the same in the
/// linear domain clipped at 0 when a replicate is 0.
/// @throws AnalysisError when fewer than 2 replicates could be fitted; ContractViolation when
///   POINTS and M_LIST differ in size, options.replicates < 2, N_SAMPLES < 2 or τ0 ≤ 0.
BootstrapResult bootstrap_fit(const analysis::FitResult& fit,
                              std::span<const analysis::FitPoint> points,
                              std::span<const std::int64_t> m_list, std::int64_t n_samples,
                              double tau0_s, const analysis::FitOptions& fit_options,
                              const BootstrapOptions& options);

/// The interval bootstrap_fit reports for ESTIMATE from the replicate values SAMPLES: the
/// bias-corrected normal interval of ln θ with Student's t for the replicate count, or the same
/// in the linear domain clipped at 0 when a replicate is ≤ 0 ({estimate, estimate} for fewer
/// than 2 replicates). Exposed for pipeline/recording_plan, which groups the replicates.
Interval bootstrap_interval(double estimate, const std::vector<double>& samples, double confidence);

}  // namespace imunoise::pipeline
