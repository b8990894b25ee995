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
  /// Per term, the PSD of the sampled record y_k = (θ_{k+1} − θ_k)/τ0 (each sample the
  /// average of the rate over its interval; docs/conventions.md §4.1 derives each row), x = fτ0,
  /// s = sin(πx), for 0 < f ≤ f_s/2 (all 0 above): Q 8s²Q²/τ0; N 2N²; B (B²τ0/π³)·s²·[ζ(3, x) +
  /// ζ(3, 1 − x)] (Hurwitz ζ; no low-frequency cut-off f₀); K K²τ0²(2 + cos 2πx)/(6s²); R 0
  /// (a deterministic ramp has no density). Where x ≪ 1 they are theory.md §5.3's continuous
  /// 2(2πf)²τ0Q², 2N², B²/(πf), K²/(2π²f²); at 0.4·f_s Q, B and K are 0.57, 0.77 and 0.69
  /// of those.
  PerTerm<double> terms{};
  /// One per model term, the τ0-averaged Gauss–Markov: with r = τ0/T_c, φ = e^{−r},
  /// 2τ0[(c₀ − A) + A(1 − φ²)/((1 − φ)² + 4φs²)], c₀ = 2σ²[1 − (1 − φ)/r]/r,
  /// A = σ²(1 − φ)²/(φr²); 4σ²T_c/(1 + (2πfT_c)²) where r ≪ 1 and x ≪ 1.
  std::vector<double> gauss_markov;
  double total() const;  ///< sum of all terms
};

/// S₁ of each term at f (see PsdTerms). Sinusoids are lines, not densities: they carry
/// power A²/2 at their frequency and no density anywhere, so they are left out here.
/// These sampled forms are the spectra whose AVAR at τ = mτ0 (the kernel of τ0-spaced
/// samples) is exactly theory.md §4.1's, the model noise_fit fits.
/// @param[in] f_hz frequency, > 0 [Hz]; above f_s/2 every term is 0
/// @param[in] tau0_s sample interval τ0, > 0 [s]
/// @throws ContractViolation for f or τ0 not positive and finite, a negative or non-finite
/// coefficient, or a Gauss–Markov correlation time ≤ 0 (fitted or read models are valid).
PsdTerms model_psd_terms(const NoiseCoefficients& model, double f_hz, double tau0_s);

/// Total S₁(f) of the model (PsdTerms::total() without allocating). Same rules and errors.
double model_psd_one_sided(const NoiseCoefficients& model, double f_hz, double tau0_s);

/// @}
/// @name Cross-check of a fitted model against a measured spectrum
/// @{

/// The likely cause of a band of bins outside their interval (cross_check_psd()).
enum class PsdMisfitCause {
  spectral_line,          ///< narrow peak (≤ 2 bins, ≥ 1.5×) away from the bottom: a line
  isolated,               ///< one bin alone, not a peak: chance or a small local misfit
  high_frequency_excess,  ///< above the model in the top band: aliasing, unmodelled HF noise
  low_pass,               ///< below the model in the top band: the sensor's low-pass filter
  low_frequency_excess,   ///< above at the bottom: a missing K or R, or a warm-up (non-stationary)
  low_frequency_deficit,  ///< below at the bottom: a fitted K, R or B the spectrum does not show
  level,                  ///< a flat offset over a wide band: the broadband level (N)
  band_excess,            ///< above the model in a middle band: an unmodelled term there (GM bump)
  band_deficit,           ///< below the model in a middle band: a fitted term too large there
};

/// A band of compared bins outside their 99 % interval on the same side of the model.
struct PsdMisfitBand {
  double f_low_hz = 0.0;       ///< lowest bin frequency of the band [Hz]
  double f_high_hz = 0.0;      ///< highest bin frequency of the band [Hz]
  std::size_t bins = 0;        ///< bins outside in the band
  bool above = false;          ///< measured above the model
  double extreme_ratio = 1.0;  ///< measured/model of the band's bin farthest from 1 (in log)
  PsdMisfitCause cause = PsdMisfitCause::level;
};

/// A single top bin is called a low-pass roll-off only below this measured/model ratio.
inline constexpr double kSingleBinRollOffRatio = 0.9;

/// Outcome of cross_check_psd().
struct PsdCrossCheck {
  std::size_t bins_compared = 0;   ///< binned points inside the compared band
  std::size_t bins_outside = 0;    ///< of those, outside the model's two-sided 99 % χ² interval
  double worst_log10_ratio = 0.0;  ///< max |log10(measured/model)| over the compared bins
  double f_min_hz = 0.0;           ///< lowest compared bin frequency [Hz]
  double f_max_hz = 0.0;           ///< highest compared bin frequency [Hz]
  bool pass = false;  ///< bins_outside ≤ max(2, ⌊0.05·bins_compared⌋), see cross_check_psd()
  /// When the check fails: its bands of outside bins, in frequency order (empty on a pass).
  std::vector<PsdMisfitBand> misfits;
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
///
/// Diagnosis (a failed check only): the compared bins in frequency order are cut into bands,
/// each a run of outside bins on the same side of the model that may bridge one inside bin on
/// that side. A band is flat when it has ≥ 4 outside bins and the mean log ratio of their
/// upper half is within 30 % of that of their lower half; it is at the bottom (top) when it
/// touches the two lowest (highest) compared bins. Its likely cause (PsdMisfitCause): at both
/// ends, level when flat, else the end with the larger mean log ratio decides as below; at the
/// bottom, low_frequency_excess or _deficit; a peak of ≤ 2 bins elsewhere (≥ 1.5× the model,
/// its neighbours within a third of that excess), spectral_line; any other single bin not at
/// the top, and a single top bin below the model by less than kSingleBinRollOffRatio,
/// isolated; at the top, level when flat, else high_frequency_excess (above) or low_pass
/// (below);
/// otherwise level when flat and over half the compared bins, else band_excess or
/// band_deficit. Causes are likely, not proven: one low bin cannot tell a warm-up from a
/// random walk.
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
