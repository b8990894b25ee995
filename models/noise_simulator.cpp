/// @file
/// @brief Implementation of the streaming IMU error simulator (noise_simulator.h).
#include "models/noise_simulator.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <system_error>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"

namespace imunoise::models {

namespace {

/// Stream ids: each stochastic term of a channel owns an engine seeded from
/// (seed, channel, id), so terms are independent and do not shift each other's draws.
constexpr std::uint32_t kWhiteStream = 1;
constexpr std::uint32_t kQuantizationStream = 2;
constexpr std::uint32_t kRandomWalkStream = 3;
constexpr std::uint32_t kGaussMarkovStreamBase = 1000;
constexpr std::uint32_t kFlickerStreamBase = 2000;
/// Distinguishes this simulator's streams from any other user of the same seed ("imunoise").
constexpr std::uint64_t kSalt = 0x696d756e6f697365ULL;

void check_non_negative(double value, std::string_view where, std::string_view field) {
  if (!std::isfinite(value) || value < 0.0) {
    throw InputError(std::string(where) + "." + std::string(field) +
                     ": must be finite and >= 0 (got " + shortest_number_text(value) + ")");
  }
}

void check_finite(double value, std::string_view where, std::string_view field) {
  if (!std::isfinite(value)) {
    throw InputError(std::string(where) + "." + std::string(field) + ": must be finite (got " +
                     shortest_number_text(value) + ")");
  }
}

/// The xoshiro256++ stream of (seed, channel, stream). Key derivation: k1 = splitmix64 of
/// (seed ⊕ salt), k2 = splitmix64 of (k1 ⊕ (channel·2³² + stream)); the engine state is four
/// splitmix64 outputs from k2. Each splitmix64 step is a bijection of its input, so for one seed
/// distinct (channel, stream) pairs get distinct keys and states. Streams start at unrelated
/// points of the 2^256 − 1 cycle: two runs of 2^64 words overlap with probability ~2^−191.
Xoshiro256PlusPlus make_engine(std::uint64_t seed, std::uint32_t channel, std::uint32_t stream) {
  std::uint64_t state = seed ^ kSalt;
  state = splitmix64(state) ^ ((static_cast<std::uint64_t>(channel) << 32U) | stream);
  return Xoshiro256PlusPlus(splitmix64(state));
}

/// f(e) = e − 2(1 − e^{−e}) + (1 − e^{−2e})/2, the bracket of Var v below divided by T.
/// For small e it is e³/3 − e⁴/4 + …: the direct form cancels ~e³ relative, so use the
/// series Σ_{n≥3} (−1)^n (2 − 2^{n−1}) eⁿ/n! below e = 0.1 (truncation < 1e-20 relative).
double averaged_ou_bracket(double e) {
  if (e >= 0.1) return e + 2.0 * std::expm1(-e) - 0.5 * std::expm1(-2.0 * e);
  double sum = 0.0;
  double power_over_factorial = e * e / 2.0;  // e^n/n! for n = 2
  double two_to_n_minus_1 = 2.0;              // 2^{n−1} for n = 2
  for (int n = 3; n <= 20; ++n) {
    power_over_factorial *= e / n;
    two_to_n_minus_1 *= 2.0;
    const double sign = (n % 2 == 0) ? 1.0 : -1.0;
    sum += sign * (2.0 - two_to_n_minus_1) * power_over_factorial;
  }
  return sum;
}

/// Ziggurat tables for f(x) = e^{−x²/2}: C = 256 layers of equal area v. Layer 0 is the box
/// [0, r]×[0, f(r)] plus the tail x > r, drawn as the box [0, v/f(r)]×[0, f(r)]; layer i ≥ 1 is
/// the box [0, w_i]×[f_i, f_{i+1}] with f_{i+1} = f_i + v/w_i. r is Marsaglia & Tsang's value
/// for C = 256; with v = r f(r) + √(π/2)·erfc(r/√2) the recursion closes at f_C = 1 to 2e-15.
/// Fast path: with u the 53-bit abscissa word, x = u·2⁻⁵³·w_i lies under the curve for sure
/// when x < w_{i+1}, i.e. u < accept_i = ⌊2⁵³·w_{i+1}/w_i⌋; scale holds ±w_i·2⁻⁵³ indexed by
/// the 9 low bits (layer and sign), so an accepted draw costs one compare and one multiply.
struct ZigguratTables {
  static constexpr int kLayers = 256;
  static constexpr double kR = 3.6541528853610088;
  static constexpr double kTwoPow53 = 0x1.0p53;
  std::array<double, kLayers + 1> w{};          ///< box widths (w_0 = v/f(r), w_1 = r, w_C = 0)
  std::array<double, kLayers + 1> f{};          ///< f at the box bottoms (f_C = 1)
  std::array<std::uint64_t, kLayers> accept{};  ///< fast-path bound on the 53-bit word
  std::array<double, 2 * kLayers> scale{};      ///< ±w_i·2⁻⁵³, index = layer + 256·sign

