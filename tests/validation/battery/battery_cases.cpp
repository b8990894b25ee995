#include "battery/battery_cases.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace imunoise::battery {

namespace {

constexpr double kPi = std::numbers::pi;

/// @name Datasheet units → SI (theory.md §1.3; own constants, the battery uses no imunoise
/// header). Densities are two-sided (theory.md §1.2).
/// @{
constexpr double kDeg = kPi / 180.0;
constexpr double kDegPerSqrtHour = kDeg / 60.0;             // deg/√h → rad/√s
constexpr double kDegPerHour = kDeg / 3600.0;               // deg/h → rad/s
constexpr double kDegPerHourPerSqrtHour = kDeg / 216000.0;  // deg/h/√h → rad/s^{3/2}
constexpr double kStandardGravity = 9.80665;                // g₀ [m/s²]
constexpr double kMicroG = 1e-6 * kStandardGravity;         // µg → m/s²
constexpr double kMicroGPerSqrtHz = kMicroG;                // µg/√Hz → m/s/√s
constexpr double kMicroGPerSqrtS = kMicroG;                 // µg/√s → m/s^{5/2}
constexpr double kMPerSPerSqrtHour = 1.0 / 60.0;            // m/s/√h → m/s/√s
constexpr double kMicroradian = 1e-6;
/// @}

constexpr double kEarthRate = 7.292115e-5;  // Ω_ie [rad/s] (WGS84)
constexpr double kLatitude = 45.0 * kDeg;

/// The noise of one sensor kind of a grade (SI).
struct SensorNoise {
  double n = 0.0, b = 0.0, k = 0.0;
};

struct Grade {
  const char* name;
  double rate_hz;
  double duration_s;
  SensorNoise gyro, accel;
};

// Typical datasheet values (docs/validation.md "Grades" gives them in both unit systems).
const Grade kConsumer{"consumer",
                      1000.0,
                      3600.0,
                      {0.6 * kDegPerSqrtHour, 10.0 * kDegPerHour, 50.0 * kDegPerHourPerSqrtHour},
                      {150.0 * kMicroGPerSqrtHz, 40.0 * kMicroG, 4.0 * kMicroGPerSqrtS}};
const Grade kIndustrial{"industrial",
                        400.0,
                        4.0 * 3600.0,
                        {0.15 * kDegPerSqrtHour, 2.0 * kDegPerHour, 5.0 * kDegPerHourPerSqrtHour},
                        {0.02 * kMPerSPerSqrtHour, 5.0 * kMicroG, 0.2 * kMicroGPerSqrtS}};
const Grade kTactical{"tactical",
                      100.0,
                      12.0 * 3600.0,
                      {0.05 * kDegPerSqrtHour, 0.3 * kDegPerHour, 0.5 * kDegPerHourPerSqrtHour},
                      {0.03 * kMPerSPerSqrtHour, 20.0 * kMicroG, 0.5 * kMicroGPerSqrtS}};
/// The sensor of the phenomenon classes: industrial noise at 100 Hz for 2 h.
const Grade kPhenomenonBase{"industrial", 100.0, 2.0 * 3600.0, kIndustrial.gyro, kIndustrial.accel};

/// Per-axis scale of every coefficient (x, y, z): axes of one sensor differ a little.
constexpr std::array<double, 3> kAxisScale = {1.0, 1.2, 0.85};
/// Constant bias per channel in units of that channel's B (plus Earth rate and gravity).
constexpr std::array<double, 6> kBiasInB = {3.0, -2.0, 1.5, 2.0, -3.0, 1.0};
/// Warm-up amplitude per channel in units of that channel's B.
constexpr std::array<double, 6> kWarmupInB = {10.0, -8.0, 6.0, -10.0, 8.0, 12.0};

const std::array<const char*, 6> kChannelNames = {"gyro_x",  "gyro_y",  "gyro_z",
                                                  "accel_x", "accel_y", "accel_z"};

/// The generator seed of (CLASS, SEED): the class name's FNV-1a hash mixed with the seed, so
/// that no two classes share a random stream (their rows pool as independent samples).
std::uint64_t class_seed(const std::string& class_name, std::uint64_t seed) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char ch : class_name) h = (h ^ ch) * 0x100000001b3ULL;
  return h ^ (seed * 0x9e3779b97f4a7c15ULL);
}

double per_sample_sigma(const ChannelTruth& t, double tau0_s) {
  return t.white_noise / std::sqrt(tau0_s);
}

