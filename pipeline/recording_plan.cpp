#include "pipeline/recording_plan.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>

#include "analysis/deviation.h"
#include "analysis/noise_terms.h"
#include "analysis/selection_uncertainty.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "common/parallel_for.h"
#include "pipeline/axis_analysis.h"
#include "pipeline/bootstrap.h"

namespace imunoise::pipeline {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
/// Bisection steps in ln T inside the bracket of a required duration (table steps ≤ ×2.5,
/// so the result is resolved to ×2.5^(1/32) ≈ 3 %).
constexpr int kBisectionSteps = 5;
/// The table stops once every condition holds at this many consecutive table durations.
constexpr std::size_t kSettledDurations = 3;

std::string trimmed(std::string_view text) {
  std::size_t a = 0, b = text.size();
  while (a < b && (text[a] == ' ' || text[a] == '\t')) ++a;
  while (b > a && (text[b - 1] == ' ' || text[b - 1] == '\t')) --b;
  return std::string(text.substr(a, b - a));
}

/// The table's durations [s] inside [LOW, HIGH]: human steps of at most ×2.5.
std::vector<double> table_durations(double low, double high) {
  const double minute = 60.0, hour = 3600.0, day = 86400.0;
  std::vector<double> all;
  for (double m : {1.0, 2.0, 5.0, 10.0, 20.0, 30.0}) all.push_back(m * minute);
  for (double h : {1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0}) all.push_back(h * hour);
  for (double d : {1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 7.0, 10.0, 14.0, 20.0, 30.0, 45.0, 60.0, 90.0,
                   120.0, 180.0, 270.0, 365.0}) {
    all.push_back(d * day);
  }
  std::vector<double> out;
  for (double d : all) {
    if (d >= low * (1.0 - 1e-12) && d <= high * (1.0 + 1e-12)) out.push_back(d);
  }
  return out;
}

/// What a required duration asks of one term's precision.
struct Condition {
  NoiseTerm term;
  bool identify_only;
  double target;  ///< relative half-width (unused when identify_only)
  bool holds(const PerTerm<TermPrecision>& p) const {
    return identify_only ? p[term].identified : meets_target(p[term], {term, target});
  }
};

}  // namespace

bool meets_target(const TermPrecision& precision, const PlanTarget& target) {
  return precision.identified && precision.relative_halfwidth <= target.relative_halfwidth;
}

std::vector<PlanTarget> parse_plan_targets(std::string_view text, std::string_view setting) {
  std::vector<PlanTarget> out;
  const std::string where(setting);
  std::size_t start = 0;
  if (trimmed(text).empty()) return out;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = trimmed(text.substr(start, comma - start));
    start = comma + 1;
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos) {
      throw InputError(where + ": '" + item +
                       "' is not TERM:WIDTH (e.g. K:20% — a term Q, N, B, K or R and the "
                       "relative half-width of its 95 % interval)");
    }
    const std::string symbol = trimmed(std::string_view(item).substr(0, colon));
    std::string width = trimmed(std::string_view(item).substr(colon + 1));
    const NoiseTerm* term = nullptr;
    for (const NoiseTerm& t : kNoiseTerms) {
      if (symbol == term_symbol(t)) term = &t;
    }
    if (term == nullptr) {
      throw InputError(where + ": '" + symbol + "' in '" + item +
                       "' is not a term; expected Q, N, B, K or R");
    }
    const bool percent = !width.empty() && width.back() == '%';
    if (percent) width = trimmed(std::string_view(width).substr(0, width.size() - 1));
    double value = 0.0;
    const char* end = width.data() + width.size();
    const auto [ptr, ec] = std::from_chars(width.data(), end, value);
    if (width.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) {
      throw InputError(where + ": '" + item + "': the width is not a number (e.g. 20%)");
    }
    if (percent) value /= 100.0;
    if (!(value > 0.0) || value > 10.0) {
      throw InputError(where + ": '" + item +
                       "': the relative half-width must be in (0, 1000 %], got " +
                       shortest_number_text(value * 100.0) + " %");
    }
    for (const PlanTarget& t : out) {
      if (t.term == *term) {
        throw InputError(where + ": term " + symbol + " is given twice");
      }
    }
    out.push_back({*term, value});
    if (comma == text.size()) break;
  }
  return out;
}

