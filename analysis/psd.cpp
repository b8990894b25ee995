/// @file
/// @brief Welch PSD, window helpers and log binning (see psd.h; theory.md §5.1–5.2).
#include "analysis/psd.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <utility>

#include "analysis/psd_internal.h"
#include "common/errors.h"
#include "common/fftw_planner_lock.h"

namespace imunoise::analysis {
namespace {

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};

/// A number for an error message, %g style (std::to_string prints 1e-9 as 0.000000).
std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

/// Mean square of the whole record about its trend of MODE (two passes, no copy).
double detrended_mean_square(std::span<const double> x, Detrend mode) {
  const detail::Trend trend = detail::fit_trend(x, mode);
  double sum = 0.0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    const double r = x[n] - trend.at(n);
    sum += r * r;
  }
  return sum / static_cast<double>(x.size());
}

}  // namespace

namespace detail {

bool is_real_bin(std::size_t j, std::size_t length) {
  return j == 0 || (length % 2 == 0 && j == length / 2);
}

/// The double sum is done in O(b − a) by grouping pairs by j − k and by j + k, with the
/// weights written c_j = 2 − e_j (e_j = 1 at the real DC / Nyquist bins).
double averaged_dof(const PowerCovariance& cov, std::size_t segments, std::size_t a,
                    std::size_t b) {
  const std::size_t m = b - a + 1;
  double all_pairs = 0.0;  // Σ_{j,k} cov(j, k)
  for (std::size_t d = 0; d < m; ++d) {
    all_pairs += (d == 0 ? 1.0 : 2.0) * static_cast<double>(m - d) * cov.at(d);
  }
  for (std::size_t s = 2 * a; s <= 2 * b; ++s) {
    const std::size_t centre = a + b;
    const std::size_t off = s > centre ? s - centre : centre - s;
    all_pairs += static_cast<double>(m - off) * cov.at(s);
  }
  std::size_t edges[2] = {0, 0};
  std::size_t n_edges = 0;
  for (std::size_t j : {a, b}) {
    if (is_real_bin(j, cov.length) && (n_edges == 0 || edges[0] != j)) edges[n_edges++] = j;
  }
  double weighted = 4.0 * all_pairs;
  for (std::size_t e = 0; e < n_edges; ++e) weighted -= 4.0 * cov.row(edges[e], a, b);
  for (std::size_t e = 0; e < n_edges; ++e) {
    for (std::size_t f = 0; f < n_edges; ++f) weighted += cov.pair(edges[e], edges[f]);
  }
  const double weight_sum = 2.0 * static_cast<double>(m) - static_cast<double>(n_edges);
  return 2.0 * static_cast<double>(segments) * weight_sum * weight_sum / weighted;
}

void check_options(const WelchOptions& options) {
  IMUNOISE_EXPECT(std::isfinite(options.overlap) && options.overlap >= 0.0 && options.overlap < 1.0,
                  "welch: overlap must be in [0, 1) (got " + text(options.overlap) + ")");
  switch (options.window) {
    case Window::hann:
    case Window::hamming:
    case Window::blackman_harris:
    case Window::rectangular:
      break;
    default:
      throw ContractViolation("welch: unknown window");
  }
  switch (options.detrend) {
    case Detrend::none:
    case Detrend::constant:
    case Detrend::linear:
      break;
    default:
      throw ContractViolation("welch: unknown detrend mode");
  }
}

double lane_sum(const double* x, std::size_t n) {
  constexpr std::size_t kLanes = 8;
  double lane[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    for (std::size_t l = 0; l < kLanes; ++l) lane[l] += x[i + l];
  }
  for (; i < n; ++i) lane[i % kLanes] += x[i];
  for (std::size_t width = kLanes / 2; width >= 1; width /= 2) {
    for (std::size_t l = 0; l < width; ++l) lane[l] += lane[l + width];
  }
  return lane[0];
}

Trend fit_trend(std::span<const double> x, Detrend mode) {
  Trend t;
  if (mode == Detrend::none || x.empty()) return t;
  const double count = static_cast<double>(x.size());
  t.mean = lane_sum(x.data(), x.size()) / count;
  t.centre = 0.5 * (count - 1.0);
  if (mode == Detrend::linear && x.size() > 1) {
    double sxt = 0.0;
    for (std::size_t n = 0; n < x.size(); ++n) {
      sxt += (static_cast<double>(n) - t.centre) * (x[n] - t.mean);
    }
    t.slope = sxt / (count * (count * count - 1.0) / 12.0);
  }
  return t;
}

struct SegmentTransform::Impl {
  std::size_t length = 0;  // L
  std::size_t step = 0;    // segment advance
  std::size_t bins = 0;    // ⌊L/2⌋ + 1
  Detrend detrend = Detrend::constant;
  std::vector<double> window;
  double window_energy = 0.0;  // Σ w²
  std::unique_ptr<double[], FftwFree> in;
  std::unique_ptr<fftw_complex[], FftwFree> out;
  fftw_plan plan = nullptr;
  bool from_wisdom = false;  // plan rebuilt from imported wisdom (FFTW_MEASURE or better)

