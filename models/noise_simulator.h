/// @file
/// @brief Streaming simulator of stationary IMU sensor errors: quantization, white noise,
/// bias instability (flicker, as a sum of Gauss–Markov terms), random walk, ramp, Gauss–Markov,
/// sinusoids and constants, per channel, deterministic for a seed.
///
/// Every term is generated so that the overlapping AVAR of the output matches the closed
/// forms of ../shared/docs/theory.md §1.3 and §4.1 exactly in expectation at every τ = m·τ0
/// (except user Gauss–Markov terms, which are point-sampled AR(1) and follow the [ZH08] form
/// quoted there). SI throughout: the gyro unit is rad/s, the accelerometer unit m/s²; the
/// same code serves both ("angle" reads "velocity" for an accelerometer).
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "common/noise_coefficients.h"

namespace imunoise::models {

/// Error model of one channel (one gyro or accelerometer axis), SI units, theory.md §1.3.
/// All coefficients default to 0 (term off).
struct ChannelNoiseModel : NoiseCoefficients {
  // The terms (theory.md §4.1) as NoiseCoefficients holds them: Q white angle noise, per-sample
  // σ of the integrated error [rad | m/s] (AVAR 3Q²/τ²); N ARW/VRW density [rad/√s | m/s/√s]
  // (AVAR N²/τ); B flicker coefficient [rad/s | m/s²] (AVAR (2 ln2/π)B² over the flicker band
  // of SimulationOptions); K RRW / accel RW [rad/s^{3/2} | m/s^{5/2}] (AVAR K²τ/3); R
  // deterministic slope [rad/s² | m/s³] (AVAR R²τ²/2); point-sampled AR(1) Gauss–Markov terms;
  // deterministic sinusoids.
  double constant = 0.0;    ///< constant bias plus true signal, e.g. −g₀ on a level FRD
                            ///< accelerometer z [rad/s | m/s²]
  double output_lsb = 0.0;  ///< step of a uniform rounding quantizer applied to the output
                            ///< [rad/s | m/s²]; 0 = off. For noise ≫ LSB it adds white rate
                            ///< noise of variance LSB²/12 per sample, i.e. N² += LSB²·τ0/12.
};

/// The simulator model of fitted coefficients (parametric bootstrap): Q, N, B, K, R, the
/// Gauss–Markov terms and sinusoids copied as they are; no constant, no output quantizer.
ChannelNoiseModel channel_model_from(const NoiseCoefficients& coefficients);

/// Throws imunoise::InputError "WHERE.field: …" if a coefficient is negative or not finite,
/// a correlation time is not positive, or a frequency is negative.
void validate_channel_model(const ChannelNoiseModel& model, std::string_view where);

/// Band of averaging times over which the bias-instability ADEV is flat.
struct FlickerBand {
  double tau_min_s = 0.0;  ///< lower end [s]; ≤ 0 means one sample period
  double tau_max_s = 1e5;  ///< upper end [s]; set it to at least the record length
};

/// Gauss–Markov terms whose sum has an ADEV within ±1.1 % of 0.664·B (AVAR (2 ln2/π)B²) for
/// every τ in [tau_min_s, tau_max_s].
///
/// Construction (derivation in the .cpp): correlation times one per decade, T_k = 10^k s for
/// k = ⌊log10 τ_min⌋ − 2 … ⌈log10 τ_max⌉ + 2, all with σ_k² = B²·ln(10)/π. A log-uniform
/// density of Lorentzians of equal variance sums to a 1/f spectrum; with this weight it is
/// S_Ω = B²/(2πf), the bias-instability PSD of theory.md §4.1. One term per decade leaves a
/// ±1.04 % ripple on the ADEV; two extra decades at each end of the band keep the roll-off
/// outside it. The slowest terms (T ≫ record) act as random turn-on biases of σ ≈ 0.86·B each.
/// Throws InputError unless 0 < tau_min_s < tau_max_s and B ≥ 0.
std::vector<GaussMarkov> flicker_gauss_markov_terms(double bias_instability, double tau_min_s,
                                                    double tau_max_s);

/// splitmix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number generators", OOPSLA
/// 2014; the seeding generator Blackman & Vigna recommend for xoshiro): adds the golden gamma
/// 0x9e3779b97f4a7c15 to STATE and returns a mix of the new state. The mix is a bijection, so
/// distinct states give distinct outputs. From state 0 the first outputs are 0xe220a8397b1dcdaf,
/// 0x6e789e6aa1b965f4, 0x06c45d188009454f.
constexpr std::uint64_t splitmix64(std::uint64_t& state) {
  state += 0x9e3779b97f4a7c15ULL;
  std::uint64_t z = state;
  z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31U);
}