  ZigguratTables() {
    const auto density = [](double x) { return std::exp(-0.5 * x * x); };
    const double v =
        kR * density(kR) + std::sqrt(std::numbers::pi / 2.0) * std::erfc(kR / std::numbers::sqrt2);
    w[0] = v / density(kR);
    f[0] = 0.0;
    w[1] = kR;
    f[1] = density(kR);
    for (int i = 1; i < kLayers; ++i) {
      f[i + 1] = std::min(f[i] + v / w[i], 1.0);
      w[i + 1] = std::sqrt(-2.0 * std::log(f[i + 1]));
    }
    w[kLayers] = 0.0;
    f[kLayers] = 1.0;
    for (int i = 0; i < kLayers; ++i) {
      accept[static_cast<std::size_t>(i)] =
          static_cast<std::uint64_t>(std::floor(kTwoPow53 * (w[i + 1] / w[i])));
      scale[static_cast<std::size_t>(i)] = w[i] / kTwoPow53;
      scale[static_cast<std::size_t>(i + kLayers)] = -w[i] / kTwoPow53;
    }
  }
};

const ZigguratTables& ziggurat_tables() {
  static const ZigguratTables tables;
  return tables;
}

/// Uniform on [0, 1) from the top 53 bits of a 64-bit word.
double unit_uniform(std::uint64_t word) {
  // Through int64: the 53-bit value converts with one instruction, unlike uint64.
  return static_cast<double>(static_cast<std::int64_t>(word >> 11U)) * 0x1.0p-53;
}

/// A draw and the engine after it.
struct SlowDraw {
  double z;
  Xoshiro256PlusPlus engine;
};

/// The rest of the ziggurat for a WORD the fast path rejected: tail or wedge test, then fresh
/// draws (full algorithm) until one is accepted. Rare (1.5 %), so kept out of line; it takes
/// and returns the engine by value so that the engine's address never escapes the fill() loop
/// and its state stays in registers there.
[[gnu::noinline]] SlowDraw ziggurat_slow(const ZigguratTables& t, Xoshiro256PlusPlus engine,
                                         std::uint64_t word) {
  for (;;) {
    const auto layer = static_cast<int>(word & 0xffU);
    const double sign = (word & 0x100U) != 0 ? -1.0 : 1.0;
    const double x = unit_uniform(word) * t.w[layer];
    if (x < t.w[layer + 1]) return {sign * x, engine};  // fresh words (or the bound's rounding)
    if (layer == 0) {
      // Tail x > r: Marsaglia's method, x = r + e1/r accepted when 2·e2 > (e1/r)², e1, e2
      // standard exponentials.
      double tail = 0.0;
      double e2 = 0.0;
      do {
        tail = -std::log(1.0 - unit_uniform(engine())) / ZigguratTables::kR;
        e2 = -std::log(1.0 - unit_uniform(engine()));
      } while (e2 + e2 < tail * tail);
      return {sign * (ZigguratTables::kR + tail), engine};
    }
    // Wedge: accept when a uniform height in [f_i, f_{i+1}] falls under the curve.
    const double y = t.f[layer] + unit_uniform(engine()) * (t.f[layer + 1] - t.f[layer]);
    if (y < std::exp(-0.5 * x * x)) return {sign * x, engine};
    word = engine();
  }
}

/// One draw, the fast path inline.
inline double ziggurat_draw(const ZigguratTables& t, Xoshiro256PlusPlus& engine) {
  const std::uint64_t word = engine();
  const std::uint64_t u = word >> 11U;
  if (u < t.accept[word & 0xffU]) [[likely]] {
    return static_cast<double>(static_cast<std::int64_t>(u)) * t.scale[word & 0x1ffU];
  }
  const SlowDraw slow = ziggurat_slow(t, engine, word);
  engine = slow.engine;
  return slow.z;
}

}  // namespace

double StandardNormal::operator()() { return ziggurat_draw(ziggurat_tables(), engine_); }

void StandardNormal::fill(std::span<double> out) {
  const ZigguratTables& t = ziggurat_tables();
  Xoshiro256PlusPlus engine = engine_;  // a local copy: its state lives in registers
  for (double& z : out) z = ziggurat_draw(t, engine);
  engine_ = engine;
}

ChannelNoiseModel channel_model_from(const NoiseCoefficients& coefficients) {
  ChannelNoiseModel model;
  static_cast<NoiseCoefficients&>(model) = coefficients;
  return model;
}

void validate_channel_model(const ChannelNoiseModel& model, std::string_view where) {
  check_non_negative(model.quantization, where, "quantization");
  check_non_negative(model.white_noise, where, "white_noise");
  check_non_negative(model.bias_instability, where, "bias_instability");
  check_non_negative(model.random_walk, where, "random_walk");
  check_finite(model.ramp, where, "ramp");
  check_finite(model.constant, where, "constant");
  check_non_negative(model.output_lsb, where, "output_lsb");
  for (std::size_t j = 0; j < model.gauss_markov.size(); ++j) {
    const std::string field = "gauss_markov[" + std::to_string(j) + "]";
    check_non_negative(model.gauss_markov[j].sigma, where, field + ".sigma");
    const double tau_c = model.gauss_markov[j].tau_c_s;
    if (!std::isfinite(tau_c) || !(tau_c > 0.0)) {
      throw InputError(std::string(where) + "." + field + ".tau_c_s: must be finite and > 0 (got " +
                       shortest_number_text(tau_c) + ")");
    }
  }
  for (std::size_t j = 0; j < model.sinusoids.size(); ++j) {
    const std::string field = "sinusoids[" + std::to_string(j) + "]";
    check_finite(model.sinusoids[j].amplitude, where, field + ".amplitude");
    check_non_negative(model.sinusoids[j].frequency_hz, where, field + ".frequency_hz");
    check_finite(model.sinusoids[j].phase_rad, where, field + ".phase_rad");
  }
}

// Flicker as a sum of Gauss–Markov terms. A GM term of variance σ² and correlation time T has
// the two-sided PSD S(f) = 2σ²T/(1 + (2πfT)²) (theory.md §4.1 with q_c² = 2σ²/T). Spreading
// terms of equal σ² log-uniformly in T, one per decade (density 1/ln10 per unit of ln T):
//   Σ_k S_k(f) ≈ (2σ²/ln10)∫₀^∞ dT/(1 + (2πfT)²) = (2σ²/ln10)·1/(4f) = σ²/(2 f ln10),
// which equals the bias-instability PSD B²/(2πf) for σ² = B² ln10/π ≈ 0.733 B². Checked
// with the exact GM AVAR of §4.1 summed over the terms (tests/models/noise_simulator_test.cpp,
// FlickerConstruction): the interior ripple of the ADEV is ±1.04 % at one term per decade
// (worst case over all band positions, scanned on a fine τ grid); the sum stays within it for
// 100·T_min ≤ τ ≤ T_max/100 and falls off outside (1.4 % near T_max/15, 6 % at T_max). Hence two
// extra decades on each side of the band.
std::vector<GaussMarkov> flicker_gauss_markov_terms(double bias_instability, double tau_min_s,
                                                    double tau_max_s) {
  check_non_negative(bias_instability, "flicker", "bias_instability");
  if (!std::isfinite(tau_min_s) || !std::isfinite(tau_max_s) || !(tau_min_s > 0.0) ||
      !(tau_max_s > tau_min_s)) {
    throw InputError("flicker band: need 0 < tau_min_s < tau_max_s (got " +
                     shortest_number_text(tau_min_s) + ", " + shortest_number_text(tau_max_s) +
                     ")");
  }
  std::vector<GaussMarkov> terms;
  if (bias_instability == 0.0) return terms;
  const double sigma = bias_instability * std::sqrt(std::numbers::ln10 / std::numbers::pi);
  const int first = static_cast<int>(std::floor(std::log10(tau_min_s))) - 2;
  const int last = static_cast<int>(std::ceil(std::log10(tau_max_s))) + 2;
  for (int k = first; k <= last; ++k) terms.push_back({sigma, std::pow(10.0, k)});
  return terms;
}

ChannelSimulator::ChannelSimulator(const ChannelNoiseModel& model, const SimulationOptions& options,
                                   std::uint32_t channel_index)
    : model_(model) {
  validate_channel_model(model, "channel " + std::to_string(channel_index));
  if (!std::isfinite(options.sample_rate_hz) || !(options.sample_rate_hz > 0.0)) {
    throw InputError("simulation: sample_rate_hz must be finite and > 0 (got " +
                     shortest_number_text(options.sample_rate_hz) + ")");
  }
  sample_rate_hz_ = options.sample_rate_hz;
  tau0_s_ = 1.0 / sample_rate_hz_;
  const std::uint64_t seed = options.seed;
  const auto stream = [&](std::uint32_t id) {
    return StandardNormal(make_engine(seed, channel_index, id));
  };

  // White rate noise: a τ0-average of white noise of intensity N² has variance N²/τ0
  // (Kalibr σ_gd = σ_g/√Δt, theory.md §1.4); the m-sample average then has N²/τ exactly.
  white_sigma_ = model.white_noise / std::sqrt(tau0_s_);
  white_draw_ = stream(kWhiteStream);

  // Quantization as white angle noise q_k (σ = Q) at the sample instants; the rate sample is
  // (q_{k+1} − q_k)/τ0, so the integrated error is q_k − q_0: AVAR 3Q²/τ² (theory.md §4.1).
  quant_draw_ = stream(kQuantizationStream);
  if (model.quantization > 0.0) quant_previous_ = model.quantization * quant_draw_();

  // Random walk b(t) with ḃ = K·w: the increment over τ0 has σ = K√τ0 (theory.md §1.4); the
  // sample is the exact τ0-average of b(t), see next_block().
  rw_step_sigma_ = model.random_walk * std::sqrt(tau0_s_);
  rw_draw_ = stream(kRandomWalkStream);
  // Two normals per sample for each term of a group of averaged terms (the widest user).
  scratch_.resize(2 * kChunk * kGroup);

  // User Gauss–Markov terms: exact point-sampled AR(1), φ = e^{−τ0/T_c},
  // q_d = σ²(1 − φ²), stationary start x_0 ~ N(0, σ²) (theory.md §4.1, §6.2).
  for (std::size_t j = 0; j < model.gauss_markov.size(); ++j) {
    const GaussMarkov& gm = model.gauss_markov[j];
    OuTerm term{stream(kGaussMarkovStreamBase + static_cast<std::uint32_t>(j))};
    const double e = tau0_s_ / gm.tau_c_s;
    term.phi = std::exp(-e);
    term.step_sigma = gm.sigma * std::sqrt(-std::expm1(-2.0 * e));
    term.state_gain = 1.0;
    term.state = gm.sigma * term.draw();
    point_terms_.push_back(std::move(term));
  }

  // Flicker terms: exact τ0-averages of an Ornstein–Uhlenbeck process (not point samples),
  // so that terms with T ≪ τ0 contribute their true white level 2σ²T/τ instead of σ² per
  // sample and the ADEV stays flat down to τ = τ0. Over one step h = τ0, with e = h/T,
  // φ = e^{−e}, q_c² = 2σ²/T and x_k the state at the start of the step:
  //   x_{k+1} = φ x_k + w,        w = q_c ∫₀^h e^{−(h−u)/T} dW(u)
  //   ∫ x dt  = T(1−φ) x_k + v,   v = q_c T ∫₀^h (1 − e^{−(h−u)/T}) dW(u)
  //   Var w = σ²(1−φ²),  Var v = 2σ²T² f(e),  Cov(w, v) = σ²T(1−φ)²  (Itô isometry),
  // with f from averaged_ou_bracket(). (w, v) is drawn as w = a z1, v = c z1 + d z2 with
  // a = √Var w, c = Cov/a, d² = Var v − c² = σ²T²[2f(e) − (1−φ)³/(1+φ)]; the sample is
  // ∫ x dt / h. Check: its variance is 2σ²(e − (1−φ))/e², the variance of the τ0-average.
  if (model.bias_instability > 0.0) {
    const double tau_min =
        options.flicker_band.tau_min_s > 0.0 ? options.flicker_band.tau_min_s : tau0_s_;
    const std::vector<GaussMarkov> flicker =
        flicker_gauss_markov_terms(model.bias_instability, tau_min, options.flicker_band.tau_max_s);
    for (std::size_t j = 0; j < flicker.size(); ++j) {
      const double sigma = flicker[j].sigma;
      OuTerm term{stream(kFlickerStreamBase + static_cast<std::uint32_t>(j))};
      const double e = tau0_s_ / flicker[j].tau_c_s;
      const double one_minus_phi = -std::expm1(-e);
      const double one_minus_phi2 = -std::expm1(-2.0 * e);
      term.phi = std::exp(-e);
      term.step_sigma = sigma * std::sqrt(one_minus_phi2);
      term.state_gain = one_minus_phi / e;
      term.out_z1 = sigma * one_minus_phi * one_minus_phi / (e * std::sqrt(one_minus_phi2));
      const double d2 = 2.0 * averaged_ou_bracket(e) -
                        one_minus_phi * one_minus_phi * one_minus_phi / (1.0 + term.phi);
      term.out_z2 = sigma * std::sqrt(std::max(d2, 0.0)) / e;
      term.state = sigma * term.draw();
      averaged_terms_.push_back(std::move(term));
    }
  }
}

template <std::size_t K>
void ChannelSimulator::add_averaged_group(std::size_t first, std::span<double> out) {
  static_assert(K >= 1 && K <= kGroup);
  const std::size_t n = out.size();
  // Coefficients and states copied to locals: the compiler keeps them in registers (no
  // aliasing with OUT) and the K recursions interleave.
  std::array<const double*, K> z{};
  std::array<double, K> state{}, phi{}, gain{}, step{}, w1{}, w2{};
  for (std::size_t k = 0; k < K; ++k) {
    OuTerm& term = averaged_terms_[first + k];
    const std::span<double> normals(scratch_.data() + k * 2 * kChunk, 2 * n);
    term.draw.fill(normals);  // z1 = [2i], z2 = [2i+1]
    z[k] = normals.data();
    state[k] = term.state;
    phi[k] = term.phi;
    gain[k] = term.state_gain;
    step[k] = term.step_sigma;
    w1[k] = term.out_z1;
    w2[k] = term.out_z2;
  }
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0.0;
    for (std::size_t k = 0; k < K; ++k) {
      const double z1 = z[k][2 * i];
      const double z2 = z[k][2 * i + 1];
      sum += gain[k] * state[k] + w1[k] * z1 + w2[k] * z2;
      state[k] = phi[k] * state[k] + step[k] * z1;
    }
    out[i] += sum;
  }
  for (std::size_t k = 0; k < K; ++k) averaged_terms_[first + k].state = state[k];
}

