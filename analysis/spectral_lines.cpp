#include "analysis/spectral_lines.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <mutex>
#include <numbers>
#include <tuple>

#include "analysis/chi_square.h"
#include "analysis/golden_section.h"
#include "common/errors.h"

namespace imunoise::analysis {

namespace {

constexpr double kPi = std::numbers::pi;

/// Pr(X/Ĉ > r) for X ~ χ²_ν/ν and Ĉ = exp(s·Z), Z standard normal (the continuum estimate's
/// relative scatter s, as a log-normal): ∫ sf(ν·r·e^{sz}; ν) φ(z) dz by the trapezoid rule
/// over |z| ≤ 6 (the integrand is smooth; 121 nodes are exact to ~1e-6 relative).
double exceedance(double r, double nu, double s) {
  if (s <= 0.0) return chi_square_sf(nu * r, nu);
  constexpr int kNodes = 121;
  constexpr double kZMax = 6.0;
  const double dz = 2.0 * kZMax / (kNodes - 1);
  double sum = 0.0;
  for (int i = 0; i < kNodes; ++i) {
    const double z = -kZMax + dz * i;
    const double w = (i == 0 || i == kNodes - 1 ? 0.5 : 1.0) * std::exp(-0.5 * z * z);
    sum += w * chi_square_sf(nu * r * std::exp(s * z), nu);
  }
  return sum * dz / std::sqrt(2.0 * kPi);
}

/// The threshold r with exceedance(r, ν, s) = P (bisection on ln r; exceedance falls with r),
/// to ~1e-9 relative. Memoised process-wide: every channel of a recording and every record of
/// one length asks for the same few (P, ν, s).
double threshold_ratio(double probability, double nu, double s) {
  static std::mutex mutex;
  static std::map<std::tuple<double, double, double>, double> memo;
  const auto key = std::make_tuple(probability, nu, s);
  {
    const std::lock_guard lock(mutex);
    if (const auto it = memo.find(key); it != memo.end()) return it->second;
  }
  double low = 1.0, high = 2.0;
  while (exceedance(high, nu, s) > probability) {
    low = high;
    high *= 2.0;
  }
  for (int i = 0; i < 30; ++i) {
    const double mid = std::sqrt(low * high);
    (exceedance(mid, nu, s) > probability ? low : high) = mid;
  }
  const std::lock_guard lock(mutex);
  if (memo.size() > 4096) memo.clear();  // bounded: a long-running process sees many lengths
  memo.emplace(key, high);
  return high;
}

/// Correlation of the powers of two raw bins Δ apart, from the spectrum's power covariance
/// g(Δ)/g(0) (0 when not given).
double power_correlation(const Spectrum& raw, std::size_t lag) {
  const auto& g = raw.power_covariance;
  if (g.size() <= lag || !(g[0] > 0.0)) return 0.0;
  return g[lag] / g[0];
}

/// Phasor e^{-iωt} for t = 0, 1, …: exact at every multiple of kAnchor samples and advanced by
/// one complex multiplication in between (rounding grows ~kAnchor·1e-16).
class Phasor {
 public:
  explicit Phasor(double omega) : omega_(omega), step_(std::polar(1.0, omega)) {}
  std::complex<double> at_anchor(std::size_t t) const {
    return std::polar(1.0, omega_ * static_cast<double>(t));
  }
  std::complex<double> step() const { return step_; }
  static constexpr std::size_t kAnchor = 4096;

