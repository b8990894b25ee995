/// @file
/// @brief Internal to the PSD modules (analysis/psd, analysis/multirate_psd): the Welch segment
/// kernel (one FFTW r2c plan and its buffers) and the dof model of averaged raw bins, shared
/// so that the classic and the multi-rate estimates do the same arithmetic on a segment.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "analysis/psd.h"

namespace imunoise::analysis::detail {

/// Bins j = 0 and j = L/2 (even L) are real-valued: weight c_j = 1 instead of 2 in the
/// one-sided density (theory.md §5.1), and χ² with half the dof.
bool is_real_bin(std::size_t j, std::size_t length);

/// Covariance of the powers of raw bins j and j' summed over segments (see
/// Spectrum::power_covariance): g(|j − j'|) + g(fold(j + j')), the second term being the
/// pseudo-covariance E[X_j X_j'] that couples bins to their mirror images about DC and
/// Nyquist (Isserlis: Cov(|X|², |Y|²) = |E[XY*]|² + |E[XY]|²).
struct PowerCovariance {
  std::span<const double> g;  ///< g(Δ), Δ = 0…⌊L/2⌋
  std::size_t length = 0;     ///< L

  /// g at any lag: L-periodic and even. The callers' lags stay below 2L, so one subtraction
  /// replaces the division (4.2 M raw bins per channel at L = 2^23).
  double at(std::size_t lag) const {
    if (lag >= length) lag = lag < 2 * length ? lag - length : lag % length;
    return g[lag < length - lag ? lag : length - lag];
  }
  double pair(std::size_t j, std::size_t k) const { return at(j > k ? j - k : k - j) + at(j + k); }
  /// Σ_{k=a}^{b} pair(j, k).
  double row(std::size_t j, std::size_t a, std::size_t b) const {
    double sum = 0.0;
    for (std::size_t k = a; k <= b; ++k) sum += pair(j, k);
    return sum;
  }
};

/// Equivalent χ² dof of the average of the one-sided densities of raw bins a…b of a spectrum
/// of SEGMENTS segments, for a spectrum flat over them:
/// ν = 2·(E Σ)²/Var Σ = 2K(Σc_j)² / Σ_{j,k} c_j c_k cov(j, k).
double averaged_dof(const PowerCovariance& cov, std::size_t segments, std::size_t a, std::size_t b);

/// Throws ContractViolation for an overlap outside [0, 1) or an unknown window / detrend.
void check_options(const WelchOptions& options);

/// Least-squares trend of MODE: x_n ≈ mean + slope·(n − centre), with the centred index
/// (centre = (n−1)/2) so that mean and slope decouple; slope = Σt·x/Σt², Σt² = n(n²−1)/12.
struct Trend {
  double mean = 0.0;
  double slope = 0.0;
  double centre = 0.0;
  double at(std::size_t n) const { return mean + slope * (static_cast<double>(n) - centre); }
};
/// Trend of X; the mean is a lane_sum (vectorised, fixed order).
Trend fit_trend(std::span<const double> x, Detrend mode);

/// Σ x[0 … n): eight interleaved partial sums (lane i mod 8) combined in a fixed tree, so the
/// result does not depend on the vector width the compiler picks.
double lane_sum(const double* x, std::size_t n);

/// The Welch segment kernel for one segment length L: the window, one FFTW r2c plan and its
/// buffers, made as WelchEstimator documents it (wisdom of FFTW_MEASURE rigour or more when
/// the process holds it, never measured here, else FFTW_ESTIMATE; plan creation and
/// destruction under the global planner mutex). Not for two threads at once.
class SegmentTransform {
 public:
  /// @throws ContractViolation for bad options or L outside 2 … INT_MAX; AnalysisError when
  ///   FFTW cannot allocate or plan.
  SegmentTransform(std::size_t length, const WelchOptions& options);
  ~SegmentTransform();
  SegmentTransform(SegmentTransform&&) noexcept;
  SegmentTransform& operator=(SegmentTransform&&) noexcept;
  SegmentTransform(const SegmentTransform&) = delete;
  SegmentTransform& operator=(const SegmentTransform&) = delete;

  std::size_t length() const;    ///< L
  std::size_t step() const;      ///< segment advance L − ⌊overlap·L⌋ (at least 1)
  std::size_t bins() const;      ///< ⌊L/2⌋ + 1
  double window_energy() const;  ///< Σ w²
  bool from_wisdom() const;
  Detrend detrend() const;

  /// Detrends (options' mode) and tapers the L samples at SEGMENT, transforms them and adds
  /// |X_j|² to power[j], j = 0 … bins() − 1. No allocation.
  void add_segment(const double* segment, double* power);

  /// Spectrum::power_covariance g(Δ) of a Welch average over SEGMENTS segments (two or three
  /// transforms; see WelchEstimator::estimate).
  std::vector<double> power_covariance(std::size_t segments);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace imunoise::analysis::detail