/// The plain case of grade G: N, B, K on every channel but K_FREE, constants, no phenomenon.
BatteryCase base_case(const std::string& class_name, const Grade& g, BatterySize size,
                      std::uint64_t seed, int k_free_channel) {
  BatteryCase c;
  c.class_name = class_name;
  c.grade = g.name;
  c.seed = seed;
  c.spec.seed = class_seed(class_name, seed);
  double rate = g.rate_hz, duration = g.duration_s;
  if (size == BatterySize::reduced) {
    rate = std::min(rate, 100.0);
    duration = 1200.0;
  }
  if (size == BatterySize::long_record) {
    rate = std::min(rate, 100.0);
    duration = std::max(duration, 6.0 * 3600.0);
  }
  c.spec.rate_hz = rate;
  c.spec.samples = static_cast<std::size_t>(std::llround(rate * duration));
  {
    std::ostringstream datasheet;
    datasheet.precision(17);
    datasheet << "name: battery " << g.name
              << " grade\ngyro:\n  arw_deg_per_sqrt_h: " << g.gyro.n / kDegPerSqrtHour
              << "\naccel:\n  vrw_ug_per_sqrt_hz: " << g.accel.n / kMicroGPerSqrtHz << "\n";
    c.datasheet = datasheet.str();
  }
  for (int ch = 0; ch < 6; ++ch) {
    const bool gyro = ch < 3;
    const SensorNoise& s = gyro ? g.gyro : g.accel;
    const double scale = kAxisScale[static_cast<std::size_t>(ch % 3)];
    ChannelTruth& t = c.truth[static_cast<std::size_t>(ch)];
    ChannelSpec& cs = c.spec.channels[static_cast<std::size_t>(ch)];
    t.name = kChannelNames[static_cast<std::size_t>(ch)];
    t.gyro = gyro;
    t.white_noise = cs.white = scale * s.n;
    t.bias_instability = cs.flicker = scale * s.b;
    t.random_walk = cs.random_walk = ch == k_free_channel ? 0.0 : scale * s.k;
    t.white_noise_as_recorded = t.white_noise;
    cs.constant = kBiasInB[static_cast<std::size_t>(ch)] * cs.flicker;
    if (ch == 0) cs.constant += kEarthRate * std::cos(kLatitude);  // x north
    if (ch == 2) cs.constant -= kEarthRate * std::sin(kLatitude);  // z down
    if (ch == 5) cs.constant -= kStandardGravity;                  // level FRD: f_z = −g₀
  }
  return c;
}

double record_length_s(const BatteryCase& c) {
  return static_cast<double>(c.spec.samples) / c.spec.rate_hz;
}

void add_phenomenon(BatteryCase& c, Phenomenon p) { c.phenomena.push_back(p); }

/// Warm-up a·e^{−t/τ_w} with τ_w = T/8 (900 s at 2 h) and a = kWarmupInB·B per channel.
void add_warmup(BatteryCase& c) {
  const double tau_w = record_length_s(c) / 8.0;
  for (std::size_t ch = 0; ch < 6; ++ch) {
    ChannelSpec& cs = c.spec.channels[ch];
    cs.warmup_amplitude = kWarmupInB[ch] * cs.flicker;
    cs.warmup_tau_s = tau_w;
  }
  add_phenomenon(c, Phenomenon::warmup);
}

/// Lines of the lines class: (channel, f [Hz], SNR), the SNR as TruthLine::snr defines it.
struct LinePlan {
  int channel;
  double frequency_hz;
  double snr;
};
constexpr std::array<LinePlan, 10> kLines = {{{0, 0.57, 30.0},
                                              {1, 0.02, 30.0},
                                              {1, 0.08, 10.0},
                                              {2, 1.5, 100.0},
                                              {2, 20.0, 10.0},
                                              {3, 0.18, 30.0},
                                              {3, 0.57, 100.0},
                                              {4, 0.57, 30.0},
                                              {5, 0.57, 10.0},
                                              {5, 0.04, 30.0}}};

}  // namespace

const char* phenomenon_name(Phenomenon p) {
  switch (p) {
    case Phenomenon::warmup:
      return "warmup";
    case Phenomenon::outliers:
      return "outliers";
    case Phenomenon::low_pass:
      return "low_pass";
    case Phenomenon::decimation:
      return "decimation";
    case Phenomenon::stamps:
      return "stamps";
    case Phenomenon::lsb:
      return "lsb";
    case Phenomenon::lines:
      return "lines";
    case Phenomenon::temperature:
      return "temperature";
  }
  return "unknown";
}

std::vector<std::string> battery_classes() {
  return {"consumer", "industrial", "tactical", "gm",        "lines",  "lowpass",    "lsb7",
          "lsb1",     "warmup",     "outliers", "decimated", "stamps", "temperature"};
}