  ~Impl() {
    // FFTW guarantees thread safety for fftw_execute only, so buffers are freed under the
    // planner mutex too.
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    if (plan != nullptr) fftw_destroy_plan(plan);
    in.reset();
    out.reset();
  }
};

SegmentTransform::SegmentTransform(std::size_t length, const WelchOptions& options)
    : impl_(std::make_unique<Impl>()) {
  check_options(options);
  IMUNOISE_EXPECT(
      length >= 2 && length <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
      "welch: segment_length must be >= 2 and fit an int (got " + std::to_string(length) + ")");
  Impl& s = *impl_;
  s.length = length;
  s.detrend = options.detrend;
  const auto shared =
      static_cast<std::size_t>(std::floor(options.overlap * static_cast<double>(s.length)));
  s.step = s.length - std::min(shared, s.length - 1);
  s.bins = s.length / 2 + 1;
  s.window = window_coefficients(options.window, s.length);
  for (double v : s.window) s.window_energy += v * v;
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    s.in.reset(static_cast<double*>(fftw_malloc(sizeof(double) * s.length)));
    s.out.reset(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * s.bins)));
    if (s.in && s.out) {
      // Wisdom first: a plan of at least FFTW_MEASURE rigour rebuilt from imported wisdom
      // (never a measurement here: WISDOM_ONLY returns null instead); else the heuristic plan.
      const int n = static_cast<int>(s.length);
      s.plan = fftw_plan_dft_r2c_1d(n, s.in.get(), s.out.get(), FFTW_MEASURE | FFTW_WISDOM_ONLY);
      s.from_wisdom = s.plan != nullptr;
      if (s.plan == nullptr) {
        s.plan = fftw_plan_dft_r2c_1d(n, s.in.get(), s.out.get(), FFTW_ESTIMATE);
      }
    }
  }
  if (!s.in || !s.out) throw AnalysisError("welch: out of memory for FFT buffers");
  if (s.plan == nullptr) throw AnalysisError("welch: FFTW could not plan the transform");
}

SegmentTransform::~SegmentTransform() = default;
SegmentTransform::SegmentTransform(SegmentTransform&&) noexcept = default;
SegmentTransform& SegmentTransform::operator=(SegmentTransform&&) noexcept = default;

std::size_t SegmentTransform::length() const { return impl_->length; }
std::size_t SegmentTransform::step() const { return impl_->step; }
std::size_t SegmentTransform::bins() const { return impl_->bins; }
double SegmentTransform::window_energy() const { return impl_->window_energy; }
bool SegmentTransform::from_wisdom() const { return impl_->from_wisdom; }
Detrend SegmentTransform::detrend() const { return impl_->detrend; }