 private:
  double omega_;
  std::complex<double> step_;
};

/// Mean and slope per sample of X (least squares, centred index).
struct LineTrend {
  double mean = 0.0, slope = 0.0, centre = 0.0;
};
LineTrend trend_of(std::span<const double> x) {
  LineTrend t;
  const double n = static_cast<double>(x.size());
  t.centre = 0.5 * (n - 1.0);
  double sum = 0.0, sum_t = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sum += x[i];
    sum_t += (static_cast<double>(i) - t.centre) * x[i];
  }
  t.mean = sum / n;
  t.slope = sum_t / (n * (n * n - 1.0) / 12.0);
  return t;
}

/// Least-squares frequency of one sinusoid near F0 in the pieces: the maximum over
/// |f − f0| ≤ HALF_WIDTH of Σ_pieces |Σ_t (x_t − trend) e^{−i2πft/fs}|² (each piece its own
/// phase). Zoom DFT: the detrended samples are demodulated by f0 and summed in blocks of M
/// samples, M such that the phase of the largest offset turns by ≤ 2π/64 over a block (the
/// block sum then passes every offset with gain within 0.1 % of 1, the same for all, so the
/// maximum stays in place); a grid of step 1/(8T) over the window (the periodogram's main lobe
/// is 2/T wide) then golden-section search around the best grid point.
double refine_frequency(std::span<const std::span<const double>> pieces, double fs, double f0,
                        double half_width) {
  if (!(half_width > 0.0)) return f0;
  std::size_t longest = 0;
  for (const auto& p : pieces) longest = std::max(longest, p.size());
  const auto block = static_cast<std::size_t>(std::max(1.0, std::floor(fs / (64.0 * half_width))));
  struct BlockSums {
    std::vector<std::complex<double>> z;
    std::vector<double> t_s;  // block centre [s]
  };
  std::vector<BlockSums> sums(pieces.size());
  const Phasor phasor(-2.0 * kPi * f0 / fs);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const auto& x = pieces[k];
    const LineTrend trend = trend_of(x);
    std::complex<double> p;
    for (std::size_t start = 0; start < x.size(); start += block) {
      const std::size_t end = std::min(x.size(), start + block);
      std::complex<double> acc = 0.0;
      for (std::size_t t = start; t < end; ++t) {
        if (t % Phasor::kAnchor == 0 || t == start) p = phasor.at_anchor(t);
        acc += (x[t] - trend.mean - trend.slope * (static_cast<double>(t) - trend.centre)) * p;
        p *= phasor.step();
      }
      sums[k].z.push_back(acc);
      sums[k].t_s.push_back(0.5 * static_cast<double>(start + end - 1) / fs);
    }
  }
  const auto power = [&](double offset_hz) {
    double total = 0.0;
    for (const BlockSums& s : sums) {
      std::complex<double> acc = 0.0;
      for (std::size_t b = 0; b < s.z.size(); ++b)
        acc += s.z[b] * std::polar(1.0, -2.0 * kPi * offset_hz * s.t_s[b]);
      total += std::norm(acc);
    }
    return total;
  };
  const double duration = static_cast<double>(longest) / fs;
  const double step = 1.0 / (8.0 * duration);
  const int steps = static_cast<int>(std::ceil(half_width / step));
  double best = 0.0, best_power = -1.0;
  for (int i = -steps; i <= steps; ++i) {
    const double v = power(i * step);
    if (v > best_power) {
      best_power = v;
      best = i * step;
    }
  }
  // Golden section on [best − step, best + step] (unimodal there: the grid resolves the lobe),
  // to 1e-8 of the grid step.
  const double refined = golden_section_minimum([&](double offset) { return -power(offset); },
                                                best - step, best + step, 1e-8 * step);
  return f0 + std::clamp(refined, -half_width, half_width);
}

/// The continuum's reference values at bin J: the raw densities j − h … j + h without the main
/// lobe |k − j| ≤ e, into REFERENCE (replacing its content).
void collect_reference(const Spectrum& raw, std::size_t j, std::size_t h, std::size_t e,
                       std::vector<double>& reference) {
  reference.clear();
  for (std::size_t k = j - h; k <= j + h; ++k) {
    if (k + e < j || k > j + e) reference.push_back(raw.density[k]);
  }
}

/// The median of collect_reference()'s values (REFERENCE is scratch).
double reference_median(const Spectrum& raw, std::size_t j, std::size_t h, std::size_t e,
                        std::vector<double>& reference) {
  collect_reference(raw, j, h, e, reference);
  const std::size_t m = reference.size();
  const auto middle = reference.begin() + static_cast<std::ptrdiff_t>(m / 2);
  std::nth_element(reference.begin(), middle, reference.end());
  double median = *middle;
  if (m % 2 == 0) median = 0.5 * (median + *std::max_element(reference.begin(), middle));
  return median;
}

}  // namespace

double line_continuum_density(const Spectrum& raw, double f_hz, const LineSearchOptions& options) {
  IMUNOISE_EXPECT(raw.first_raw_bin.empty() && raw.density.size() >= 8 &&
                      raw.dof.size() == raw.density.size() && raw.resolution_hz > 0.0,
                  "line_continuum_density: needs a raw spectrum of at least 8 bins");
  const std::size_t bins = raw.density.size();
  const auto j = static_cast<std::size_t>(
      std::clamp(std::round(f_hz / raw.resolution_hz), 4.0, static_cast<double>(bins - 3)));
  // The detection's symmetric window; near DC or Nyquist at least e + 2 bins each side, cut
  // to what exists (and the main lobe narrowed when even that does not fit).
  const std::size_t room = std::min(j, bins - 1 - j);
  const std::size_t h =
      std::min(room, std::max(options.main_lobe_half_width + 2,
                              std::min({options.continuum_half_width, j - 3, bins - 2 - j})));
  const std::size_t e = std::min(options.main_lobe_half_width, h - 1);
  std::vector<double> reference;
  const double median = reference_median(raw, j, h, e, reference);
  return median / (chi_square_quantile(0.5, raw.dof[j]) / raw.dof[j]);
}