BatteryCase make_case(const std::string& name, BatterySize size, std::uint64_t seed) {
  if (name == "consumer") {
    BatteryCase c = base_case(name, kConsumer, size, seed, 4);
    c.description = "consumer MEMS, clean";
    return c;
  }
  if (name == "industrial") {
    BatteryCase c = base_case(name, kIndustrial, size, seed, 4);
    c.description = "industrial MEMS, clean, ramp on gyro_z";
    c.truth[2].ramp = c.spec.channels[2].ramp = 5e-9;  // rad/s² (3.7 deg/h per hour)
    return c;
  }
  if (name == "tactical") {
    BatteryCase c = base_case(name, kTactical, size, seed, 1);
    c.description = "tactical (RLG-like), angle counter Q on the gyros, ramp on accel_x";
    for (std::size_t ch = 0; ch < 3; ++ch) {
      // Angle counter with dither stripping: Q = Δ/√12 exactly (docs/validation.md).
      const double q = 2.0 * kMicroradian * kAxisScale[ch];
      c.spec.channels[ch].angle_step = q * std::sqrt(12.0);
      c.spec.channels[ch].angle_dither = true;
      c.truth[ch].quantization = q;
    }
    c.truth[3].ramp = c.spec.channels[3].ramp = 4e-8;  // m/s³ (15 µg per hour)
    return c;
  }
  BatteryCase c = base_case(name, kPhenomenonBase, size, seed, 4);
  const double tau0 = 1.0 / c.spec.rate_hz;
  const double length = record_length_s(c);
  if (name == "gm") {
    c.description = "Gauss-Markov dominated (N + first-order GM, no B, no K)";
    // T_c as fractions of T (30 s, 300 s, 10 s + 500 s, 60 s, 10 s, 150 s at 2 h); σ puts the
    // GM's ADEV peak 0.6174σ at 4× the N line at τ* = 1.8926·T_c: σ = 4.71·N/√T_c.
    const std::array<std::vector<double>, 6> tcs = {std::vector<double>{length / 240.0},
                                                    {length / 24.0},
                                                    {length / 720.0, length / 14.4},
                                                    {length / 120.0},
                                                    {length / 720.0},
                                                    {length / 48.0}};
    for (std::size_t ch = 0; ch < 6; ++ch) {
      ChannelSpec& cs = c.spec.channels[ch];
      ChannelTruth& t = c.truth[ch];
      cs.flicker = t.bias_instability = 0.0;
      cs.random_walk = t.random_walk = 0.0;
      for (double tc : tcs[ch]) {
        const GaussMarkovSpec gm{4.71 * t.white_noise / std::sqrt(tc), tc};
        cs.gauss_markov.push_back(gm);
        t.gauss_markov.push_back(gm);
      }
    }
    return c;
  }
  if (name == "lines") {
    c.description = "spectral lines 0.02-20 Hz (SNR 10-100 in a T/16 Welch bin)";
    NormalStream phases(stream_seed(c.spec.seed, 0, StreamTerm::sinusoid_phase, 0));
    for (const LinePlan& l : kLines) {
      ChannelTruth& t = c.truth[static_cast<std::size_t>(l.channel)];
      const double continuum = truth_psd(t, l.frequency_hz, tau0);
      const double amplitude = std::sqrt(2.0 * l.snr * continuum * 16.0 / length);
      const double phase = 2.0 * kPi * phases.uniform();
      t.lines.push_back({amplitude, l.frequency_hz, phase, l.snr});
      c.spec.channels[static_cast<std::size_t>(l.channel)].sinusoids.push_back(
          {amplitude, l.frequency_hz, phase});
    }
    add_phenomenon(c, Phenomenon::lines);
    return c;
  }
  if (name == "lowpass") {
    c.description = "2nd-order Butterworth low-pass at fs/4 (N unchanged)";
    c.spec.low_pass_hz = c.spec.rate_hz / 4.0;
    add_phenomenon(c, Phenomenon::low_pass);
    return c;
  }
  if (name == "lsb7" || name == "lsb1") {
    const double fraction = name == "lsb7" ? 1.0 / 7.0 : 1.0;
    c.description = name == "lsb7" ? "output LSB = sigma/7" : "output LSB = 1 sigma";
    for (std::size_t ch = 0; ch < 6; ++ch) {
      ChannelTruth& t = c.truth[ch];
      const double lsb = fraction * per_sample_sigma(t, tau0);
      c.spec.channels[ch].lsb = lsb;
      // Rounding error: white, variance Δ²/12 per sample → N² += Δ²τ0/12.
      t.white_noise = std::sqrt(t.white_noise * t.white_noise + lsb * lsb * tau0 / 12.0);
      t.white_noise_as_recorded = t.white_noise;
    }
    add_phenomenon(c, Phenomenon::lsb);
    return c;
  }
  if (name == "warmup") {
    c.description = "exponential warm-up a*exp(-t/(T/8)), a = 6-12 B";
    add_warmup(c);
    return c;
  }
  if (name == "outliers") {
    c.description = "5 % outliers of +-8 sigma";
    for (std::size_t ch = 0; ch < 6; ++ch) {
      ChannelTruth& t = c.truth[ch];
      const double p = 0.05, k = 8.0;
      c.spec.channels[ch].outlier_fraction = p;
      c.spec.channels[ch].outlier_size = k * per_sample_sigma(t, tau0);
      t.white_noise_as_recorded = t.white_noise * std::sqrt(1.0 + p * k * k);
    }
    add_phenomenon(c, Phenomenon::outliers);
    return c;
  }
  if (name == "decimated") {
    c.description = "generated at 4x the rate, every 4th sample kept (N x2)";
    c.spec.decimation = 4;
    for (ChannelTruth& t : c.truth) {
      // Point samples of white noise at d·f_s kept every d-th: N² → d·N²; the aliased
      // flicker adds ~B²·ln(d)/(π f_s), below 1e-4 of N² here (docs/validation.md).
      t.white_noise *= 2.0;
      t.white_noise_as_recorded = t.white_noise;
    }
    add_phenomenon(c, Phenomenon::decimation);
    return c;
  }
  if (name == "stamps") {
    c.description = "true 98.6 Hz, stamps rounded to 1 ms (0.010/0.011 s intervals)";
    c.spec.rate_hz = 98.6;
    c.spec.samples = static_cast<std::size_t>(std::llround(98.6 * length));
    c.spec.stamp_resolution_s = 1e-3;
    c.write_stamps = true;
    add_phenomenon(c, Phenomenon::stamps);
    return c;
  }
  if (name == "temperature") {
    c.description = "warm-up as 'warmup' with a temperature column 25 -> 33 degC";
    add_warmup(c);
    c.spec.temperature = {true, 25.0, 8.0, length / 8.0, 0.02, 1.0 / 256.0};
    for (std::size_t ch = 0; ch < 6; ++ch) {
      // a·e^{−t/τ} = c·(T − T_∞) with T − T_∞ = −ΔT·e^{−t/τ}: c = −a/ΔT.
      c.truth[ch].temperature_coefficient = -c.spec.channels[ch].warmup_amplitude / 8.0;
    }
    add_phenomenon(c, Phenomenon::temperature);
    return c;
  }
  throw std::invalid_argument("unknown battery class '" + name + "'");
}

