/// @file
/// @brief The one-sided PSD of a stochastic error model (theory.md §5.3), its cross-check
/// against a measured log-binned Welch spectrum, and the slope-region PSD read-off.
///
/// Every density is the **one-sided** S₁ on [0, f_s/2] in unit²/Hz (S₁ = 2S_Ω, theory.md
/// §1.2); coefficients are in the theory.md §1.3 convention (common/noise_coefficients.h).
#pragma once

#include <cstddef>
#include <vector>

#include "analysis/psd.h"
#include "common/noise_coefficients.h"

namespace imunoise::analysis {

/// @name Model spectrum (theory.md §5.3)
/// @{

/// The terms of S₁(f) separately, for plotting [unit²/Hz].
struct PsdTerms {
  /// Per term: Q 2(2πf)²τ0Q² for f ≤ f_s/2, else 0; N 2N²; B B²/(πf) (no low-frequency
  /// cut-off f₀); K K²/(2π²f²); R 2R²/(2πf)³.
  PerTerm<double> terms{};
  std::vector<double> gauss_markov;  ///< 4σ²T_c/(1 + (2πfT_c)²), one per model term
  double total() const;              ///< sum of all terms
};

/// S₁ of each term at f (see PsdTerms). Sinusoids are lines, not densities: they carry
/// power A²/2 at their frequency and no density anywhere, so they are left out here.
/// @param[in] f_hz frequency, > 0 [Hz]
/// @param[in] tau0_s sample interval τ0, > 0 [s] (sets the Q term and its f_s/2 cut-off)
/// @throws ContractViolation for f or τ0 not positive and finite, a negative or non-finite
/// coefficient, or a Gauss–Markov correlation time ≤ 0 (fitted or read models are valid).
PsdTerms model_psd_terms(const NoiseCoefficients& model, double f_hz, double tau0_s);

/// Total S₁(f) of the model (PsdTerms::total() without allocating). Same rules and errors.
double model_psd_one_sided(const NoiseCoefficients& model, double f_hz, double tau0_s);

/// @}
/// @name Cross-check of a fitted model against a measured spectrum
/// @{

/// Outcome of cross_check_psd().
struct PsdCrossCheck {
  std::size_t bins_compared = 0;   ///< binned points inside the compared band
  std::size_t bins_outside = 0;    ///< of those, outside the model's two-sided 99 % χ² interval
  double worst_log10_ratio = 0.0;  ///< max |log10(measured/model)| over the compared bins
  double f_min_hz = 0.0;           ///< lowest compared bin frequency [Hz]
  double f_max_hz = 0.0;           ///< highest compared bin frequency [Hz]
  bool pass = false;  ///< bins_outside ≤ max(2, ⌊0.05·bins_compared⌋), see cross_check_psd()
};

/// Compares a measured spectrum with a model bin by bin: under the model, dof·S₁/S₁_model of
/// a bin is χ²_dof, so a bin is "outside" when the ratio leaves
/// [χ²_dof(0.005), χ²_dof(0.995)]/dof. For a log-binned spectrum S₁_model is the model's
/// mean over the bin's raw frequencies, like the measured value.
///
/// Band: bins with frequency ≥ 3·resolution_hz (the Hann main lobe is ±2 raw bins wide, so
/// below that the estimate mixes in DC, which the detrend removed, and the steep low-frequency
/// power of red noise: +14 % at bin 3 for f⁻²; for a multi-rate spectrum resolution_hz is the
/// deepest level's, that of the lowest bins) and ≤ f_max_hz. Binned points whose raw bins,
/// widened by 4 bins (the Blackman–Harris main lobe) of their own spacing (bin_resolution_hz
/// when given), contain a model sinusoid are skipped: a line is not a density.
///
/// Pass rule: with 99 % intervals ~1 % of the bins fall outside by chance, and a correct
/// model compared on 30–60 bins has two or more outliers in 4–12 % of records; allowing
/// max(2, ⌊5 % of the compared bins⌋) brings that below ~2.5 %. A wrong level pushes whole
/// runs of high-dof bins outside, far beyond the allowance.
/// @param[in] binned log-binned (or raw, or multi-rate) Welch spectrum with dof
/// @param[in] model  coefficients to test
/// @param[in] tau0_s sample interval τ0 [s], > 0
/// @param[in] f_max_hz upper end of the band [Hz], e.g. the sensor's low-pass; ≤ 0 selects
///            0.8·f_s/2, away from the anti-alias roll-off
/// @throws ContractViolation on bad arguments; AnalysisError when no bin falls in the band.
PsdCrossCheck cross_check_psd(const Spectrum& binned, const NoiseCoefficients& model, double tau0_s,
                              double f_max_hz = 0.0);

/// @}
/// @name Slope-region read-off (traceability, theory.md §5.3 table; not the primary fit)
/// @{

/// One coefficient read from the region where its slope dominates.
struct PsdReadoffTerm {
  double value = 0.0;      ///< coefficient in the §1.3 unit (GM: plateau S₁ or f_c, below)
  bool found = false;      ///< false when no region of ≥ 3 bins with this slope exists
  double f_low_hz = 0.0;   ///< lowest bin frequency of the region [Hz]
  double f_high_hz = 0.0;  ///< highest bin frequency of the region [Hz]
  std::size_t bins = 0;    ///< binned points in the region
};

/// Coefficients read off a log-binned spectrum.
struct PsdReadoff {
  /// Per term: Q [rad | m/s], slope +2: Q = √(S₁/(2τ0))/(2πf); N [rad/√s | m/s/√s], slope 0:
  /// N = √(S₁/2); B [rad/s | m/s²], slope −1: B = √(πfS₁); K [rad/s^{3/2} | m/s^{5/2}],
  /// slope −2: K = πf√(2S₁); R [rad/s² | m/s³], slope −3: R = √(S₁(2πf)³/2).
  PerTerm<PsdReadoffTerm> terms;
  PsdReadoffTerm gm_plateau;    ///< plateau S₁ = 4σ²T_c of a Gauss–Markov [unit²/Hz]
  PsdReadoffTerm gm_corner_hz;  ///< corner f_c = 1/(2πT_c) where S₁ falls to half [Hz];
                                ///< its region is the −2 roll-off run
};

/// Slope-region read-off of a log-binned spectrum.
///
/// Method: the local log-log slope at each binned point is the least-squares slope of
/// log S₁ against log f over that point and two neighbours on each side (fewer at the
/// ends); 5 points rather than 3 because a slope from 3 points of a 10-per-decade spectrum
/// has sd ≈ 3·√(2/ν), too noisy for a ±0.3 window below ν ≈ 400.
/// A term's region is a contiguous run of ≥ 3 points whose local slope is within ±0.3 of
/// the term's slope (+2, 0, −1, −2, −3), the red ones (≤ −1) only below f_s/8, where the
/// sampling of a τ0-averaged red process has bent S₁ by < 5 %; ±0.3 keeps the windows of
/// neighbouring integer slopes disjoint and lets another term carry at most 30 % (one slope unit
/// away) or 15 % (two units away) of the power at the region's edge. When several runs qualify, the
/// longest is used (ties: more total dof). Each point of the region implies a coefficient² by the
/// theory.md §5.3 formula; these are averaged as power (not in log, which would bias low by ~1/ν,
/// §4.2), weighted by dof (inverse variance, since Var(S₁) = 2S₁²/ν).
///
/// Gauss–Markov: a slope-0 run followed by a slope −2 run starting within a decade of its
/// end (a Lorentzian's slope passes from −0.3 to −1.7 over a factor 5.7 in f). Its
/// plateau and corner solve together: f_c is where S₁ first falls to half the plateau
/// (log-interpolated), and each plateau point implies the plateau S₁·(1 + (f/f_c)²), of
/// which the dof-weighted mean is taken (the run reaches where the Lorentzian is already
/// ~15 % down). N is then read only from flat runs above the start of the roll-off (white
/// noise below a visible plateau would hide it), and the roll-off is not used for K.
/// Limitation: white noise followed by a sensor low-pass falling as f⁻² looks the same.
///
/// τ0 for Q is 1/sample_rate_hz (hand-made spectra without it: 1/(resolution_hz·segment_length)).
/// @throws ContractViolation when the spectrum is empty, its sizes differ or neither its sample
///   rate nor its resolution is set; InputError when a bin's frequency, density or dof is not
///   positive and finite.
PsdReadoff psd_readoff(const Spectrum& binned);

/// @}

}  // namespace imunoise::analysis