LineDetection detect_spectral_lines(const Spectrum& raw, const LineSearchOptions& options) {
  IMUNOISE_EXPECT(raw.first_raw_bin.empty(), "detect_spectral_lines: needs a raw spectrum");
  IMUNOISE_EXPECT(
      raw.frequency_hz.size() == raw.density.size() && raw.dof.size() == raw.density.size(),
      "detect_spectral_lines: sizes differ");
  IMUNOISE_EXPECT(options.false_alarm_probability > 0.0 && options.false_alarm_probability < 1.0,
                  "detect_spectral_lines: false-alarm probability outside (0, 1)");
  IMUNOISE_EXPECT(options.continuum_half_width > options.main_lobe_half_width &&
                      options.min_reference_bins >= 2,
                  "detect_spectral_lines: bad window");
  LineDetection out;
  const std::size_t bins = raw.density.size();
  const std::size_t e = options.main_lobe_half_width;
  // Bins 0 … 2 carry the detrend's notch (the Hann main lobe reaches DC); the last bin is
  // Nyquist (real, half the dof). The window around j is symmetric: h_j ≤ j − 3 and
  // h_j ≤ (bins − 2) − j, and needs 2(h_j − e) ≥ min_reference_bins.
  const std::size_t h_min = e + (options.min_reference_bins + 1) / 2;
  if (bins < 2 * h_min + 6) return out;
  const std::size_t j_low = 3 + h_min;
  const std::size_t j_high = bins - 2 - h_min;
  if (j_high < j_low) return out;
  out.bins_searched = j_high - j_low + 1;
  out.f_low_hz = raw.frequency_hz[j_low];
  out.f_high_hz = raw.frequency_hz[j_high];
  const double per_bin = options.false_alarm_probability / static_cast<double>(out.bins_searched);
  // m_eff: the reference powers are correlated with their neighbours (window and overlap);
  // the count is divided by 1 + 2Σρ(Δ) over the lags that matter (ρ falls to ~0 by Δ = 3).
  double correlation_sum = 0.0;
  for (std::size_t lag = 1; lag <= 3; ++lag) correlation_sum += power_correlation(raw, lag);
  std::map<std::pair<std::size_t, long long>, double> thresholds;  // (m, ν·100) → r
  std::map<long long, double> median_ratios;                       // ν·100 → median(χ²_ν/ν)
  struct Hit {
    std::size_t bin;
    double ratio, continuum, threshold;
  };
  std::vector<Hit> hits;
  // The reference window of collect_reference(), kept sorted while j steps by one with the same
  // h: two values leave it (j − 1 − h, and j + e, which enters the main lobe) and two enter
  // (j + h, and j − 1 − e, which leaves the lobe) — a few moves of ~2h values per bin instead
  // of a copy and a selection (this loop was the analysis's largest single cost at 8 h × 50 Hz).
  // The same values, so the same median as reference_median() bit for bit.
  std::vector<double> window;
  std::size_t window_h = 0;
  const auto erase_value = [&window](double v) {
    window.erase(std::lower_bound(window.begin(), window.end(), v));
  };
  const auto insert_value = [&window](double v) {
    window.insert(std::upper_bound(window.begin(), window.end(), v), v);
  };
  for (std::size_t j = j_low; j <= j_high; ++j) {
    const std::size_t h = std::min({options.continuum_half_width, j - 3, bins - 2 - j});
    if (j > j_low && h == window_h) {
      erase_value(raw.density[j - 1 - h]);
      erase_value(raw.density[j + e]);
      insert_value(raw.density[j + h]);
      insert_value(raw.density[j - 1 - e]);
    } else {
      collect_reference(raw, j, h, e, window);
      std::sort(window.begin(), window.end());
      window_h = h;
    }
    const std::size_t m = window.size();
    const double median = m % 2 == 1 ? window[m / 2] : 0.5 * (window[m / 2] + window[m / 2 - 1]);
    const double nu = raw.dof[j];
    const long long nu_key = std::llround(nu * 100.0);
    auto median_ratio = median_ratios.find(nu_key);
    if (median_ratio == median_ratios.end()) {
      median_ratio = median_ratios.emplace(nu_key, chi_square_quantile(0.5, nu) / nu).first;
    }
    const double continuum = median / median_ratio->second;
    if (!(continuum > 0.0)) continue;
    const double ratio = raw.density[j] / continuum;
    const auto key = std::make_pair(m, nu_key);
    auto it = thresholds.find(key);
    if (it == thresholds.end()) {
      const double m_eff = static_cast<double>(m) / (1.0 + 2.0 * correlation_sum);
      const double s = std::sqrt(kPi / 2.0) * std::sqrt(2.0 / nu) / std::sqrt(m_eff);
      it = thresholds.emplace(key, threshold_ratio(per_bin, nu, s)).first;
    }
    if (ratio > it->second) hits.push_back({j, ratio, continuum, it->second});
  }
  // Adjacent hits are one line (its main lobe); a weaker peak within 2e bins of a stronger
  // one is its sidelobe or its other half, not a second line.
  std::vector<Hit> peaks;
  for (std::size_t i = 0; i < hits.size();) {
    std::size_t end = i + 1;
    while (end < hits.size() && hits[end].bin == hits[end - 1].bin + 1) ++end;
    peaks.push_back(*std::max_element(
        hits.begin() + static_cast<std::ptrdiff_t>(i),
        hits.begin() + static_cast<std::ptrdiff_t>(end),
        [&](const Hit& a, const Hit& b) { return raw.density[a.bin] < raw.density[b.bin]; }));
    i = end;
  }
  std::sort(peaks.begin(), peaks.end(),
            [&](const Hit& a, const Hit& b) { return raw.density[a.bin] > raw.density[b.bin]; });
  std::vector<Hit> kept;
  for (const Hit& p : peaks) {
    const bool near = std::any_of(kept.begin(), kept.end(), [&](const Hit& q) {
      return (p.bin > q.bin ? p.bin - q.bin : q.bin - p.bin) <= 2 * e;
    });
    if (!near && kept.size() < options.max_lines) kept.push_back(p);
  }
  for (const Hit& p : kept) {
    // Peak between bins: the vertex of the parabola through the log powers of the peak bin
    // and its neighbours (exact for a Gaussian lobe; within ~0.05 bin for Hann).
    const double a = std::log(raw.density[p.bin - 1]);
    const double b = std::log(raw.density[p.bin]);
    const double c = std::log(raw.density[p.bin + 1]);
    const double curvature = a - 2.0 * b + c;
    const double offset = curvature < 0.0 ? std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5) : 0.0;
    const double spacing = raw.frequency_hz[p.bin + 1] - raw.frequency_hz[p.bin];
    out.candidates.push_back(
        {raw.frequency_hz[p.bin] + offset * spacing, p.bin, p.continuum, p.ratio, p.threshold});
  }
  std::sort(out.candidates.begin(), out.candidates.end(),
            [](const LineCandidate& a, const LineCandidate& b) {
              return a.frequency_hz < b.frequency_hz;
            });
  return out;
}

