/// @file
/// @brief Everything `imunoise analyze` computes for one sensor axis, as pure computation:
/// OADEV and OHDEV with chi-square intervals, multi-rate Welch PSD, the weighted NNLS fit of the
/// whole model (theory.md §4.3) with its parametric-bootstrap intervals, the IEEE-952 and PSD
/// read-offs for traceability, the B → Gauss–Markov conversions (§4.4) and the PSD
/// cross-check (§5.4) — assembled into a models::AxisModel.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/deviation.h"
#include "analysis/noise_fit.h"
#include "analysis/psd.h"
#include "analysis/psd_model.h"
#include "analysis/slope_readoff.h"
#include "analysis/spectral_lines.h"
#include "analysis/tau_grid.h"
#include "analysis/variance_covariance.h"
#include "common/progress_callback.h"
#include "models/noise_model.h"
#include "pipeline/bootstrap.h"
#include "pipeline/low_pass_corner.h"

namespace imunoise::pipeline {

/// Settings shared by every axis of one analysis.
struct AxisAnalysisOptions {
  double confidence = 0.95;  ///< level of every reported interval
  analysis::TauGridSpec grid = analysis::parse_tau_grid("log:10");  ///< τ grid of the curves
  analysis::FitOptions fit;   ///< fit settings (tau_min_s 0 = automatic low-pass check)
  bool auto_low_pass = true;  ///< drop leading τ bent below the white line (§4.3)
  /// Re-estimate the selected structure (and every interval replicate) by generalized least
  /// squares with the correlation of the estimates under the fitted model, twice re-derived
  /// (analysis::generalized_refit; `--estimator gls`); false: the independent-point fit.
  bool generalized_least_squares = false;
  /// PSD window, overlap and detrend of every level of the multi-rate estimate
  /// (analysis/multirate_psd.h); welch.segment_length is the classic L₀ that fixes the
  /// lowest resolution (0 = automatic).
  analysis::WelchOptions welch;
  std::size_t psd_level_segment_length = 4096;  ///< L of every level of the multi-rate PSD
  int psd_bins_per_decade = 10;
  /// Spectral lines (analysis/spectral_lines.h): searched in a raw Welch spectrum by default,
  /// fitted on the samples and removed before the deviations; fit.sinusoid_frequencies_hz are
  /// fitted the same way whether or not they stand above the continuum (one concept: a line
  /// is a sinusoid fitted on the samples, never a column of the AVAR fit here).
  bool find_lines = true;
  analysis::LineSearchOptions lines;
  /// Longest Welch segment of the line search [samples]: the automatic length of the record,
  /// at most this (2^20: 1 ms of FFT per segment point budget, ~0.001 Hz at 1 kHz).
  std::size_t line_segment_length_max = std::size_t{1} << 20;
  int bootstrap_replicates = 200;  ///< 0 = no bootstrap: intervals from (ΦᵀWΦ)⁻¹ instead
  /// Where the replicates' variances come from (pipeline/bootstrap.h).
  ReplicateSource interval_source = ReplicateSource::variance_distribution;
  std::uint64_t seed = 1;  ///< bootstrap master seed (axis index is mixed in)
  unsigned threads = 1;    ///< threads for this axis (deviation τ and bootstrap)
  /// How the fit note names the way to ask for the bootstrap ("Gauss-Markov intervals need the
  /// bootstrap (…)"); the CLI passes its flag, "--bootstrap N".
  std::string bootstrap_setting = "bootstrap_replicates >= 2";
  /// Optional progress of one axis, in units of 4 + bootstrap_replicates (0 without the
  /// bootstrap): OADEV, OHDEV, fit, PSD, then one per replicate. The stage named is the one
  /// now running: "deviations", "fit", "PSD", "bootstrap" or "intervals", and "done" at the
  /// end (done == total). Does not change the result.
  ProgressCallback progress;
};

/// The complete result of one axis.
struct AxisAnalysis {
  analysis::DeviationCurve oadev;
  analysis::DeviationCurve ohdev;
  analysis::Spectrum psd;  ///< log-binned one-sided PSD (multi-rate, analysis/multirate_psd.h)
  analysis::FitResult fit;
  analysis::SlopeReadoff slope;
  analysis::PsdReadoff psd_readoff;
  analysis::PsdCrossCheck psd_check;
  /// The PSD's low-pass roll-off against the fitted model (pipeline/low_pass_corner.h), found
  /// once per axis: it bounds psd_check's band and makes the recording's low-pass finding.
  LowPassCorner low_pass;
  /// The −3 dB low-pass corner that bounded psd_check's band (pipeline/low_pass_corner.h;
  /// 0 = none found or the check off) [Hz].
  double psd_check_low_pass_hz = 0.0;
  analysis::LineDetection lines;  ///< the line search (empty when not run)
  models::AxisModel model;
};

/// Analyses the rate samples of one axis (SI: rad/s for a gyro, m/s² for an accelerometer)
/// at sample period TAU0_S. AXIS_INDEX only decorrelates the bootstrap seeds of the axes.
/// Throws AnalysisError with a clear reason when the record cannot support a fit (too short,
/// constant, non-finite).
AxisAnalysis analyze_axis(const std::string& name, SensorKind kind, std::span<const double> rate,
                          double tau0_s, int axis_index, const AxisAnalysisOptions& options);

/// analyze_axis over the independent gap-free PIECES of one record (`--gaps split`): OADEV
/// and OHDEV pooled per τ over the pieces (analysis::compute_pooled_deviation: σ² weighted
/// by the term counts, EDF summed), the multi-rate PSD pooled over pieces level by level
/// (analysis::pooled_multirate_psd), then the fit on the pooled curves as usual. The bootstrap
/// simulates one record of the total length — an approximation the fit note states. One
/// piece is exactly analyze_axis. PIECES must not be empty (ContractViolation).
AxisAnalysis analyze_axis_pieces(const std::string& name, SensorKind kind,
                                 std::span<const std::span<const double>> pieces, double tau0_s,
                                 int axis_index, const AxisAnalysisOptions& options);

/// The likely cause of a PSD misfit band as the finding says it ("likely …"), for the note
/// below and for report/finding_remedies, which recognises it.
std::string_view psd_misfit_cause_text(analysis::PsdMisfitCause cause);

/// The PSD cross-check note of model.yaml: "B of C PSD bins outside their 99 % interval
/// (F1–F2 Hz)" (", up to 1/4 of the low-pass corner X Hz" inside the brackets when
/// LOW_PASS_CORNER_HZ > 0 bounded the band), and when the check failed its largest bands (at most
/// three, by bins; in frequency order), each "above|below the model at F1–F2 Hz (n bins, up to ×r):
/// likely …".
std::string psd_check_note(const analysis::PsdCrossCheck& check, double low_pass_corner_hz = 0.0);

/// The PSD cross-check compares bins up to this fraction of a detected low-pass corner: a
/// 2nd-order roll-off (|H|² = 1/(1 + (f/f_c)⁴), the gentlest MEMS DLPF) is 0.4 % down there,
/// below the scatter of the highest bins, and at 0.44·f_c already 3.6 % (the battery's
/// lowpass class failed on every channel there). The model has no filter term; the fit
/// starts above the filter's τ (low_pass_tau_min) for the same reason.
inline constexpr double kPsdCheckLowPassFraction = 0.25;

/// Noise type α (S_y ∝ f^α) of the term of C that dominates the AVAR (HADAMARD: HVAR) at τ.
int model_noise_alpha(const NoiseCoefficients& c, double tau_s, bool hadamard);

/// Re-derives α, EDF and the interval of every point of CURVE from the model C instead of the
/// lag-1 identification (which is unreliable with few points at large m).
void apply_model_noise_type(analysis::DeviationCurve& curve, const NoiseCoefficients& c);

/// The fit of CURVE's OAVAR as analyze runs it (theory.md §4.3, model-based weights): a first
/// fit with CURVE's noise types, then CURVE's α, EDF and intervals re-derived from that model
/// (apply_model_noise_type) and the fit repeated on them; POINTS is set to the points of that
/// second fit. With GaussMarkovMode::automatic the first fit is the power-law one: it only
/// sets the noise types, and the GM candidate (the costly half of an automatic fit) is fitted
/// once, on the final EDFs.
analysis::FitResult fit_with_model_noise_types(analysis::DeviationCurve& curve,
                                               const analysis::FitOptions& options,
                                               std::vector<analysis::FitPoint>& points);

/// The joint moments of the OAVAR (OHVAR when FIT.hadamard) estimates at FIT.used under FIT's
/// model (analysis::overlapping_variance_covariance); M_LIST[k] is the averaging factor of the
/// k-th fit point, the record TOTAL_SAMPLES samples at period TAU0_S. Empty when FIT uses none.
analysis::VarianceCovariance used_point_moments(const analysis::FitResult& fit,
                                                std::span<const std::int64_t> m_list, double tau0_s,
                                                std::int64_t total_samples);

/// The correlation of MOMENTS' estimates, row-major (analysis::correlation_matrix); empty for
/// empty moments.
std::vector<double> row_major_correlation(const analysis::VarianceCovariance& moments);

/// row_major_correlation(used_point_moments(…)): the correlation of the OAVAR (OHVAR when
/// FIT.hadamard) estimates at FIT.used under FIT's model, row-major n_used². A point without
/// variance under the model is uncorrelated.
std::vector<double> used_point_correlation(const analysis::FitResult& fit,
                                           std::span<const std::int64_t> m_list, double tau0_s,
                                           std::int64_t total_samples);

/// The profile upper bound of every term FIT did not identify (0 for identified terms), as the
/// analysis reports it and widens the identified terms' intervals with
/// (analysis::selection_widened_intervals, model-selection uncertainty):
/// analysis::profile_upper_bound with the correlation of the variance estimates at FIT.used
/// under FIT's model (analysis/variance_covariance.h). M_LIST[k] is the averaging factor of
/// POINTS[k]; the record has TOTAL_SAMPLES samples at period TAU0_S. Shared by analyze_axis
/// and the recording plan (pipeline/recording_plan.h), so both widen the same way.
/// USED_CORRELATION: that correlation when the caller has it (used_point_correlation() of FIT),
/// empty: computed here.
PerTerm<double> selection_upper_bounds(std::span<const analysis::FitPoint> points,
                                       const analysis::FitResult& fit,
                                       std::span<const std::int64_t> m_list, double tau0_s,
                                       std::int64_t total_samples, double confidence,
                                       int weight_iterations,
                                       std::span<const double> used_correlation = {});

/// The first τ index not affected by a sensor low-pass: leading points whose σ²·τ is below
/// 0.8× that of the next point (the curve bends under the N/√τ line), looking only at
/// τ ≤ 8·τ0 where a digital anti-alias filter acts; when any is, the fit starts 50 times
/// above the first unbent τ (the deficit decays like 1/m). Returns the τ to start the fit at.
double low_pass_tau_min(const analysis::DeviationCurve& oadev);

}  // namespace imunoise::pipeline
