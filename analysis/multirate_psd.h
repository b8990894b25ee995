/// @file
/// @brief Log-frequency PSD of long records by multi-rate Welch: a cascade of half-band
/// decimations by 2, a short Welch spectrum at every level, each log bin taken from one level.
/// The PSD of `imunoise analyze`; theory.md §5.1–5.2 conventions (one-sided S₁, Welch
/// normalisation, log bins of log_bin()).
///
/// Why multi-rate Welch and not LPSD (Tröbs & Heinzel 2006, Measurement 39, 120): LPSD
/// computes one DFT per log frequency with a segment length chosen per frequency, which costs
/// O(n) per frequency and needs its own dof model per bin; the multi-rate estimate keeps
/// Welch's segments, windows and the correlation-aware dof of log_bin() unchanged (the same
/// segment kernel, analysis/psd_internal.h), and costs O(n log L) in cache-resident work.
///
/// Method. Level 0 is the record at f_s; level d + 1 is level d low-passed by the half-band
/// filter of analysis/halfband.h and decimated by 2 (rate f_d = f_s/2^d). The deepest level D
/// is chosen so that L·2^D = L₀, the classic segment length (automatic_segment_length(n), the
/// largest power of two ≤ n/8): the deepest level's spectrum has today's resolution f_s/L₀, and
/// with n/2^D ≈ n·L/L₀ ≥ 8L samples it averages as many segments (K ≥ 14). Every level runs
/// Welch with the same L (default 4096, 32 KiB: in cache), window, overlap and detrend (Hann,
/// 50 %, constant by default). A level d ≥ 1 is clean up to its passband edge f_d/4 (the
/// filter's; what folds onto it is ≥ 137 dB down); raw bins whose Hann main lobe (±2 bins)
/// stays inside it, j ≤ J = L/4 − 2, are usable. Level 0 needs no filter: all bins to f_s/2.
///
/// Level of a log bin (edges 10^{k/b} Hz as in log_bin()): the deepest level whose usable band
/// contains the whole bin, i.e. whose raw bin J + 1 already lies in a higher bin. That level
/// also has the most raw bins in the bin (the spacing halves with every level), so the rule
/// "enough raw bins" is met by the same choice: every bin above the deepest level's band
/// holds ≥ ~0.1·L·(10^{1/b} − 1) raw bins (≥ 100 at L = 4096, b = 10; the top bin may be cut
/// by f_s/2), and only the deepest level has sparse bins — the lowest bins, exactly as in the
/// classic spectrum. Each level thus
/// serves one octave [≈ f_d/8, f_d/4] (the deepest: everything below its band edge).
///
/// dof: log_bin()'s rule per level (averaged_dof on the level's power covariance and segment
/// count). Parseval: Spectrum::integrated_power sums S₁·Δf over the raw bins behind the bins,
/// each at its level's spacing, plus the deepest level's DC bin; the tiling between levels is
/// exact to about one raw bin per level (~6/L of the power of a flat spectrum).
///
/// A line within ~2 raw bins of a level boundary is split between the two levels (each sees
/// part of it), and the part seen by the deeper level is attenuated by its filter's roll-off;
/// elsewhere its power is in the bins around it as in Welch.
///
/// Cost: one pass over the record; per input sample ~2·(5 multiply-adds of the filter +
/// 2 FFT points), all in cache; memory O(D·L) (the levels are streamed, nothing of size n is
/// allocated). Sequential and deterministic. When L₀ ≤ L there is one level, and the result is
/// log_bin(welch_psd(x)) (resp. of pooled_welch_psd) bit for bit, except sample_variance
/// (computed in one blocked pass here: equal to rounding) and the density of the bin holding
/// f_s/2: there the Nyquist raw bin (c = 1, half density over half the width) counts as half
/// a bin, Σ S₁/(count − ½), unbiased where log_bin()'s Σ S₁/count reads 1/(2·count) low (−10 %
/// for the 5 raw bins of [199.5, 200] Hz at f_s = 400 Hz, L = 4096). Same dof (a rescaling).
#pragma once

#include <cstddef>
#include <span>

#include "analysis/psd.h"

namespace imunoise::analysis {

/// Options of the multi-rate estimate.
struct MultirateOptions {
  /// Window, overlap and detrend of every level. welch.segment_length is the classic L₀ whose
  /// resolution f_s/L₀ the deepest level keeps: 0 = automatic_segment_length() of the record
  /// (of the longest piece); when L₀ > level_segment_length it must be level_segment_length·2^D.
  WelchOptions welch;
  std::size_t level_segment_length = 4096;  ///< L of every level: a power of two ≥ 256
  int bins_per_decade = 10;                 ///< b of the log bins (as log_bin())
};

/// The levels a record of SAMPLES samples (the longest piece) is analysed with.
struct MultiratePlan {
  std::size_t segment_length = 0;  ///< L of every level: min(L₀, level_segment_length)
  std::size_t deepest_level = 0;   ///< D, with L·2^D = L₀ (0: one level, the classic spectrum)
};

/// The plan for SAMPLES samples: what multirate_psd() uses, and the one FFT length to plan
/// for (`imunoise fftw-wisdom --samples`).
/// @throws ContractViolation for bad options, or SAMPLES < 16 when L₀ is automatic.
MultiratePlan multirate_plan(std::size_t samples, const MultirateOptions& options = {});

/// Multi-rate log-binned one-sided PSD of one record (see the file comment). The Spectrum is
/// binned: first_raw_bin/raw_bins index the raw bins of each bin's level, whose spacing is
/// bin_resolution_hz; resolution_hz is the deepest level's (finest) spacing f_s/L₀, segments
/// the deepest level's K, segment_length L, sample_rate_hz f_s.
/// @param[in] x rate samples [unit], all finite
/// @param[in] sample_rate_hz f_s = 1/τ0 [Hz], > 0
/// @throws ContractViolation as welch_psd() (non-finite sample, f_s ≤ 0, record shorter than
///   16 samples or than one segment at the deepest level), or for bad options.
Spectrum multirate_psd(std::span<const double> x, double sample_rate_hz,
                       const MultirateOptions& options = {});

/// multirate_psd() pooled over independent pieces of one record, with pooled_welch_psd()'s
/// semantics at every level: the plan of the longest piece (L₀ = its automatic length unless
/// given); at each level the segments of every piece long enough for one segment there are
/// averaged together (piece spectra weighted by their segment counts K_k, power covariance
/// Σ K_k·g_k/K, dof by log_bin()'s rule with K = Σ K_k). Pieces shorter than L are left out
/// entirely; sample_variance is the sample-weighted mean over the pieces used. One piece gives
/// exactly multirate_psd().
/// @param[out] pieces_used number of pieces that entered (at least level 0; optional)
/// @throws ContractViolation when no piece is at least one segment long, or as multirate_psd().
Spectrum pooled_multirate_psd(std::span<const std::span<const double>> pieces,
                              double sample_rate_hz, const MultirateOptions& options = {},
                              std::size_t* pieces_used = nullptr);

}  // namespace imunoise::analysis