PerTerm<TermPrecision> expected_precision(const NoiseCoefficients& model, double rate_hz,
                                          double duration_s, int axis_index,
                                          const RecordingPlanOptions& options) {
  IMUNOISE_EXPECT(rate_hz > 0.0 && std::isfinite(rate_hz), "expected_precision: rate <= 0");
  IMUNOISE_EXPECT(duration_s > 0.0 && std::isfinite(duration_s),
                  "expected_precision: duration <= 0");
  IMUNOISE_EXPECT(options.interval_draws >= 2, "expected_precision: fewer than 2 draws");
  PerTerm<TermPrecision> out{};
  for (NoiseTerm term : kNoiseTerms) out[term].present = coefficient(model, term) > 0.0;
  const double tau0_s = 1.0 / rate_hz;
  const auto n_samples = static_cast<std::int64_t>(std::llround(duration_s * rate_hz));
  if (n_samples < 16) return out;  // analyze refuses such a record (axis_analysis)
  try {
    // 1. The τ grid of the record and the model's AVAR there (theory.md §4.1): the expected
    // OAVAR, to the discrete-sampling corrections at τ ≲ 5τ0 (docs/validation.md).
    const std::vector<std::int64_t> m_list =
        analysis::averaging_factors(options.grid, analysis::DeviationType::oadev, n_samples + 1);
    analysis::DeviationCurve curve;
    curve.type = analysis::DeviationType::oadev;
    curve.tau0_s = tau0_s;
    curve.n_phase = n_samples + 1;
    curve.confidence = options.confidence;
    for (std::size_t i = 0; i < m_list.size(); ++i) {
      analysis::DeviationPoint p;
      p.m = m_list[i];
      p.tau_s = static_cast<double>(m_list[i]) * tau0_s;
      p.value = analysis::model_adev(model, p.tau_s);
      p.n_terms =
          analysis::estimator_term_count(analysis::DeviationType::oadev, curve.n_phase, p.m);
      curve.points.push_back(p);
    }
    // 2. The fit as analyze runs it: EDF from the dominant term, fit, EDF from the fit, refit.
    apply_model_noise_type(curve, model);
    analysis::FitOptions fit_options = options.fit;
    if (fit_options.tau_min_s <= 0.0) fit_options.tau_min_s = low_pass_tau_min(curve);
    // On the exact curve of a model without GM terms the power-law fit has deviance ~0, so the
    // automatic GM candidate can never win (it needs a strictly lower penalized deviance):
    // skip it, the costly half of the fit, at every duration the plan tries.
    if (model.gauss_markov.empty() &&
        fit_options.gauss_markov == analysis::GaussMarkovMode::automatic)
      fit_options.gauss_markov = analysis::GaussMarkovMode::off;
    std::vector<analysis::FitPoint> points;
    const analysis::FitResult fit = fit_with_model_noise_types(curve, fit_options, points);
    // 3. The default intervals: draws of the OAVAR vector under the fitted model, refitted.
    // SETS sets of the analysis's draw count, in one call (one covariance): replicate r
    // depends only on (seed, r), so the first set is exactly the analysis's draws and the
    // others are what other seeds would give. The half-width is the median over the sets:
    // one set of 200 scatters by ±20 % where a term is weak (a few draws near 0 stretch
    // the log-domain spread), and the plan wants the typical interval, not one seed's.
    const int sets = std::max(1, options.interval_draw_sets);
    BootstrapOptions draws;
    draws.source = ReplicateSource::variance_distribution;
    draws.replicates = options.interval_draws * sets;
    draws.seed = options.seed * 1000003ULL + static_cast<std::uint64_t>(axis_index);
    draws.confidence = options.confidence;
    draws.threads = 1;
    const BootstrapResult replicates =
        bootstrap_fit(fit, points, m_list, n_samples, tau0_s, fit_options, draws);
    // 4. Each set's intervals widened by model-selection uncertainty as analyze widens its
    // own (pipeline/axis_analysis.h selection_upper_bounds, analysis/selection_uncertainty.h):
    // a term the fit drops (Q, R, K) held at its profile upper bound moves the identified
    // terms — R's bound widens K's interval most, both living at the longest τ.
    const PerTerm<double> upper_bounds = selection_upper_bounds(
        points, fit, m_list, tau0_s, n_samples, options.confidence, fit_options.weight_iterations);
    const auto per_set = static_cast<std::size_t>(options.interval_draws);
    PerTerm<std::vector<double>> widths;
    for (std::size_t first = 0; first + per_set <= replicates.term_samples.size();
         first += per_set) {
      PerTerm<Interval> intervals{};
      for (NoiseTerm term : kNoiseTerms) {
        const analysis::TermFit& t = fit.terms[term];
        if (!(t.identified && t.value > 0.0)) continue;
        std::vector<double> values;
        for (std::size_t r = first; r < first + per_set; ++r) {
          values.push_back(replicates.term_samples[r][term]);
        }
        intervals[term] = bootstrap_interval(t.value, values, options.confidence);
      }
      const PerTerm<analysis::SelectionWidening> widened = analysis::selection_widened_intervals(
          points, fit, intervals, upper_bounds, fit_options.weight_iterations);
      for (NoiseTerm term : kNoiseTerms) {
        const analysis::TermFit& t = fit.terms[term];
        if (!(t.identified && t.value > 0.0)) continue;
        const double low = std::min(widened[term].interval.low, t.value);
        const double high = std::max(widened[term].interval.high, t.value);
        widths[term].push_back((high - low) / (2.0 * t.value));
      }
    }
    for (NoiseTerm term : kNoiseTerms) {
      const analysis::TermFit& t = fit.terms[term];
      TermPrecision& p = out[term];
      p.identified = t.identified && t.value > 0.0;
      std::vector<double>& w = widths[term];
      if (!p.identified || w.empty()) continue;  // most draws failed to refit: no interval
      std::sort(w.begin(), w.end());
      const std::size_t n = w.size();
      p.relative_halfwidth = n % 2 == 1 ? w[n / 2] : 0.5 * (w[n / 2 - 1] + w[n / 2]);
    }
  } catch (const AnalysisError&) {
    // Too short for any fit, or no draw could be refitted: nothing identified.
    for (NoiseTerm term : kNoiseTerms) {
      out[term].identified = false;
      out[term].relative_halfwidth = kInf;
    }
  }
  return out;
}

