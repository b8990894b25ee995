/// @file
/// @brief Equivalent degrees of freedom (EDF) of the Allan-family variance estimators for
/// power-law noise: Greenhall & Riley 2003 [GR03] for ADEV/OADEV/MDEV/TDEV/HDEV/OHDEV, the
/// NIST SP 1065 b·T/τ − c fit for TOTDEV, and the SP 1065 Table 5 "simple" OADEV formulas.
///
/// Conventions (theory.md §1.1, §3): n_phase = M phase samples x_0 … x_{M−1} (M = n + 1 for
/// n rate samples); τ = m·τ0; alpha = exponent of S_y(f) ∝ f^alpha (2 white PM, 1 flicker PM,
/// 0 white FM, −1 flicker FM, −2 random-walk FM, −3 flicker-walk FM, −4 random-run FM).
/// Every function throws imunoise::AnalysisError for a noise type alpha outside its range (alpha
/// may be the user's `allan --alpha`) or a record too short for m, and ContractViolation for a
/// d or m outside its range or an unknown deviation type (the callers derive them).
#pragma once

#include <cstdint>

#include "analysis/deviation_type.h"

namespace imunoise::analysis {

/// @name Greenhall–Riley EDF [GR03] (theory.md §3.3)
/// @{

/// EDF of a d-th difference variance (d = 1 first difference, 2 Allan, 3 Hadamard), computed
/// with the GR03 algorithm exactly as W. Riley implemented it for Stable32 ("CombinedEDF"):
/// J ≤ 100 summands are evaluated directly (GR03 eq. 13), larger J use the asymptotic
/// Tables 1–3 (r = M'/S ≥ d+1) or the reduced sum with m' = 100/r (r < d+1).
/// @param[in] alpha noise exponent, −4 … 2, with alpha + 2d > 1 (the variance must converge)
/// @param[in] d     difference order, 1 … 3
/// @param[in] m     averaging factor ≥ 1
/// @param[in] n_phase number of phase samples M; needs M ≥ L = m/F + m·d (F = 1 or m)
/// @param[in] overlapping stride S = m (overlapping) or S = 1 (non-overlapping)
/// @param[in] modified    filter factor F = 1 (modified) or F = m (unmodified)
/// @return EDF ν (> 0, not necessarily an integer)
double edf_greenhall(int alpha, int d, std::int64_t m, std::int64_t n_phase, bool overlapping,
                     bool modified);

/// The GR03 EDF model evaluated by its defining sum, with no large-J shortcut: F = m (or 1)
/// exactly and all J = min(M', (d+1)S) summands. O(J) cost; a reference to validate the
/// asymptotic tables used by edf_greenhall(). Same arguments and errors.
double edf_greenhall_direct(int alpha, int d, std::int64_t m, std::int64_t n_phase,
                            bool overlapping, bool modified);

/// Coefficients of the large-r forms 1/ν ≈ (1/r)(a0 − a1/r) of GR03.
struct GreenhallCoefficients {
  double c0;  ///< a0 (Tables 1, 2) or b0 (Table 3)
  double c1;  ///< a1 (Tables 1, 2) or b1 (Table 3)
};

/// GR03 Table 1 (modified variances, F = 1): a0, a1 for alpha −4 … 2 and d 1 … 3.
GreenhallCoefficients greenhall_table1(int alpha, int d);
/// GR03 Table 2 (unmodified variances, F = m → ∞): a0, a1 for alpha −4 … 2 and d 1 … 3.
GreenhallCoefficients greenhall_table2(int alpha, int d);
/// GR03 Table 3 (unmodified flicker PM, alpha = 1): s_z(0; m) ≈ b0 + b1·ln m, for d 1 … 3.
GreenhallCoefficients greenhall_table3(int d);

/// @}
/// @name Other EDF models
/// @{

/// EDF of TOTDEV, ν = b·(T/τ) − c with T/τ = M/m (T = M·τ0 as in Stable32) and (b, c) from
/// NIST SP 1065 Table 7: (1.50, 0) white FM, (1.17, 0.22) flicker FM, (0.93, 0.36) RW FM.
/// SP 1065 gives no TOTDEV EDF for PM noise; for alpha = 1 and 2 this returns the SP 1065
/// Table 5 simple OADEV EDF, edf_simple_oadev(), which is what Stable32 uses (deduced from
/// its OCXO and Keysight TOTDEV tables) and is sound because TOTDEV ≈ OADEV for PM noise.
/// alpha < −2 throws (the Allan-type TOTDEV does not converge there).
double edf_totdev(int alpha, std::int64_t m, std::int64_t n_phase);

/// SP 1065 Table 5 "simple" EDF of the fully overlapping AVAR (theory.md §3.2), with the
/// flicker-FM m = 1 case in its correct squared form 2(M−2)²/(2.3M − 4.9).
/// @param[in] alpha 2, 1, 0, −1 or −2
double edf_simple_oadev(int alpha, std::int64_t m, std::int64_t n_phase);

/// @}

}  // namespace imunoise::analysis