void ChannelSimulator::next_block(std::span<double> out) {
  for (std::size_t start = 0; start < out.size(); start += kChunk) {
    next_chunk(out.subspan(start, std::min(kChunk, out.size() - start)));
  }
}

void ChannelSimulator::next_chunk(std::span<double> out) {
  const std::size_t n = out.size();
  const std::int64_t first = next_index_;
  const std::span<double> z1(scratch_.data(), n);       // one normal per sample
  const std::span<double> z12(scratch_.data(), 2 * n);  // two per sample: z1 = [2i], z2 = [2i+1]
  for (std::size_t i = 0; i < n; ++i) out[i] = model_.constant;

  if (model_.ramp != 0.0) {
    for (std::size_t i = 0; i < n; ++i) {
      out[i] += model_.ramp * (static_cast<double>(first + static_cast<std::int64_t>(i)) * tau0_s_);
    }
  }
  for (const Sinusoid& s : model_.sinusoids) {
    // Cycles from the integer index, so the phase does not accumulate rounding over long runs.
    const double cycles_per_sample = s.frequency_hz * tau0_s_;
    for (std::size_t i = 0; i < n; ++i) {
      const double cycles = std::fmod(
          cycles_per_sample * static_cast<double>(first + static_cast<std::int64_t>(i)), 1.0);
      out[i] += s.amplitude * std::sin(2.0 * std::numbers::pi * cycles + s.phase_rad);
    }
  }
  if (white_sigma_ > 0.0) {
    white_draw_.fill(z1);
    for (std::size_t i = 0; i < n; ++i) out[i] += white_sigma_ * z1[i];
  }
  if (model_.quantization > 0.0) {
    quant_draw_.fill(z1);
    const double scale = model_.quantization;
    double previous = quant_previous_;
    for (std::size_t i = 0; i < n; ++i) {
      const double next = scale * z1[i];
      out[i] += (next - previous) / tau0_s_;
      previous = next;
    }
    quant_previous_ = previous;
  }
  if (rw_step_sigma_ > 0.0) {
    // Exact τ0-average of a Wiener process b with increment w = s·z1 (s = K√τ0) over the
    // sample: b_k + (1/τ0)∫₀^τ0 W dt, where the integral has variance s²/3 and covariance s/2
    // with w, i.e. s·(z1/2 + z2/√12). Point samples b_k would add a white term
    // (K²τ0²/6τ, theory.md §4.1 [ZH08]: AV(n) = (2n²+1)σ²/(6n)); the average gives K²τ/3.
    rw_draw_.fill(z12);
    const double s = rw_step_sigma_;
    const double half_s = 0.5 * s;
    const double s_over_sqrt12 = s / std::sqrt(12.0);
    double state = rw_state_;
    for (std::size_t i = 0; i < n; ++i) {
      out[i] += state + half_s * z12[2 * i] + s_over_sqrt12 * z12[2 * i + 1];
      state += s * z12[2 * i];
    }
    rw_state_ = state;
  }
  for (OuTerm& term : point_terms_) {
    term.draw.fill(z1);
    double state = term.state;
    for (std::size_t i = 0; i < n; ++i) {
      out[i] += state;
      state = term.phi * state + term.step_sigma * z1[i];
    }
    term.state = state;
  }
  for (std::size_t first = 0; first < averaged_terms_.size(); first += kGroup) {
    switch (std::min(kGroup, averaged_terms_.size() - first)) {
      case 1:
        add_averaged_group<1>(first, out);
        break;
      case 2:
        add_averaged_group<2>(first, out);
        break;
      case 3:
        add_averaged_group<3>(first, out);
        break;
      default:
        add_averaged_group<4>(first, out);
        break;
    }
  }
  if (model_.output_lsb > 0.0) {
    const double lsb = model_.output_lsb;
    for (std::size_t i = 0; i < n; ++i) out[i] = lsb * std::nearbyint(out[i] / lsb);
  }
  next_index_ += static_cast<std::int64_t>(n);
}

ImuSimulator::ImuSimulator(const ImuNoiseModel& model, const SimulationOptions& options) {
  channels_.reserve(kImuChannels);
  for (std::uint32_t axis = 0; axis < 3; ++axis) {
    channels_.emplace_back(model.gyro[axis], options, axis);
  }
  for (std::uint32_t axis = 0; axis < 3; ++axis) {
    channels_.emplace_back(model.accel[axis], options, 3 + axis);
  }
}

void ImuSimulator::next_block(const std::array<std::span<double>, kImuChannels>& out) {
  for (std::size_t c = 0; c < kImuChannels; ++c) {
    IMUNOISE_EXPECT(out[c].size() == out[0].size(),
                    "ImuSimulator::next_block: channel blocks differ in size");
  }
  for (std::size_t c = 0; c < kImuChannels; ++c) channels_[c].next_block(out[c]);
}

}  // namespace imunoise::models