RecordingPlan plan_recording(std::span<const PlanAxis> axes, double rate_hz,
                             std::span<const PlanTarget> targets,
                             const RecordingPlanOptions& options, std::string_view target_setting) {
  IMUNOISE_EXPECT(!axes.empty(), "plan_recording: no axis");
  IMUNOISE_EXPECT(options.min_duration_s > 0.0 && options.max_duration_s > options.min_duration_s,
                  "plan_recording: empty duration range");
  for (const PlanTarget& t : targets) {
    const bool any = std::any_of(axes.begin(), axes.end(), [&](const PlanAxis& a) {
      return coefficient(a.model, t.term) > 0.0;
    });
    if (!any) {
      throw InputError(std::string(target_setting) + ": no axis of the model has " +
                       term_symbol(t.term) + " (" + std::string(term_name(t.term)) +
                       "); drop that target");
    }
  }
  RecordingPlan plan;
  plan.rate_hz = rate_hz;
  plan.targets.assign(targets.begin(), targets.end());
  plan.durations_s = table_durations(options.min_duration_s, options.max_duration_s);
  IMUNOISE_EXPECT(plan.durations_s.size() >= 2, "plan_recording: duration range too narrow");
  const std::size_t n_axes = axes.size();

  // The conditions of each axis: every term the model has identified, every target met.
  struct Request {
    std::size_t axis;
    Condition condition;
    bool is_target;
    std::ptrdiff_t last_fail;  ///< −1: holds everywhere; n_dur − 1: fails at the longest
  };
  std::vector<Request> requests;
  for (std::size_t a = 0; a < n_axes; ++a) {
    for (NoiseTerm term : kNoiseTerms) {
      if (!(coefficient(axes[a].model, term) > 0.0)) continue;
      requests.push_back({a, {term, true, 0.0}, false, -1});
      for (const PlanTarget& t : targets) {
        if (t.term == term) requests.push_back({a, {term, false, t.relative_halfwidth}, true, -1});
      }
    }
  }
  // The table durations in ascending batches, until every condition holds at the last
  // kSettledDurations evaluated (the rest of the table is then not computed: it is the costly
  // part, and past that point longer records only narrow the intervals). Every evaluation is
  // one work item, deterministic whichever thread runs it.
  std::vector<PerTerm<TermPrecision>> coarse;  // [duration][axis] flattened
  std::size_t n_dur = 0;
  const std::size_t batch = std::max<std::size_t>(
      2, 2 * resolve_threads(options.threads) / std::max<std::size_t>(1, n_axes));
  const auto all_hold = [&](std::size_t d) {
    return std::all_of(requests.begin(), requests.end(), [&](const Request& r) {
      return r.condition.holds(coarse[d * n_axes + r.axis]);
    });
  };
  while (n_dur < plan.durations_s.size()) {
    const std::size_t next = std::min(plan.durations_s.size(), n_dur + batch);
    coarse.resize(next * n_axes);
    parallel_for((next - n_dur) * n_axes, options.threads, [&](std::size_t k) {
      const std::size_t d = n_dur + k / n_axes, a = k % n_axes;
      coarse[d * n_axes + a] = expected_precision(axes[a].model, rate_hz, plan.durations_s[d],
                                                  static_cast<int>(a), options);
    });
    n_dur = next;
    bool settled = n_dur >= kSettledDurations;
    for (std::size_t d = n_dur - std::min(n_dur, kSettledDurations); settled && d < n_dur; ++d) {
      settled = all_hold(d);
    }
    if (settled) break;
  }
  plan.durations_s.resize(n_dur);

  for (Request& r : requests) {
    for (std::size_t j = 0; j < n_dur; ++j) {
      if (!r.condition.holds(coarse[j * n_axes + r.axis])) {
        r.last_fail = static_cast<std::ptrdiff_t>(j);
      }
    }
  }
  // Bisection in ln T inside each bracket (condition fails at the low end, holds at the high
  // end). For a tighter target the condition fails wherever the looser one fails, so at every
  // step the tighter target's interval is the same or lies above the looser one's: the result
  // is monotone in the target (and the coarse bracket is too).
  std::vector<double> required(requests.size(), 0.0);
  parallel_for(requests.size(), options.threads, [&](std::size_t k) {
    const Request& r = requests[k];
    if (r.last_fail < 0) {
      required[k] = plan.durations_s.front();
      return;
    }
    const auto j = static_cast<std::size_t>(r.last_fail);
    if (j + 1 >= n_dur) {
      required[k] = kInf;
      return;
    }
    double lo = std::log(plan.durations_s[j]), hi = std::log(plan.durations_s[j + 1]);
    for (int step = 0; step < kBisectionSteps; ++step) {
      const double mid = 0.5 * (lo + hi);
      const PerTerm<TermPrecision> p = expected_precision(
          axes[r.axis].model, rate_hz, std::exp(mid), static_cast<int>(r.axis), options);
      (r.condition.holds(p) ? hi : lo) = mid;
    }
    required[k] = std::exp(hi);
  });

  plan.axes.resize(n_axes);
  for (std::size_t a = 0; a < n_axes; ++a) {
    AxisPlan& ap = plan.axes[a];
    ap.name = axes[a].name;
    for (std::size_t d = 0; d < n_dur; ++d) ap.table.push_back(coarse[d * n_axes + a]);
    ap.identify_duration_s.fill(kNaN);
    ap.target_duration_s.fill(kNaN);
  }
  for (std::size_t k = 0; k < requests.size(); ++k) {
    const Request& r = requests[k];
    AxisPlan& ap = plan.axes[r.axis];
    (r.is_target ? ap.target_duration_s : ap.identify_duration_s)[r.condition.term] = required[k];
  }
  if (!targets.empty()) {
    plan.all_targets_duration_s = 0.0;
    for (const AxisPlan& ap : plan.axes) {
      for (double d : ap.target_duration_s) {
        if (!std::isnan(d)) plan.all_targets_duration_s = std::max(plan.all_targets_duration_s, d);
      }
    }
  }
  return plan;
}

RecordingPlan precision_at(std::span<const PlanAxis> axes, double rate_hz, double duration_s,
                           std::span<const PlanTarget> targets,
                           const RecordingPlanOptions& options) {
  IMUNOISE_EXPECT(!axes.empty(), "precision_at: no axis");
  RecordingPlan plan;
  plan.rate_hz = rate_hz;
  plan.targets.assign(targets.begin(), targets.end());
  plan.durations_s = {duration_s};
  plan.axes.resize(axes.size());
  parallel_for(axes.size(), options.threads, [&](std::size_t a) {
    AxisPlan& ap = plan.axes[a];
    ap.name = axes[a].name;
    ap.table = {
        expected_precision(axes[a].model, rate_hz, duration_s, static_cast<int>(a), options)};
    ap.identify_duration_s.fill(kNaN);
    ap.target_duration_s.fill(kNaN);
  });
  return plan;
}

}  // namespace imunoise::pipeline
