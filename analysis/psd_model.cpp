/// @file
/// @brief Model PSD, PSD cross-check and slope-region read-off (see psd_model.h;
/// theory.md §5.3).
#include "analysis/psd_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "analysis/chi_square.h"
#include "common/errors.h"

namespace imunoise::analysis {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

void check_coefficient(double value, const char* name) {
  IMUNOISE_EXPECT(
      std::isfinite(value) && value >= 0.0,
      std::string("model_psd: ") + name + " must be finite and >= 0 (got " + text(value) + ")");
}

void check_model(const NoiseCoefficients& model, double f_hz, double tau0_s) {
  IMUNOISE_EXPECT(std::isfinite(f_hz) && f_hz > 0.0,
                  "model_psd: frequency must be finite and > 0 (got " + text(f_hz) + " Hz)");
  IMUNOISE_EXPECT(std::isfinite(tau0_s) && tau0_s > 0.0,
                  "model_psd: tau0 must be finite and > 0 (got " + text(tau0_s) + " s)");
  check_coefficient(model.quantization, "quantization Q");
  check_coefficient(model.white_noise, "white_noise N");
  check_coefficient(model.bias_instability, "bias_instability B");
  check_coefficient(model.random_walk, "random_walk K");
  check_coefficient(model.ramp, "ramp R");
  for (const GaussMarkov& gm : model.gauss_markov) {
    check_coefficient(gm.sigma, "gauss_markov sigma");
    IMUNOISE_EXPECT(
        std::isfinite(gm.tau_c_s) && gm.tau_c_s > 0.0,
        "model_psd: gauss_markov tau_c_s must be finite and > 0 (got " + text(gm.tau_c_s) + " s)");
  }
}

/// @name The S₁ of the sampled rate record, one row per term (docs/conventions.md §4.1)
/// The record is y_k = (θ_{k+1} − θ_k)/τ0: each rate sample is the average of the continuous
/// rate over its interval (an angle increment over τ0), so its one-sided PSD on [0, 1/(2τ0)]
/// is S₁(f) = Σ_k S₁c(f + k/τ0)·sinc²(π(f + k/τ0)τ0) — the continuous law S₁c of theory.md
/// §5.3 folded at Nyquist after the τ0 boxcar. With x = fτ0 and s = sin(πx), since
/// sin²(π(x + k)) = s² for every k, each fold sum is a closed form or a Hurwitz zeta. These are
/// the spectra whose sampled AVAR, 2∫₀^{1/2τ0} S₁ sin⁴(πfmτ0)/(m² sin²(πfτ0)) df, is exactly the
/// continuous AVAR of theory.md §4.1 at τ = mτ0, i.e. the model the fit uses
/// (tests/analysis/psd_model_test.cpp checks both and each against a simulated record).
/// Above Nyquist a sampled record has no density: every row is 0 there.
/// @{

/// Q: white angle error of σ = Q on each angle sample, differenced: S₁ = 2τ0·|1 − e^{−i2πx}|²
/// ·Q²/τ0² = 8 sin²(πx)·Q²/τ0. It is theory.md §4.1's continuous (2πf)²τ0Q² (doubled to
/// one-sided) where x ≪ 1 and 4/π² = 0.405 of it at Nyquist, where the continuous law made a
/// complete model fail its cross-check on quantized angle increments (issue 20).
double quantization_psd(double q, double s, double tau0) { return 8.0 * s * s * q * q / tau0; }

/// N: averages of white noise of S₁c = 2N² are white with variance N²/τ0: S₁ = 2N², exact.
double white_psd(double n) { return 2.0 * n * n; }

/// ζ(3, a) + ζ(3, 1 − a) = Σ_{k∈ℤ} |a + k|⁻³ for 0 < a ≤ 1/2: ten terms of each series, then
/// the Euler–Maclaurin tail Σ_{j≥0} (b + j)⁻³ = 1/(2b²) + 1/(2b³) + 1/(4b⁴) − 1/(12b⁶) +
/// 1/(12b⁸) + O(0.15/b¹⁰) at b ≥ 10, i.e. a relative error below 1e-11.
double two_sided_zeta3(double a) {
  const auto series = [](double start) {
    double sum = 0.0;
    for (int k = 0; k < 10; ++k) {
      const double t = start + k;
      sum += 1.0 / (t * t * t);
    }
    const double b = start + 10.0, b2 = b * b, b4 = b2 * b2;
    return sum + 0.5 / b2 + 0.5 / (b2 * b) + 0.25 / b4 - 1.0 / (12.0 * b4 * b2) +
           1.0 / (12.0 * b4 * b4);
  };
  return series(a) + series(1.0 - a);
}

/// B: S₁c = B²/(πf) folded: S₁ = (B²τ0/π)·(s²/π²)·Σ_k |x + k|⁻³ = (B²τ0/π³)·s²·[ζ(3, x) +
/// ζ(3, 1 − x)] → B²/(πf) where x ≪ 1; 0.77 of it at 0.4/τ0 and 7ζ(3)/π² = 0.853 at Nyquist.
double flicker_psd(double b, double x, double s, double tau0) {
  return b * b * tau0 / (kPi * kPi * kPi) * s * s * two_sided_zeta3(x);
}

/// K: S₁c = K²/(2π²f²) folded, with Σ_k (x + k)⁻⁴ = (π⁴/3)(2 + cos 2πx)/s⁴:
/// S₁ = K²τ0²(2 + cos 2πx)/(6s²) → K²/(2π²f²) where x ≪ 1, 0.69 of it at 0.4/τ0 and π²/12 = 0.822
/// at Nyquist. A point-sampled discrete walk of step K√τ0 (theory.md §1.4) has K²τ0²/(2s²), i.e.
/// this plus a white K²τ0²/3 (an N² of K²τ0²/6, which its AVAR (2m² + 1)K²τ0/(6m) shows too).
double random_walk_psd(double k, double x, double s, double tau0) {
  return k * k * tau0 * tau0 * (2.0 + std::cos(kTwoPi * x)) / (6.0 * s * s);
}

/// R: the ramp is deterministic. A rate R·t has no density: after each Welch segment's mean
/// removal its Hann-windowed remainder R(t − t_mid) has DFT magnitude falling as k⁻³ (the
/// window and its slope vanish at both ends), so beyond the ±2-bin main lobe that
/// cross_check_psd() skips it leaves nothing a bin resolves. It is therefore not in the model
/// PSD (theory.md §5.3's 2R²/(2πf)³ is the spectrum of a random process with R's AVAR, which a
/// drifting rate is not).
double ramp_psd() { return 0.0; }

/// GM: the τ0-averages of a stationary first-order Gauss–Markov process (autocovariance
/// σ²e^{−|t|/T}), with r = τ0/T and φ = e^{−r}, have the autocovariance
///   c₀ = 2σ²(1/r)[1 − (1 − φ)/r],   c_j = Aφ^{|j|} (j ≠ 0),   A = σ²(1 − φ)²/(φr²),
/// (∫∫ of σ²e^{−|t−u|/T} over two intervals), so
///   S₁ = 2τ0[(c₀ − A) + A(1 − φ²)/((1 − φ)² + 4φs²)]:
/// an AR(1) spectrum of variance A plus a negative white 2τ0(c₀ − A) ≈ −(2/3)σ²τ0r. It tends to
/// 4σ²T at DC and to 4σ²T/(1 + (2πfT)²) where r ≪ 1 and x ≪ 1. A point-sampled AR(1) (the exact
/// discrete GM) is this with σ² → σ²·(r/2)²/sinh²(r/2) plus a white ≈ (2/3)σ²τ0r, again an N
/// the fit absorbs.
double gauss_markov_psd(const GaussMarkov& gm, double s, double tau0) {
  const double r = tau0 / gm.tau_c_s;
  const double one_minus_phi = -std::expm1(-r);
  const double phi = 1.0 - one_minus_phi;
  const double var = gm.sigma * gm.sigma;
  const double c0 = 2.0 * var / r * (1.0 - one_minus_phi / r);
  const double a = var * one_minus_phi * one_minus_phi / (phi * r * r);
  const double ar1 =
      a * -std::expm1(-2.0 * r) / (one_minus_phi * one_minus_phi + 4.0 * phi * s * s);
  return 2.0 * tau0 * ((c0 - a) + ar1);
}
/// @}

/// The read-off inverses of the rows above: coefficient² implied by S₁ at f.
double squared_coefficient(int slope, double f, double s1, double tau0) {
  const double w = kTwoPi * f;
  switch (slope) {
    case 2: {
      const double s = std::sin(kPi * f * tau0);  // Q² = S₁τ0/(8 sin²(πfτ0)), sampled form
      return s1 * tau0 / (8.0 * s * s);
    }
    case 0:
      return 0.5 * s1;  // N² = S₁/2
    case -1:
      return kPi * f * s1;  // B² = πfS₁
    case -2:
      return 2.0 * kPi * kPi * f * f * s1;  // K² = 2π²f²S₁
    case -3:
      return 0.5 * s1 * w * w * w;  // R² = S₁(2πf)³/2
    default:
      return 0.0;
  }
}

/// A contiguous run [first, last] of binned points with a common local slope.
struct Run {
  std::size_t first = 0;
  std::size_t last = 0;
  double dof = 0.0;
  std::size_t size() const { return last - first + 1; }
};

constexpr double kSlopeTolerance = 0.3;
constexpr std::size_t kSlopeHalfWidth = 2;
constexpr std::size_t kMinRunBins = 3;
/// A Lorentzian's local slope goes from −0.3 to −1.7 between f = 0.42·f_c and 2.38·f_c, a
/// factor 5.7: the roll-off run must start within a decade of the plateau's end.
constexpr double kMaxGmGapRatio = 10.0;

/// Runs of ≥ kMinRunBins points whose local slope is within kSlopeTolerance of TARGET,
/// among the points below f_top_hz.
std::vector<Run> runs_with_slope(const std::vector<double>& slopes, const Spectrum& s,
                                 double target, double f_top_hz) {
  const auto matches = [&](std::size_t i) {
    return s.frequency_hz[i] <= f_top_hz && std::fabs(slopes[i] - target) <= kSlopeTolerance;
  };
  const std::vector<double>& dof = s.dof;
  std::vector<Run> runs;
  std::size_t i = 0;
  while (i < slopes.size()) {
    if (!matches(i)) {
      ++i;
      continue;
    }
    Run run{i, i, 0.0};
    while (run.last + 1 < slopes.size() && matches(run.last + 1)) ++run.last;
    for (std::size_t k = run.first; k <= run.last; ++k) run.dof += dof[k];
    if (run.size() >= kMinRunBins) runs.push_back(run);
    i = run.last + 1;
  }
  return runs;
}

/// Longer wins, then more dof.
bool better(const Run& a, const Run& b) {
  return a.size() != b.size() ? a.size() > b.size() : a.dof > b.dof;
}

const Run* longest(const std::vector<Run>& runs, const Run* excluded) {
  const Run* best = nullptr;
  for (const Run& r : runs) {
    if (excluded != nullptr && r.first == excluded->first) continue;
    if (best == nullptr || better(r, *best)) best = &r;
  }
  return best;
}

PsdReadoffTerm read_term(const Spectrum& s, const Run* run, int slope, double tau0) {
  PsdReadoffTerm term;
  if (run == nullptr) return term;
  double weighted = 0.0;
  for (std::size_t i = run->first; i <= run->last; ++i) {
    weighted += s.dof[i] * squared_coefficient(slope, s.frequency_hz[i], s.density[i], tau0);
  }
  term.value = std::sqrt(weighted / run->dof);
  term.found = true;
  term.f_low_hz = s.frequency_hz[run->first];
  term.f_high_hz = s.frequency_hz[run->last];
  term.bins = run->size();
  return term;
}

/// One bin of cross_check_psd(): its frequency, measured/model and verdict.
struct ComparedBin {
  double f_hz = 0.0;
  double ratio = 1.0;
  bool outside = false;
};

/// A narrow excess [FIRST, LAST] is a line when it is at least kLineRatio above the model
/// and the compared bins next to it carry at most a third of its excess (a local peak, not a
/// piece of a broad misfit).
constexpr double kLineRatio = 1.5;
bool is_peak(const std::vector<ComparedBin>& bins, std::size_t first, std::size_t last,
             double extreme) {
  if (!(extreme >= kLineRatio)) return false;
  const double side = 1.0 + (extreme - 1.0) / 3.0;
  if (first > 0 && bins[first - 1].ratio > side) return false;
  if (last + 1 < bins.size() && bins[last + 1].ratio > side) return false;
  return true;
}

/// The bands of a failed check (rules in psd_model.h, cross_check_psd()).
std::vector<PsdMisfitBand> misfit_bands(std::vector<ComparedBin> bins) {
  std::sort(bins.begin(), bins.end(),
            [](const ComparedBin& a, const ComparedBin& b) { return a.f_hz < b.f_hz; });
  const std::size_t n = bins.size();
  std::vector<PsdMisfitBand> out;
  std::size_t i = 0;
  while (i < n) {
    if (!bins[i].outside) {
      ++i;
      continue;
    }
    const bool above = bins[i].ratio > 1.0;
    const auto same_side = [&](std::size_t k) { return (bins[k].ratio > 1.0) == above; };
    std::size_t first = i, last = i, count = 1;
    double extreme = bins[i].ratio;
    const auto farther = [](double a, double b) {
      return std::fabs(std::log(a)) > std::fabs(std::log(b));
    };
    for (std::size_t k = i + 1; k < n; ++k) {
      if (bins[k].outside && same_side(k)) {
        last = k;
        ++count;
        if (farther(bins[k].ratio, extreme)) extreme = bins[k].ratio;
        continue;
      }
      // Bridge one inside bin on the same side when an outside bin on that side follows.
      if (!bins[k].outside && same_side(k) && k + 1 < n && bins[k + 1].outside &&
          same_side(k + 1)) {
        continue;
      }
      break;
    }
    PsdMisfitBand band;
    band.f_low_hz = bins[first].f_hz;
    band.f_high_hz = bins[last].f_hz;
    band.bins = count;
    band.above = above;
    band.extreme_ratio = extreme;
    // Mean log ratio of the lower and upper half of the band's outside bins: a flat band is
    // a level error, a trend a roll-off or an excess growing towards one end.
    std::vector<double> logs;
    for (std::size_t k = first; k <= last; ++k)
      if (bins[k].outside) logs.push_back(std::log(bins[k].ratio));
    const std::size_t half = logs.size() / 2;
    double lower = 0.0, upper = 0.0;
    for (std::size_t k = 0; k < logs.size(); ++k)
      (k < (logs.size() + 1) / 2 ? lower : upper) += logs[k];
    lower /= static_cast<double>((logs.size() + 1) / 2);
    upper = half > 0 ? upper / static_cast<double>(half) : lower;
    const bool flat = logs.size() >= 4 && std::fabs(upper - lower) <=
                                              0.3 * std::max(std::fabs(lower), std::fabs(upper));
    const bool bottom = first <= 1, top = last + 2 >= n, wide = 2 * count > n;
    const PsdMisfitCause low =
        above ? PsdMisfitCause::low_frequency_excess : PsdMisfitCause::low_frequency_deficit;
    const PsdMisfitCause high =
        above ? PsdMisfitCause::high_frequency_excess : PsdMisfitCause::low_pass;
    if (bottom && top) {
      band.cause =
          flat ? PsdMisfitCause::level : (std::fabs(lower) > std::fabs(upper) ? low : high);
    } else if (bottom) {
      band.cause = low;
    } else if (last - first + 1 <= 2 && is_peak(bins, first, last, extreme)) {
      band.cause = PsdMisfitCause::spectral_line;
    } else if (count == 1 && (!top || (!above && extreme > kSingleBinRollOffRatio))) {
      // One top bin a few % low is not a roll-off: the highest bins hold 10⁴–10⁵ dof, so a
      // 1.5 % deficit leaves their 99 % interval (gm class: ×0.985 at 0.36·f_s was named
      // "the sensor's low-pass filter").
      band.cause = PsdMisfitCause::isolated;
    } else if (top) {
      band.cause = flat ? PsdMisfitCause::level : high;
    } else if (wide && flat) {
      band.cause = PsdMisfitCause::level;
    } else {
      band.cause = above ? PsdMisfitCause::band_excess : PsdMisfitCause::band_deficit;
    }
    out.push_back(band);
    i = last + 1;
  }
  return out;
}

}  // namespace

