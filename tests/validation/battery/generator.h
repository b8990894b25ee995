/// @file
/// @brief The independent recording generator of the validation battery (issue 20, issue 21):
/// six channels of rate samples at τ0 built from a spec of noise terms and "real sensor"
/// phenomena. It shares no code with imunoise: only the C++ standard library and FFTW3 (no file
/// of models/, analysis/, pipeline/ or any other imunoise folder; tests/validation/battery/
/// generator_verification_test.cpp checks the includes). Conventions are those of
/// ../shared/docs/theory.md §1–§4 (S_Ω two-sided, S₁ = 2S_Ω); the derivations of what each
/// term and phenomenon does to the AVAR are in docs/validation.md.
///
/// Order of operations for one channel (internal rate f_i = d·f_s, d = decimation):
///  1. the rate terms at f_i: constant, white N, flicker B (FFT-shaped), discrete random walk
///     K, ramp R, first-order Gauss–Markov (exact AR(1)), sinusoids, warm-up a·e^{−t/τ_w};
///  2. the sensor's low-pass (2nd-order Butterworth by bilinear transform) at f_i, started in
///     its steady state and run over a burn-in that is then dropped;
///  3. decimation without averaging: every d-th sample kept (t = 0 at the first kept one);
///  4. the angle (velocity) counter: the cumulative angle rounded to a step Δ (Q = Δ/√12),
///     rate = difference / τ0; optionally with subtractive dither (ring-laser-gyro style);
///  5. outliers: each sample independently, with probability p, gets ±k·σ (random sign);
///  6. output rounding of the rate to an LSB.
/// Every term of every channel draws from its own stream, seeded from (seed, channel, term,
/// index), so adding a term never changes the others.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace imunoise::battery {

/// First-order Gauss–Markov term: autocovariance σ²·e^{−|s|/T_c} (theory.md §4.1).
struct GaussMarkovSpec {
  double sigma = 0.0;    ///< stationary σ [rad/s | m/s²]
  double tau_c_s = 0.0;  ///< correlation time T_c [s]
};

/// Deterministic sinusoid A·sin(2πf·t + φ), t = 0 at the first output sample.
struct SinusoidSpec {
  double amplitude = 0.0;     ///< A [rad/s | m/s²]
  double frequency_hz = 0.0;  ///< f [Hz]
  double phase_rad = 0.0;     ///< φ [rad]
};

/// The terms and phenomena of one channel, SI units of the channel (rad/s or m/s²).
struct ChannelSpec {
  double constant = 0.0;     ///< deterministic offset: bias, Earth rate, gravity [rate]
  double white = 0.0;        ///< N, two-sided S_Ω = N² [rate·√s]
  double flicker = 0.0;      ///< B, S_Ω = B²/(2πf) [rate]
  double random_walk = 0.0;  ///< K, discrete RW of step K·√τ_i [rate/√s]
  double ramp = 0.0;         ///< R: rate R·t [rate/s]
  std::vector<GaussMarkovSpec> gauss_markov;
  std::vector<SinusoidSpec> sinusoids;
  double warmup_amplitude = 0.0;  ///< a of a·e^{−t/τ_w} [rate]
  double warmup_tau_s = 0.0;      ///< τ_w [s] (> 0 when a ≠ 0)
  double angle_step = 0.0;        ///< Δ of the angle (velocity) counter [rate·s]; 0 = none
  bool angle_dither = false;      ///< subtractive uniform dither on the counter (exact Q)
  double outlier_fraction = 0.0;  ///< p, probability of a spike per output sample
  double outlier_size = 0.0;      ///< k·σ, magnitude of a spike [rate]
  double lsb = 0.0;               ///< output rounding step of the rate [rate]; 0 = none
};

/// An optional temperature column: T(t) = T0 + ΔT·(1 − e^{−t/τ_T}) + noise, rounded.
struct TemperatureSpec {
  bool present = false;
  double start_degc = 25.0;    ///< T0 [°C]
  double rise_degc = 0.0;      ///< ΔT [°C]
  double tau_s = 1.0;          ///< τ_T [s]
  double noise_degc = 0.0;     ///< σ of white sensor noise [°C]
  double resolution_degc = 0;  ///< rounding step [°C]; 0 = none
};