void SegmentTransform::add_segment(const double* segment, double* power) {
  Impl& s = *impl_;
  // Trend and taper straight from the record, with no copy of the segment first: at
  // L = 2^23 a segment is 64 MiB, out of cache, and the copy was one more pass over memory.
  const Trend trend = fit_trend(std::span<const double>(segment, s.length), s.detrend);
  double* __restrict buffer = s.in.get();
  const double* __restrict window = s.window.data();
  if (trend.slope == 0.0) {
    // No detrend or the mean only: the same numbers as the line below (trend.at(n) is the
    // mean exactly), in a loop the compiler vectorises.
    const double mean = trend.mean;
    for (std::size_t n = 0; n < s.length; ++n) buffer[n] = (segment[n] - mean) * window[n];
  } else {
    for (std::size_t n = 0; n < s.length; ++n) {
      buffer[n] = (segment[n] - trend.at(n)) * window[n];
    }
  }
  fftw_execute(s.plan);
  const double* __restrict spectrum = s.out[0];  // re, im interleaved
  double* __restrict sum = power;
  for (std::size_t j = 0; j < s.bins; ++j) {
    sum[j] += spectrum[2 * j] * spectrum[2 * j] + spectrum[2 * j + 1] * spectrum[2 * j + 1];
  }
}

std::vector<double> SegmentTransform::power_covariance(std::size_t segments) {
  Impl& s = *impl_;
  // For white input of variance σ², the DFTs of two segments d samples apart have, at bins
  // Δ apart, covariance σ²·C(Δ, d) with C(Δ, d) = Σ_n w_n w_{n+d} e^{−2πiΔn/L}. Hence
  // g(Δ) = Σ_{k,k'} |C(Δ, (k'−k)·step)|² / (K (Σw²)²), lag l occurring 2(K − l) times (once
  // for l = 0); g(0) is Welch's K/K_eff. Only lags l·step < L overlap: at 50 % overlap that
  // is two FFTs, and never more than K, so this costs at most as much as the estimate.
  std::vector<double> g(s.bins, 0.0);
  double* buffer = s.in.get();
  const double k_count = static_cast<double>(segments);
  const double norm = 1.0 / (s.window_energy * s.window_energy);
  for (std::size_t l = 0; l < segments && l * s.step < s.length; ++l) {
    const std::size_t d = l * s.step;
    for (std::size_t n = 0; n < s.length; ++n) {
      buffer[n] = n + d < s.length ? s.window[n] * s.window[n + d] : 0.0;
    }
    fftw_execute(s.plan);
    const double weight = (l == 0 ? 1.0 : 2.0 * (1.0 - static_cast<double>(l) / k_count)) * norm;
    for (std::size_t j = 0; j < s.bins; ++j) {
      g[j] += weight * (s.out[j][0] * s.out[j][0] + s.out[j][1] * s.out[j][1]);
    }
  }
  return g;
}

}  // namespace detail

std::vector<double> window_coefficients(Window window, std::size_t length) {
  IMUNOISE_EXPECT(length >= 2,
                  "window_coefficients: length must be >= 2 (got " + std::to_string(length) + ")");
  std::vector<double> w(length);
  const double step = 2.0 * std::numbers::pi / static_cast<double>(length);
  for (std::size_t n = 0; n < length; ++n) {
    const double a = step * static_cast<double>(n);
    switch (window) {
      case Window::hann:
        w[n] = 0.5 - 0.5 * std::cos(a);
        break;
      case Window::hamming:
        w[n] = 0.54 - 0.46 * std::cos(a);
        break;
      case Window::blackman_harris:  // Harris 1978, Proc. IEEE 66(1), 4-term −92 dB
        w[n] = 0.35875 - 0.48829 * std::cos(a) + 0.14128 * std::cos(2.0 * a) -
               0.01168 * std::cos(3.0 * a);
        break;
      case Window::rectangular:
        w[n] = 1.0;
        break;
      default:
        throw ContractViolation("window_coefficients: unknown window");
    }
  }
  return w;
}