double PsdTerms::total() const {
  double sum = terms[NoiseTerm::quantization] + terms[NoiseTerm::white_noise] +
               terms[NoiseTerm::bias_instability] + terms[NoiseTerm::random_walk] +
               terms[NoiseTerm::ramp];
  for (double g : gauss_markov) sum += g;
  return sum;
}

PsdTerms model_psd_terms(const NoiseCoefficients& model, double f_hz, double tau0_s) {
  check_model(model, f_hz, tau0_s);
  PsdTerms t;
  t.gauss_markov.assign(model.gauss_markov.size(), 0.0);
  const double x = f_hz * tau0_s;
  if (x > 0.5) return t;  // no density above Nyquist
  const double s = std::sin(kPi * x);
  t.terms[NoiseTerm::quantization] = quantization_psd(model.quantization, s, tau0_s);
  t.terms[NoiseTerm::white_noise] = white_psd(model.white_noise);
  t.terms[NoiseTerm::bias_instability] = flicker_psd(model.bias_instability, x, s, tau0_s);
  t.terms[NoiseTerm::random_walk] = random_walk_psd(model.random_walk, x, s, tau0_s);
  t.terms[NoiseTerm::ramp] = ramp_psd();
  for (std::size_t j = 0; j < model.gauss_markov.size(); ++j) {
    t.gauss_markov[j] = gauss_markov_psd(model.gauss_markov[j], s, tau0_s);
  }
  return t;
}

