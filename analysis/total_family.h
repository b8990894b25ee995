/// @file
/// @brief The "total" family of NIST SP 1065 §5.2.12–5.2.14: modified total (MTOT), time total
/// (TTOT) and Hadamard total (HTOT) variances, their bias corrections and their EDF.
///
/// Conventions (as in deviation.h): M phase samples x_0 … x_{M−1} at spacing τ0; τ = m·τ0;
/// alpha = exponent of S_y(f) ∝ f^alpha (2 white PM … −4 random-run FM).
///
/// Definitions (SP 1065 eqs. 27–29 and §5.2.14; Howe & Vernotte 1999; Howe et al., PTTI 2000):
/// - MTOT: for each of the M − 3m + 1 runs of 3m phase points, remove the linear trend whose
///   slope is (mean of the last ⌊3m/2⌋ points − mean of the first ⌊3m/2⌋ points) / ⌈3m/2⌉,
///   extend the run to 9m points by uninverted even reflection at both ends, and average the
///   6m squared second differences of m-point phase averages; MTOT(τ) is the mean of those
///   run averages divided by 2τ².
/// - TTOT: the time variance τ²/3 · MTOT(τ) (phase unit²).
/// - HTOT: the same construction on the N = M − 1 frequency values y_i = (x_{i+1} − x_i)/τ0
///   (3m-point runs, linear frequency trend removed, 9m reflection, 6m squared second
///   differences of m-point frequency averages), scaled by 1/6 as the Hadamard variance; at
///   m = 1 the overlapping Hadamard variance is used instead, as in SP 1065 and Stable32.
///
/// Complexity: O(M·m) per τ (each of the ~M runs is detrended, reflected and summed in O(m));
/// one scratch buffer of 9m + 1 values per call, no per-run allocation. A whole "all τ" curve
/// up to m = M/3 therefore costs O(M³): use octave/decade grids for long records.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "analysis/deviation_type.h"
#include "analysis/variance_estimate.h"

namespace imunoise::analysis {

/// Members of the total family.
enum class TotalFamilyType {
  mtotdev,  ///< modified total deviation (rate unit)
  ttotdev,  ///< time total deviation (phase unit)
  htotdev,  ///< Hadamard total deviation (rate unit)
};

/// Variance of TYPE at averaging factor m from M phase samples (TTOT: time variance, phase
/// unit²; MTOT, HTOT: (phase unit / s)²).
///
/// With bias_corrected, the plain estimate is divided by its expected ratio to the ordinary
/// variance for noise type alpha:
/// - MTOT and TTOT: Mod σ²_tot / Mod σ²_y = 0.94 (alpha 2), 0.83 (1), 0.73 (0), 0.70 (−1),
///   0.69 (−2) (W. Riley, "Confidence intervals and bias corrections for the Stable32 variance
///   functions", CI2.pdf p. 6, the factors Stable32 applies);
/// - HTOT: Htot/Hvar = 1 + a, a = −0.005 (alpha 0), −0.149 (−1), −0.229 (−2), −0.283 (−3),
///   −0.321 (−4) (Howe, Beard, Greenhall, Riley, PTTI 2000, Table 4); no correction for PM
///   noise (alpha 1, 2) nor at m = 1 (the overlapping Hadamard variance is unbiased).
/// Without it, the plain estimator (what Stable32 prints as "no bias correction").
/// @param[in] type    statistic
/// @param[in] phase   M phase samples (any unit)
/// @param[in] m       averaging factor, 1 ≤ m ≤ total_family_max_m(type, M)
/// @param[in] tau0_s  sample spacing τ0 > 0 [s]
/// @param[in] bias_corrected apply the bias correction for alpha
/// @param[in] alpha   noise type for the correction: −2 … 2 (MTOT, TTOT), −4 … 2 (HTOT)
/// @throws AnalysisError for a record too short for one term or an alpha outside the table
///         when bias_corrected; ContractViolation for m < 1 or τ0 ≤ 0.
VarianceEstimate total_family_variance(TotalFamilyType type, std::span<const double> phase,
                                       std::int64_t m, double tau0_s, bool bias_corrected = false,
                                       int alpha = 0);

/// The total-family member of a DeviationType (mtotdev, ttotdev, htotdev); nullopt otherwise.
std::optional<TotalFamilyType> total_family_type(DeviationType type);

/// Number of terms (runs) in the estimator, Stable32's "#" column: M − 3m + 1 for MTOT and
/// TTOT, M − 3m for HTOT (N − 3m + 1 frequency runs; at m = 1 the M − 3 overlapping Hadamard
/// differences). Zero or negative when the record is too short.
std::int64_t total_family_term_count(TotalFamilyType type, std::int64_t n_phase, std::int64_t m);

/// Largest averaging factor (Stable32 stop ratio 3 for all three): ⌊M/3⌋ for MTOT and TTOT,
/// ⌊(M − 1)/3⌋ for HTOT (3 on the N = M − 1 frequency values). Every m up to it has ≥ 1 term.
std::int64_t total_family_max_m(TotalFamilyType type, std::int64_t n_phase);

/// Equivalent degrees of freedom:
/// - MTOT, TTOT: ν = b·(M/m) − c with (b, c) = (1.90, 2.10) alpha 2, (1.20, 1.40) alpha 1,
///   (1.10, 1.20) alpha 0, (0.85, 0.50) alpha −1, (0.75, 0.31) alpha −2 (SP 1065 Table 8);
/// - HTOT: SP 1065 gives no formula; the Greenhall–Riley EDF of the overlapping Hadamard
///   variance, edf_greenhall(alpha, 3, m, M, overlapping, unmodified), which Stable32 also
///   uses for small m (Riley, Stable32 help). Alpha −4 … 2.
/// Stable32's printed MTOT/TTOT/HTOT bounds for PHASE.DAT are NOT reproduced by these models
/// (implied Stable32 ν, MTOT alpha 0: 790, 485, 243, 120 at m = 1, 2, 4, 8 ≈ GR03 MDEV EDF
/// +1 %; ≈ (4/3)·1000/m − 1.9 for m ≥ 16; HTOT alpha 0: 677, 578, 352, 186, 110 at
/// m = 1 … 16, about 1.1–1.5× the GR03 OHDEV EDF); no source for those models was found.
/// @throws AnalysisError for alpha outside the table, m < 1 or m > total_family_max_m.
double total_family_edf(TotalFamilyType type, int alpha, std::int64_t m, std::int64_t n_phase);

}  // namespace imunoise::analysis