double window_overlap_correlation(std::span<const double> window, std::size_t shift) {
  double energy = 0.0;
  for (double v : window) energy += v * v;
  IMUNOISE_EXPECT(energy > 0.0, "window_overlap_correlation: window is all zero");
  if (shift >= window.size()) return 0.0;
  double lagged = 0.0;
  for (std::size_t n = 0; n + shift < window.size(); ++n) lagged += window[n] * window[n + shift];
  return (lagged * lagged) / (energy * energy);
}

double effective_segments(std::span<const double> window, std::size_t segments, std::size_t step) {
  IMUNOISE_EXPECT(segments > 0 && step > 0,
                  "effective_segments: segments and step must be > 0 (got " +
                      std::to_string(segments) + ", " + std::to_string(step) + ")");
  const double k = static_cast<double>(segments);
  double sum = 0.0;
  for (std::size_t l = 1; l < segments && l * step < window.size(); ++l) {
    sum += (1.0 - static_cast<double>(l) / k) * window_overlap_correlation(window, l * step);
  }
  return k / (1.0 + 2.0 * sum);
}

struct WelchEstimator::Impl {
  detail::SegmentTransform transform;
  std::vector<double> power;  // Σ over segments of |X_j|²
};

WelchEstimator::WelchEstimator(std::size_t segment_length, const WelchOptions& options) {
  detail::SegmentTransform transform(segment_length, options);  // checks options and L
  IMUNOISE_EXPECT(options.segment_length == 0 || options.segment_length == segment_length,
                  "welch: options.segment_length (" + std::to_string(options.segment_length) +
                      ") differs from the estimator's segment_length (" +
                      std::to_string(segment_length) + ")");
  std::vector<double> power(transform.bins(), 0.0);
  impl_ = std::make_unique<Impl>(Impl{std::move(transform), std::move(power)});
}

WelchEstimator::~WelchEstimator() = default;
WelchEstimator::WelchEstimator(WelchEstimator&&) noexcept = default;
WelchEstimator& WelchEstimator::operator=(WelchEstimator&&) noexcept = default;

std::size_t WelchEstimator::segment_length() const { return impl_->transform.length(); }

bool WelchEstimator::planned_from_wisdom() const { return impl_->transform.from_wisdom(); }

std::size_t automatic_segment_length(std::size_t samples) {
  IMUNOISE_EXPECT(samples >= 16,
                  "welch: record of " + std::to_string(samples) +
                      " samples is too short (automatic segment length needs >= 16)");
  std::size_t length = 16;
  while (length * 2 <= samples / 8) length *= 2;
  return length;
}

Spectrum WelchEstimator::estimate(std::span<const double> x, double sample_rate_hz) {
  detail::SegmentTransform& t = impl_->transform;
  const std::size_t length = t.length(), step = t.step(), bins = t.bins();
  IMUNOISE_EXPECT(
      std::isfinite(sample_rate_hz) && sample_rate_hz > 0.0,
      "welch: sample rate must be finite and > 0 (got " + text(sample_rate_hz) + " Hz)");
  IMUNOISE_EXPECT(x.size() >= length, "welch: record of " + std::to_string(x.size()) +
                                          " samples is shorter than one segment of " +
                                          std::to_string(length));
  for (std::size_t n = 0; n < x.size(); ++n) {
    if (!std::isfinite(x[n])) {
      throw ContractViolation("welch: sample " + std::to_string(n) + " is not finite (" +
                              text(x[n]) + ")");
    }
  }

  const std::size_t segments = (x.size() - length) / step + 1;
  std::vector<double>& power = impl_->power;
  std::fill(power.begin(), power.end(), 0.0);
  for (std::size_t k = 0; k < segments; ++k) t.add_segment(x.data() + k * step, power.data());

  Spectrum result;
  result.segments = segments;
  result.segment_length = length;
  result.sample_rate_hz = sample_rate_hz;
  result.fft_plan_from_wisdom = t.from_wisdom();
  result.resolution_hz = sample_rate_hz / static_cast<double>(length);
  result.frequency_hz.resize(bins);
  result.density.resize(bins);
  result.dof.resize(bins);
  // theory.md §5.1: P(f_j) = c_j |Σ w_n x_n e^{−2πijn/L}|² / (f_s Σ w_n²), averaged over K.
  const double scale = 1.0 / (sample_rate_hz * t.window_energy() * static_cast<double>(segments));
  for (std::size_t j = 0; j < bins; ++j) {
    result.frequency_hz[j] = static_cast<double>(j) * result.resolution_hz;
    result.density[j] = (detail::is_real_bin(j, length) ? 1.0 : 2.0) * scale * power[j];
    result.integrated_power += result.density[j] * result.resolution_hz;
  }
  result.power_covariance = t.power_covariance(segments);
  const detail::PowerCovariance cov{result.power_covariance, length};
  for (std::size_t j = 0; j < bins; ++j) result.dof[j] = detail::averaged_dof(cov, segments, j, j);

  result.sample_variance = detrended_mean_square(x, t.detrend());
  return result;
}