/// xoshiro256++ 1.0 (Blackman & Vigna, "Scrambled linear pseudorandom number generators", ACM
/// Trans. Math. Softw. 47(4), 2021): 256-bit state, period 2^256 − 1, 64-bit output
/// rotl(s0 + s3, 23) + s0; passes BigCrush and PractRand (the authors' tests). A 32-byte
/// state (std::mt19937_64: 2.5 KiB) and ~1.5 ns per word here, conversion to double included.
/// A std::uniform_random_bit_generator.
class Xoshiro256PlusPlus {
 public:
  using result_type = std::uint64_t;

  /// State = four successive splitmix64 outputs from SEED (never all zero, since splitmix64
  /// outputs of distinct states differ).
  explicit Xoshiro256PlusPlus(std::uint64_t seed = 0) {
    for (std::uint64_t& word : s_) word = splitmix64(seed);
  }
  /// A given raw state (not all zero), for published reference sequences.
  static Xoshiro256PlusPlus from_state(const std::array<std::uint64_t, 4>& state) {
    Xoshiro256PlusPlus engine;
    engine.s_ = state;
    return engine;
  }

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type{0}; }

  /// Next 64-bit word.
  result_type operator()() {
    const std::uint64_t result = std::rotl(s_[0] + s_[3], 23) + s_[0];
    const std::uint64_t t = s_[1] << 17U;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = std::rotl(s_[3], 45);
    return result;
  }

 private:
  std::array<std::uint64_t, 4> s_{};
};

/// Standard normal draws from a private xoshiro256++ by the ziggurat method (Marsaglia &
/// Tsang 2000, J. Stat. Softw. 5(8); 256 layers, tail by their exponential rejection). One
/// 64-bit word per draw 98.5 % of the time: bits 0–7 pick the layer, bit 8 the sign, bits 11–63
/// the abscissa, accepted by one integer comparison; the wedges and the tail (the other 1.5 %)
/// run out of line. fill() runs the fast path inline over a block (~2.9 ns per normal on a
/// 2.5 GHz Xeon, against 22 ns for the former out-of-line draw on std::mt19937_64).
/// operator() gives the same sequence one draw at a time: fill(n) then fill(m) equals
/// fill(n + m) and n + m calls of operator().
class StandardNormal {
 public:
  StandardNormal() = default;
  explicit StandardNormal(Xoshiro256PlusPlus engine) : engine_(engine) {}
  /// Seeds the xoshiro256++ engine with one word of SEED_SOURCE. Kept for callers written for
  /// the former std::mt19937_64 engine; prefer StandardNormal(Xoshiro256PlusPlus(seed)).
  explicit StandardNormal(std::mt19937_64 seed_source) : engine_(seed_source()) {}

  /// Next N(0, 1) draw.
  double operator()();
  /// Overwrites OUT with the next OUT.size() N(0, 1) draws.
  void fill(std::span<double> out);

 private:
  Xoshiro256PlusPlus engine_;
};

/// Rate, seed and flicker band shared by every channel of one simulation.
struct SimulationOptions {
  double sample_rate_hz = 100.0;  ///< f_s = 1/τ0 [Hz], > 0
  std::uint64_t seed = 1;         ///< master seed; each channel and term derives its own stream
  FlickerBand flicker_band;       ///< band of the bias-instability construction
};

