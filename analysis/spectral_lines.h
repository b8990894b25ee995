/// @file
/// @brief Spectral lines (sinusoids) of a rate record: found in a raw Welch spectrum against the
/// local continuum with a stated false-alarm probability per channel, then their frequency,
/// amplitude and phase fitted by least squares on the samples, with an amplitude interval from
/// the continuum PSD at the line (theory.md §5.1 conventions: one-sided S₁; the derivations are
/// in docs/spectral-lines.md).
///
/// Detection. Under a smooth Gaussian continuum C(f) a raw Welch bin j is C·χ²_ν/ν with ν its
/// dof (2·K_eff). The continuum at j is the running median of the raw bins j − h … j + h
/// without the tested bin's main lobe (|Δj| ≤ main_lobe_half_width), divided by the median of
/// χ²_ν/ν (the median/mean ratio, chi_square_quantile(0.5, ν)/ν): for a continuum monotone
/// over the window — the 1/f and random-walk rise at low f, a low-pass roll-off — the median
/// of a symmetric window is the value at its centre, so the window is kept symmetric in bins
/// and shrinks near DC and Nyquist. A bin is a line when S_j/Ĉ_j exceeds the threshold r with
/// Pr(χ²_ν/ν > r·Ĉ/C) = P_FA/M, M the bins searched (Bonferroni: at most P_FA false lines per
/// channel); the scatter of Ĉ itself (the median of m reference bins, relative sd
/// √(π/2)·√(2/ν)/√m_eff with m_eff the bins' count corrected for the powers' correlation) is
/// integrated over in that probability, so r grows where the window shrinks.
///
/// Fit. Each line's frequency is refined to the maximum of the record's own periodogram near
/// the detected peak (a zoom DFT of the demodulated, block-summed samples; the periodogram's
/// maximum is the least-squares frequency of one sinusoid), then every line's cos/sin pair is
/// fitted jointly with a mean and a linear trend by least squares on the samples of each
/// piece. The amplitude's standard deviation is σ_A = √(C(f)/T) (T the total duration, C the
/// continuum one-sided S₁ at f): a least-squares sinusoid component (2/n)Σ e_t cos ωt of
/// noise with local density C has variance C/T, and the amplitude's radial error is one such
/// component when A ≫ σ_A.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "analysis/psd.h"
#include "common/noise_coefficients.h"

namespace imunoise::analysis {

/// Settings of the line search.
struct LineSearchOptions {
  double false_alarm_probability = 0.01;  ///< per channel, over all searched bins, in (0, 1)
  std::size_t continuum_half_width = 32;  ///< h of the running median [raw bins]
  std::size_t main_lobe_half_width = 2;   ///< bins around the tested one left out (Hann: ±2)
  std::size_t min_reference_bins = 8;     ///< fewest median bins: sets the lowest bin searched
  std::size_t max_lines = 16;             ///< the strongest lines kept
};

/// A bin (group of adjacent bins) standing above the continuum.
struct LineCandidate {
  double frequency_hz = 0.0;       ///< peak interpolated between bins [Hz]
  std::size_t bin = 0;             ///< raw bin of the peak
  double continuum_density = 0.0;  ///< Ĉ at the peak, one-sided [unit²/Hz]
  double peak_ratio = 0.0;         ///< S₁ of the peak bin / Ĉ
  double threshold_ratio = 0.0;    ///< the ratio that bin had to exceed
};

/// Outcome of detect_spectral_lines().
struct LineDetection {
  std::vector<LineCandidate> candidates;   ///< by frequency
  std::size_t bins_searched = 0;           ///< M of the Bonferroni correction
  double f_low_hz = 0.0, f_high_hz = 0.0;  ///< searched band [Hz]
};

/// The lines of a raw one-sided Welch spectrum (welch_psd / pooled_welch_psd, not log-binned).
/// Empty when the spectrum is too short for any searched bin.
/// @throws ContractViolation for a binned spectrum, sizes that differ or bad options.
LineDetection detect_spectral_lines(const Spectrum& raw, const LineSearchOptions& options = {});

/// The continuum Ĉ at F_HZ of a raw spectrum, as the detection estimates it at the nearest bin
/// (for a caller's candidate frequency, which need not stand above it).
/// @throws ContractViolation for a binned spectrum or fewer than 8 raw bins.
double line_continuum_density(const Spectrum& raw, double f_hz,
                              const LineSearchOptions& options = {});

/// One fitted line.
struct FittedLine {
  Sinusoid value;                  ///< A ≥ 0, f, φ of A·sin(2πft + φ) at the first sample of
                                   ///< the first piece (A: √ of the duration-weighted mean A²
                                   ///< over the pieces, each piece with its own phase)
  double amplitude_sd = 0.0;       ///< σ_A = √(C/T) [unit]
  double amplitude_ci_low = 0.0;   ///< max(0, A − z·σ_A) [unit]
  double amplitude_ci_high = 0.0;  ///< A + z·σ_A [unit]
  double continuum_density = 0.0;  ///< C at f [unit²/Hz]
};

/// The least-squares fit of lines to the pieces of one record.
struct LineFit {
  std::vector<FittedLine> lines;
  /// Per piece, per line: the (cos, sin) coefficients of that piece, c·cos(ωt) + s·sin(ωt)
  /// with t from the piece's first sample, two values per line.
  std::vector<std::vector<double>> piece_coefficients;
};

/// Fits one sinusoid per frequency of FREQUENCIES_HZ (a detected peak or a user's candidate)
/// to the PIECES at SAMPLE_RATE_HZ: frequency refined within ±SEARCH_HALF_WIDTH_HZ (≥ 0; 0
/// keeps it), then all amplitudes jointly with a mean and a trend per piece. CONTINUUM gives
/// C at each frequency for the interval at CONFIDENCE.
/// @throws ContractViolation when the sizes differ, a piece is shorter than 8 samples, a
///   frequency is outside (0, f_s/2) or the confidence outside (0, 1).
LineFit fit_spectral_lines(std::span<const std::span<const double>> pieces, double sample_rate_hz,
                           std::span<const double> frequencies_hz,
                           std::span<const double> continuum, double search_half_width_hz,
                           double confidence);

/// PIECE (the index-th of the fit) with FIT's sinusoids of that piece subtracted.
std::vector<double> remove_spectral_lines(std::span<const double> piece, std::size_t index,
                                          const LineFit& fit, double sample_rate_hz);

}  // namespace imunoise::analysis