Spectrum welch_psd(std::span<const double> x, double sample_rate_hz, const WelchOptions& options) {
  std::size_t length = options.segment_length;
  if (length == 0) {
    IMUNOISE_EXPECT(x.size() >= 16,
                    "welch: record of " + std::to_string(x.size()) +
                        " samples is too short (automatic segment length needs >= 16)");
    length = automatic_segment_length(x.size());
  }
  WelchOptions resolved = options;
  resolved.segment_length = length;
  WelchEstimator estimator(length, resolved);
  return estimator.estimate(x, sample_rate_hz);
}

Spectrum pooled_welch_psd(std::span<const std::span<const double>> pieces, double sample_rate_hz,
                          const WelchOptions& options, std::size_t* pieces_used) {
  std::size_t longest = 0;
  for (const auto& p : pieces) longest = std::max(longest, p.size());
  std::size_t length = options.segment_length;
  if (length == 0) {
    // The automatic length of welch_psd for the longest piece.
    IMUNOISE_EXPECT(longest >= 16,
                    "welch: the longest piece has " + std::to_string(longest) +
                        " samples, too short (automatic segment length needs >= 16)");
    length = automatic_segment_length(longest);
  }
  WelchOptions resolved = options;
  resolved.segment_length = length;
  WelchEstimator estimator(length, resolved);
  std::vector<Spectrum> parts;
  std::size_t total_samples = 0;
  for (const auto& p : pieces) {
    if (p.size() < length) continue;
    parts.push_back(estimator.estimate(p, sample_rate_hz));
    total_samples += p.size();
  }
  if (pieces_used != nullptr) *pieces_used = parts.size();
  IMUNOISE_EXPECT(!parts.empty(), "welch: no piece is as long as one segment of " +
                                      std::to_string(length) + " samples");
  if (parts.size() == 1) return std::move(parts.front());

  Spectrum out;
  out.segment_length = length;
  out.sample_rate_hz = sample_rate_hz;
  out.fft_plan_from_wisdom = parts.front().fft_plan_from_wisdom;  // one estimator for all
  out.resolution_hz = parts.front().resolution_hz;
  out.frequency_hz = parts.front().frequency_hz;
  const std::size_t bins = out.frequency_hz.size();
  out.density.assign(bins, 0.0);
  out.power_covariance.assign(bins, 0.0);
  std::vector<double> inverse_dof(bins, 0.0);  // Σ_k K_k²/ν_k
  for (const Spectrum& s : parts) {
    const double k = static_cast<double>(s.segments);
    out.segments += s.segments;
    for (std::size_t j = 0; j < bins; ++j) {
      out.density[j] += k * s.density[j];
      out.power_covariance[j] += k * s.power_covariance[j];
      inverse_dof[j] += k * k / s.dof[j];
    }
  }
  const double k_total = static_cast<double>(out.segments);
  out.dof.resize(bins);
  for (std::size_t j = 0; j < bins; ++j) {
    out.density[j] /= k_total;
    out.power_covariance[j] /= k_total;
    out.dof[j] = k_total * k_total / inverse_dof[j];
    out.integrated_power += out.density[j] * out.resolution_hz;
  }
  // Mean square over all samples of the pieces used, each piece detrended on its own.
  std::size_t part = 0;
  for (const auto& p : pieces) {
    if (p.size() < length) continue;
    out.sample_variance += static_cast<double>(p.size()) * parts[part++].sample_variance;
  }
  out.sample_variance /= static_cast<double>(total_samples);
  return out;
}