/// The six channels of a recording and how they are sampled.
struct RecordingSpec {
  double rate_hz = 100.0;     ///< true output rate f_s = 1/τ0 [Hz]
  std::size_t samples = 0;    ///< output samples per channel
  int decimation = 1;         ///< d: generated at d·f_s, every d-th sample kept
  double low_pass_hz = 0.0;   ///< Butterworth corner at the internal rate [Hz]; 0 = none
  double flicker_span = 4.0;  ///< the flicker is synthesized over ≥ this × the internal record
  double stamp_resolution_s = 0.0;      ///< stamps t_k = k·τ0 rounded to this [s]; 0 = exact
  std::array<ChannelSpec, 6> channels;  ///< gyro_x, gyro_y, gyro_z, accel_x, accel_y, accel_z
  TemperatureSpec temperature;
  std::uint64_t seed = 1;
};

/// A generated recording. Channel k holds rate samples at t_k = k·τ0 (exact), whatever
/// `time_s` says.
struct GeneratedRecording {
  double sample_period_s = 0.0;  ///< true τ0 = 1/f_s [s]
  std::vector<double> time_s;    ///< stamps (exact or rounded), always filled
  std::array<std::vector<double>, 6> channels;
  std::vector<double> temperature_degc;  ///< empty unless spec.temperature.present
};

/// The term a random stream belongs to (part of its seed).
enum class StreamTerm : std::uint64_t {
  white = 1,
  flicker,
  random_walk,
  gauss_markov,
  sinusoid_phase,
  angle_dither,
  outlier,
  temperature
};

/// Seed of the stream of TERM number INDEX of channel CHANNEL (splitmix64 of the four).
std::uint64_t stream_seed(std::uint64_t seed, int channel, StreamTerm term, int index = 0);

/// Standard normal deviates from std::mt19937_64 (its sequence is fixed by the standard) by
/// the Box–Muller transform — own code, because std::normal_distribution differs between
/// standard libraries.
class NormalStream {
 public:
  explicit NormalStream(std::uint64_t seed) : engine_(seed) {}
  double next();     ///< N(0, 1)
  double uniform();  ///< U[0, 1) with 53 random bits

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

/// The smallest 2^a·3^b·5^c ≥ N (an FFT size FFTW transforms fast).
std::size_t fft_friendly_size(std::size_t n);

/// The FFT length the flicker of SPEC is synthesized over (internal samples).
std::size_t flicker_fft_length(const RecordingSpec& spec);

/// Internal samples dropped before the record (burn-in of the low-pass; 0 without it).
std::size_t burn_in_samples(const RecordingSpec& spec);

/// @name Building blocks (exposed for the verification test)
/// @{

/// COUNT samples of discrete flicker of level B synthesized over an FFT of LENGTH ≥ COUNT:
/// bin j (1 ≤ j < L/2) carries a random-phase Gaussian cosine of variance c_j² = B²/(πj),
/// i.e. S₁(f_j)·Δf with S₁ = B²/(πf) (theory.md §5.3), Δf = 1/(Lτ); DC and Nyquist are 0.
/// Independent of τ. Thread-safe (FFTW planning is serialized).
std::vector<double> flicker_samples(double b, std::size_t count, std::size_t length,
                                    std::uint64_t seed);

/// The 2nd-order Butterworth low-pass at CORNER_HZ for RATE_HZ by the bilinear transform with
/// pre-warping: coefficients b0, b1, b2, a1, a2 (a0 = 1), DC gain 1.
std::array<double, 5> butterworth2(double corner_hz, double rate_hz);

/// X filtered by butterworth2 in place, started in the steady state of a constant X[0].
void low_pass_in_place(std::span<double> x, const std::array<double, 5>& coefficients);

/// @}

/// One channel of SPEC (index 0–5), exactly as generate() makes it.
std::vector<double> generate_channel(const RecordingSpec& spec, int channel);

/// The whole recording: the six channels (two at a time in threads), stamps and temperature.
/// Deterministic for a spec.
GeneratedRecording generate(const RecordingSpec& spec);

}  // namespace imunoise::battery
