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

/// @name The S₁ rows of theory.md §5.3 (one-sided, §1.3 coefficients)
/// @{
/// Q in its sampled form: the rate samples are differences of a white angle sequence of
/// variance Q² over τ0, so S₁ = 2·|1 − e^{−i2πfτ0}|²·Q²τ0/τ0² = 8 sin²(πfτ0)·Q²/τ0 on
/// [0, 1/(2τ0)]. It is theory.md §4.1's continuous (2πf)²τ0Q² (doubled to one-sided) where
/// fτ0 ≪ 1 and 4/π² = 0.405 of it at Nyquist, where the continuous law made a complete model
/// fail its cross-check on quantized angle increments (issue 20). With the sampled AVAR kernel
/// it integrates to 3Q²/τ² exactly.
double quantization_psd(double q, double f, double tau0) {
  if (f > 0.5 / tau0) return 0.0;
  const double s = std::sin(kPi * f * tau0);
  return 8.0 * s * s * q * q / tau0;
}
double white_psd(double n) { return 2.0 * n * n; }
double flicker_psd(double b, double f) { return b * b / (kPi * f); }
double random_walk_psd(double k, double f) { return k * k / (2.0 * kPi * kPi * f * f); }
double ramp_psd(double r, double f) {
  const double w = kTwoPi * f;
  return 2.0 * r * r / (w * w * w);
}
double gauss_markov_psd(const GaussMarkov& gm, double f) {
  const double x = kTwoPi * f * gm.tau_c_s;
  return 4.0 * gm.sigma * gm.sigma * gm.tau_c_s / (1.0 + x * x);
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
  t.terms[NoiseTerm::quantization] = quantization_psd(model.quantization, f_hz, tau0_s);
  t.terms[NoiseTerm::white_noise] = white_psd(model.white_noise);
  t.terms[NoiseTerm::bias_instability] = flicker_psd(model.bias_instability, f_hz);
  t.terms[NoiseTerm::random_walk] = random_walk_psd(model.random_walk, f_hz);
  t.terms[NoiseTerm::ramp] = ramp_psd(model.ramp, f_hz);
  t.gauss_markov.reserve(model.gauss_markov.size());
  for (const GaussMarkov& gm : model.gauss_markov) {
    t.gauss_markov.push_back(gauss_markov_psd(gm, f_hz));
  }
  return t;
}

double model_psd_one_sided(const NoiseCoefficients& model, double f_hz, double tau0_s) {
  check_model(model, f_hz, tau0_s);
  double sum = quantization_psd(model.quantization, f_hz, tau0_s) + white_psd(model.white_noise) +
               flicker_psd(model.bias_instability, f_hz) +
               random_walk_psd(model.random_walk, f_hz) + ramp_psd(model.ramp, f_hz);
  for (const GaussMarkov& gm : model.gauss_markov) sum += gauss_markov_psd(gm, f_hz);
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
      continue;
    }
    const double ratio = measured / expected;
    check.worst_log10_ratio = std::max(check.worst_log10_ratio, std::fabs(std::log10(ratio)));
    // ν·Ŝ/S ~ χ²_ν under the model: two-sided 99 % acceptance interval of the ratio.
    const double lower = chi_square_quantile(0.005, nu) / nu;
    const double upper = chi_square_upper_quantile(0.005, nu) / nu;
    if (ratio < lower || ratio > upper) ++check.bins_outside;
  }
  if (check.bins_compared == 0) {
    throw AnalysisError("cross_check_psd: no spectrum bin between " + text(f_low) + " and " +
                        text(f_high) + " Hz to compare");
  }
  const std::size_t allowed =
      std::max<std::size_t>(2, static_cast<std::size_t>(0.05 * check.bins_compared));
  check.pass = check.bins_outside <= allowed;
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