double model_psd_one_sided(const NoiseCoefficients& model, double f_hz, double tau0_s) {
  check_model(model, f_hz, tau0_s);
  const double x = f_hz * tau0_s;
  if (x > 0.5) return 0.0;
  const double s = std::sin(kPi * x);
  double sum = quantization_psd(model.quantization, s, tau0_s) + white_psd(model.white_noise) +
               random_walk_psd(model.random_walk, x, s, tau0_s) + ramp_psd();
  if (model.bias_instability > 0.0) {
    sum += flicker_psd(model.bias_instability, x, s, tau0_s);
  }
  for (const GaussMarkov& gm : model.gauss_markov) sum += gauss_markov_psd(gm, s, tau0_s);
  return sum;
}

PsdCrossCheck cross_check_psd(const Spectrum& binned, const NoiseCoefficients& model, double tau0_s,
                              double f_max_hz) {
  IMUNOISE_EXPECT(std::isfinite(tau0_s) && tau0_s > 0.0,
                  "cross_check_psd: tau0 must be finite and > 0 (got " + text(tau0_s) + " s)");
  IMUNOISE_EXPECT(std::isfinite(f_max_hz),
                  "cross_check_psd: f_max is not finite (" + text(f_max_hz) + ")");
  IMUNOISE_EXPECT(binned.frequency_hz.size() == binned.density.size() &&
                      binned.frequency_hz.size() == binned.dof.size(),
                  "cross_check_psd: frequency, density and dof sizes differ");
  IMUNOISE_EXPECT(binned.resolution_hz > 0.0,
                  "cross_check_psd: spectrum resolution must be > 0 (got " +
                      text(binned.resolution_hz) + " Hz)");
  const bool has_ranges = binned.first_raw_bin.size() == binned.frequency_hz.size() &&
                          binned.raw_bins.size() == binned.frequency_hz.size();
  IMUNOISE_EXPECT(binned.bin_resolution_hz.empty() ||
                      binned.bin_resolution_hz.size() == binned.frequency_hz.size(),
                  "cross_check_psd: bin_resolution_hz has " +
                      std::to_string(binned.bin_resolution_hz.size()) + " values for " +
                      std::to_string(binned.frequency_hz.size()) + " bins");
  for (const Sinusoid& line : model.sinusoids) {
    IMUNOISE_EXPECT(std::isfinite(line.frequency_hz) && std::isfinite(line.amplitude),
                    "cross_check_psd: sinusoid with a non-finite value");
  }
  const double f_low = 3.0 * binned.resolution_hz;
  const double f_high = f_max_hz > 0.0 ? f_max_hz : 0.8 * 0.5 / tau0_s;

  PsdCrossCheck check;
  check.f_min_hz = std::numeric_limits<double>::infinity();
  std::vector<ComparedBin> compared;
  for (std::size_t i = 0; i < binned.frequency_hz.size(); ++i) {
    const double f = binned.frequency_hz[i];
    if (!(f >= f_low && f <= f_high)) continue;
    // Raw bin spacing of this bin: a multi-rate spectrum's bins come from levels of
    // different spacing.
    const double res =
        binned.bin_resolution_hz.empty() ? binned.resolution_hz : binned.bin_resolution_hz[i];
    double lo = f, hi = f;
    if (has_ranges) {
      IMUNOISE_EXPECT(binned.raw_bins[i] > 0,
                      "cross_check_psd: bin " + std::to_string(i) + " holds no raw bin");
      lo = static_cast<double>(binned.first_raw_bin[i]) * res;
      hi = static_cast<double>(binned.first_raw_bin[i] + binned.raw_bins[i] - 1) * res;
    }
    const bool has_line =
        std::any_of(model.sinusoids.begin(), model.sinusoids.end(), [&](const Sinusoid& line) {
          return line.amplitude > 0.0 && line.frequency_hz >= lo - 4.0 * res &&
                 line.frequency_hz <= hi + 4.0 * res;
        });
    if (has_line) continue;
    const double nu = binned.dof[i];
    IMUNOISE_EXPECT(std::isfinite(nu) && nu > 0.0, "cross_check_psd: dof of the bin at " + text(f) +
                                                       " Hz must be > 0 (got " + text(nu) + ")");
    // The binned value is the mean of the raw bins: compare it with the model's mean over
    // the same raw frequencies (evaluating at the geometric centre would be 1–4 % low for
    // red terms, see log_bin()).
    double expected = 0.0;
    if (has_ranges) {
      for (std::size_t j = 0; j < binned.raw_bins[i]; ++j) {
        const double fj = static_cast<double>(binned.first_raw_bin[i] + j) * res;
        expected += model_psd_one_sided(model, fj, tau0_s);
      }
      expected /= static_cast<double>(binned.raw_bins[i]);
    } else {
      expected = model_psd_one_sided(model, f, tau0_s);
    }
    const double measured = binned.density[i];
    ++check.bins_compared;
    check.f_min_hz = std::min(check.f_min_hz, f);
    check.f_max_hz = std::max(check.f_max_hz, f);
    if (!(expected > 0.0) || !(measured > 0.0)) {
      ++check.bins_outside;
      check.worst_log10_ratio = std::numeric_limits<double>::infinity();
      compared.push_back({f, measured > 0.0 ? std::numeric_limits<double>::infinity() : 0.0, true});
      continue;
    }
    const double ratio = measured / expected;
    check.worst_log10_ratio = std::max(check.worst_log10_ratio, std::fabs(std::log10(ratio)));
    // ν·Ŝ/S ~ χ²_ν under the model: two-sided 99 % acceptance interval of the ratio.
    const double lower = chi_square_quantile(0.005, nu) / nu;
    const double upper = chi_square_upper_quantile(0.005, nu) / nu;
    const bool outside = ratio < lower || ratio > upper;
    if (outside) ++check.bins_outside;
    compared.push_back({f, ratio, outside});
  }
  if (check.bins_compared == 0) {
    throw AnalysisError("cross_check_psd: no spectrum bin between " + text(f_low) + " and " +
                        text(f_high) + " Hz to compare");
  }
  const std::size_t allowed =
      std::max<std::size_t>(2, static_cast<std::size_t>(0.05 * check.bins_compared));
  check.pass = check.bins_outside <= allowed;
  if (!check.pass) check.misfits = misfit_bands(std::move(compared));
  return check;
}