LineFit fit_spectral_lines(std::span<const std::span<const double>> pieces, double sample_rate_hz,
                           std::span<const double> frequencies_hz,
                           std::span<const double> continuum, double search_half_width_hz,
                           double confidence) {
  IMUNOISE_EXPECT(frequencies_hz.size() == continuum.size(),
                  "fit_spectral_lines: one continuum value per frequency");
  IMUNOISE_EXPECT(confidence > 0.0 && confidence < 1.0, "fit_spectral_lines: bad confidence");
  IMUNOISE_EXPECT(sample_rate_hz > 0.0 && search_half_width_hz >= 0.0,
                  "fit_spectral_lines: bad rate or search width");
  for (const auto& p : pieces) IMUNOISE_EXPECT(p.size() >= 8, "fit_spectral_lines: short piece");
  for (double f : frequencies_hz) {
    IMUNOISE_EXPECT(f > 0.0 && f < 0.5 * sample_rate_hz,
                    "fit_spectral_lines: frequency outside (0, Nyquist)");
  }
  LineFit out;
  const std::size_t lines = frequencies_hz.size();
  if (lines == 0) return out;
  std::vector<double> refined(lines);
  for (std::size_t k = 0; k < lines; ++k) {
    refined[k] = std::clamp(
        refine_frequency(pieces, sample_rate_hz, frequencies_hz[k], search_half_width_hz),
        1e-9 * sample_rate_hz, (0.5 - 1e-9) * sample_rate_hz);
  }
  // Joint least squares per piece: columns 1, trend τ ∈ [−1, 1], then (cos ω_k t, sin ω_k t)
  // for every line; normal equations (the columns are nearly orthogonal for lines ≫ 1/T apart).
  const auto columns = static_cast<Eigen::Index>(2 + 2 * lines);
  double total_samples = 0.0;
  std::vector<double> weighted_a2(lines, 0.0);
  out.piece_coefficients.resize(pieces.size());
  std::vector<Phasor> phasors;
  for (double f : refined) phasors.emplace_back(2.0 * kPi * f / sample_rate_hz);
  std::vector<std::complex<double>> p(lines);
  Eigen::VectorXd row(columns);
  for (std::size_t piece = 0; piece < pieces.size(); ++piece) {
    const auto& x = pieces[piece];
    const LineTrend trend = trend_of(x);
    const double half = 0.5 * static_cast<double>(x.size());
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(columns, columns);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(columns);
    for (std::size_t t = 0; t < x.size(); ++t) {
      if (t % Phasor::kAnchor == 0) {
        for (std::size_t k = 0; k < lines; ++k) p[k] = phasors[k].at_anchor(t);
      }
      const double tau = (static_cast<double>(t) - trend.centre) / half;
      row[0] = 1.0;
      row[1] = tau;
      for (std::size_t k = 0; k < lines; ++k) {
        row[static_cast<Eigen::Index>(2 + 2 * k)] = p[k].real();
        row[static_cast<Eigen::Index>(3 + 2 * k)] = p[k].imag();
        p[k] *= phasors[k].step();
      }
      const double y = x[t] - trend.mean - trend.slope * (static_cast<double>(t) - trend.centre);
      gram.selfadjointView<Eigen::Lower>().rankUpdate(row);
      rhs += y * row;
    }
    const Eigen::VectorXd beta = gram.selfadjointView<Eigen::Lower>().ldlt().solve(rhs);
    auto& coefficients = out.piece_coefficients[piece];
    const double n = static_cast<double>(x.size());
    for (std::size_t k = 0; k < lines; ++k) {
      const double c = beta[static_cast<Eigen::Index>(2 + 2 * k)];
      const double s = beta[static_cast<Eigen::Index>(3 + 2 * k)];
      coefficients.push_back(c);
      coefficients.push_back(s);
      weighted_a2[k] += n * (c * c + s * s);
    }
    total_samples += static_cast<double>(x.size());
  }
  const double z = std::sqrt(chi_square_quantile(confidence, 1.0));
  const double duration = total_samples / sample_rate_hz;
  for (std::size_t k = 0; k < lines; ++k) {
    FittedLine line;
    line.value.frequency_hz = refined[k];
    line.value.amplitude = std::sqrt(weighted_a2[k] / total_samples);
    const double c = out.piece_coefficients[0][2 * k];
    const double s = out.piece_coefficients[0][2 * k + 1];
    // c·cos ωt + s·sin ωt = A·sin(ωt + φ) with A sin φ = c, A cos φ = s.
    line.value.phase_rad = std::atan2(c, s);
    line.continuum_density = continuum[k];
    line.amplitude_sd = std::sqrt(std::max(continuum[k], 0.0) / duration);
    line.amplitude_ci_low = std::max(0.0, line.value.amplitude - z * line.amplitude_sd);
    line.amplitude_ci_high = line.value.amplitude + z * line.amplitude_sd;
    out.lines.push_back(line);
  }
  return out;
}

std::vector<double> remove_spectral_lines(std::span<const double> piece, std::size_t index,
                                          const LineFit& fit, double sample_rate_hz) {
  IMUNOISE_EXPECT(index < fit.piece_coefficients.size(), "remove_spectral_lines: bad piece");
  std::vector<double> out(piece.begin(), piece.end());
  const auto& coefficients = fit.piece_coefficients[index];
  for (std::size_t k = 0; k < fit.lines.size(); ++k) {
    const Phasor phasor(2.0 * kPi * fit.lines[k].value.frequency_hz / sample_rate_hz);
    const double c = coefficients[2 * k], s = coefficients[2 * k + 1];
    std::complex<double> p;
    for (std::size_t t = 0; t < out.size(); ++t) {
      if (t % Phasor::kAnchor == 0) p = phasor.at_anchor(t);
      out[t] -= c * p.real() + s * p.imag();
      p *= phasor.step();
    }
  }
  return out;
}

}  // namespace imunoise::analysis
