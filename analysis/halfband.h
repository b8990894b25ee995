/// @file
/// @brief The half-band FIR low-pass of the multi-rate PSD (analysis/multirate_psd.h) and its
/// polyphase decimation by 2.
///
/// Design: Kaiser-windowed sinc with cut-off at a quarter of the input rate f_in (Kaiser 1974;
/// Oppenheim & Schafer, Discrete-Time Signal Processing, 3rd ed., §7.6), 4m − 1 = 39 taps,
/// window parameter β = 15, the odd taps scaled so that H(0) = 1 exactly. Being half-band
/// (h_c = ½ at the centre c = 19, h_{c±2i} = 0), H(f) + H(f_in/2 − f) = 1, so the passband
/// ripple equals the stopband level δ:
/// - passband [0, f_in/8] (half the output band): |H − 1| ≤ 1.3e-7 (|H|² within ±1.1e-6 dB);
/// - stopband [3f_in/8, f_in/2] (what folds onto the passband at f_in/2): |H| ≤ 1.3e-7
///   (≥ 137 dB).
/// Both are checked on a dense grid in tests/analysis/halfband_test.cpp. Decimating k times
/// multiplies the passband gains: after 12 stages the power gain stays within ±1.3e-5 dB of 1
/// over the band every stage passes.
#pragma once

#include <cstddef>
#include <span>

namespace imunoise::analysis {

/// Number of taps N of the half-band filter.
inline constexpr std::size_t kHalfbandTaps = 39;

/// The N coefficients h_0 … h_{N−1}: symmetric, h_19 = ½, h_{19±2i} = 0 for i ≥ 1, Σh = 1.
std::span<const double> halfband_coefficients();

/// Number of outputs of halfband_decimate() for INPUTS input samples: ⌊(INPUTS − N)/2⌋ + 1,
/// 0 when INPUTS < N (only outputs whose N inputs all exist: no edge transients).
std::size_t halfband_outputs(std::size_t inputs);

/// y[k] = Σ_{i=0}^{N−1} h_i·x[2k + i] for k < y.size(): low-pass and keep every second sample,
/// as a polyphase filter (the even phase through the 2m = 20 non-zero side taps, folded in
/// symmetric pairs, the odd phase through the centre tap): m + 1 multiplications and 2m
/// additions per output, i.e. ~5 multiply-adds per input sample. Fixed summation order
/// (deterministic); AVX-512 / AVX2 / baseline clones picked at load time, which may differ in
/// the last bit across machines (FMA), not across calls or threads. No allocation.
/// @throws ContractViolation when y.size() > halfband_outputs(x.size()).
void halfband_decimate(std::span<const double> x, std::span<double> y);

}  // namespace imunoise::analysis