/// Generates one channel in blocks. The k-th sample is the sensor error (plus constant signal)
/// averaged over [k·τ0, (k+1)·τ0) for the white, quantization, random-walk and flicker terms,
/// and point-sampled at t_k = k·τ0 for Gauss–Markov, ramp and sinusoid terms.
///
/// Each stochastic term draws from its own xoshiro256++ stream seeded from (seed, channel
/// index, term id), so the output does not depend on how it is split into blocks, channels are
/// independent, and switching one term on or off leaves the others' realisations unchanged.
/// Blocks are processed in chunks of kChunk samples: each term first draws its normals for the
/// chunk into a scratch buffer (StandardNormal::fill), then runs its recursion over them.
/// No heap allocation after construction. About 110 ns per sample for a channel with N, K and
/// B (11 flicker terms; 25 normals per sample), 5× faster than with std::mt19937_64.
class ChannelSimulator {
 public:
  /// @param[in] model          the channel's terms (validated; InputError on bad values)
  /// @param[in] options        rate, master seed, flicker band
  /// @param[in] channel_index  distinguishes the channels of one simulation (0…)
  ChannelSimulator(const ChannelNoiseModel& model, const SimulationOptions& options,
                   std::uint32_t channel_index);

  /// Overwrites OUT with the next OUT.size() samples [rad/s | m/s²].
  void next_block(std::span<double> out);

  /// Number of samples produced so far (index of the next sample).
  std::int64_t samples_generated() const { return next_index_; }

  /// Samples per chunk of next_block().
  static constexpr std::size_t kChunk = 256;

 private:
  /// Ornstein–Uhlenbeck state whose output is either its point value (user GM terms) or its
  /// exact average over the sample interval (flicker terms); see the .cpp.
  struct OuTerm {
    StandardNormal draw;
    double state = 0.0;       ///< x_k
    double phi = 0.0;         ///< e^{−τ0/T}
    double state_gain = 0.0;  ///< weight of x_k in the output sample
    double step_sigma = 0.0;  ///< σ of the state innovation w_k = step_sigma·z1
    double out_z1 = 0.0;      ///< output weight of z1 (averaged terms only)
    double out_z2 = 0.0;      ///< output weight of an independent z2 (averaged terms only)
  };
  /// Averaged terms advance together in groups of up to kGroup, states in registers, so their
  /// recursions overlap instead of each waiting on its own multiply–add latency.
  static constexpr std::size_t kGroup = 4;

  double tau0_s_ = 0.0;
  double sample_rate_hz_ = 0.0;
  std::int64_t next_index_ = 0;
  ChannelNoiseModel model_;
  double white_sigma_ = 0.0;     ///< N/√τ0, σ of a τ0-averaged white-rate sample
  double rw_step_sigma_ = 0.0;   ///< K·√τ0, σ of the random-walk increment per sample
  double rw_state_ = 0.0;        ///< random-walk bias at the start of the current sample
  double quant_previous_ = 0.0;  ///< white angle error at the start of the current sample
  StandardNormal white_draw_;
  StandardNormal quant_draw_;
  StandardNormal rw_draw_;
  std::vector<OuTerm> point_terms_;     ///< user Gauss–Markov terms: output x_k
  std::vector<OuTerm> averaged_terms_;  ///< flicker terms: output the τ0-average of x
  std::vector<double> scratch_;         ///< normals of one chunk: 2·kChunk per term of a group

  /// next_block() for OUT.size() ≤ kChunk.
  void next_chunk(std::span<double> out);
  /// Adds averaged_terms_[FIRST … FIRST+K) to OUT (OUT.size() ≤ kChunk).
  template <std::size_t K>
  void add_averaged_group(std::size_t first, std::span<double> out);
};

/// Number of channels of an IMU: gyro x, y, z then accelerometer x, y, z.
inline constexpr std::size_t kImuChannels = 6;

/// Error models of a 6-axis IMU.
struct ImuNoiseModel {
  std::array<ChannelNoiseModel, 3> gyro;   ///< x, y, z [rad/s]
  std::array<ChannelNoiseModel, 3> accel;  ///< x, y, z [m/s²]
};

/// The six ChannelSimulators of an IMU, channel indices 0…5 in kImuChannels order.
class ImuSimulator {
 public:
  ImuSimulator(const ImuNoiseModel& model, const SimulationOptions& options);

  /// Fills the next block of every channel; all six spans must have the same size
  /// (ContractViolation otherwise).
  void next_block(const std::array<std::span<double>, kImuChannels>& out);

  /// Number of samples produced so far per channel.
  std::int64_t samples_generated() const { return channels_.front().samples_generated(); }

 private:
  std::vector<ChannelSimulator> channels_;
};

}  // namespace imunoise::models
