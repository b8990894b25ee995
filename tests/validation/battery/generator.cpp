#include "battery/generator.h"

#include <fftw3.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>

namespace imunoise::battery {

namespace {

constexpr double kPi = std::numbers::pi;

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// FFTW's planner is not thread-safe; execution of distinct plans is.
std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("battery generator: " + what);
}

void check_spec(const RecordingSpec& spec) {
  require(spec.rate_hz > 0.0 && std::isfinite(spec.rate_hz), "rate_hz must be > 0");
  require(spec.samples >= 2, "samples must be >= 2");
  require(spec.decimation >= 1, "decimation must be >= 1");
  require(spec.flicker_span >= 1.0, "flicker_span must be >= 1");
  const double internal_rate = spec.rate_hz * spec.decimation;
  require(spec.low_pass_hz >= 0.0 && spec.low_pass_hz < internal_rate / 2.0,
          "low_pass_hz must be in [0, internal Nyquist)");
  for (const ChannelSpec& c : spec.channels) {
    require(c.warmup_amplitude == 0.0 || c.warmup_tau_s > 0.0, "warm-up needs tau > 0");
    for (const GaussMarkovSpec& g : c.gauss_markov) require(g.tau_c_s > 0.0, "GM needs T_c > 0");
    require(c.outlier_fraction >= 0.0 && c.outlier_fraction <= 1.0, "outlier fraction in [0,1]");
    require(c.white >= 0 && c.flicker >= 0 && c.random_walk >= 0 && c.angle_step >= 0 && c.lsb >= 0,
            "coefficients must be >= 0");
  }
}

}  // namespace

std::uint64_t stream_seed(std::uint64_t seed, int channel, StreamTerm term, int index) {
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ static_cast<std::uint64_t>(channel + 1));
  h = splitmix64(h ^ (static_cast<std::uint64_t>(term) << 8));
  return splitmix64(h ^ (static_cast<std::uint64_t>(index) << 16));
}

double NormalStream::uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

double NormalStream::next() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  spare_ = r * std::sin(2.0 * kPi * u2);
  has_spare_ = true;
  return r * std::cos(2.0 * kPi * u2);
}

std::size_t fft_friendly_size(std::size_t n) {
  std::size_t best = std::numeric_limits<std::size_t>::max();
  for (std::size_t p2 = 1; p2 < best; p2 *= 2) {
    for (std::size_t p3 = p2; p3 < best; p3 *= 3) {
      std::size_t p5 = p3;
      while (p5 < n) p5 *= 5;
      best = std::min(best, p5);
      if (p3 >= n) break;
    }
    if (p2 >= n) break;
  }
  return best;
}

std::size_t burn_in_samples(const RecordingSpec& spec) {
  if (spec.low_pass_hz <= 0.0) return 0;
  // The Butterworth poles decay with time constant √2/(2π f_c) ≈ 0.23/f_c: 50/f_c is over
  // 200 time constants, so the start-up is below double precision.
  return static_cast<std::size_t>(
      std::ceil(50.0 * spec.rate_hz * spec.decimation / spec.low_pass_hz));
}

std::size_t flicker_fft_length(const RecordingSpec& spec) {
  const std::size_t internal = burn_in_samples(spec) + spec.samples * spec.decimation;
  const auto half =
      static_cast<std::size_t>(std::ceil(spec.flicker_span * static_cast<double>(internal) / 2.0));
  return 2 * fft_friendly_size(half);  // even, so bin L/2 is the Nyquist bin
}

