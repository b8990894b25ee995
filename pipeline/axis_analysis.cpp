#include "pipeline/axis_analysis.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "analysis/confidence.h"
#include "analysis/edf.h"
#include "analysis/multirate_psd.h"
#include "analysis/noise_terms.h"
#include "analysis/selection_uncertainty.h"
#include "analysis/variance_covariance.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "models/bias_instability_gm.h"
#include "pipeline/bootstrap.h"

namespace imunoise::pipeline {

namespace {

std::string number_text(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

/// Range of max − min of a channel's samples (SI) that the squares of the analysis keep
/// finite and normal (see check_rate_samples).
constexpr double kMinSpread = 1e-40;
constexpr double kMaxSpread = 1e40;

/// Refuses records the estimator cannot answer, with the reason in the message. PIECES are
/// the gap-free pieces of the record (one for a record without gaps); sample indices in the
/// message count from the start of the first piece.
void check_rate_samples(const std::string& name, std::span<const std::span<const double>> pieces) {
  std::size_t total = 0;
  for (const auto& piece : pieces) total += piece.size();
  if (total < 16) {
    throw AnalysisError(name + ": too few samples for any τ range (" + std::to_string(total) +
                        "; a fit needs at least 16)");
  }
  // Range and finiteness in 8 independent lanes (vectorised, one pass: this runs on every
  // sample of every channel); the first non-finite sample is looked up only when there is one.
  constexpr std::size_t kLanes = 8;
  constexpr std::uint64_t kExponent = 0x7ff0000000000000ULL;
  std::array<double, kLanes> lane_low, lane_high;
  lane_low.fill(std::numeric_limits<double>::infinity());
  lane_high.fill(-std::numeric_limits<double>::infinity());
  std::uint64_t non_finite = 0;
  std::size_t offset = 0;
  for (const auto& rate : pieces) {
    const auto take = [&](std::size_t l, double v) {
      non_finite |=
          static_cast<std::uint64_t>((std::bit_cast<std::uint64_t>(v) & kExponent) == kExponent);
      lane_low[l] = v < lane_low[l] ? v : lane_low[l];
      lane_high[l] = v > lane_high[l] ? v : lane_high[l];
    };
    std::size_t i = 0;
    for (; i + kLanes <= rate.size(); i += kLanes) {
      for (std::size_t l = 0; l < kLanes; ++l) take(l, rate[i + l]);
    }
    for (; i < rate.size(); ++i) take(i % kLanes, rate[i]);
    if (non_finite != 0) {
      const auto bad =
          std::find_if(rate.begin(), rate.end(), [](double v) { return !std::isfinite(v); });
      throw AnalysisError(name + ": sample " +
                          std::to_string(offset + static_cast<std::size_t>(bad - rate.begin())) +
                          " is not finite (NaN/Inf); drop such rows when reading the recording");
    }
    offset += rate.size();
  }
  const double low = *std::min_element(lane_low.begin(), lane_low.end());
  const double high = *std::max_element(lane_high.begin(), lane_high.end());
  if (!(high > low)) {
    throw AnalysisError(name + ": the signal is constant (" + number_text(low) +
                        " in every sample); there is no noise to model");
  }
  // The estimators square the differences (σ², theory.md §2) and the fit squares σ² again
  // in its weights ν/(2σ⁴) (§4.3): the spread must stay far inside the double range, or
  // squares overflow to Inf or underflow to 0 and the outputs turn Inf/NaN. SI IMU noise is
  // 1e-10 … 1e2; a spread outside 1e-40 … 1e40 is a unit mistake, not a sensor.
  const double spread = high - low;
  if (!std::isfinite(spread) || spread > kMaxSpread || spread < kMinSpread) {
    throw AnalysisError(name + ": the samples span " + number_text(low) + " to " +
                        number_text(high) + " (spread " + number_text(spread) +
                        "), outside what the analysis can square in double precision (spread " +
                        number_text(kMinSpread) + " to " + number_text(kMaxSpread) +
                        " in SI units); check the column's unit");
  }
}

/// τ of the minimum of the fitted model ADEV over the fit range (log-spaced search), used as
/// τ_min of the B → GM conventions (theory.md §4.4).
double model_adev_minimum_tau(const NoiseCoefficients& c, double tau_low, double tau_high) {
  double best_tau = tau_low;
  double best = std::numeric_limits<double>::infinity();
  const int steps = 400;
  for (int i = 0; i <= steps; ++i) {
    const double tau = tau_low * std::pow(tau_high / tau_low, static_cast<double>(i) / steps);
    const double v = analysis::model_avar(c, tau);
    if (v < best) {
      best = v;
      best_tau = tau;
    }
  }
  return best_tau;
}

/// The spectral lines of the pieces (analysis/spectral_lines.h): the raw Welch spectrum at the
/// automatic segment length (at most options.line_segment_length_max), the lines standing
/// above its continuum plus the caller's candidate frequencies, fitted on the samples.
struct AxisLines {
  analysis::LineDetection detection;
  analysis::LineFit fit;
  std::size_t forced = 0;  ///< of fit.lines, the caller's candidates (the last ones)
};

AxisLines find_axis_lines(std::span<const std::span<const double>> pieces, double tau0_s,
                          const AxisAnalysisOptions& options) {
  AxisLines out;
  const std::vector<double>& forced = options.fit.sinusoid_frequencies_hz;
  if (!options.find_lines && forced.empty()) return out;
  std::size_t longest = 0;
  for (const auto& p : pieces) longest = std::max(longest, p.size());
  if (longest < 256) return out;
  analysis::WelchOptions welch = options.welch;
  welch.segment_length =
      std::min(analysis::automatic_segment_length(longest), options.line_segment_length_max);
  std::vector<std::span<const double>> usable;
  for (const auto& p : pieces) {
    if (p.size() >= welch.segment_length) usable.push_back(p);
  }
  const analysis::Spectrum raw = analysis::pooled_welch_psd(usable, 1.0 / tau0_s, welch);
  std::vector<double> frequencies, continuum;
  if (options.find_lines) {
    out.detection = analysis::detect_spectral_lines(raw, options.lines);
    for (const analysis::LineCandidate& c : out.detection.candidates) {
      frequencies.push_back(c.frequency_hz);
      continuum.push_back(c.continuum_density);
    }
  }
  for (double f : forced) {
    // A candidate already found is not fitted twice.
    const bool found = std::any_of(frequencies.begin(), frequencies.end(), [&](double g) {
      return std::abs(g - f) <= 2.0 * raw.resolution_hz;
    });
    if (found) continue;
    frequencies.push_back(f);
    continuum.push_back(analysis::line_continuum_density(raw, f, options.lines));
    ++out.forced;
  }
  std::vector<std::span<const double>> all(pieces.begin(), pieces.end());
  std::erase_if(all, [](std::span<const double> p) { return p.size() < 8; });
  out.fit = analysis::fit_spectral_lines(all, 1.0 / tau0_s, frequencies, continuum,
                                         raw.resolution_hz, options.confidence);
  return out;
}

}  // namespace

int model_noise_alpha(const NoiseCoefficients& c, double tau_s, bool hadamard) {
  // Power-law exponent of S_y(f) of each term (theory.md §4.1 slopes): Q white PM (α = 2),
  // N white FM (0), B flicker FM (−1), K random-walk FM (−2), R drift (−2 for the Allan
  // family; invisible to Hadamard). A GM acts as a random walk below T_c and as white noise
  // above (theory.md §4.1 limits).
  int alpha = 0;
  double best = -1.0;
  const auto consider = [&](double variance, int a) {
    if (variance > best) {
      best = variance;
      alpha = a;
    }
  };
  const auto basis = [&](NoiseTerm t) { return analysis::term_basis(t, tau_s, hadamard); };
  consider(c.quantization * c.quantization * basis(NoiseTerm::quantization), 2);
  consider(c.white_noise * c.white_noise * basis(NoiseTerm::white_noise), 0);
  consider(c.bias_instability * c.bias_instability * basis(NoiseTerm::bias_instability), -1);
  consider(c.random_walk * c.random_walk * basis(NoiseTerm::random_walk), -2);
  if (!hadamard) consider(c.ramp * c.ramp * basis(NoiseTerm::ramp), -2);
  for (const GaussMarkov& gm : c.gauss_markov) {
    const double v = analysis::gauss_markov_variance(gm.sigma, gm.tau_c_s, tau_s, hadamard);
    consider(v, tau_s < gm.tau_c_s ? -2 : 0);
  }
  return alpha;
}

analysis::FitResult fit_with_model_noise_types(analysis::DeviationCurve& curve,
                                               const analysis::FitOptions& options,
                                               std::vector<analysis::FitPoint>& points) {
  analysis::FitOptions first_options = options;
  if (options.gauss_markov == analysis::GaussMarkovMode::automatic)
    first_options.gauss_markov = analysis::GaussMarkovMode::off;
  const analysis::FitResult first =
      analysis::fit_noise_model(analysis::fit_points(curve), first_options);
  // The lag-1 noise identification becomes unreliable with few decimated points at large m
  // (e.g. white FM read as white PM, ν wrong by 10²–10³). Once a model exists, the noise type
  // at each τ is that of the model's dominant term, and the EDF, intervals and fit weights
  // follow it; the fit is then repeated once.
  apply_model_noise_type(curve, first.coefficients);
  points = analysis::fit_points(curve);
  return analysis::fit_noise_model(points, options);
}

void apply_model_noise_type(analysis::DeviationCurve& curve, const NoiseCoefficients& c) {
  const bool hadamard =
      curve.type == analysis::DeviationType::ohdev || curve.type == analysis::DeviationType::hdev;
  for (analysis::DeviationPoint& p : curve.points) {
    p.alpha = model_noise_alpha(c, p.tau_s, hadamard);
    p.edf = analysis::curve_edf(curve, p.alpha, p.m);
    const analysis::DeviationInterval ci =
        analysis::deviation_interval(p.value, p.edf, curve.confidence);
    p.ci_low = ci.low;
    p.ci_high = ci.high;
  }
}

analysis::VarianceCovariance used_point_moments(const analysis::FitResult& fit,
                                                std::span<const std::int64_t> m_list, double tau0_s,
                                                std::int64_t total_samples) {
  std::vector<std::int64_t> used_m;
  for (std::size_t k : fit.used) used_m.push_back(m_list[k]);
  if (used_m.empty()) return {};
  return analysis::overlapping_variance_covariance(fit.coefficients, tau0_s, total_samples, used_m,
                                                   fit.hadamard);
}

std::vector<double> row_major_correlation(const analysis::VarianceCovariance& moments) {
  std::vector<double> used_correlation;
  const std::size_t n = moments.expected.size();
  if (n == 0) return used_correlation;
  const Eigen::MatrixXd rho = analysis::correlation_matrix(moments);
  used_correlation.resize(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      used_correlation[i * n + j] = rho(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
  return used_correlation;
}

std::vector<double> used_point_correlation(const analysis::FitResult& fit,
                                           std::span<const std::int64_t> m_list, double tau0_s,
                                           std::int64_t total_samples) {
  return row_major_correlation(used_point_moments(fit, m_list, tau0_s, total_samples));
}

PerTerm<double> selection_upper_bounds(std::span<const analysis::FitPoint> points,
                                       const analysis::FitResult& fit,
                                       std::span<const std::int64_t> m_list, double tau0_s,
                                       std::int64_t total_samples, double confidence,
                                       int weight_iterations,
                                       std::span<const double> given_correlation) {
  // The correlation of the variance estimates at the fitted points under the fitted model.
  std::vector<double> computed;
  std::span<const double> used_correlation = given_correlation;
  if (used_correlation.empty()) {
    computed = used_point_correlation(fit, m_list, tau0_s, total_samples);
    used_correlation = computed;
  }
  PerTerm<double> upper_bounds{};
  for (NoiseTerm term : kNoiseTerms) {
    upper_bounds[term] = fit.terms[term].identified
                             ? 0.0
                             : analysis::profile_upper_bound(points, fit, term, confidence,
                                                             weight_iterations, used_correlation);
  }
  return upper_bounds;
}

double low_pass_tau_min(const analysis::DeviationCurve& oadev) {
  constexpr double kLowPassStartFactor = 50.0;
  const auto& pts = oadev.points;
  if (pts.empty()) return 0.0;
  std::size_t first = 0;
  while (first + 1 < pts.size() && pts[first].m <= 8) {
    const double here = pts[first].value * pts[first].value * pts[first].tau_s;
    const double next = pts[first + 1].value * pts[first + 1].value * pts[first + 1].tau_s;
    if (!(here < 0.8 * next)) break;
    ++first;
  }
  if (first == 0) return pts.front().tau_s;
  // A low-pass filter with unit DC gain leaves the white-noise AVAR short by a fraction that
  // decays only like 1/m (the filter memory matters at the two block edges of each
  // difference; docs/validation.md "Low-pass of white noise": AVAR = N²/τ − 3τ0²Σ|l|R(l)/(2τ²)
  // beyond the memory): a deficit of ~20 % at the first unbent point is still ~2 % ten times
  // further out, which left N −0.63 % under a 2nd-order Butterworth at f_s/4 (battery lowpass
  // class) against ±0.2 % intervals. Start the fit 50 times above the bend: ~0.4 % there,
  // less beyond, and N still has the decades up to the B/K corner.
  return kLowPassStartFactor * pts[first].tau_s;
}

AxisAnalysis analyze_axis(const std::string& name, SensorKind kind, std::span<const double> rate,
                          double tau0_s, int axis_index, const AxisAnalysisOptions& options) {
  const std::span<const double> whole[] = {rate};
  return analyze_axis_pieces(name, kind, whole, tau0_s, axis_index, options);
}

AxisAnalysis analyze_axis_pieces(const std::string& name, SensorKind kind,
                                 std::span<const std::span<const double>> pieces, double tau0_s,
                                 int axis_index, const AxisAnalysisOptions& options) {
  IMUNOISE_EXPECT(!pieces.empty(), name + ": no samples to analyse");
  check_rate_samples(name, pieces);
  std::int64_t total_samples = 0;
  for (const auto& piece : pieces) total_samples += static_cast<std::int64_t>(piece.size());
  const bool pooled = pieces.size() > 1;
  const int replicates = options.bootstrap_replicates >= 2 ? options.bootstrap_replicates : 0;
  const std::int64_t units = 4 + replicates;  // see AxisAnalysisOptions::progress
  const auto progress = [&](std::string_view stage, std::int64_t done) {
    report_progress(options.progress, stage, done, units);
  };
  progress("deviations", 0);
  AxisAnalysis out;
  // 0. Spectral lines: found and fitted on the samples, removed before the deviations so that
  // the AVAR fit sees the continuum only (a line's AVAR hump would otherwise be read as B, K
  // or a ramp); the PSD below stays that of the record as given (psd.csv shows the lines; the
  // cross-check skips the bins that hold them).
  const AxisLines lines = find_axis_lines(pieces, tau0_s, options);
  out.lines = lines.detection;
  std::vector<std::vector<double>> cleaned;
  std::vector<std::span<const double>> cleaned_spans;
  std::span<const std::span<const double>> work = pieces;
  if (!lines.fit.lines.empty()) {
    std::size_t fitted = 0;
    for (const auto& piece : pieces) {
      if (piece.size() < 8) {
        cleaned.emplace_back(piece.begin(), piece.end());
      } else {
        cleaned.push_back(
            analysis::remove_spectral_lines(piece, fitted++, lines.fit, 1.0 / tau0_s));
      }
    }
    for (const auto& c : cleaned) cleaned_spans.emplace_back(c);
    work = cleaned_spans;
  }
  // One phase record per piece, each from its own mean (theory.md §2 "Numerics"); the grid
  // is that of the longest piece, which bounds the largest m any piece can answer.
  std::vector<std::vector<double>> phases;
  std::vector<std::span<const double>> phase_spans;
  phases.reserve(pieces.size());
  std::int64_t n_phase = 0;
  for (const auto& piece : work) {
    phases.push_back(analysis::phase_from_rate(piece, tau0_s));
    phase_spans.emplace_back(phases.back());
    n_phase = std::max(n_phase, static_cast<std::int64_t>(phases.back().size()));
  }

  // 1. Deviations with chi-square intervals at the reported confidence.
  analysis::DeviationOptions dev;
  dev.confidence = options.confidence;
  dev.threads = options.threads;
  // No lag-1 noise identification here: the noise type of every point is re-derived from the
  // fitted model below (apply_model_noise_type), so the first pass only needs a provisional
  // EDF — white FM (α = 0), capped per point by fit_points. This skips ~30 % of the work.
  dev.alpha = 0;
  // OADEV and OHDEV in shared passes: a factor of both grids is read once for both.
  const std::vector<std::int64_t> m_oadev =
      analysis::averaging_factors(options.grid, analysis::DeviationType::oadev, n_phase);
  const std::vector<std::int64_t> m_ohdev =
      analysis::averaging_factors(options.grid, analysis::DeviationType::ohdev, n_phase);
  analysis::AllanHadamardCurves curves =
      analysis::compute_pooled_allan_hadamard(phase_spans, tau0_s, m_oadev, m_ohdev, dev);
  out.oadev = std::move(curves.oadev);
  out.ohdev = std::move(curves.ohdev);
  progress("deviations", 1);
  // Nothing below reads the phase: free it before the PSD and the intervals (a 24 h record at
  // 1 kHz has 0.7 GB of phase per channel).
  phase_spans.clear();
  std::vector<std::vector<double>>().swap(phases);
  cleaned_spans.clear();
  std::vector<std::vector<double>>().swap(cleaned);
  progress("fit", 2);

  // 2. The fit on OAVAR (σ² domain, theory.md §4.3).
  // fit_points caps each EDF at the largest value of the white/flicker/RW noise types for that
  // m, so a mis-identified noise type at large m cannot over-weight a point.
  std::vector<analysis::FitPoint> points;
  analysis::FitOptions fit_options = options.fit;
  fit_options.sinusoid_frequencies_hz.clear();  // fitted on the samples above
  if (fit_options.tau_min_s <= 0.0 && options.auto_low_pass) {
    fit_options.tau_min_s = low_pass_tau_min(out.oadev);
  }
  out.fit = fit_with_model_noise_types(out.oadev, fit_options, points);
  if (options.generalized_least_squares) {
    // The selected structure re-estimated with the correlation across τ in the weights: the
    // first pass weights from the selected model, the second from the first GLS model; the
    // interval draws then use the final model's correlation (below).
    for (int pass = 0; pass < 2; ++pass) {
      out.fit = analysis::generalized_refit(
          points, out.fit, fit_options,
          used_point_correlation(out.fit, m_oadev, tau0_s, total_samples));
    }
  }
  apply_model_noise_type(out.oadev, out.fit.coefficients);
  apply_model_noise_type(out.ohdev, out.fit.coefficients);

  // 3. Read-offs (traceability) and the PSD cross-check.
  std::vector<double> taus, adevs;
  for (const auto& p : out.oadev.points) {
    taus.push_back(p.tau_s);
    adevs.push_back(p.value);
  }
  out.slope = analysis::slope_readoff(taus, adevs);
  progress("PSD", 3);
  // Multi-rate Welch straight into log bins (analysis/multirate_psd.h): the deepest level keeps
  // the resolution of the classic segment length, the others are decimated copies streamed
  // through short cache-resident segments. Pieces: at every level the segments of every piece
  // long enough are averaged together; one piece is exactly multirate_psd.
  std::size_t psd_pieces = 0;
  analysis::MultirateOptions psd_options;
  psd_options.welch = options.welch;
  psd_options.level_segment_length = options.psd_level_segment_length;
  psd_options.bins_per_decade = options.psd_bins_per_decade;
  out.psd = analysis::pooled_multirate_psd(pieces, 1.0 / tau0_s, psd_options, &psd_pieces);
  out.psd_readoff = analysis::psd_readoff(out.psd);
  NoiseCoefficients with_lines = out.fit.coefficients;
  for (const analysis::FittedLine& line : lines.fit.lines)
    with_lines.sinusoids.push_back(line.value);
  double check_max_hz = 0.4 / tau0_s;
  out.low_pass = find_low_pass_corner(out.psd, out.fit.coefficients, tau0_s);
  if (options.auto_low_pass && out.low_pass.found &&
      kPsdCheckLowPassFraction * out.low_pass.corner_hz < check_max_hz) {
    out.psd_check_low_pass_hz = out.low_pass.corner_hz;
    check_max_hz = kPsdCheckLowPassFraction * out.low_pass.corner_hz;
  }
  out.psd_check = analysis::cross_check_psd(out.psd, with_lines, tau0_s, check_max_hz);
  progress(replicates > 0 ? "bootstrap" : "intervals", 4);

  // 4. Intervals.
  models::AxisModel& model = out.model;
  model.name = name;
  model.kind = kind;
  model.fit_tau_min_s = out.fit.tau_min_s;
  model.fit_tau_max_s = out.fit.tau_max_s;
  model.fit_note = out.fit.selection_note;
  if (pooled) {
    std::string note = "curves pooled over " + std::to_string(pieces.size()) +
                       " gap-free pieces (PSD: " + std::to_string(psd_pieces) +
                       " long enough for a Welch segment)";
    if (options.bootstrap_replicates >= 2) {
      note += options.interval_source == ReplicateSource::simulated_record
                  ? "; the bootstrap simulates one record of the total length, an approximation"
                  : "; the interval draws model one record of the total length, an "
                    "approximation";
    }
    model.fit_note += std::string(model.fit_note.empty() ? "" : "; ") + note;
  }
  // The joint moments of the OAVAR estimates at the fitted points under the final model, once
  // per axis: the interval draws' distribution and, as a correlation, the weights of the GLS
  // refits (--estimator gls) and the variance inflation of the upper bounds and the
  // Gauss–Markov bound curve.
  const analysis::VarianceCovariance moments =
      used_point_moments(out.fit, m_oadev, tau0_s, total_samples);
  const std::vector<double> correlation = row_major_correlation(moments);
  PerTerm<Interval> intervals{};
  std::string interval_method;
  std::vector<Interval> gm_sigma, gm_tau;
  if (options.bootstrap_replicates >= 2) {
    BootstrapOptions boot;
    boot.replicates = options.bootstrap_replicates;
    boot.source = options.interval_source;
    boot.seed = options.seed * 1000003ULL + static_cast<std::uint64_t>(axis_index);
    boot.confidence = options.confidence;
    boot.threads = options.threads;
    if (options.generalized_least_squares) boot.used_correlation = correlation;
    boot.moments = &moments;
    if (options.progress) {
      boot.progress = [&progress](std::string_view stage, std::int64_t done, std::int64_t) {
        progress(stage, 4 + done);
      };
    }
    const BootstrapResult result =
        bootstrap_fit(out.fit, points, m_oadev, total_samples, tau0_s, fit_options, boot);
    intervals = result.terms;
    gm_sigma = result.gauss_markov_sigma;
    gm_tau = result.gauss_markov_tau_c;
    interval_method =
        (options.interval_source == ReplicateSource::simulated_record
             ? "parametric bootstrap, "
             : "parametric bootstrap of the OAVAR vector (model covariance across tau), ") +
        std::to_string(result.replicates) +
        " replicates, bias-corrected normal interval of the log";
  } else {
    intervals = analysis::least_squares_intervals(points, out.fit, options.confidence);
    interval_method = "weighted least squares covariance (ignores inter-tau correlation)";
  }
  // Upper bounds of the terms not identified, then the identified terms' intervals widened
  // by them (analysis/selection_uncertainty.h): dropping K must not leave B's interval
  // conditional on K = 0 when the data allow K up to its bound.
  const PerTerm<double> upper_bounds =
      selection_upper_bounds(points, out.fit, m_oadev, tau0_s, total_samples, options.confidence,
                             fit_options.weight_iterations, correlation);
  // The GMs the data exclude (issue 20): a GM the selection leaves out, or a second one beside
  // a fitted one, is bounded at each T_c of the fitted range instead of being silently absent.
  if (!out.fit.used.empty() && out.fit.tau_min_s > 0.0) {
    model.gauss_markov_bounds = analysis::gauss_markov_upper_bounds(
        points, out.fit, analysis::gauss_markov_bound_grid(out.fit.tau_min_s, out.fit.tau_max_s),
        options.confidence, fit_options.weight_iterations, correlation);
  }
  const PerTerm<analysis::SelectionWidening> widened = analysis::selection_widened_intervals(
      points, out.fit, intervals, upper_bounds, fit_options.weight_iterations);
  for (NoiseTerm term : kNoiseTerms) {
    const auto t = static_cast<std::size_t>(term);
    models::Estimate& e = model.terms[t];
    e.value = out.fit.terms[t].identified ? out.fit.terms[t].value : 0.0;
    e.identified = out.fit.terms[t].identified && e.value > 0.0;
    e.method = options.generalized_least_squares ? "gls-oavar" : "wnnls-oavar";
    if (e.identified) {
      e.ci_low = std::min(widened[t].interval.low, e.value);
      e.ci_high = std::max(widened[t].interval.high, e.value);
      e.interval_method = interval_method;
      if (!widened[t].moved_by.empty()) {
        e.interval_method += "; widened over " + widened[t].moved_by +
                             " at its upper bound (model-selection uncertainty, "
                             "analysis::selection_widened_intervals)";
      }
    } else {
      e.ci_low = 0.0;
      const double bound = upper_bounds[t];
      e.ci_high = std::isfinite(bound) ? bound : 0.0;
      e.interval_method = std::isfinite(bound)
                              ? "not identified; profile upper bound (deviance rise chi2_1 x "
                                "the variance inflation of the term's direction under the "
                                "model's tau correlation, analysis::profile_upper_bound)"
                              : "not identified; no bound from the fitted range";
    }
  }
  const auto slope_value = [](const analysis::SlopeReadoffTerm& r) {
    return r.found ? r.value : 0.0;
  };
  const auto psd_value = [](const analysis::PsdReadoffTerm& r) { return r.found ? r.value : 0.0; };
  for (NoiseTerm term : kNoiseTerms) {
    model.readoff.slope[term] = slope_value(out.slope[term]);
    model.readoff.psd[term] = psd_value(out.psd_readoff.terms[term]);
  }
  for (std::size_t j = 0; j < out.fit.coefficients.gauss_markov.size(); ++j) {
    models::GaussMarkovEstimate gm;
    gm.value = out.fit.coefficients.gauss_markov[j];
    if (j < gm_sigma.size()) {
      gm.sigma_ci_low = gm_sigma[j].low;
      gm.sigma_ci_high = gm_sigma[j].high;
      gm.tau_c_ci_low_s = gm_tau[j].low;
      gm.tau_c_ci_high_s = gm_tau[j].high;
    } else {
      // No bootstrap: no interval for the nonlinear GM parameters; an empty interval at the
      // estimate says so (and the fit note spells it out).
      gm.sigma_ci_low = gm.sigma_ci_high = gm.value.sigma;
      gm.tau_c_ci_low_s = gm.tau_c_ci_high_s = gm.value.tau_c_s;
    }
    model.gauss_markov.push_back(gm);
  }
  if (!model.gauss_markov.empty() && gm_sigma.empty()) {
    model.fit_note += std::string(model.fit_note.empty() ? "" : "; ") +
                      "Gauss-Markov intervals need the bootstrap (" + options.bootstrap_setting +
                      ")";
  }
  for (const analysis::FittedLine& line : lines.fit.lines) {
    model.sinusoids.push_back({line.value, line.amplitude_ci_low, line.amplitude_ci_high});
  }
  if (!lines.fit.lines.empty()) {
    const std::size_t found = lines.fit.lines.size() - lines.forced;
    std::string note = std::to_string(found) + " spectral line" + (found == 1 ? "" : "s") +
                       " found (false-alarm probability " +
                       number_text(100.0 * options.lines.false_alarm_probability) +
                       " % per channel over " + std::to_string(lines.detection.bins_searched) +
                       " bins, " + number_text(lines.detection.f_low_hz) + "–" +
                       number_text(lines.detection.f_high_hz) + " Hz)";
    if (lines.forced > 0) note += " and " + std::to_string(lines.forced) + " candidate(s) given";
    note += ", fitted by least squares on the samples and removed before the deviations";
    model.fit_note += std::string(model.fit_note.empty() ? "" : "; ") + note;
  }

  // 5. B → Gauss–Markov (theory.md §4.4): every convention, named, and the multi-GM form.
  model.tau_min_adev_s =
      model_adev_minimum_tau(out.fit.coefficients, out.fit.tau_min_s, out.fit.tau_max_s);
  const double b = model.terms[NoiseTerm::bias_instability].value;
  if (b > 0.0) {
    for (models::GmConvention convention :
         {models::GmConvention::min_adev_at_tau_min, models::GmConvention::peak_match,
          models::GmConvention::sigma_equals_b}) {
      // Convention (a) takes the ADEV minimum itself (lifted by N and K, theory.md §8.3), here
      // the fitted model's.
      model.bias_instability_gm.push_back(
          {std::string(models::name_of(convention)),
           models::gauss_markov_from_bias_instability(
               b, model.tau_min_adev_s, convention,
               analysis::model_adev(out.fit.coefficients, model.tau_min_adev_s))});
    }
    model.multi_gm = analysis::multi_gm_representation(points, out.fit);
    NoiseCoefficients with_gm = out.fit.coefficients;
    with_gm.bias_instability = 0.0;
    with_gm.gauss_markov.insert(with_gm.gauss_markov.end(), model.multi_gm.begin(),
                                model.multi_gm.end());
    model.multi_gm_fraction_inside_ci =
        analysis::fraction_inside_ci(points, out.fit.used, with_gm, options.confidence);
  }

  // 6. PSD cross-check verdict.
  model.psd_check_pass = out.psd_check.pass;
  model.psd_check_note = psd_check_note(out.psd_check, out.psd_check_low_pass_hz);
  progress("done", units);
  return out;
}

std::string_view psd_misfit_cause_text(analysis::PsdMisfitCause cause) {
  using analysis::PsdMisfitCause;
  switch (cause) {
    case PsdMisfitCause::spectral_line:
      return "likely a spectral line (vibration, a fan or motor, an electrical tone) the model "
             "does not hold";
    case PsdMisfitCause::isolated:
      return "likely chance, or a small misfit its neighbours do not confirm";
    case PsdMisfitCause::high_frequency_excess:
      return "likely aliasing or unmodelled high-frequency noise (vibration or noise folded "
             "from above Nyquist, quantization)";
    case PsdMisfitCause::low_pass:
      return "likely the sensor's low-pass filter (a roll-off towards Nyquist)";
    case PsdMisfitCause::low_frequency_excess:
      return "likely a missing random walk K or ramp R, or a slow drift the start-of-record scan "
             "did not flag";
    case PsdMisfitCause::low_frequency_deficit:
      return "likely a fitted K, R or B the spectrum does not show (a drift fitted as a "
             "random walk)";
    case PsdMisfitCause::level:
      return "likely a broadband level (N) the spectrum does not have, or a spectrum of "
             "another shape than the model's terms";
    case PsdMisfitCause::band_excess:
      return "likely an unmodelled term in this band (a Gauss-Markov bump, broadband "
             "vibration)";
    case PsdMisfitCause::band_deficit:
      return "likely a fitted term too large in this band";
  }
  return "likely an unmodelled term";
}

std::string psd_check_note(const analysis::PsdCrossCheck& check, double low_pass_corner_hz) {
  std::string note = std::to_string(check.bins_outside) + " of " +
                     std::to_string(check.bins_compared) +
                     " PSD bins outside their 99 % interval (" + number_text(check.f_min_hz) + "–" +
                     number_text(check.f_max_hz) + " Hz";
  if (low_pass_corner_hz > 0.0) {
    note += ", up to 1/4 of the low-pass corner ";
    note += significant_number_text(low_pass_corner_hz, 3);
    note += " Hz";
  }
  note += ")";
  if (check.pass || check.misfits.empty()) return note;
  // The three largest bands (ties: the lower one), reported in frequency order.
  std::vector<std::size_t> order(check.misfits.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return check.misfits[a].bins > check.misfits[b].bins;
  });
  order.resize(std::min<std::size_t>(order.size(), 3));
  std::sort(order.begin(), order.end());
  for (std::size_t i : order) {
    const analysis::PsdMisfitBand& band = check.misfits[i];
    const std::string where = band.f_low_hz == band.f_high_hz
                                  ? number_text(band.f_low_hz)
                                  : number_text(band.f_low_hz) + "–" + number_text(band.f_high_hz);
    note += "; " + std::string(band.above ? "above" : "below") + " the model at " + where +
            " Hz (" + std::to_string(band.bins) + (band.bins == 1 ? " bin" : " bins") +
            ", up to ×" + significant_number_text(band.extreme_ratio, 3) +
            "): " + std::string(psd_misfit_cause_text(band.cause));
  }
  if (check.misfits.size() > order.size()) {
    note += "; " + std::to_string(check.misfits.size() - order.size()) + " smaller band(s)";
  }
  return note;
}

}  // namespace imunoise::pipeline