PsdReadoff psd_readoff(const Spectrum& binned) {
  const std::size_t n = binned.frequency_hz.size();
  IMUNOISE_EXPECT(n > 0, "psd_readoff: the spectrum is empty");
  IMUNOISE_EXPECT(binned.density.size() == n && binned.dof.size() == n,
                  "psd_readoff: frequency, density and dof sizes differ");
  IMUNOISE_EXPECT(
      binned.sample_rate_hz > 0.0 || (binned.resolution_hz > 0.0 && binned.segment_length > 0),
      "psd_readoff: sample_rate_hz, or resolution_hz and segment_length, must be set "
      "(got " +
          text(binned.sample_rate_hz) + " Hz, " + text(binned.resolution_hz) + " Hz, " +
          std::to_string(binned.segment_length) + ")");
  for (std::size_t i = 0; i < n; ++i) {
    const bool ok = std::isfinite(binned.frequency_hz[i]) && binned.frequency_hz[i] > 0.0 &&
                    std::isfinite(binned.density[i]) && binned.density[i] > 0.0 &&
                    std::isfinite(binned.dof[i]) && binned.dof[i] > 0.0;
    IMUNOISE_CHECK(ok, InputError,
                   "psd_readoff: point " + std::to_string(i) +
                       " needs positive finite frequency, density and dof (got " +
                       text(binned.frequency_hz[i]) + " Hz, " + text(binned.density[i]) + ", " +
                       text(binned.dof[i]) + ")");
  }
  const double tau0 =
      binned.sample_rate_hz > 0.0
          ? 1.0 / binned.sample_rate_hz
          : 1.0 / (binned.resolution_hz * static_cast<double>(binned.segment_length));

  // Local slope: least squares over the point and kSlopeHalfWidth neighbours on each side
  // (fewer at the ends).
  std::vector<double> log_f(n), log_s(n), slopes(n, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < n; ++i) {
    log_f[i] = std::log(binned.frequency_hz[i]);
    log_s[i] = std::log(binned.density[i]);
  }
  for (std::size_t i = 0; n >= 2 && i < n; ++i) {
    const std::size_t a = i >= kSlopeHalfWidth ? i - kSlopeHalfWidth : 0;
    const std::size_t b = std::min(n - 1, i + kSlopeHalfWidth);
    double mf = 0.0, ms = 0.0;
    for (std::size_t k = a; k <= b; ++k) {
      mf += log_f[k];
      ms += log_s[k];
    }
    const double count = static_cast<double>(b - a + 1);
    mf /= count;
    ms /= count;
    double sff = 0.0, sfs = 0.0;
    for (std::size_t k = a; k <= b; ++k) {
      sff += (log_f[k] - mf) * (log_f[k] - mf);
      sfs += (log_f[k] - mf) * (log_s[k] - ms);
    }
    slopes[i] = sfs / sff;
  }

  PsdReadoff out;
  // Red terms only below f_s/8: sampling a τ0-averaged red process bends its spectrum near
  // Nyquist while the slope stays within tolerance (rate random walk: factor
  // (2/3 + cos ω/3)·(ω/2)²/sin²(ω/2), ω = 2πfτ0, i.e. −5 % at f_s/8 but −25 % at 0.3·f_s),
  // and dof weighting would give that bent top the most weight.
  const double all = std::numeric_limits<double>::infinity();
  const double red_top = 1.0 / (8.0 * tau0);
  const std::vector<Run> plus2 = runs_with_slope(slopes, binned, 2.0, all);
  const std::vector<Run> flat = runs_with_slope(slopes, binned, 0.0, all);
  const std::vector<Run> minus1 = runs_with_slope(slopes, binned, -1.0, red_top);
  const std::vector<Run> minus2 = runs_with_slope(slopes, binned, -2.0, red_top);
  const std::vector<Run> minus3 = runs_with_slope(slopes, binned, -3.0, red_top);

  // Gauss–Markov: plateau followed closely by a −2 roll-off; keep the longest plateau.
  const Run* plateau = nullptr;
  const Run* rolloff = nullptr;
  for (const Run& p : flat) {
    for (const Run& r : minus2) {
      if (r.first > p.last &&
          binned.frequency_hz[r.first] <= kMaxGmGapRatio * binned.frequency_hz[p.last] &&
          (plateau == nullptr || better(p, *plateau))) {
        plateau = &p;
        rolloff = &r;
      }
    }
  }
  if (plateau != nullptr) {
    // First bin above the plateau where S₁ falls to LEVEL/2, log-interpolated; 0 if none.
    const auto half_power_frequency = [&](double level) {
      const double half = std::log(0.5 * level);
      for (std::size_t i = plateau->last + 1; i < n; ++i) {
        if (log_s[i] > half) continue;
        // log_s[i − 1] > half except when the plateau's last point is already below it.
        const double t =
            log_s[i - 1] > half ? (half - log_s[i - 1]) / (log_s[i] - log_s[i - 1]) : 0.0;
        return std::exp(log_f[i - 1] + t * (log_f[i] - log_f[i - 1]));
      }
      return 0.0;
    };
    // The run reaches up to where the Lorentzian has fallen by ~15 % (slope −0.3), and its
    // highest points carry the most dof: each point rather implies the plateau
    // S₁·(1 + (f/f_c)²) (§5.3 GM row). Iterate plateau ↔ f_c to a fixed point (exact for a
    // Lorentzian; converges in a few steps because the correction is small).
    double level = 0.0;
    for (std::size_t i = plateau->first; i <= plateau->last; ++i) {
      level += binned.dof[i] * binned.density[i];
    }
    level /= plateau->dof;
    double corner = half_power_frequency(level);
    for (int iteration = 0; iteration < 50 && corner > 0.0; ++iteration) {
      double corrected = 0.0;
      for (std::size_t i = plateau->first; i <= plateau->last; ++i) {
        const double x = binned.frequency_hz[i] / corner;
        corrected += binned.dof[i] * binned.density[i] * (1.0 + x * x);
      }
      corrected /= plateau->dof;
      const bool converged = std::fabs(corrected - level) <= 1e-9 * level;
      level = corrected;
      corner = half_power_frequency(level);
      if (converged) break;
    }
    out.gm_plateau = {level, true, binned.frequency_hz[plateau->first],
                      binned.frequency_hz[plateau->last], plateau->size()};
    if (corner > 0.0) {
      out.gm_corner_hz = {corner, true, binned.frequency_hz[rolloff->first],
                          binned.frequency_hz[rolloff->last], rolloff->size()};
    }
  }

  out.terms[NoiseTerm::quantization] = read_term(binned, longest(plus2, nullptr), 2, tau0);
  // White noise cannot show below a visible Gauss–Markov plateau (it would hide it), so
  // with one, only flat runs above the start of its roll-off qualify; flat runs below it
  // are pieces of the same plateau split by noisy slopes.
  std::vector<Run> white_runs;
  for (const Run& r : flat) {
    if (rolloff == nullptr || r.first > rolloff->first) white_runs.push_back(r);
  }
  out.terms[NoiseTerm::white_noise] = read_term(binned, longest(white_runs, nullptr), 0, tau0);
  out.terms[NoiseTerm::bias_instability] = read_term(binned, longest(minus1, nullptr), -1, tau0);
  out.terms[NoiseTerm::random_walk] = read_term(binned, longest(minus2, rolloff), -2, tau0);
  out.terms[NoiseTerm::ramp] = read_term(binned, longest(minus3, nullptr), -3, tau0);
  return out;
}

}  // namespace imunoise::analysis