std::vector<double> flicker_samples(double b, std::size_t count, std::size_t length,
                                    std::uint64_t seed) {
  require(length % 2 == 0 && length >= count, "flicker FFT length must be even and >= count");
  const std::size_t bins = length / 2 + 1;
  auto* spectrum = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins));
  auto* series = static_cast<double*>(fftw_malloc(sizeof(double) * length));
  require(spectrum != nullptr && series != nullptr, "out of memory for the flicker FFT");
  fftw_plan plan = nullptr;
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    plan = fftw_plan_dft_c2r_1d(static_cast<int>(length), spectrum, series, FFTW_ESTIMATE);
  }
  // FFTW's c2r gives x_k = Σ_j Y_j e^{+2πijk/L} over the Hermitian spectrum, i.e.
  // Y_0 + 2 Σ_{0<j<L/2} Re(Y_j e^{2πijk/L}) + Y_{L/2}(−1)^k. With Y_j = (c_j/2)(a_j − i b_j)
  // each bin contributes c_j (a_j cos + b_j sin): a random-phase cosine of variance c_j².
  NormalStream normal(seed);
  spectrum[0][0] = spectrum[0][1] = 0.0;
  for (std::size_t j = 1; j < length / 2; ++j) {
    const double c = b / std::sqrt(kPi * static_cast<double>(j));
    const double a_j = normal.next();
    const double b_j = normal.next();
    spectrum[j][0] = 0.5 * c * a_j;
    spectrum[j][1] = -0.5 * c * b_j;
  }
  spectrum[length / 2][0] = spectrum[length / 2][1] = 0.0;
  fftw_execute(plan);
  std::vector<double> out(series, series + count);
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_destroy_plan(plan);
  }
  fftw_free(series);
  fftw_free(spectrum);
  return out;
}

std::array<double, 5> butterworth2(double corner_hz, double rate_hz) {
  // Analog prototype 1/(s² + √2 s + 1) at ω_c, bilinear s = (2/T)(z−1)/(z+1) with the
  // corner pre-warped: K = tan(π f_c / f_s).
  const double k = std::tan(kPi * corner_hz / rate_hz);
  const double norm = 1.0 / (1.0 + std::numbers::sqrt2 * k + k * k);
  const double b0 = k * k * norm;
  return {b0, 2.0 * b0, b0, 2.0 * (k * k - 1.0) * norm,
          (1.0 - std::numbers::sqrt2 * k + k * k) * norm};
}

void low_pass_in_place(std::span<double> x, const std::array<double, 5>& c) {
  if (x.empty()) return;
  // Direct form I; a constant input x[0] since forever is the steady state y = x[0].
  double x1 = x[0], x2 = x[0], y1 = x[0], y2 = x[0];
  for (double& v : x) {
    const double y = c[0] * v + c[1] * x1 + c[2] * x2 - c[3] * y1 - c[4] * y2;
    x2 = x1;
    x1 = v;
    y2 = y1;
    y1 = y;
    v = y;
  }
}

