/// @file
/// @brief Welch power spectral density of a stationary record (theory.md §5.1) and its
/// log-binned average (§5.2), with the equivalent χ² degrees of freedom of every value.
///
/// Convention (theory.md §1.2): every density here is the **one-sided** S₁ on [0, f_s/2] in
/// unit²/Hz, S₁ = 2S (two-sided). White rate noise of ARW N sits at S₁ = 2N².
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace imunoise::analysis {

/// Data taper applied to each segment. All are the periodic ("DFT-even") forms, the ones
/// used for spectral analysis (scipy.signal.get_window default).
enum class Window {
  hann,             ///< 0.5 − 0.5 cos(2πn/L); sidelobes −31 dB, falling 18 dB/octave
  hamming,          ///< 0.54 − 0.46 cos(2πn/L); sidelobes −43 dB, falling 6 dB/octave
  blackman_harris,  ///< 4-term Blackman–Harris; sidelobes −92 dB, for steep red spectra
  rectangular,      ///< no taper; leaks badly, for tests and line-free white data only
};

/// Trend removed from each segment (and from the whole record for sample_variance).
enum class Detrend {
  none,      ///< keep the data as is (the DC bin then carries the mean)
  constant,  ///< subtract the mean
  linear,    ///< subtract the least-squares line (suppresses the leakage of a drift)
};

/// Options of the Welch estimate.
struct WelchOptions {
  /// Segment length L [samples]. 0 = automatic in welch_psd(): the largest power of two
  /// ≤ n/8, at least 16 (automatic_segment_length()). At 50 % overlap that leaves K ≥ 15
  /// segments, i.e. ≥ ~28 χ² dof per raw bin (±~50 % at 99 %) while resolving down to
  /// f_s/L ≈ 8/(n·τ0).
  std::size_t segment_length = 0;
  double overlap = 0.5;  ///< fraction of L shared by consecutive segments, in [0, 1)
  Window window = Window::hann;
  Detrend detrend = Detrend::constant;
};

/// A one-sided spectrum, raw (one value per DFT bin), log-binned (log_bin()) or multi-rate
/// log-binned (analysis/multirate_psd.h: every bin from one level of a decimation cascade, each
/// level its own raw bin spacing, given per bin in bin_resolution_hz).
struct Spectrum {
  std::vector<double> frequency_hz;  ///< raw: j·f_s/L, j = 0…⌊L/2⌋; binned: geometric mean
                                     ///< of the raw frequencies in the bin [Hz]
  std::vector<double> density;       ///< S₁ [unit²/Hz]; binned: mean of the raw S₁ in the bin
  std::vector<double> dof;           ///< equivalent χ² degrees of freedom of each value
  /// Raw bin spacing f_s/L [Hz]; multi-rate: the finest spacing, that of the deepest level
  /// (f_s/L₀ with the classic L₀ = automatic_segment_length(n), the lowest bins' spacing).
  double resolution_hz = 0.0;
  std::size_t segments = 0;           ///< K, number of segments averaged (multi-rate: at the
                                      ///< deepest level)
  std::size_t segment_length = 0;     ///< L [samples] (multi-rate: of every level)
  double sample_rate_hz = 0.0;        ///< f_s of the record [Hz]; 0 in hand-made spectra, whose
                                      ///< users then take resolution_hz·segment_length
  bool fft_plan_from_wisdom = false;  ///< the FFT plan came from imported FFTW wisdom
  double sample_variance = 0.0;       ///< mean square of the whole record after the same detrend
                                      ///< (none: raw mean square) [unit²], for the Parseval check
  /// Σ S₁·f_s/L over all raw bins [unit²]; multi-rate: Σ S₁·Δf over the raw bins behind the
  /// bins (each at its level's spacing Δf) plus the deepest level's DC bin.
  double integrated_power = 0.0;
  /// Raw spectra only: g(Δ), Δ = 0…⌊L/2⌋, the covariance of the segment-summed powers of
  /// two bins Δ apart, Cov(P_j, P_{j+Δ}) / (K·E[|X_j|²]²), for a locally flat Gaussian
  /// spectrum. It combines the window's frequency correlation with the segment overlap;
  /// g(0) = K/K_eff. log_bin() uses it for the dof of averaged bins. Empty: independent bins.
  std::vector<double> power_covariance;
  /// Binned spectra only: index j of the first raw bin in each bin and the number of raw
  /// bins averaged (raw frequencies first·Δf … (first + count − 1)·Δf, Δf = resolution_hz or,
  /// when given, bin_resolution_hz of the bin). Empty for raw.
  std::vector<std::size_t> first_raw_bin;
  std::vector<std::size_t> raw_bins;
  /// Multi-rate spectra only: the raw bin spacing Δf of each bin's level [Hz]. Empty: every
  /// bin at resolution_hz.
  std::vector<double> bin_resolution_hz;
};

/// @name Windows and the Welch overlap correction (Welch 1967, IEEE Trans. AU-15, eq. for
/// the variance of the averaged periodogram)
/// @{

/// The L window coefficients w_0 … w_{L−1}. Throws ContractViolation when length < 2.
std::vector<double> window_coefficients(Window window, std::size_t length);

/// ρ(shift) = (Σ_n w_n w_{n+shift})² / (Σ_n w_n²)², the squared correlation of two segments
/// shift samples apart (0 when shift ≥ L). Periodic Hann at shift L/2: exactly 1/36.
double window_overlap_correlation(std::span<const double> window, std::size_t shift);

/// Equivalent number of independent segments
/// K_eff = K / (1 + 2 Σ_{l=1}^{K−1} (1 − l/K) ρ(l·step)); a raw bin has 2·K_eff dof
/// (K_eff at DC and Nyquist). Throws ContractViolation when segments or step is 0.
double effective_segments(std::span<const double> window, std::size_t segments, std::size_t step);

/// @}

/// Welch estimator for a fixed segment length: owns one FFTW r2c plan and its buffers, reused
/// for every segment and every call. The plan comes from FFTW wisdom when the process holds
/// wisdom of at least FFTW_MEASURE rigour for that transform (imported beforehand, e.g. by
/// io::import_fftw_wisdom); it is never measured here, so construction stays fast. Without
/// such wisdom it is an FFTW_ESTIMATE plan. The two differ only in rounding (~1e-16
/// relative). One instance must not be used by two threads at once; distinct instances may
/// run in parallel (plan creation and destruction are serialised by a global mutex,
/// execution is re-entrant).
class WelchEstimator {
 public:
  /// @param[in] segment_length L ≥ 2 samples (options.segment_length must be 0 or equal)
  /// @param[in] options overlap, window, detrend
  /// @throws ContractViolation on bad options or a segment length outside 2 … INT_MAX.
  WelchEstimator(std::size_t segment_length, const WelchOptions& options);
  ~WelchEstimator();
  WelchEstimator(WelchEstimator&&) noexcept;
  WelchEstimator& operator=(WelchEstimator&&) noexcept;
  WelchEstimator(const WelchEstimator&) = delete;
  WelchEstimator& operator=(const WelchEstimator&) = delete;

  /// Raw one-sided spectrum of x. Segments start at sample 0 and advance by
  /// step = L − ⌊overlap·L⌋; the n − (K−1)·step − L tail samples that do not fill a
  /// segment are ignored (they still enter sample_variance). No heap allocation per segment.
  /// @param[in] x rate samples [unit], n ≥ L, all finite
  /// @param[in] sample_rate_hz f_s = 1/τ0 [Hz], > 0
  /// @throws ContractViolation when n < L, a value is not finite, or f_s is not positive (the
  ///   axis analysis refuses non-finite samples and records too short before).
  Spectrum estimate(std::span<const double> x, double sample_rate_hz);

  std::size_t segment_length() const;

  /// True when the FFT plan was rebuilt from imported FFTW wisdom (FFTW_MEASURE or more
  /// rigorous), false when it is the FFTW_ESTIMATE fallback.
  bool planned_from_wisdom() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The automatic Welch segment length for a record of SAMPLES samples: the largest power of
/// two ≤ SAMPLES/8, at least 16 (see WelchOptions::segment_length). A 24 h record at 1 kHz
/// (86.4 M samples) gives 2^23. The one place this rule lives: welch_psd, pooled_welch_psd
/// and `imunoise fftw-wisdom --samples` use it.
/// @throws ContractViolation when SAMPLES < 16 (`fftw-wisdom --samples` is checked first).
std::size_t automatic_segment_length(std::size_t samples);

/// One-shot Welch estimate (resolves segment_length = 0, see WelchOptions).
/// @throws ContractViolation as WelchEstimator::estimate(), or when n < 16 for automatic L.
Spectrum welch_psd(std::span<const double> x, double sample_rate_hz,
                   const WelchOptions& options = {});

/// Welch estimate pooled over independent pieces of one record (the gap-free pieces of a
/// recording with time-stamp gaps): every piece at the same segment length L (options'
/// value, else the automatic L of the longest piece), the segments of all pieces averaged
/// together — i.e. the piece spectra weighted by their segment counts K_k. Pieces shorter
/// than L are left out. Raw dof ν = K²/Σ_k(K_k²/ν_k) (the variance of that weighted mean of
/// independent estimates), power_covariance Σ_k K_k·g_k/K with segments = K = Σ K_k, so
/// log_bin() gives the same dof model as for one record. One piece gives exactly welch_psd.
/// @param[out] pieces_used number of pieces that entered (optional)
/// @throws ContractViolation when no piece is at least one segment long, or as welch_psd().
Spectrum pooled_welch_psd(std::span<const std::span<const double>> pieces, double sample_rate_hz,
                          const WelchOptions& options = {}, std::size_t* pieces_used = nullptr);

/// Log-binned spectrum (theory.md §5.2): the DC bin is dropped; raw bin j goes to the bin
/// ⌊b·log10 f_j⌋ (edges at 10^{k/b} Hz, so spectra of different records share edges); the
/// raw S₁ are averaged as linear power; empty bins are omitted. The frequency is the
/// geometric mean of the raw frequencies in the bin — the centre on the log axis of the
/// values actually averaged (for a sparse low bin the nominal edge centre can be far from
/// every raw bin). The bin mean of a power law f^a exceeds its value at that frequency, by
/// 0.2 / 0.9 / 2 % for a = −1 / −2 / −3 in a dense 10-per-decade bin and up to 4 % for f⁻²
/// in a bin of two raw bins; cross_check_psd() therefore averages the model over the raw
/// bins instead of evaluating it there.
/// dof: from raw.power_covariance when present (accounts for the ~2× correlation of
/// neighbouring Hann bins: summing raw dofs would overstate the dof of wide bins), else the
/// sum of the raw dofs.
/// @throws ContractViolation when bins_per_decade < 1, the vectors differ in size, raw is
/// already binned or its frequencies do not increase.
Spectrum log_bin(const Spectrum& raw, int bins_per_decade = 10);

}  // namespace imunoise::analysis
