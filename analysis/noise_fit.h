/// @file
/// @brief The primary noise-coefficient estimator (theory.md §4.3): iteratively re-weighted
/// non-negative least squares of the Allan (or Hadamard) variance in the σ² domain, with
/// optional Gauss–Markov and sinusoid terms, model selection by a correlation-aware penalty,
/// and the multi-Gauss–Markov stand-in for bias instability (theory.md §4.4 "Preferred").
///
/// Units: τ in s; variances in (rate unit)², e.g. (rad/s)²; coefficients as in
/// common/noise_coefficients.h (SI).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "analysis/deviation.h"
#include "analysis/noise_terms.h"
#include "common/noise_coefficients.h"

namespace imunoise::analysis {

/// One measured variance: σ̂²(τ) and its equivalent degrees of freedom.
struct FitPoint {
  double tau_s = 0.0;  ///< averaging time τ [s], > 0
  double avar = 0.0;   ///< σ̂²(τ) [rate unit²]: OAVAR, or OHVAR when FitOptions::hadamard
  double edf = 0.0;    ///< EDF ν of σ̂² (≤ 0: unknown; such a point is not fitted)
};

/// The points of an AVAR-type (adev, oadev, totdev) or HVAR-type (hdev, ohdev; set
/// FitOptions::hadamard) deviation curve, in curve order: avar = value², edf = the curve's EDF
/// capped at the largest EDF of white, flicker and random-walk rate noise (alpha 0, −1, −2)
/// for that m and M. The cap matters at large m, where the per-τ noise identification falls
/// back to a lag-1 estimate on ~30 points and can report white or flicker angle noise
/// (alpha 2, 1), whose EDF is of order M: such a point would get ~10³× its due weight. It
/// never raises an EDF; it lowers genuine quantization-dominated points by at most ~3×.
/// @throws ContractViolation for the other statistics (their expectation is not AVAR or HVAR).
std::vector<FitPoint> fit_points(const DeviationCurve& curve);

/// Whether fit_noise_model() adds first-order Gauss–Markov terms.
enum class GaussMarkovMode {
  off,  ///< power-law terms and sinusoids only
  on,   ///< add a grid of GM terms (3 per decade of T_c over the τ range), merge the non-zero
        ///< ones into clusters and refine each cluster's (σ, T_c) by a 1-D search in ln T_c
  /// fit both ways (each with its own model selection) and keep the GM model only when its
  /// penalized deviance D + p·κ·n_used/n_eff is below the power-law model's: a sum of GM
  /// terms can stand in for flicker B and a long-T_c GM for K, so within one backward
  /// elimination GMs displace B and K (battery, `on` on every channel: GMs on 94 % of the
  /// channels without one); compared whole, the power-law model wins where it is as good
  automatic,
};

/// Penalty threshold κ of the model selection, per parameter and per effective point (see
/// fit_noise_model()). For one absent term at the boundary the deviance drop per effective
/// point would be ½χ²₀ + ½χ²₁ if the octaves were independent (κ = 6.6 → 0.5 % false), but the
/// measured null is heavier for the long-τ terms (B, K: few independent intervals, ν ~ 5–20),
/// so κ is calibrated by simulation (white noise only, 1 h at 100 Hz, log:10 grid, 600 seeds):
/// κ = 6.6 keeps at least one of Q, B, K, R in 4.0 % of the seeds, κ = 9 in 2.0 %, κ = 12 in
/// 0.7 %, while a random walk with the §8 K is kept in 100 % at each of these κ.
inline constexpr double kSelectionThreshold = 12.0;

/// Options of fit_noise_model().
struct FitOptions {
  PerTerm<bool> allow_terms{true, true, true, true, true};
  GaussMarkovMode gauss_markov = GaussMarkovMode::automatic;
  std::vector<double> sinusoid_frequencies_hz;  ///< candidate lines f > 0 [Hz] (e.g. PSD peaks);
                                                ///< amplitude fitted per frequency
  int weight_iterations = 5;  ///< re-weightings w_k = ν_k/(2m_k²) from the model after the first
                              ///< solve with m_k = σ̂²_k (theory.md §4.3), ≥ 0
  double min_edf = 4.0;       ///< drop τ with ν below this (theory.md §4.3: ν < ~3–5)
  double tau_min_s = 0.0;     ///< drop τ below this [s] (sensor low-pass region); 0 = keep all
  double tau_max_s = 0.0;     ///< drop τ above this [s]; 0 = no limit
  bool hadamard = false;      ///< points are HVAR (OHDEV²): fit with the HVAR basis (no ramp)
  double selection_threshold = kSelectionThreshold;  ///< κ of the model selection (see
                                                     ///< fit_noise_model()); 0 = keep every
                                                     ///< term NNLS does not set to zero
};

/// Fit of one power-law term.
struct TermFit {
  double value = 0.0;         ///< coefficient (Q, N, B, K or R, SI); 0 when not identified
  bool identified = false;    ///< kept by the fit and the model selection
  double contribution = 0.0;  ///< max over the used τ of (this term's variance)/(model variance)
};

/// Result of fit_noise_model() / refit_fixed_terms().
struct FitResult {
  NoiseCoefficients coefficients;  ///< fitted model; 0 for terms not identified
  PerTerm<TermFit> terms;
  std::vector<std::size_t> used;            ///< indices of the input points that were fitted
  double tau_min_s = 0.0;                   ///< smallest fitted τ [s]
  double tau_max_s = 0.0;                   ///< largest fitted τ [s]
  std::vector<double> residual_halfwidths;  ///< per input point: (σ̂ − σ_model) divided by the
                                            ///< 95 % CI half-width of σ̂ on the model's side;
                                            ///< |r| ≤ 1 ⇔ model inside the CI; NaN if ν ≤ 0
  double weighted_sse = 0.0;  ///< Σ_used w_k(σ̂²_k − m_k)² = Σ (ν_k/2)(r_k − 1)², r_k = σ̂²_k/m_k,
                              ///< m_k the final model (diagnostic)
  double deviance = 0.0;  ///< Σ_used ν_k(r_k − 1 − ln r_k): the gamma deviance, equal to
                          ///< weighted_sse to second order in r_k − 1; the selection criterion
  int parameters = 0;     ///< fitted parameters: 1 per power-law term and sinusoid, 2 per GM
  double effective_points = 0.0;  ///< n_eff of the selection penalty (one per octave of τ)
  bool hadamard = false;          ///< fitted with the HVAR basis (FitOptions::hadamard)
  std::string selection_note;     ///< why each candidate term was dropped, e.g.
                                  ///< "ramp dropped: deviance drop 0.8 < penalty 32.7"
};

/// Fits the noise model to measured AVAR (or HVAR) points (theory.md §4.3).
///
/// Estimator: the model σ²(τ) = Σ c_i φ_i(τ) is linear in c ≥ 0 (squared coefficients), solved
/// by NNLS on the √w-weighted system with w_k = ν_k/(2 m_k²); m_k starts at σ̂²_k and is then the
/// model value (1 + weight_iterations solves). This is Fisher scoring for σ̂² ~ m·χ²_ν/ν, so it
/// converges to the constrained maximum-likelihood fit, unbiased where data weights are not.
///
/// GM mode: NNLS over a grid of T_c (3 per decade, peaks inside the τ range) together with the
/// other terms; each run of adjacent non-zero grid terms becomes one GM whose T_c is refined by
/// golden-section search in ln T_c (all linear coefficients re-solved at each trial).
///
/// Model selection: a term NNLS sets to zero is not identified. Then backward elimination:
/// among the kept terms (power-law terms, GMs, sinusoids) the one with the smallest
/// ΔD/penalty is removed while ΔD < penalty, where ΔD is the rise of the deviance when it is
/// removed and the rest refitted, and penalty = p·κ·n_used/n_eff (p parameters of the term,
/// κ = options.selection_threshold). The deviance is the weighted SSE to second order; its
/// difference is the likelihood-ratio statistic of σ̂² ~ m·χ²_ν/ν, which stays close to χ² at the
/// small ν of long τ, where the Pearson SSE (r − 1)² has a heavy tail (seed study below: null
/// ΔSSE of B 3.6 per effective point against 2.0 for ΔD; a χ²₁ gives 1).
/// The factor n_used/n_eff corrects for the correlation of neighbouring τ (theory.md §3.5):
/// overlapping AVAR estimates one octave apart are nearly independent (Haar wavelet variances
/// of different octaves), a denser grid repeats the same information, so the summed weights
/// over-count it by the number of points per octave: n_eff = 1 + Σ over consecutive used τ of
/// min(1, log₂(τ_{k+1}/τ_k)). Check (white noise, 1 h at 100 Hz, 300 seeds, absent term added
/// to N alone): the null ΔD per n_used/n_eff, averaged over the seeds where NNLS keeps the term,
/// is 1.03 | 1.41 (Q), 2.04 | 1.94 (B), 1.33 | 1.28 (K), 1.00 | 1.02 (R) on a log:10 grid
/// (n_used/n_eff = 2.72) | an octave grid (1.00): the same for both densities, as intended.
/// κ is calibrated by simulation (kSelectionThreshold).
///
/// @throws AnalysisError when a value is not finite, τ ≤ 0, σ̂² < 0, all variances are 0, or
///         fewer than 2 points survive the EDF/τ filters (the message names the reason);
///         InputError when the τ range (the user's) is out of range; ContractViolation when
///         another option is, or no term is allowed.
FitResult fit_noise_model(std::span<const FitPoint> points, const FitOptions& options = {});

/// Re-fits the structure of a previous fit — the same points (STRUCTURE.used), the identified
/// power-law terms, the GM terms (T_c re-refined by the same 1-D search within ±1/3 decade of
/// the structure's value) and the sinusoid frequencies — with no model selection and no τ-range
/// choice. The estimator the parametric bootstrap re-runs on each simulated replicate.
/// Only weight_iterations is read from OPTIONS; the basis (AVAR/HVAR) is STRUCTURE's.
/// The result has no residual_halfwidths (empty): the refits of a bootstrap never read them.
/// With USED_CORRELATION (row-major n_used², the correlation of the estimates at
/// STRUCTURE.used, e.g. analysis/variance_covariance.h under the fitted model) the estimator is
/// feasible generalized least squares: Cov = DρD with D = diag(m_k·√(2/ν_k)), m_k STRUCTURE's
/// model held (not re-weighted per solve), i.e. the covariance across τ (theory.md §3.5) of
/// the estimates under that model as the weighting matrix.
/// The correlation's Cholesky factor is analysis::correlation_factor's (a ridge, else the nearest
/// positive definite matrix).
/// @throws AnalysisError when a used point is unusable or the structure has no term;
///   ContractViolation when a used index is out of
///   range, fewer than 2 points are used or USED_CORRELATION has the wrong size.
FitResult refit_fixed_terms(std::span<const FitPoint> points, const FitResult& structure,
                            const FitOptions& options,
                            std::span<const double> used_correlation = {});

/// FIT's structure (as selected by fit_noise_model) re-estimated by generalized least squares
/// with USED_CORRELATION, as refit_fixed_terms() does, but a complete result: residuals and
/// FIT's selection note kept. The `--estimator gls` of the analysis (docs/validation.md
/// compares it with the independent-point fit).
/// @throws as refit_fixed_terms(); ContractViolation when USED_CORRELATION is empty.
FitResult generalized_refit(std::span<const FitPoint> points, const FitResult& fit,
                            const FitOptions& options, std::span<const double> used_correlation);

/// Replaces bias instability B by first-order GM terms (theory.md §4.4 "Preferred"): correlation
/// times 1/per_decade decade apart (at least 2) spanning the fitted τ range
/// [FIT.tau_min_s, FIT.tau_max_s], σ_j fitted by the same re-weighted NNLS on FIT.used with the
/// other identified terms held at their fitted values; terms NNLS sets to zero are omitted.
/// The replacement model is FIT.coefficients with B = 0 plus the returned terms; check it with
/// fraction_inside_ci(). Spanning the whole range rather than only the flat region (§4.4 says
/// "2–4 over the flat region") is needed because B's constant variance is resolved by the
/// high-ν short-τ points too (seed study in tests/analysis/noise_fit_test.cpp: 2 h at 100 Hz,
/// §8 model, flat region only → ~50 % of the points inside their 95 % CI, whole range → ~100 %).
/// Empty when B is not identified.
/// @throws AnalysisError when a point of FIT.used is unusable; ContractViolation when FIT.used
///         does not index POINTS (or names fewer than 2) or per_decade is outside 1 … 10.
std::vector<GaussMarkov> multi_gm_representation(std::span<const FitPoint> points,
                                                 const FitResult& fit, int per_decade = 1);

/// Fraction of the points POINTS[USED] at which the model deviation √model_avar (√model_hvar
/// when HADAMARD) lies inside the two-sided χ² interval of coverage CONFIDENCE of the measured
/// deviation √σ̂² (theory.md §3.1). 1 means the model never leaves the intervals.
/// @throws AnalysisError when a point has no EDF; ContractViolation when USED is empty, an index
///   is out of range or CONFIDENCE is outside (0, 1).
double fraction_inside_ci(std::span<const FitPoint> points, std::span<const std::size_t> used,
                          const NoiseCoefficients& model, double confidence = 0.95,
                          bool hadamard = false);

/// An interval of one coefficient [its SI unit].
struct CoefficientInterval {
  double low = 0.0;
  double high = 0.0;
};

/// (ΦᵀWΦ)⁻¹ intervals of the identified power-law terms of FIT (normal approximation on c from
/// the covariance of c², weights ν/(2m²) from the fitted model, FIT's basis); zero intervals
/// for terms not identified. Ignores the correlation between τ points (theory.md §3.5), so it
/// is optimistic: the fallback when no bootstrap is run.
PerTerm<CoefficientInterval> least_squares_intervals(std::span<const FitPoint> points,
                                                     const FitResult& fit, double confidence);

/// FIT's structure (its identified power-law terms, sinusoids and GM terms, T_c held) re-fitted
/// on FIT.used by the same re-weighted NNLS with TERM — one FIT did not identify — held at
/// HELD (c²·basis as a fixed offset, as profile_upper_bound() does). The model that
/// lies at the edge of what the data allow for TERM: the identified terms of the result are
/// where they move when TERM is as large as its bound (analysis/selection_uncertainty.h).
/// The result's coefficients hold TERM at HELD; terms[TERM] stays not identified.
/// @throws AnalysisError when a point of FIT.used is unusable; ContractViolation when TERM is
///   identified in FIT, HELD is negative or not finite, or FIT.used does not index POINTS.
FitResult refit_with_term_held(std::span<const FitPoint> points, const FitResult& fit,
                               NoiseTerm term, double held,
                               int weight_iterations = FitOptions{}.weight_iterations);

/// Profile upper bound of a term FIT did not identify: the coefficient c at which forcing the
/// term to c (c²·basis added as a fixed offset, FIT's other terms re-fitted by the same
/// re-weighted NNLS, GM T_c held) raises the gamma deviance by χ²₁(CONFIDENCE)·f. Without
/// USED_CORRELATION, f = n_used/n_eff, the correlation-corrected scale of the model selection.
/// With it — the correlation matrix of the variance estimates at FIT.used (row-major, n_used²;
/// e.g. analysis/variance_covariance.h under FIT's model) — f is the variance inflation of the
/// term's own direction: f = uᵀCu/uᵀu (at least 1), u the term's weighted basis made orthogonal
/// to FIT's fitted columns (theory.md §4.3): a term carried by a few strongly correlated long-τ
/// points (K, R) gets the wider bound its estimate's real spread calls for. Infinity if no c
/// within reach of the data (the term alone 100× the data at its most favourable point) does.
/// @throws AnalysisError when a point of FIT.used is unusable, ContractViolation when FIT.used
///   does not index POINTS or USED_CORRELATION is neither empty nor n_used².
double profile_upper_bound(std::span<const FitPoint> points, const FitResult& fit, NoiseTerm term,
                           double confidence,
                           int weight_iterations = FitOptions{}.weight_iterations,
                           std::span<const double> used_correlation = {});

/// T_c grid of gauss_markov_upper_bounds(): PER_DECADE points per decade on round values
/// (10^(j/PER_DECADE) to three significant digits) from the one at or below TAU_MIN_S to the one at
/// or above TAU_MAX_S — a GM with T_c far outside the fitted τ range acts as white noise (below) or
/// a random walk (above) there, which N and K's bounds already cover.
/// @throws ContractViolation unless 0 < TAU_MIN_S ≤ TAU_MAX_S and PER_DECADE ≥ 1.
std::vector<double> gauss_markov_bound_grid(double tau_min_s, double tau_max_s, int per_decade = 4);

/// Profile upper bounds of a Gauss–Markov term FIT does not hold, one per T_c of TAU_C_GRID_S
/// (issue 20: when the selection keeps no GM, or fewer than the data have, say which GMs the
/// data exclude instead of nothing). At each T_c, σ² times the GM's basis is held in the model
/// and FIT's structure (GM T_c held) re-fitted, as profile_upper_bound() does; σ_max is where the
/// deviance rises above FIT's own (no further GM) by χ²_p(CONFIDENCE)·f — f as in
/// profile_upper_bound() (the variance inflation of the GM's direction under USED_CORRELATION,
/// taken at the best σ; n_used/n_eff without it), p = 1 + the number of FIT's terms the held
/// fit sets to zero (a K standing in for the GM goes to 0 when the GM is held: a chi-bar-square
/// statistic). Pointwise in T_c: for a GM of that T_c, σ_max is an upper bound of σ (measured
/// coverage: tests/analysis/gauss_markov_bound_test.cpp); the region below the curve is a joint
/// statement on (σ, T_c) whose T_c projection is every T_c. A T_c with no bound within reach of
/// the data (the GM alone 100× the data at its most favourable point) is left out. Empty when
/// FIT has fewer than 2 points.
/// @throws AnalysisError when a point of FIT.used is unusable; ContractViolation when FIT.used
///   does not index POINTS, a T_c is not positive or USED_CORRELATION is neither empty nor
///   n_used².
std::vector<GaussMarkovBound> gauss_markov_upper_bounds(
    std::span<const FitPoint> points, const FitResult& fit, std::span<const double> tau_c_grid_s,
    double confidence, int weight_iterations = FitOptions{}.weight_iterations,
    std::span<const double> used_correlation = {});

}  // namespace imunoise::analysis