std::vector<double> generate_channel(const RecordingSpec& spec, int channel) {
  check_spec(spec);
  const ChannelSpec& c = spec.channels.at(static_cast<std::size_t>(channel));
  const std::size_t d = static_cast<std::size_t>(spec.decimation);
  const std::size_t burn = burn_in_samples(spec);
  const std::size_t n_int = burn + spec.samples * d;
  const double tau0 = 1.0 / spec.rate_hz;
  const double tau_i = tau0 / static_cast<double>(d);
  const auto time_of = [&](std::size_t k) {
    return (static_cast<double>(k) - static_cast<double>(burn)) * tau_i;
  };
  const auto seed_of = [&](StreamTerm term, int index) {
    return stream_seed(spec.seed, channel, term, index);
  };

  // 1. The rate terms at the internal rate.
  std::vector<double> x(n_int, c.constant);
  if (c.white > 0.0) {
    NormalStream g(seed_of(StreamTerm::white, 0));
    const double sd = c.white / std::sqrt(tau_i);  // σ_d = N/√τ (theory.md §1.4)
    for (double& v : x) v += sd * g.next();
  }
  if (c.flicker > 0.0) {
    const std::vector<double> f = flicker_samples(c.flicker, n_int, flicker_fft_length(spec),
                                                  seed_of(StreamTerm::flicker, 0));
    for (std::size_t k = 0; k < n_int; ++k) x[k] += f[k];
  }
  if (c.random_walk > 0.0) {
    NormalStream g(seed_of(StreamTerm::random_walk, 0));
    const double step = c.random_walk * std::sqrt(tau_i);  // σ_bd = K·√τ (theory.md §1.4)
    double level = 0.0;
    for (double& v : x) {
      level += step * g.next();
      v += level;
    }
  }
  if (c.ramp != 0.0) {
    for (std::size_t k = 0; k < n_int; ++k) x[k] += c.ramp * time_of(k);
  }
  for (std::size_t j = 0; j < c.gauss_markov.size(); ++j) {
    const GaussMarkovSpec& gm = c.gauss_markov[j];
    NormalStream g(seed_of(StreamTerm::gauss_markov, static_cast<int>(j)));
    const double phi = std::exp(-tau_i / gm.tau_c_s);
    const double innovation = gm.sigma * std::sqrt(1.0 - phi * phi);
    double state = gm.sigma * g.next();  // stationary start
    for (double& v : x) {
      v += state;
      state = phi * state + innovation * g.next();
    }
  }
  for (const SinusoidSpec& s : c.sinusoids) {
    for (std::size_t k = 0; k < n_int; ++k) {
      x[k] += s.amplitude * std::sin(2.0 * kPi * s.frequency_hz * time_of(k) + s.phase_rad);
    }
  }
  if (c.warmup_amplitude != 0.0) {
    for (std::size_t k = 0; k < n_int; ++k) {
      x[k] += c.warmup_amplitude * std::exp(-time_of(k) / c.warmup_tau_s);
    }
  }
  // 2. The sensor's low-pass at the internal rate.
  if (spec.low_pass_hz > 0.0) {
    low_pass_in_place(x, butterworth2(spec.low_pass_hz, spec.rate_hz * spec.decimation));
  }
  // 3. Decimation without averaging.
  std::vector<double> y(spec.samples);
  for (std::size_t j = 0; j < spec.samples; ++j) y[j] = x[burn + j * d];
  std::vector<double>().swap(x);
  // 4. The angle counter: reading_j = Δ·round((θ_j + D_j)/Δ) − D_j, θ_j = τ0·Σ_{i<j} y_i.
  if (c.angle_step > 0.0) {
    NormalStream u(seed_of(StreamTerm::angle_dither, 0));
    const long double step = c.angle_step;
    const auto reading = [&](long double theta) {
      const long double dither = c.angle_dither ? (u.uniform() - 0.5L) * step : 0.0L;
      return step * std::nearbyint((theta + dither) / step) - dither;
    };
    long double theta = 0.0L;
    long double previous = reading(theta);
    for (double& v : y) {
      theta += static_cast<long double>(v) * tau0;
      const long double now = reading(theta);
      v = static_cast<double>((now - previous) / tau0);
      previous = now;
    }
  }
  // 5. Outliers, 6. output rounding.
  if (c.outlier_fraction > 0.0 && c.outlier_size > 0.0) {
    NormalStream u(seed_of(StreamTerm::outlier, 0));
    for (double& v : y) {
      if (u.uniform() < c.outlier_fraction)
        v += u.uniform() < 0.5 ? -c.outlier_size : c.outlier_size;
    }
  }
  if (c.lsb > 0.0) {
    for (double& v : y) v = c.lsb * std::nearbyint(v / c.lsb);
  }
  return y;
}

GeneratedRecording generate(const RecordingSpec& spec) {
  check_spec(spec);
  GeneratedRecording out;
  out.sample_period_s = 1.0 / spec.rate_hz;
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto worker = [&] {
    for (int ch = next++; ch < 6; ch = next++) {
      try {
        out.channels[static_cast<std::size_t>(ch)] = generate_channel(spec, ch);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  std::thread helper(worker);
  worker();
  helper.join();
  if (error) std::rethrow_exception(error);

  out.time_s.resize(spec.samples);
  for (std::size_t k = 0; k < spec.samples; ++k) {
    const double t = static_cast<double>(k) * out.sample_period_s;
    out.time_s[k] = spec.stamp_resolution_s > 0.0
                        ? spec.stamp_resolution_s * std::nearbyint(t / spec.stamp_resolution_s)
                        : t;
  }
  if (spec.temperature.present) {
    const TemperatureSpec& ts = spec.temperature;
    NormalStream g(stream_seed(spec.seed, 6, StreamTerm::temperature, 0));
    out.temperature_degc.resize(spec.samples);
    for (std::size_t k = 0; k < spec.samples; ++k) {
      const double t = static_cast<double>(k) * out.sample_period_s;
      double v =
          ts.start_degc + ts.rise_degc * (1.0 - std::exp(-t / ts.tau_s)) + ts.noise_degc * g.next();
      if (ts.resolution_degc > 0.0) v = ts.resolution_degc * std::nearbyint(v / ts.resolution_degc);
      out.temperature_degc[k] = v;
    }
  }
  return out;
}

}  // namespace imunoise::battery