double truth_avar(const ChannelTruth& t, double tau) {
  double v = 3.0 * t.quantization * t.quantization / (tau * tau) +
             t.white_noise * t.white_noise / tau +
             2.0 * std::numbers::ln2 / kPi * t.bias_instability * t.bias_instability +
             t.random_walk * t.random_walk * tau / 3.0 + t.ramp * t.ramp * tau * tau / 2.0;
  for (const GaussMarkovSpec& g : t.gauss_markov) {
    const double tc = g.tau_c_s;
    v += g.sigma * g.sigma * tc / (tau * tau) *
         (2.0 * tau - tc * (3.0 - 4.0 * std::exp(-tau / tc) + std::exp(-2.0 * tau / tc)));
  }
  for (const TruthLine& l : t.lines) {
    const double x = kPi * l.frequency_hz * tau;
    v += l.amplitude * l.amplitude * std::pow(std::sin(x), 4) / (x * x);
  }
  return v;
}

double random_walk_share(const ChannelTruth& t, double tau) {
  return t.random_walk * t.random_walk * tau / 3.0 / truth_avar(t, tau);
}

double truth_psd(const ChannelTruth& t, double f, double tau0) {
  const double w = 2.0 * kPi * f;
  double s = 2.0 * w * w * tau0 * t.quantization * t.quantization +
             2.0 * t.white_noise * t.white_noise +
             t.bias_instability * t.bias_instability / (kPi * f) +
             t.random_walk * t.random_walk / (2.0 * kPi * kPi * f * f) +
             2.0 * t.ramp * t.ramp / (w * w * w);
  for (const GaussMarkovSpec& g : t.gauss_markov) {
    s += 4.0 * g.sigma * g.sigma * g.tau_c_s / (1.0 + w * w * g.tau_c_s * g.tau_c_s);
  }
  return s;
}

}  // namespace imunoise::battery