Spectrum log_bin(const Spectrum& raw, int bins_per_decade) {
  IMUNOISE_EXPECT(bins_per_decade >= 1, "log_bin: bins_per_decade must be >= 1 (got " +
                                            std::to_string(bins_per_decade) + ")");
  IMUNOISE_EXPECT(
      raw.frequency_hz.size() == raw.density.size() && raw.frequency_hz.size() == raw.dof.size(),
      "log_bin: frequency, density and dof sizes differ (" +
          std::to_string(raw.frequency_hz.size()) + ", " + std::to_string(raw.density.size()) +
          ", " + std::to_string(raw.dof.size()) + ")");
  IMUNOISE_EXPECT(raw.raw_bins.empty(), "log_bin: the spectrum is already binned");
  // The covariance model indexes raw bins by j = f/Δf: only for a complete Welch spectrum.
  const bool correlated = !raw.power_covariance.empty() && raw.segments > 0 &&
                          raw.power_covariance.size() == raw.segment_length / 2 + 1 &&
                          raw.frequency_hz.size() == raw.power_covariance.size();
  const detail::PowerCovariance cov{raw.power_covariance, raw.segment_length};

  Spectrum out;
  out.resolution_hz = raw.resolution_hz;
  out.segments = raw.segments;
  out.segment_length = raw.segment_length;
  out.sample_rate_hz = raw.sample_rate_hz;
  out.fft_plan_from_wisdom = raw.fft_plan_from_wisdom;
  out.sample_variance = raw.sample_variance;
  out.integrated_power = raw.integrated_power;

  const double b = static_cast<double>(bins_per_decade);
  // The small offset keeps exact edges (f = 1 Hz, 10 Hz, …) in the bin they open despite
  // rounding in log10.
  const auto bin_of = [b](double f) { return std::floor(b * std::log10(f) + 1e-9); };
  std::size_t j = 0;
  const std::size_t n = raw.frequency_hz.size();
  while (j < n && !(raw.frequency_hz[j] > 0.0)) ++j;  // drop DC (and anything ≤ 0)
  for (std::size_t k = j; k < n; ++k) {
    const double f = raw.frequency_hz[k];
    IMUNOISE_EXPECT(std::isfinite(f) && (k == j || f > raw.frequency_hz[k - 1]),
                    "log_bin: frequencies must be finite and increasing (bin " + std::to_string(k) +
                        ": " + text(f) + " Hz)");
  }
  while (j < n) {
    const double key = bin_of(raw.frequency_hz[j]);
    std::size_t end = j;
    double power = 0.0, log_f = 0.0, dof_sum = 0.0;
    while (end < n && bin_of(raw.frequency_hz[end]) == key) {
      power += raw.density[end];
      log_f += std::log(raw.frequency_hz[end]);
      dof_sum += raw.dof[end];
      ++end;
    }
    const std::size_t count = end - j;
    out.frequency_hz.push_back(count == 1 ? raw.frequency_hz[j]
                                          : std::exp(log_f / static_cast<double>(count)));
    out.density.push_back(power / static_cast<double>(count));
    out.dof.push_back(correlated ? detail::averaged_dof(cov, raw.segments, j, end - 1) : dof_sum);
    out.first_raw_bin.push_back(j);
    out.raw_bins.push_back(count);
    j = end;
  }
  return out;
}

}  // namespace imunoise::analysis
